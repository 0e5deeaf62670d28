// app.js: the page. The map (the bundled one, or a PNG dropped or chosen), the view (from
// and to the URL), the panel, the orbit camera, and drawing on demand through
// relief_gl.js. Its state is on <html> for scripts and tests: data-state "loading",
// "ready" (a picture of the current view is on the canvas) or "error" (none can be: the
// reason in #error); data-map, the map's name; data-map-error, why the last map offered was
// refused (the previous one stays); data-opened, how many files dropped or chosen were
// dealt with (shown or refused); data-frames, how many pictures were drawn; data-cone-maps,
// the cone maps the current map has (cone's "conservative", rcsm's "relaxed"), each made
// only when its method is chosen (cone's on the GPU, rcsm's in WebAssembly: cone_maps.js),
// the state "loading" meanwhile. Every view is held to the programs' own checks before it is
// drawn (scene_checks.js: the C++ in WebAssembly): one the programs refuse is an error in
// their words, the state "error", never a blank canvas called "ready". data-api: the API the
// last picture was drawn with, "webgpu" (relief_gpu.js, on its own canvas) or "webgl2"
// (relief_gl.js): WebGPU where the browser gives an adapter and relief_gpu.js draws the view
// (gpuRefusal), else WebGL 2; the URL's api= forces one, and where it cannot draw the view
// the page says so in one line (an error at start, a refused edit in the panel) rather than
// drawing with the other. The WebGPU path reads the map's pyramids and albedo from the WebGL
// renderer, which builds them in either case.
import createSceneChecksModule from './generated/scene_checks_wasm.js';
import {ConeMapBuilder, ConeMapCancelled} from './cone_maps.js';
import {decodePng, heightsFromPng, PngError} from './png.js';
import {ReliefRenderer} from './relief_gl.js';
import {GpuReliefRenderer, gpuRefusal, requestGpu} from './relief_gpu.js';
import {baseTypeNamed, kBaseSizes, kBaseTypes} from './relief_core.js';
import * as scene from './scene.js';
import {largestSample, SceneChecks} from './scene_checks.js';

const root = document.documentElement;
const $ = (id) => document.getElementById(id);
const kShaderRoot = new URL('../shaders/', document.baseURI).href;
const kDefaultMap = new URL('../assets/cobbles.png', document.baseURI).href;
const kDefaultAlbedo = new URL('../assets/cobbles-albedo.png', document.baseURI).href;

const app = {
    view: null,
    initialView: null,
    renderer: null,     // WebGL 2 (relief_gl.js): the map's textures, pyramids and cone maps, and its pictures
    gpu: null,          // WebGPU (relief_gpu.js), where the browser gives an adapter and the URL does not say api=webgl2
    gpuWhy: '',         // why there is no WebGPU renderer, where there is none
    checks: null,       // the programs' checks of a view (SceneChecks)
    map: null,          // {name, bundled, width, height, samples, maxHeight}
    albedoImage: null,  // the bundled map's colours, RGBA
    coneMaps: new ConeMapBuilder(),  // rcsm's relaxed maps, in WebAssembly
    coneBuilds: new Map(),  // kind -> {started, done}: cone maps under way for the current map
    coneSeconds: {},        // kind -> seconds its build took, for the current map
    coneProgress: {},       // kind -> the fractions its build reported (WebAssembly's), for the current map
    frames: 0,
    opened: 0,
    dirty: false,
    drawing: false,
    fatal: false,
    refused: false,  // the current view is one the programs refuse at this picture's size
};
window.microrelief = app;  // for the console and tests

function setState(state) {
    root.dataset.state = state;
    $('status').textContent = {loading: 'Loading\u2026', ready: 'Ready.', error: 'Error.'}[state];
}

function fail(message) {
    app.fatal = true;
    $('error').textContent = message;
    $('error').hidden = false;
    setState('error');
    console.error(message);
}

// The view, drawn at `pixels` over `map`, refused by the programs' checks: why, or ''.
function refusal(view, map = app.map, size = pixels()) {
    return app.checks.refusal(view, map && {width: map.width, height: map.height, maxHeight: map.maxHeight, name: map.name}, size);
}

// A view the checks refuse where it is to be drawn (a canvas resized to a height its field
// of view cannot fill): the reason in #error and the state "error" until a view is drawn.
function refuse(message) {
    app.refused = true;
    $('error').textContent = message;
    $('error').hidden = false;
    setState('error');
}

function mapError(message) {
    root.dataset.mapError = message;
    $('map-error').textContent = message;
    $('map-error').hidden = !message;
}

// A value the panel refused (the view stays as it was).
function inputError(message) {
    $('input-error').textContent = message;
    $('input-error').hidden = !message;
}

// ---- the map ----

async function fetchBytes(url) {
    const response = await fetch(url, {cache: 'no-store'});
    if (!response.ok) throw new PngError(`cannot read it (HTTP ${response.status})`);
    return new Uint8Array(await response.arrayBuffer());
}

// A map from a PNG file's bytes: {width, height, samples}. Throws PngError.
async function mapFromBytes(bytes) {
    const png = await decodePng(bytes);
    const samples = heightsFromPng(png, 0);
    return {width: png.width, height: png.height, samples, maxHeight: largestSample(samples)};
}

// An albedo's RGBA bytes (AlbedoFile.cpp: grey spread to RGB, alpha 255), 8-bit only.
async function albedoFromBytes(bytes) {
    const png = await decodePng(bytes);
    if (png.bitDepth !== 8) throw new PngError('the page takes 8-bit albedos');
    const count = png.width * png.height, rgba = new Uint8Array(count * 4), used = Math.min(png.channels, 4);
    for (let p = 0; p < count; ++p) {
        for (let c = 0; c < 3; ++c) rgba[4 * p + c] = png.values[p * png.channels + (used < 3 ? 0 : c)];
        rgba[4 * p + 3] = 255;
    }
    return {width: png.width, height: png.height, rgba};
}

// Makes `map` the current one: its textures and pyramids first, then the switch (the
// cone maps under way for the old one dropped; the new one's made when drawn).
function useMap(map) {
    app.renderer.setMap(map.samples, map.width, map.height, scene.wrapsU(scene.viewBase(app.view)), scene.methodReadsMaxPyramid(app.view.method));
    app.coneMaps.cancel('a new map');
    app.coneBuilds.clear();
    app.coneSeconds = {};
    app.coneProgress = {};
    showConeMaps();
    app.map = map;
    app.mapWrapsU = scene.wrapsU(scene.viewBase(app.view));
    root.dataset.map = map.name;
    $('map-name').textContent = `${map.name}: ${map.width} x ${map.height}`;
    app.renderer.setAlbedo(map.bundled && app.view.albedo ? app.albedoImage : null);
}

// A file dropped or chosen: decoded, checked, then shown; on failure the current map stays
// and the reason shows, naming the file.
async function openFile(file) {
    mapError('');
    try {
        const bytes = new Uint8Array(await file.arrayBuffer());
        const decoded = await mapFromBytes(bytes);
        const map = {...decoded, name: file.name, bundled: false};
        // A map the current view cannot be drawn over, as the programs check it: refused.
        const why = refusal(app.view, map);
        if (why) throw new PngError(why.startsWith(`${file.name}: `) ? why.slice(file.name.length + 2) : why);
        useMap(map);
        syncPanel();
        requestRender();
    } catch (e) {
        const reason = e instanceof PngError ? e.message : `cannot be shown (${e.message})`;
        mapError(`${file.name}: ${reason}`);
        // The previous map is still there, and so is its picture.
    }
    root.dataset.opened = String(++app.opened);
}

// ---- the cone maps of cone and rcsm ----

const kConeMethod = {conservative: 'cone', relaxed: 'rcsm'};
const kConeBuiltWhere = {conservative: 'on the GPU', relaxed: 'in WebAssembly'};

// The cone map `kind` of the current map, made when missing (as ReliefRenderer::addConeMapFor
// makes it when cone or rcsm is drawn): cone's conservative one drawn on the GPU
// (PyramidBuilder.buildConeMap), rcsm's relaxed one by the C++ build in WebAssembly in a
// worker; a redraw once it is there. The panel shows the seconds so far meanwhile, and for
// the WebAssembly build how far it is (the worker's reports, each whole percent).
function ensureConeMap(kind) {
    const textures = app.renderer.textures;
    if (!kind || textures.cones[kind] || app.coneBuilds.has(kind)) return;
    const map = app.map, started = performance.now();
    const build = {started, done: 0};
    app.coneBuilds.set(kind, build);
    showConeMaps();
    const current = () => app.renderer.textures === textures;  // no other map since
    const done = () => {
        app.coneBuilds.delete(kind);
        app.coneSeconds[kind] = (performance.now() - started) / 1000;
        showConeMaps();
        requestRender();
    };
    const failed = (e) => {
        // A lost context has said so already (and how to go on).
        if (e instanceof ConeMapCancelled || !current() || app.fatal || app.renderer.gl.isContextLost()) return;
        app.coneBuilds.delete(kind);
        fail(`${map.name}: ${kConeMethod[kind]}'s ${kind} cone map: ${e.message}`);
    };
    if (kind === 'conservative') {
        app.renderer.addConservativeConeMap().then((added) => added && done(), failed);
        return;
    }
    app.coneProgress[kind] = [];
    const onProgress = (fraction) => {
        if (!current()) return;
        build.done = fraction;
        app.coneProgress[kind].push(fraction);
        showConeMaps();
    };
    app.coneMaps.build(map.samples, map.width, map.height, onProgress).then((texels) => {
        if (!current()) return;
        try {
            textures.uploadConeMap(kind, texels);
        } catch (e) {
            failed(e);
            return;
        }
        done();
    }, failed);
}

// The cone maps' line in the panel and data-cone-maps: those built (with their time) and
// those under way (with the seconds so far, updated each second while any is).
function showConeMaps() {
    const textures = app.renderer?.textures;
    const parts = [], built = [];
    for (const kind of ['conservative', 'relaxed']) {
        const build = app.coneBuilds.get(kind);
        if (build) {
            const percent = kind === 'relaxed' ? `${Math.floor(build.done * 100)} %, ` : '';
            parts.push(
                `building ${kConeMethod[kind]}'s ${kind} cone map ${kConeBuiltWhere[kind]}: ${
                    percent}${((performance.now() - build.started) / 1000).toFixed(0)} s\u2026`);
        } else if (textures?.cones[kind]) {
            built.push(kind);
            parts.push(`${kConeMethod[kind]}'s ${kind} cone map built ${kConeBuiltWhere[kind]} in ${
                app.coneSeconds[kind].toFixed(1)} s`);
        }
    }
    root.dataset.coneMaps = built.join(' ');
    $('cone-maps').textContent = parts.join('; ');
    $('cone-maps').hidden = parts.length === 0;
    clearTimeout(app.coneTimer);
    if (app.coneBuilds.size) app.coneTimer = setTimeout(showConeMaps, 1000);
}

// ---- the view and the panel ----

function syncUrl() {
    const query = scene.queryFromView(app.view);
    history.replaceState(null, '', `${location.pathname}?${query}`);
}

function pixels() {
    const canvas = $('canvas');
    return [canvas.width, canvas.height];
}

// The page's canvases: WebGL 2's, and WebGPU's where there is a WebGPU renderer (a canvas
// takes one API). Both have the same size; the one drawn last is shown.
const canvases = () => [$('canvas'), ...(app.gpu ? [app.gpu.canvas] : [])];

// The API `view` is drawn with: api= where the URL says, else WebGPU where it can draw it.
const apiFor = (view) => view.api ?? (app.gpu && !gpuRefusal(view) ? 'webgpu' : 'webgl2');

// Why `view` cannot be drawn with the API its api= asks for, one line, or ''.
function apiRefusal(view) {
    if (view.api !== 'webgpu') return '';
    const why = app.gpu ? gpuRefusal(view) : app.gpuWhy;
    return why ? `api=webgpu: ${why}` : '';
}

function commandLine() {
    return scene.renderCommandLine(app.view, app.map && !app.map.bundled ? app.map.name : null, pixels());
}

function lightAngles(light) {
    const l = scene.normalize(light);
    return [Math.atan2(l[2], l[0]) / scene.kDegree, Math.asin(Math.min(1, Math.max(-1, l[1]))) / scene.kDegree];
}

function syncPanel() {
    const v = app.view;
    $('height-scale').value = scene.exactFloat(v.heightScale);
    $('interpolation').value = v.interpolation;
    $('base').value = v.base;
    const base = scene.viewBase(v);
    // Each size's box: its number(s) where the chosen base has it, else empty (and hidden).
    const type = baseTypeNamed(v.base);
    for (const {key} of kBaseSizes) {
        const size = type.sizes.find((s) => s.key === key);
        $(key).value = size ? size.read(base).join(',') : '';
    }
    for (const label of document.querySelectorAll('[data-base]'))
        label.hidden = !label.dataset.base.split(' ').includes(v.base);
    // Ticked only where the colours are drawn: with a map of the user's the box is off and
    // greyed, and the choice comes back with the bundled map.
    const bundled = !!(app.map && app.map.bundled);
    $('albedo').checked = v.albedo && bundled;
    $('albedo').disabled = !bundled;
    const method = $('method');
    for (const option of method.options) option.disabled = !scene.methodRunsOnBase(option.value, base);
    method.value = v.method;
    $('steps').value = v.steps;
    document.querySelector('[data-steps]').hidden = !scene.methodHasSteps(v.method);
    $('pixel-error').value = v.pixelError;
    document.querySelector('[data-pixel-error]').hidden = v.method !== 'multilevel';
    $('view').value = v.view;
    const [azimuth, elevation] = lightAngles(v.light);
    $('light-azimuth').value = Math.round(azimuth);
    $('light-elevation').value = Math.round(elevation);
    $('shadows').value = v.shadows;
    for (const option of $('shadows').options) option.disabled = option.value !== 'off' && !scene.methodTracesTheSolid(v.method);
    $('light-size').value = v.lightSize;
    document.querySelector('[data-soft]').hidden = v.shadows !== 'soft';
    $('fovy').value = v.fovy;
    $('resolution').value = String(v.resolution);
}

function sizeCanvas() {
    const canvas = $('canvas'), v = app.view;
    const dpr = window.devicePixelRatio || 1;
    let css;
    if (v.size) {
        css = v.size;
    } else {
        const stage = $('stage');
        css = [Math.max(1, stage.clientWidth), Math.max(1, stage.clientHeight)];
    }
    // One ray a device pixel, or a 1/resolution of them (the canvas scales the picture up).
    const w = Math.max(1, Math.round((css[0] * dpr) / v.resolution));
    const h = Math.max(1, Math.round((css[1] * dpr) / v.resolution));
    for (const c of canvases()) {
        c.style.width = `${css[0]}px`;
        c.style.height = `${css[1]}px`;
    }
    if (canvas.width !== w || canvas.height !== h) {
        for (const c of canvases()) {
            c.width = w;
            c.height = h;
        }
        requestRender();
    }
}

// A change from the panel: `change` edits a copy of the view; the copy is checked by the
// programs' checks, and kept only when it passes (else the panel shows why).
function edit(change) {
    const next = structuredClone(app.view);
    try {
        change(next);
        const why = apiRefusal(next) || refusal(next);
        if (why) throw new Error(why);
    } catch (e) {
        inputError(e.message);
        syncPanel();
        return;
    }
    inputError('');
    const before = app.view;
    app.view = next;
    const wraps = scene.wrapsU(scene.viewBase(next));
    try {
        if (app.map && wraps !== app.mapWrapsU) useMap(app.map);  // the seam: the pyramid wraps in u or not
        else if (app.map && next.albedo !== before.albedo) app.renderer.setAlbedo(app.map.bundled && next.albedo ? app.albedoImage : null);
        if (scene.methodReadsMaxPyramid(next.method)) app.renderer.ensureMaxMip();
    } catch (e) {
        fail(e.message);
        return;
    }
    syncPanel();
    syncUrl();
    sizeCanvas();
    requestRender();
}

function number(id) {
    const value = Number($(id).value);
    if ($(id).value.trim() === '' || !Number.isFinite(value)) throw new Error(`${id}: not a number`);
    return value;
}

// The bases' menu and a box for each of their sizes, from the table of bases
// (relief_core.js). The menu lists a kind's rows together, in the table's order of kinds,
// the rows that name some of its shapes before the kind's own (plane, cylinder, sphere,
// ellipsoid: as baseType tries them). A size's box is labelled by its key in words
// ("radii": Radii); one number is a number box, a vector a text box of comma-separated
// numbers; each box is shown with the bases that have the size (data-base).
function baseControls() {
    const kinds = [...new Set(kBaseTypes.map((type) => type.kind))];
    const rank = (type) => 2 * kinds.indexOf(type.kind) + (type.names === null ? 1 : 0);
    const menu = $('base');
    for (const type of [...kBaseTypes].sort((a, b) => rank(a) - rank(b))) menu.add(new Option(type.name));
    let after = menu.closest('label');
    for (const size of kBaseSizes) {
        const label = document.createElement('label');
        label.dataset.base = size.bases.join(' ');
        const words = size.key.replace(/-/g, ' ');
        label.append(`${words[0].toUpperCase()}${words.slice(1)} `);
        const input = document.createElement('input');
        input.id = size.key;
        if (size.count === 1) Object.assign(input, {type: 'number', step: '0.05', min: '0.01'});
        else {
            // The placeholder: the size's default in the first row that has it (0.5,0.5,0.5).
            const first = baseTypeNamed(size.bases[0]);
            const placeholder = first.sizes.find((s) => s.field === size.field).read(first.defaults).join(',');
            Object.assign(input, {type: 'text', placeholder});
        }
        label.append(input);
        after.after(label);
        after = label;
    }
}

function wirePanel() {
    const method = $('method');
    for (const m of scene.kMethods) method.add(new Option(m, m));
    for (const v of scene.kViews) $('view').add(new Option(v, v));
    const on = (id, event, change) => $(id).addEventListener(event, () => edit(change));
    on('height-scale', 'change', (v) => (v.heightScale = Math.fround(number('height-scale'))));
    on('interpolation', 'change', (v) => (v.interpolation = $('interpolation').value));
    on('base', 'change', (v) => {
        v.base = $('base').value;
        for (const size of kBaseSizes) v[size.viewName] = null;
        if (!scene.methodRunsOnBase(v.method, scene.viewBase(v))) v.method = 'multilevel';
    });
    for (const size of kBaseSizes)
        on(size.key, 'change', (v) => (v[size.viewName] = size.count === 1 ? number(size.key) : $(size.key).value.split(',').map(Number)));
    on('albedo', 'change', (v) => (v.albedo = $('albedo').checked));
    on('method', 'change', (v) => {
        v.method = method.value;
        if (!scene.methodTracesTheSolid(v.method)) v.shadows = 'off';
    });
    on('steps', 'change', (v) => (v.steps = number('steps')));
    on('pixel-error', 'change', (v) => (v.pixelError = Math.fround(number('pixel-error'))));
    on('view', 'change', (v) => (v.view = $('view').value));
    const light = (v) => {
        const a = number('light-azimuth') * scene.kDegree, e = number('light-elevation') * scene.kDegree;
        v.light = scene.toFloat([Math.cos(e) * Math.cos(a), Math.sin(e), Math.cos(e) * Math.sin(a)]);
    };
    on('light-azimuth', 'input', light);
    on('light-elevation', 'input', light);
    on('shadows', 'change', (v) => (v.shadows = $('shadows').value));
    on('light-size', 'change', (v) => (v.lightSize = Math.fround(number('light-size'))));
    on('fovy', 'change', (v) => (v.fovy = number('fovy')));
    on('resolution', 'change', (v) => (v.resolution = Number($('resolution').value)));
    $('reset').addEventListener('click', () => edit((v) => Object.assign(v, {
        eye: app.initialView.eye, target: app.initialView.target, up: app.initialView.up, fovy: app.initialView.fovy,
    })));
    $('continuous').addEventListener('change', requestRender);
    $('copy').addEventListener('click', () => navigator.clipboard?.writeText($('command').textContent));
    $('file').addEventListener('change', () => {
        const file = $('file').files[0];
        if (file) openFile(file);
    });
    // Drops anywhere on the page.
    const stage = $('stage');
    window.addEventListener('dragover', (event) => {
        event.preventDefault();
        stage.classList.add('drop');
    });
    window.addEventListener('dragleave', () => stage.classList.remove('drop'));
    window.addEventListener('drop', (event) => {
        event.preventDefault();
        stage.classList.remove('drop');
        const file = event.dataTransfer?.files?.[0];
        if (file) openFile(file);
    });
}

// ---- the orbit camera ----

// Turntable: yaw about world y through the target, pitch short of the poles (the
// viewer's CameraController); the first turn makes up the world's y.
const kPitchLimit = 89.5;

function orbit(v, dx, dy) {
    const offset = scene.sub(v.eye, v.target);
    const distance = scene.length(offset);
    let yaw = Math.atan2(offset[2], offset[0]);
    let pitch = Math.asin(Math.min(1, Math.max(-1, offset[1] / distance)));
    yaw += dx * 0.008;
    pitch = Math.min(kPitchLimit * scene.kDegree, Math.max(-kPitchLimit * scene.kDegree, pitch + dy * 0.008));
    v.eye = scene.add(v.target, scene.scale([Math.cos(pitch) * Math.cos(yaw), Math.sin(pitch), Math.cos(pitch) * Math.sin(yaw)], distance));
    v.up = [0, 1, 0];
}

function pan(v, dx, dy, heightPixels) {
    const frame = scene.resolveCamera(v, 1, 1, 1);
    const distance = scene.length(scene.sub(v.target, v.eye));
    const perPixel = (2 * scene.length(frame.up) * distance) / heightPixels;
    const right = scene.normalize(frame.right), up = scene.normalize(frame.up);
    const move = scene.add(scene.scale(right, -dx * perPixel), scene.scale(up, dy * perPixel));
    v.eye = scene.add(v.eye, move);
    v.target = scene.add(v.target, move);
}

function zoom(v, steps) {
    const offset = scene.sub(v.eye, v.target);
    const distance = scene.length(offset);
    const wanted = distance * Math.exp(steps * 0.0015);
    if (wanted < 1e-3) {
        // Close in, the target travels with the eye, into the relief's box.
        const forward = scene.scale(offset, -1 / distance);
        const move = scene.scale(forward, distance - wanted);
        v.eye = scene.add(v.eye, move);
        v.target = scene.add(v.target, move);
        return;
    }
    v.eye = scene.add(v.target, scene.scale(offset, wanted / distance));
}

function wireCamera(canvas) {
    let drag = null;
    canvas.addEventListener('contextmenu', (event) => event.preventDefault());
    canvas.addEventListener('pointerdown', (event) => {
        drag = {x: event.clientX, y: event.clientY, pan: event.shiftKey || event.button !== 0};
        canvas.setPointerCapture(event.pointerId);
    });
    canvas.addEventListener('pointermove', (event) => {
        if (!drag) return;
        const dx = event.clientX - drag.x, dy = event.clientY - drag.y;
        drag.x = event.clientX;
        drag.y = event.clientY;
        if (dx === 0 && dy === 0) return;
        edit((v) => (drag.pan ? pan(v, dx, dy, canvas.clientHeight) : orbit(v, -dx, dy)));
    });
    const end = () => (drag = null);
    canvas.addEventListener('pointerup', end);
    canvas.addEventListener('pointercancel', end);
    canvas.addEventListener('wheel', (event) => {
        event.preventDefault();
        edit((v) => zoom(v, event.deltaY));
    }, {passive: false});
}

// ---- drawing ----

// A new picture is wanted: the state is "loading" until it is on the screen.
function requestRender() {
    app.dirty = true;
    if (app.fatal) return;
    setState('loading');
    if (!app.drawing) requestAnimationFrame(frame);
}

async function frame() {
    if (app.fatal || !app.map || !app.dirty || app.drawing) return;
    const cones = scene.methodConeMap(app.view.method);
    if (cones && !app.renderer.textures.cones[cones]) {
        ensureConeMap(cones);  // draws when it is there; "loading" till then
        return;
    }
    // While the GPU draws cone's map, a picture would wait behind it, and the page with it
    // (the read-back below): it is drawn once the map is done (ensureConeMap).
    if (app.coneBuilds.has('conservative')) return;
    app.drawing = true;
    app.dirty = false;
    const view = app.view;
    const config = {
        method: view.method,
        base: baseTypeNamed(view.base).kind,  // the shader's MICRORELIEF_BASE: the row's kind (the sphere's, the ellipsoid)
        interpolation: view.interpolation,
        shadows: scene.methodTracesTheSolid(view.method) ? view.shadows : 'off',
        albedoMap: !!app.renderer.albedo,
    };
    const api = apiFor(view);
    const drawer = api === 'webgpu' ? app.gpu : app.renderer;
    let program;
    try {
        program = await drawer.program(config);
    } catch (e) {
        app.drawing = false;
        fail(e.message);
        return;
    }
    if (app.view !== view) {
        // Changed while the program compiled: draw the newer view.
        app.drawing = false;
        app.dirty = true;
        requestAnimationFrame(frame);
        return;
    }
    const gl = app.renderer.gl;
    const size = pixels();
    // Checked where it is drawn: the canvas may have changed size since the view was.
    const why = refusal(view, app.map, size);
    if (why) {
        app.drawing = false;
        refuse(why);
        return;
    }
    if (app.refused) {
        app.refused = false;
        $('error').hidden = true;
        $('error').textContent = '';
    }
    const start = performance.now();
    try {
        if (api === 'webgpu') {
            await app.gpu.draw(program, view, size, app.albedoImage);  // resolves once the GPU is done
        } else {
            app.renderer.draw(program, view, size);
            gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));  // waits for the picture
        }
    } catch (e) {
        app.drawing = false;
        fail(`drawing failed: ${e.message}`);
        return;
    }
    $('canvas').hidden = api !== 'webgl2';
    if (app.gpu) app.gpu.canvas.hidden = api !== 'webgpu';
    root.dataset.api = api;
    const error = gl.getError();
    if (error !== gl.NO_ERROR) {
        app.drawing = false;
        fail(`WebGL error 0x${error.toString(16)} while drawing`);
        return;
    }
    const elapsed = performance.now() - start;
    ++app.frames;
    root.dataset.frames = String(app.frames);
    $('frame-time').textContent = `${elapsed.toFixed(1)} ms at ${size[0]} x ${size[1]} in ${api === 'webgpu' ? 'WebGPU' : 'WebGL 2'} (wall time to finish)`;
    $('command').textContent = commandLine();
    app.drawing = false;
    if ($('continuous').checked) app.dirty = true;
    // Ready once this picture is on the screen: after the next frame is composited.
    requestAnimationFrame(() => {
        if (app.fatal) return;
        if (app.dirty) frame();
        else setState('ready');
    });
}

// ---- start ----

async function start() {
    baseControls();  // the panel's bases as the markup had them, whatever happens next
    try {
        app.checks = await SceneChecks.load(createSceneChecksModule);
    } catch (e) {
        fail(`the scene checks: ${e.message}`);
        return;
    }
    try {
        app.view = scene.viewFromQuery(location.search);
        const why = refusal(app.view, null, [1, 1]);
        if (why) throw new Error(why);
    } catch (e) {
        fail(`the URL: ${e.message}`);
        return;
    }
    app.initialView = structuredClone(app.view);
    root.classList.toggle('clean', app.view.clean);
    const canvas = $('canvas');
    const gl = canvas.getContext('webgl2', {antialias: false, alpha: false, depth: false, preserveDrawingBuffer: true});
    if (!gl) {
        fail('this browser gives the page no WebGL 2 context');
        return;
    }
    canvas.addEventListener('webglcontextlost', (event) => {
        event.preventDefault();
        fail('the WebGL context was lost (the GPU was reset or is needed elsewhere): reload the page');
    });
    try {
        app.renderer = await ReliefRenderer.create(gl, kShaderRoot);
    } catch (e) {
        fail(e.message);
        return;
    }
    // WebGPU unless the URL says api=webgl2: where it cannot be had, api=webgpu fails in one
    // line, and without the key the page draws with WebGL 2.
    if (app.view.api !== 'webgl2') {
        const gpu = await requestGpu();
        if (gpu.why) {
            app.gpuWhy = gpu.why;
        } else {
            const gpuCanvas = document.createElement('canvas');
            gpuCanvas.id = 'gpu-canvas';
            gpuCanvas.hidden = true;
            canvas.after(gpuCanvas);
            try {
                app.gpu = await GpuReliefRenderer.create(gpuCanvas, gpu, app.renderer, kShaderRoot);
                app.gpu.onLost = (message) => fail(`the WebGPU device was lost (${message}): reload the page`);
            } catch (e) {
                gpuCanvas.remove();
                app.gpuWhy = e.message;
            }
        }
        const why = apiRefusal(app.view);
        if (why) {
            fail(why);
            return;
        }
    }
    wirePanel();
    for (const c of canvases()) wireCamera(c);
    sizeCanvas();
    new ResizeObserver(sizeCanvas).observe($('stage'));
    try {
        const [heights, albedo] = await Promise.all([fetchBytes(kDefaultMap), fetchBytes(kDefaultAlbedo)]);
        app.albedoImage = await albedoFromBytes(albedo);
        useMap({...(await mapFromBytes(heights)), name: 'cobbles.png', bundled: true});
        if (scene.methodReadsMaxPyramid(app.view.method)) app.renderer.ensureMaxMip();
    } catch (e) {
        fail(`${kDefaultMap}: ${e.message}`);
        return;
    }
    // The URL's view over the map, at the canvas's size: what the programs check before
    // they draw (the float limits need both).
    const why = refusal(app.view);
    if (why) {
        fail(`the URL: ${why}`);
        return;
    }
    syncPanel();
    syncUrl();
    requestRender();
}

start();
