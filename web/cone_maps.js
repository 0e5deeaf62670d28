// cone_maps.js: the relaxed cone maps of the peer rcsm (peers/ConeMap.h) for the page, made
// by the C++ build itself compiled to WebAssembly (web/wasm/cone_maps.cpp, built into
// generated/cone_maps_wasm.js beside this file) in a worker (cone_map_worker.js): the
// relaxed map of a 256 x 256 map takes seconds (5.8 s natively for the bundled one), and the
// page keeps answering meanwhile. Texels as coneMapHalfTexels lays them out: RG16F halves,
// (apex, ratio) per texel, row 0 first, for ReliefTextures.uploadConeMap. (Cone's
// conservative map is drawn on the GPU: relief_gl.js, PyramidBuilder.buildConeMap.)

export class ConeMapBuilder {
    constructor() {
        this.worker = null;
        this.pending = new Map();  // id -> {resolve, reject}
        this.next = 1;
    }

    // A promise of the texels of the relaxed cone map of `samples` (W x H floats, row 0
    // first; copied). Rejects with Error saying why (no WebAssembly cone maps in this build,
    // a worker that cannot start, the C++'s message). `onProgress(done)`, where given, hears
    // the fraction of the rows built as it grows.
    build(samples, width, height, onProgress = null) {
        const worker = this.start();
        const id = this.next++;
        return new Promise((resolve, reject) => {
            this.pending.set(id, {resolve, reject, onProgress});
            const copy = Float32Array.from(samples);
            worker.postMessage({id, samples: copy, width, height}, [copy.buffer]);
        });
    }

    // Drops every build under way (a new map): their promises reject with `reason`.
    cancel(reason) {
        if (!this.worker) return;
        this.worker.terminate();
        this.worker = null;
        this.failAll(new ConeMapCancelled(reason));
    }

    start() {
        if (this.worker) return this.worker;
        const worker = new Worker(new URL('./cone_map_worker.js', import.meta.url), {type: 'module'});
        worker.onmessage = ({data}) => {
            const job = this.pending.get(data.id);
            if (!job) return;
            if ('progress' in data) {
                job.onProgress?.(data.progress);
                return;
            }
            this.pending.delete(data.id);
            if (data.error) job.reject(new Error(data.error));
            else job.resolve(data.texels);
        };
        // A worker that cannot load (its module or the WebAssembly missing from the server).
        worker.onerror = (event) => {
            event.preventDefault();
            this.worker = null;
            worker.terminate();
            this.failAll(new Error(`the cone map worker failed: ${event.message || 'it could not load cone_map_worker.js or generated/cone_maps_wasm.js'}`));
        };
        this.worker = worker;
        return worker;
    }

    failAll(error) {
        const jobs = [...this.pending.values()];
        this.pending.clear();
        for (const job of jobs) job.reject(error);
    }
}

export class ConeMapCancelled extends Error {}
