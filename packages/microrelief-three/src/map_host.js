// map_host.js: what both entries do with a height map before their renderer sees it (the
// WebGL one, pyramid.js, and the WebGPU one, webgpu.js): the map's checks, its largest
// sample, and the windows pyramid built on the CPU by the C++ MaxPyramid itself
// (src/core/heightmap/MaxPyramid.cpp) compiled to WebAssembly (generated/pyramid_wasm.js),
// each level as R16F half bits. No renderer, no three.
import {HeightMapError} from './heights.js';

// Throws a TypeError where `map` is not heights.js's {width, height, samples}; `what` names the caller.
export function checkHeightMap(map, what) {
    if (!map || !(map.samples instanceof Float32Array) || map.samples.length !== map.width * map.height)
        throw new TypeError(`${what}: the map must be {width, height, samples: Float32Array} (heights.js: loadHeights, heightsFromArray, ...)`);
}

// The largest sample; throws HeightMapError naming a sample that is negative, NaN or infinite.
export function largestSample(map) {
    const name = map.name || 'height map';
    let maxSample = 0;
    for (let k = 0; k < map.samples.length; ++k) {
        const h = map.samples[k];
        if (!(h >= 0) || h === Infinity)
            throw new HeightMapError(`${name}: sample (${k % map.width}, ${Math.floor(k / map.width)}) is ${h}; heights must be finite and >= 0`);
        maxSample = Math.max(maxSample, h);
    }
    return maxSample;
}

let wasmModule = null;
async function pyramidModule() {
    if (!wasmModule) {
        wasmModule = import('../generated/pyramid_wasm.js').then((m) => m.default());
        wasmModule.catch(() => (wasmModule = null));
    }
    return wasmModule;
}

// The windows of `map` ({width, height, samples, name}): {levels (Uint16Array of half bits
// a level, GL's mip sizes), levelSizes, maxHeight, scaleExponent}.
export async function windowLevelsOnCpu(map, wrapU) {
    const m = await pyramidModule();
    const bytes = 4 * map.width * map.height;
    const input = m._malloc(bytes);
    if (!input) throw new HeightMapError(`${map.name}: no memory for ${map.width} x ${map.height} samples in WebAssembly`);
    let handle = 0;
    try {
        new Float32Array(m.HEAPF32.buffer, input, map.width * map.height).set(map.samples);
        handle = m._mr_build_windows(input, map.width, map.height, wrapU ? 1 : 0);
        if (!handle) throw new HeightMapError(m.UTF8ToString(m._mr_last_error()));
        const levelSizes = [], levels = [];
        for (let k = 0; k < m._mr_level_count(handle); ++k) {
            const packed = m._mr_level_size(handle, k);
            const [w, h] = [packed >>> 16, packed & 0xffff];
            const out = m._malloc(2 * w * h);
            try {
                m._mr_copy_level(handle, k, out);
                levels.push(new Uint16Array(m.HEAPU16.buffer, out, w * h).slice());
            } finally {
                m._free(out);
            }
            levelSizes.push([w, h]);
        }
        return {levels, levelSizes, maxHeight: m._mr_max_height(handle), scaleExponent: m._mr_scale_exponent(handle)};
    } finally {
        if (handle) m._mr_release(handle);
        m._free(input);
    }
}
