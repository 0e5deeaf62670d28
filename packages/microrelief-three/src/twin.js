// twin.js: the picks on the CPU, by the library's CPU twin of the shader's traversal
// (microrelief::core's MultilevelTracer, in double) compiled to WebAssembly
// (generated/twin_wasm.js, from wasm/twin_wasm.cpp). Relief.raycast, trace and traceRays use
// it when the package has it (pickWith 'auto'): no draw and no GPU readback, so a pick does
// not stall the GPU's queue. The world rays go into the relief's object space through its
// matrixWorld inside the WebAssembly (ModelTransform, in double), are traced there and come
// back as world hits, the same fields as the GPU's pick.frag writes.
//
// A twin is the relief's map (its samples, from the ReliefMap's height texture's data) and
// its max pyramid, built in WebAssembly memory for one height scale, base and last level:
// 4 bytes a sample and 4 bytes a texel of the pyramid's blocks and windows (about 14.7
// bytes a map texel: 3.9 MB for a 512 x 512 map), built at the first pick of that
// configuration and kept with the ReliefMap (the kMaxTwinsPerMap configurations picked
// last) until ReliefMap.dispose frees them.
import {baseName, baseSizeNumbers} from '../generated/relief_core.js';
import {kInterpolationValues} from '../generated/relief_layout.js';

let twinModule = null;  // the module once loaded, or the Error of a package without it
let loading = null;

// At most this many twins a map (configurations: height scale, base, last level); the one
// used longest ago is freed for a new one.
export const kMaxTwinsPerMap = 4;

// Loads generated/twin_wasm.js once (createReliefMap awaits it, so that picks can be
// synchronous). Never throws: a package packed without emscripten has a stub, and then
// picks are traced on the GPU (twinUnavailable says why).
export async function loadTwin() {
    if (twinModule) return twinModule;
    if (!loading) {
        loading = import('../generated/twin_wasm.js')
            .then((m) => m.default())
            .then((m) => (twinModule = m), (e) => (twinModule = e instanceof Error ? e : new Error(String(e))));
    }
    return loading;
}

// Whether picks can be traced by the twin now (its module loaded).
export function twinLoaded() {
    return !!twinModule && !(twinModule instanceof Error);
}

// Why the twin cannot trace ('' when it can).
export function twinUnavailable() {
    if (twinLoaded()) return '';
    if (twinModule instanceof Error) return twinModule.message;
    return 'microrelief-three: the WebAssembly twin is not loaded yet (createReliefMap loads it)';
}

// ReliefMap -> Map(key -> handle), oldest use first.
const twins = new WeakMap();

function keyOf(relief) {
    const b = relief.base;
    return [relief.heightScale, baseName(b), ...baseSizeNumbers(b), relief.interpolation].join(' ');
}

function twinFor(relief) {
    const m = twinModule, reliefMap = relief.reliefMap;
    if (!twins.has(reliefMap)) twins.set(reliefMap, new Map());
    const held = twins.get(reliefMap), key = keyOf(relief);
    if (held.has(key)) {
        const handle = held.get(key);
        held.delete(key);
        held.set(key, handle);  // the most recently used last
        return handle;
    }
    const samples = reliefMap.heights && reliefMap.heights.image && reliefMap.heights.image.data;
    if (!(samples instanceof Float32Array) || samples.length !== reliefMap.width * reliefMap.height)
        throw new Error(`microrelief-three: ${reliefMap.name}: the map's samples are gone (disposed?); the twin cannot be built`);
    // The base as its row's name and its sizes' numbers in the row's order (the table of
    // bases, which twin_wasm.cpp reads in C++: BaseType.h), the last level by its GLSL value
    // (variants.glsl, through core/GlslConstants.h there).
    const b = relief.base;
    const name = new TextEncoder().encode(`${baseName(b)}\0`), sizes = baseSizeNumbers(b);
    const samplesBytes = 8 * Math.ceil(samples.length / 2);  // the sizes' doubles after them 8-aligned
    const input = m._malloc(samplesBytes + 8 * sizes.length + name.length);
    if (!input) throw new Error(`microrelief-three: ${reliefMap.name}: no memory for the twin's ${reliefMap.width} x ${reliefMap.height} samples in WebAssembly`);
    let handle;
    try {
        const sizesAt = input + samplesBytes, nameAt = sizesAt + 8 * sizes.length;
        new Float32Array(m.HEAPF32.buffer, input, samples.length).set(samples);
        new Float64Array(m.HEAPF64.buffer, sizesAt, sizes.length).set(sizes);
        m.HEAPU8.set(name, nameAt);
        handle = m._mr_twin_create(input, reliefMap.width, reliefMap.height, relief.heightScale,
                                   nameAt, sizesAt, sizes.length, kInterpolationValues[relief.interpolation]);
    } finally {
        m._free(input);
    }
    if (!handle) throw new Error(`microrelief-three: ${reliefMap.name}: ${m.UTF8ToString(m._mr_twin_last_error())}`);
    held.set(key, handle);
    if (held.size > kMaxTwinsPerMap) {
        const [oldest, old] = held.entries().next().value;
        m._mr_twin_release(old);
        held.delete(oldest);
    }
    return handle;
}

// The world rays traced by the twin (relief.js: traceRays's arguments, checked there):
// traceRays's result, every value a double.
export function traceOnTwin(relief, origins, directions, ranges) {
    const m = twinModule;
    const handle = twinFor(relief);
    const n = origins.length / 3;
    const doubles = 16 + 3 * n + 3 * n + 2 * n + 12 * n;
    const block = m._malloc(8 * doubles);
    if (!block) throw new Error(`microrelief-three: no memory for ${n} rays in WebAssembly`);
    try {
        const at = block / 8;
        const heap = m.HEAPF64;
        const model = at, o = model + 16, d = o + 3 * n, r = d + 3 * n, out = r + 2 * n;
        heap.set(relief.matrixWorld.elements, model);
        for (let k = 0; k < 3 * n; ++k) {
            heap[o + k] = origins[k];
            heap[d + k] = directions[k];
        }
        for (let k = 0; k < n; ++k) {
            heap[r + 2 * k] = ranges.length === 2 ? ranges[0] : ranges[2 * k];
            heap[r + 2 * k + 1] = ranges.length === 2 ? ranges[1] : ranges[2 * k + 1];
        }
        if (!m._mr_twin_trace(handle, 8 * model, n, 8 * o, 8 * d, 8 * r, 8 * out)) {
            const why = m.UTF8ToString(m._mr_twin_last_error()).replace(/\{model\}/g, "the relief's matrixWorld");
            throw new Error(`Relief.traceRays: ${why}`);
        }
        const result = m.HEAPF64.subarray(out, out + 12 * n);  // the heap as it is now
        const scalar = (f, type = Float64Array) => {
            const values = new type(n);
            for (let k = 0; k < n; ++k) values[k] = result[12 * k + f];
            return values;
        };
        const vector = (f, size) => {
            const values = new Float64Array(size * n);
            for (let k = 0; k < n; ++k)
                for (let c = 0; c < size; ++c) values[size * k + c] = result[12 * k + f + c];
            return values;
        };
        return {t: scalar(0), kind: scalar(1, Float32Array), exhausted: scalar(2, Float32Array), point: vector(3, 3),
                normal: vector(6, 3), uv: vector(9, 2), iterations: scalar(11, Float32Array), on: 'cpu'};
    } finally {
        m._free(block);
    }
}

// The WebAssembly memory `reliefMap`'s twins hold, bytes (0 before the first pick).
export function twinBytes(reliefMap) {
    const held = twins.get(reliefMap);
    if (!held || !twinLoaded()) return 0;
    let bytes = 0;
    for (const handle of held.values()) bytes += twinModule._mr_twin_bytes(handle);
    return bytes;
}

// How many twins are held, all maps together (for tests of ReliefMap.dispose).
export function twinCount() {
    return twinLoaded() ? twinModule._mr_twin_count() : 0;
}

// Frees `reliefMap`'s twins (ReliefMap.dispose).
export function releaseTwins(reliefMap) {
    const held = twins.get(reliefMap);
    if (!held) return;
    for (const handle of held.values()) twinModule._mr_twin_release(handle);
    twins.delete(reliefMap);
}
