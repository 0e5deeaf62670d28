// A consumer's TypeScript entry for the WebGPU example, typechecked by tsc --strict and
// bundled by `vite build` (tests/three: ThreePackage.TheWebGPUEntryBundledByViteRunsTheExample).
// It sits in app/ of the scratch project that installed the packed tarball, three,
// @types/three and vite, beside examples/three's files, and draws their WebGPU scene of
// shading=microrelief: the URL's view (view.js), renderers.js's kit for renderer=webgpu
// (which imports 'three/webgpu' and 'microrelief-three/webgpu' as this file does) and
// compare.js's scene. It reports as examples/three's main.js does: <html data-state>
// "ready" or "error" (with #error's line) and, once the first frame is drawn, data-api.
import * as THREE from 'three/webgpu';
import {Relief, ReliefMap, ReliefShadingNodeMaterial} from 'microrelief-three/webgpu';

import {compare} from '../compare.js';
import {rendererKit} from '../renderers.js';
import {viewFromUrl} from '../view.js';

const root = document.documentElement;

async function start(): Promise<void> {
    const view = viewFromUrl(location.search);
    if (view.renderer !== 'webgpu' || view.shading !== 'microrelief') throw new Error('this page draws renderer=webgpu&shading=microrelief');
    const canvas = document.getElementById('canvas') as HTMLCanvasElement;
    const [width, height]: number[] = view.size ?? [640, 480];
    Object.assign(canvas, {width, height});
    Object.assign(canvas.style, {width: `${width}px`, height: `${height}px`});
    const kit = await rendererKit(view.renderer);
    const app = await compare(canvas, view, kit);
    // The example's objects are of the classes this file imports: the bundle holds one three
    // and one microrelief-three/webgpu, whether reached by a static import or a dynamic one.
    const renderer: THREE.WebGPURenderer = app.renderer, relief: Relief = app.relief, map: ReliefMap = app.map;
    if (!(renderer instanceof THREE.WebGPURenderer && relief instanceof Relief && map instanceof ReliefMap && relief.material instanceof ReliefShadingNodeMaterial))
        throw new Error("the example's renderer, relief, map or material is not of the classes this entry imports: two copies of a module in the bundle");
    renderer.render(app.scene, app.camera);
    await kit.finish(renderer);
    root.dataset.api = 'isWebGPUBackend' in renderer.backend ? 'webgpu' : 'webgl2';
    requestAnimationFrame(() => requestAnimationFrame(() => (root.dataset.state = 'ready')));
}

start().catch((e: unknown) => {
    console.error(e);
    document.getElementById('error')!.textContent = e instanceof Error ? e.message : String(e);
    root.dataset.state = 'error';
});
