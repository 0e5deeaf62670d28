// scene.js: the scene as microrelief-render has it (docs/scene-and-cli.md), in the
// page's JavaScript: the camera resolved to rays (src/core/scene/Camera.cpp), the methods'
// names and rules (src/core/scene/Method.cpp), and the view as a URL query and as a command
// line (app/shared/SceneOptions.cpp); the bases, the pyramids' sizes and scale and the
// traversal's budget are relief_core.js's, the host core microrelief-three shares. The
// arithmetic follows the C++ step for step, in doubles where it has doubles and in floats
// (Math.fround) where it has floats, so that the page hands the shader the uniforms
// microrelief-render hands it.

import {kMethodTraits} from './relief_layout.js';
import {baseShape, baseType, kBaseNames, kBaseSizes} from './relief_core.js';

export {wrapsU} from './relief_core.js';

const f32 = Math.fround;

// ---- vectors, as GLM computes them (no SIMD): double unless said ----
export const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
export const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
export const scale = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
export const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
export const length = (a) => Math.sqrt(dot(a, a));
export const normalize = (a) => scale(a, 1 / Math.sqrt(dot(a, a)));  // glm: v * inversesqrt(dot(v, v))
export const cross = (x, y) => [x[1] * y[2] - y[1] * x[2], x[2] * y[0] - y[2] * x[0], x[0] * y[1] - y[0] * x[1]];

// The same in float: every operation rounded as a float vec3 computes it.
export const toFloat = (a) => a.map(f32);
export function normalizeFloat(v) {
    const a = toFloat(v);
    const d = f32(f32(f32(a[0] * a[0]) + f32(a[1] * a[1])) + f32(a[2] * a[2]));
    const inverse = f32(1 / f32(Math.sqrt(d)));
    return a.map((c) => f32(c * inverse));
}

const kRadiansPerDegree = 0.01745329251994329576923690768489;  // glm::radians

// ---- the camera (src/core/scene/Camera.cpp: resolveCamera) ----

// {eye, forward, right, up, viewProjection (16 doubles, column-major), width, height}.
// Throws Error for a degenerate camera, naming the view's keys and values.
export function resolveCamera(camera, width, height, sceneRadius) {
    if (!(camera.fovy > 0 && camera.fovy < 180)) throw new Error('fovy must lie strictly between 0 and 180 degrees');
    const view = sub(camera.target, camera.eye);
    const distance = length(view);
    if (!(distance > 0) || !Number.isFinite(distance))
        throw new Error(`eye=${vectorText(camera.eye)} and target=${vectorText(camera.target)} must differ`);
    const forward = scale(view, 1 / distance);
    const side = cross(forward, camera.up);
    if (!(length(side) > 1e-9 * length(camera.up)))
        throw new Error(`up=${vectorText(camera.up)} must not be parallel to the view direction (target - eye)`);
    const right = normalize(side);
    const up = cross(right, forward);
    const tanY = Math.tan(camera.fovy * kRadiansPerDegree * 0.5);
    const aspect = width / height;

    const centre = length(camera.eye);
    const zFar = centre + 2 * sceneRadius;
    const zNear = Math.max(1e-4 * zFar, centre - 2 * sceneRadius);
    const projection = perspective(camera.fovy * kRadiansPerDegree, aspect, zNear, zFar);
    const viewMatrix = lookAt(camera.eye, add(camera.eye, forward), up);
    return {
        eye: camera.eye,
        forward,
        right: scale(right, tanY * aspect),
        up: scale(up, tanY),
        viewProjection: multiply(projection, viewMatrix),
        width,
        height,
    };
}

// glm::perspective (right-handed, clip depth [-1, 1]), column-major.
function perspective(fovy, aspect, zNear, zFar) {
    const tanHalf = Math.tan(fovy / 2);
    const m = new Array(16).fill(0);
    m[0] = 1 / (aspect * tanHalf);
    m[5] = 1 / tanHalf;
    m[10] = -(zFar + zNear) / (zFar - zNear);
    m[11] = -1;
    m[14] = -(2 * zFar * zNear) / (zFar - zNear);
    return m;
}

// glm::lookAt (right-handed), column-major.
function lookAt(eye, centre, upVector) {
    const f = normalize(sub(centre, eye));
    const s = normalize(cross(f, upVector));
    const u = cross(s, f);
    return [s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0, -dot(s, eye), -dot(u, eye), dot(f, eye), 1];
}

function multiply(a, b) {
    const m = new Array(16).fill(0);
    for (let c = 0; c < 4; ++c)
        for (let r = 0; r < 4; ++r)
            m[c * 4 + r] = a[r] * b[c * 4] + a[4 + r] * b[c * 4 + 1] + a[8 + r] * b[c * 4 + 2] + a[12 + r] * b[c * 4 + 3];
    return m;
}

// ---- base surfaces (their table, shapes and boxes: relief_core.js) ----

// Twice the largest coordinate of the box's corners (core/base/ReliefExtent.cpp: sceneRadius;
// the model is the identity here).
export function sceneRadius(extent) {
    let radius = 0;
    for (const c of [...extent.min, ...extent.max]) radius = Math.max(radius, Math.abs(c));
    return 2 * radius;
}

// ---- methods, views and shadows (src/core/scene/Method.cpp) ----

// The programs' words, in the order microrelief-render names them (tests/web/check_url_keys.py
// holds the two together); the number each selects in the shader comes by its name from
// relief_layout.js (kMethodValues, kDebugViewValues, ...: generated from variants.glsl and
// debug_views.glsl), never from a position in these lists.

// The methods and what each is: their rows in variants.glsl (MR_TRAITS_*), which the
// programs' checks read too (core/scene/Method.h: methodHas), generated into relief_layout.js.
export const kMethods = Object.keys(kMethodTraits);
const methodHas = (m, trait) => kMethodTraits[m].includes(trait);
export const kViews = ['shaded', 'iterations', 'level', 'normal', 'depth', 'position'];
export const kShadows = ['off', 'hard', 'soft'];
export const kInterpolations = ['bilinear', 'biquadratic'];
// The graphics APIs the page draws with (the key api=): relief_gpu.js, relief_gl.js.
export const kApis = ['webgpu', 'webgl2'];
export const methodHasSteps = (m) => methodHas(m, 'steps');
export const methodTracesTheSolid = (m) => methodHas(m, 'solid');
// The cone map a method reads (peers/ConeMap.h), or null: cone's conservative map, rcsm's
// relaxed one (ReliefMap::prepareFor).
export const methodConeMap = (m) =>
    (methodHas(m, 'cone_map') ? 'conservative' : methodHas(m, 'relaxed_cone_map') ? 'relaxed' : null);
export const methodRunsOnBase = (m, base) => base.kind === 'plane' || methodHas(m, 'curved');
// Whether a method reads the map's own quadtree (maxmip's aligned max levels).
export const methodReadsMaxPyramid = (m) => methodHas(m, 'max_pyramid');

// ---- the view: defaults, URL query, command line ----

export const kDefaultLight = normalizeFloat([-0.45, 0.8, -0.35]);

// microrelief-render's defaults (app/shared/SceneOptions.cpp, HeadlessRender.h).
export function defaultView() {
    return {
        eye: [0.8, 0.5, 0.85],
        target: [0, -0.03, 0],
        up: [0, 1, 0],
        fovy: 45,
        size: null,  // [W, H] in CSS pixels; null: the canvas fills the page's view area
        heightScale: f32(0.1),
        base: 'plane',
        // Each size of the bases (relief_core.js: kBaseSizes; radius, length, radii), by its
        // view name: null, its row's default.
        ...Object.fromEntries(kBaseSizes.map((size) => [size.viewName, null])),
        interpolation: 'bilinear',
        method: 'multilevel',
        steps: 64,
        pixelError: 0,
        view: 'shaded',
        light: kDefaultLight.slice(),  // floats, towards the light
        shadows: 'off',
        lightSize: 1,
        background: toFloat([0.11, 0.12, 0.14]),
        albedo: true,  // the bundled map's colours with the bundled map
        resolution: 1,  // 1, 2 or 4: the picture has a 1/resolution of the canvas's pixels
        clean: false,
        api: null,  // 'webgpu' or 'webgl2': the page draws with it or says why not; null: WebGPU where it can draw the view
    };
}

function numbers(name, text, count) {
    const parts = text.split(',');
    const values = parts.map((p) => (p.trim() === '' ? NaN : Number(p)));
    if (values.length !== count || values.some((v) => !Number.isFinite(v)))
        throw new Error(`${name}=${text}: expected ${count} comma-separated number${count > 1 ? 's' : ''}`);
    return values;
}

function choice(name, text, choices) {
    if (!choices.includes(text)) throw new Error(`${name}=${text}: expected ${choices.join(', ')}`);
    return text;
}

// A key the page does not know (a typo: pixelerror for pixel-error) is an error naming it,
// as microrelief-render refuses a flag it does not know; `known` the keys it read.
export function refuseUnknownKeys(q, known) {
    for (const key of q.keys())
        if (!known.has(key)) throw new Error(`${key}: not a key this page knows (${[...known].join(', ')})`);
}

// The view from a URL query (location.search): every key the page knows, each parsed as
// microrelief-render parses its flag; throws Error naming the key for a value that is not
// one (not a number, not one of the words) or a key it does not know. Whether the view is
// one the programs draw is the programs' own checks' to say (scene_checks.js).
export function viewFromQuery(search) {
    const q = new URLSearchParams(search);
    const v = defaultView();
    const known = new Set();
    const get = (key, parse) => {
        known.add(key);
        if (q.has(key)) parse(q.get(key));
    };
    get('eye', (t) => (v.eye = numbers('eye', t, 3)));
    get('target', (t) => (v.target = numbers('target', t, 3)));
    get('up', (t) => (v.up = numbers('up', t, 3)));
    get('fovy', (t) => (v.fovy = numbers('fovy', t, 1)[0]));
    get('size', (t) => {
        const m = /^(\d+)x(\d+)$/.exec(t);
        if (!m || +m[1] < 1 || +m[2] < 1 || +m[1] > 8192 || +m[2] > 8192) throw new Error(`size=${t}: expected WxH, each from 1 to 8192`);
        v.size = [+m[1], +m[2]];
    });
    get('height-scale', (t) => (v.heightScale = f32(numbers('height-scale', t, 1)[0])));
    get('base', (t) => (v.base = choice('base', t, kBaseNames)));
    // A base's sizes by their keys (radius, length, radii: the rows' fields as flags).
    for (const size of kBaseSizes)
        get(size.key, (t) => {
            const n = numbers(size.key, t, size.count);
            v[size.viewName] = size.count === 1 ? n[0] : n;
        });
    get('interpolation', (t) => (v.interpolation = choice('interpolation', t, kInterpolations)));
    get('method', (t) => (v.method = choice('method', t, kMethods)));
    get('steps', (t) => {
        v.steps = numbers('steps', t, 1)[0];
        // A whole number, as --steps parses one; its range is the checks'.
        if (!Number.isInteger(v.steps) || Math.abs(v.steps) > 2 ** 31 - 1) throw new Error(`steps=${t}: expected a whole number`);
    });
    get('pixel-error', (t) => (v.pixelError = f32(numbers('pixel-error', t, 1)[0])));
    get('view', (t) => (v.view = choice('view', t, kViews)));
    get('light', (t) => (v.light = toFloat(numbers('light', t, 3))));
    get('shadows', (t) => (v.shadows = choice('shadows', t, kShadows)));
    get('light-size', (t) => (v.lightSize = f32(numbers('light-size', t, 1)[0])));
    get('background', (t) => (v.background = toFloat(numbers('background', t, 3))));
    get('albedo', (t) => (v.albedo = choice('albedo', t, ['none', 'map']) === 'map'));
    get('resolution', (t) => (v.resolution = Number(choice('resolution', t, ['1', '2', '4']))));
    get('clean', (t) => (v.clean = t === '1'));
    get('api', (t) => (v.api = choice('api', t, kApis)));
    refuseUnknownKeys(q, known);
    return v;
}

// The view's base shape (relief_core.js: baseShape; a size the view leaves null, the row's
// default); throws Error naming the key of a size that is not a positive finite number.
export function viewBase(v) {
    return baseShape(v.base, Object.fromEntries(kBaseSizes.map((size) => [size.key, v[size.viewName]])));
}

// pom's samples looking straight down: MethodSettings::setSteps.
export const minSteps = (steps) => Math.min(steps, Math.max(4, Math.floor(steps / 4)));

// The shortest decimal text that reads back as the double `x` (JavaScript's own).
export const exactNumber = (x) => String(x);

// The shortest decimal text that reads back as the float `x`.
export function exactFloat(x) {
    for (let digits = 1; digits <= 9; ++digits) {
        const text = x.toPrecision(digits);
        if (f32(Number(text)) === x) return String(Number(text));
    }
    return String(x);
}

const vectorText = (v, text = exactNumber) => v.map(text).join(',');

// The view as a URL query: what differs from the defaults, and always the camera.
export function queryFromView(v) {
    const d = defaultView();
    const q = new URLSearchParams();
    q.set('eye', vectorText(v.eye));
    q.set('target', vectorText(v.target));
    if (v.up.some((c, k) => c !== d.up[k])) q.set('up', vectorText(v.up));
    q.set('fovy', exactNumber(v.fovy));
    if (v.size) q.set('size', `${v.size[0]}x${v.size[1]}`);
    if (v.heightScale !== d.heightScale) q.set('height-scale', exactFloat(v.heightScale));
    if (v.base !== d.base) q.set('base', v.base);
    for (const size of kBaseSizes) {
        const value = v[size.viewName];
        if (value !== null) q.set(size.key, size.count === 1 ? exactNumber(value) : vectorText(value));
    }
    if (v.interpolation !== d.interpolation) q.set('interpolation', v.interpolation);
    q.set('method', v.method);
    if (v.steps !== d.steps) q.set('steps', String(v.steps));
    if (v.pixelError !== d.pixelError) q.set('pixel-error', exactFloat(v.pixelError));
    if (v.view !== d.view) q.set('view', v.view);
    if (v.light.some((c, k) => c !== d.light[k])) q.set('light', vectorText(v.light, exactFloat));
    if (v.shadows !== d.shadows) q.set('shadows', v.shadows);
    if (v.lightSize !== d.lightSize) q.set('light-size', exactFloat(v.lightSize));
    if (v.background.some((c, k) => c !== d.background[k])) q.set('background', vectorText(v.background, exactFloat));
    if (!v.albedo) q.set('albedo', 'none');
    if (v.resolution !== 1) q.set('resolution', String(v.resolution));
    if (v.clean) q.set('clean', '1');
    if (v.api) q.set('api', v.api);
    return q.toString().replace(/%2C/g, ',');
}

// `text` quoted for a POSIX shell where it needs it (SceneOptions.cpp: shellQuote).
export function shellQuote(text) {
    if (text !== '' && /^[A-Za-z0-9_\-+=.,/:@%]+$/.test(text)) return text;
    return `'${text.replace(/'/g, `'\\''`)}'`;
}

// The microrelief-render command that draws this view, as the viewer's "copy as command"
// writes it (SceneOptions.cpp: renderCommandLine). `map` is null for the bundled map, else
// the file's name (the page never learns a dropped file's folder); `pixels` the picture's
// size in pixels.
export function renderCommandLine(v, map, pixels) {
    const parts = ['microrelief-render'];
    const flag = (name, value) => parts.push(value === undefined ? name : `${name} ${shellQuote(value)}`);
    if (map !== null) flag('--height', map);
    if (map === null && !v.albedo) flag('--albedo', 'none');
    flag('--height-scale', exactFloat(v.heightScale));
    if (v.interpolation !== 'bilinear') flag('--interpolation', v.interpolation);
    // The base by the name its shape goes by (an ellipsoid of equal radii is the sphere), and
    // its row's sizes: one number as a flag and its value, a vector after "=".
    const base = viewBase(v);
    const type = baseType(base);
    if (type.name !== defaultView().base) {
        flag('--base', type.name);
        for (const size of type.sizes) {
            const n = size.read(base);
            if (size.count === 1) flag(`--${size.key}`, exactNumber(n[0]));
            else parts.push(`--${size.key}=${vectorText(n)}`);
        }
    }
    // "=" keeps a leading minus from reading as a flag.
    parts.push(`--eye=${vectorText(v.eye)}`, `--target=${vectorText(v.target)}`, `--up=${vectorText(v.up)}`);
    flag('--fovy', exactNumber(v.fovy));
    flag('--size', `${pixels[0]}x${pixels[1]}`);
    parts.push(`--light=${vectorText(v.light, exactFloat)}`);
    if (v.shadows !== 'off') {
        flag('--shadows', v.shadows);
        if (v.shadows === 'soft') flag('--light-size', exactFloat(v.lightSize));
    }
    flag('--method', v.method);
    if (v.steps !== 64) flag('--steps', String(v.steps));
    if (v.pixelError !== 0) flag('--pixel-error', exactFloat(v.pixelError));
    flag('--view', v.view);
    const d = defaultView();
    if (v.background.some((c, k) => c !== d.background[k])) flag('--background', vectorText(v.background, exactFloat));
    return parts.join(' ');
}

// Radians per degree, for the panel's angles.
export const kDegree = Math.PI / 180;
