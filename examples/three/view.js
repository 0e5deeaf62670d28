// view.js: the page's URL keys, the web page's (docs/browser.md) where they mean the same:
// eye=x,y,z target=x,y,z up=x,y,z fovy=DEG size=WxH clean=1, and for shading=microrelief
// (the library's own shading: microrelief-render's picture, to hold against it) base=,
// radius=, length=, radii=, interpolation=, height-scale=, light=x,y,z, shadows=off|hard,
// albedo=none, pixel-error=, model= (microrelief-render's --model: 12 numbers, a 3 x 4 affine
// matrix in rows) and pyramid=auto|gpu|cpu (how the max pyramid is built); and
// renderer=webgl|webgpu: the three.js renderer that draws (three's WebGLRenderer and
// microrelief-three, the default; three's WebGPURenderer and microrelief-three/webgpu, forced:
// a browser without WebGPU gets one line saying so, never the other renderer's picture).
// A value that does not parse is an error naming the key; whether the view is one the
// programs draw is their own checks' to say (microrelief-three's loadSceneChecks: main.js).
// The bases and their sizes' keys are the table of bases' rows: the package's generated
// relief_core.js (the web page's, from variants.glsl's rows), by its path beside this page as
// the import map reaches the package (a module of no bare import, so that node can read this
// file alone: ctest web.checks).
import {kBaseNames, kBaseSizes} from './node_modules/microrelief-three/generated/relief_core.js';

const f32 = Math.fround;

function numbers(key, text, count) {
    const values = text.split(',').map((p) => (p.trim() === '' ? NaN : Number(p)));
    if (values.length !== count || values.some((v) => !Number.isFinite(v)))
        throw new Error(`${key}=${text}: expected ${count} comma-separated number${count > 1 ? 's' : ''}`);
    return values;
}

function choice(key, text, choices) {
    if (!choices.includes(text)) throw new Error(`${key}=${text}: expected ${choices.join(', ')}`);
    return text;
}

// A float vector normalised in float arithmetic, as microrelief-render normalises --light
// (view.light is the URL's, checked as given).
export function normalizeFloat(v) {
    const a = v.map(f32);
    const d = f32(f32(f32(a[0] * a[0]) + f32(a[1] * a[1])) + f32(a[2] * a[2]));
    const inverse = f32(1 / f32(Math.sqrt(d)));
    return a.map((c) => f32(c * inverse));
}

export function viewFromUrl(search) {
    const q = new URLSearchParams(search);
    const v = {
        eye: [0.8, 0.5, 0.85], target: [0, -0.03, 0], up: [0, 1, 0], fovy: 45, size: null, clean: false,
        shading: 'three', base: 'plane', ...Object.fromEntries(kBaseSizes.map((size) => [size.viewName, undefined])),
        interpolation: 'bilinear', heightScale: f32(0.1), light: [-0.45, 0.8, -0.35], shadows: 'off',
        albedo: true, pixelError: 0, pyramid: 'auto', model: null, renderer: 'webgl',
    };
    const known = new Set();  // a key not among them is refused, as on the web page
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
    get('clean', (t) => (v.clean = t === '1'));
    get('shading', (t) => (v.shading = choice('shading', t, ['three', 'microrelief'])));
    get('base', (t) => (v.base = choice('base', t, kBaseNames)));
    for (const size of kBaseSizes)
        get(size.key, (t) => {
            const n = numbers(size.key, t, size.count);
            v[size.viewName] = size.count === 1 ? n[0] : n;
        });
    get('interpolation', (t) => (v.interpolation = choice('interpolation', t, ['bilinear', 'biquadratic'])));
    get('height-scale', (t) => (v.heightScale = f32(numbers('height-scale', t, 1)[0])));
    get('light', (t) => (v.light = numbers('light', t, 3)));
    get('shadows', (t) => (v.shadows = choice('shadows', t, ['off', 'hard'])));
    get('albedo', (t) => (v.albedo = choice('albedo', t, ['none', 'map']) === 'map'));
    get('pixel-error', (t) => (v.pixelError = f32(numbers('pixel-error', t, 1)[0])));
    get('pyramid', (t) => (v.pyramid = choice('pyramid', t, ['auto', 'gpu', 'cpu'])));
    get('model', (t) => (v.model = numbers('model', t, 12)));
    get('renderer', (t) => (v.renderer = choice('renderer', t, ['webgl', 'webgpu'])));
    for (const key of q.keys())
        if (!known.has(key)) throw new Error(`${key}: not a key this page knows (${[...known].join(', ')})`);
    return v;
}

// The base as Relief takes it: its name, with its row's sizes by their keys where it has any.
export function viewBase(v) {
    const sizes = kBaseSizes.filter((size) => size.bases.includes(v.base));
    if (!sizes.length) return v.base;
    return {kind: v.base, ...Object.fromEntries(sizes.map((size) => [size.key, v[size.viewName]]))};
}
