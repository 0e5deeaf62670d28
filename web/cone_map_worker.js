// cone_map_worker.js: builds rcsm's relaxed cone maps in a worker for cone_maps.js, with the
// C++ (mr_build_relaxed_cone_map, web/wasm/cone_maps.cpp) in WebAssembly. A message {id,
// samples, width, height} is answered {id, texels} (Uint16Array, RG16F halves) or
// {id, error}, after messages {id, progress} (the fraction of the rows done, posted by the
// C++ as it builds).
import createConeMapModule from './generated/cone_maps_wasm.js';

let module = null;

self.onmessage = async ({data}) => {
    const {id, samples, width, height} = data;
    let input = 0, output = 0;
    try {
        if (!module) module = await createConeMapModule();
        const m = module, count = width * height;
        input = m._malloc(4 * count);
        output = m._malloc(4 * count);
        if (!input || !output) throw new Error(`no memory for a ${width} x ${height} cone map in WebAssembly`);
        new Float32Array(m.HEAPF32.buffer, input, count).set(samples);
        if (!m._mr_build_relaxed_cone_map(input, width, height, output, id))
            throw new Error(m.UTF8ToString(m._mr_last_error()));
        const texels = new Uint16Array(m.HEAPU16.buffer, output, 2 * count).slice();
        self.postMessage({id, texels}, [texels.buffer]);
    } catch (e) {
        self.postMessage({id, error: e.message || String(e)});
    } finally {
        if (input) module._free(input);
        if (output) module._free(output);
    }
};
