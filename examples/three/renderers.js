// renderers.js: what the page draws with, by the URL's renderer= key (view.js): three's
// WebGLRenderer with microrelief-three (webgl, the default), or three's WebGPURenderer with
// microrelief-three/webgpu (webgpu). A forced WebGPU that this browser cannot give is one
// line saying so: three's WebGPURenderer would fall back to WebGL 2 without a word, and the
// page would then draw, and report, the other API's picture.

// The API each draws with, as the page reports it in document.documentElement.dataset.api
// once its first frame is drawn (the web page's words: docs/browser.md).
export const kApiOf = {webgl: 'webgl2', webgpu: 'webgpu'};

function noWebGPU(why) {
    return new Error(`renderer=webgpu: ${why}; renderer=webgl draws with WebGL 2`);
}

// Whether this browser gives WebGPU, before anything is drawn: throws the one line if not.
export async function requireWebGPU() {
    if (!navigator.gpu) throw noWebGPU('this browser has no WebGPU (navigator.gpu is missing)');
    if (!(await navigator.gpu.requestAdapter())) throw noWebGPU('this browser offers no WebGPU adapter (requestAdapter gave none)');
}

// The renderer= key's three, its microrelief-three entry, a renderer of it on `canvas`
// (initialised), its relief material of the library's own shading, and how to wait for
// a frame.
export async function rendererKit(name) {
    if (name === 'webgpu') {
        await requireWebGPU();
        const [THREE, relief] = await Promise.all([import('three/webgpu'), import('microrelief-three/webgpu')]);
        return {
            THREE, relief,
            create: async (parameters) => {
                const renderer = new THREE.WebGPURenderer(parameters);
                await renderer.init();
                if (!renderer.backend.isWebGPUBackend) throw noWebGPU("three's WebGPURenderer fell back to WebGL 2 in this browser");
                return renderer;
            },
            shadingMaterial: (parameters) => new relief.ReliefShadingNodeMaterial(parameters),
            finish: (renderer) => renderer.backend.device.queue.onSubmittedWorkDone(),
        };
    }
    const [THREE, relief] = await Promise.all([import('three'), import('microrelief-three')]);
    return {
        THREE, relief,
        create: async (parameters) => new THREE.WebGLRenderer(parameters),
        shadingMaterial: (parameters) => new relief.ReliefShadingMaterial(parameters),
        finish: async (renderer) => {
            // A readPixels of one pixel stalls until the frame is drawn.
            const gl = renderer.getContext();
            gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
        },
    };
}
