#!/usr/bin/env node
// make_map.mjs OUT.json [GENERATED_DIR]: the test map of glsl_wgsl_equal.py (64 x 48 samples:
// waves and one-texel spikes, so that shadows and penumbrae fall on the relief) and its
// windows pyramids, flat and wrapped in u, made by the package's CPU builder (the C++
// MaxPyramid in WebAssembly: generated/pyramid_wasm.js of a built microrelief-three).
import * as fs from 'node:fs';
import * as path from 'node:path';
import {fileURLToPath, pathToFileURL} from 'node:url';

const repo = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const [out, generated = path.join(repo, 'build/share/microrelief/web/three/node_modules/microrelief-three/generated')] =
    process.argv.slice(2);
const wasm = path.join(generated, 'pyramid_wasm.js');
if (!out || !fs.existsSync(wasm)) {
    process.stderr.write(`make_map.mjs: ${
        out ? `no ${wasm} (build microrelief-three with emscripten)` :
              'usage: make_map.mjs OUT.json [GENERATED_DIR]'}\n`);
    process.exit(2);
}
const m = await (await import(pathToFileURL(wasm).href)).default();
const W = 64, H = 48, samples = new Float32Array(W * H);
for (let y = 0; y < H; ++y)
    for (let x = 0; x < W; ++x) {
        let h = 3 + 2 * Math.sin(x * 0.35) * Math.cos(y * 0.27) + 1.5 * Math.sin((x + 2 * y) * 0.11);
        if ((x * 7 + y * 13) % 37 === 0) h += 4;
        samples[y * W + x] = Math.max(0, h);
    }

function windows(wrapU) {
    const input = m._malloc(4 * W * H);
    new Float32Array(m.HEAPF32.buffer, input, W * H).set(samples);
    const handle = m._mr_build_windows(input, W, H, wrapU ? 1 : 0);
    if (!handle) throw new Error(m.UTF8ToString(m._mr_last_error()));
    const levels = [];
    for (let k = 0; k < m._mr_level_count(handle); ++k) {
        const packed = m._mr_level_size(handle, k), w = packed >>> 16, h = packed & 0xffff;
        const texels = m._malloc(2 * w * h);
        m._mr_copy_level(handle, k, texels);
        levels.push({w, h, halves: Array.from(new Uint16Array(m.HEAPU16.buffer, texels, w * h))});
        m._free(texels);
    }
    const pyramid = {levels, maxHeight: m._mr_max_height(handle)};
    m._mr_release(handle);
    m._free(input);
    return pyramid;
}
fs.writeFileSync(
    out, JSON.stringify({W, H, samples: Array.from(samples), flat: windows(false), wrapped: windows(true)}));
