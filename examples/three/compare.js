// shading=microrelief: the relief alone, drawn by ReliefShadingMaterial (the library's own
// shading, one directional light, the bundled map's colours), with microrelief-render's
// camera, background and light, so that the picture can be held against
// microrelief-render's of the same flags (tests/three). `kit` is the renderer= key's
// (renderers.js): WebGL's ReliefShadingMaterial or WebGPU's ReliefShadingNodeMaterial, the
// same scene.
import {normalizeFloat, viewBase} from './view.js';

export async function compare(canvas, view, kit) {
    const {THREE, relief: {createReliefMap, loadAlbedo, loadHeights, Relief, reliefExtent}} = kit;
    // microrelief-three/webgpu builds the max pyramid in WebAssembly only (docs/three.md).
    if (view.renderer === 'webgpu' && view.pyramid === 'gpu')
        throw new Error('pyramid=gpu: renderer=webgpu builds the max pyramid in WebAssembly (pyramid=auto or cpu)');
    const renderer = await kit.create({canvas, antialias: false, preserveDrawingBuffer: true});
    const base = viewBase(view);
    const heights = await loadHeights('../../assets/cobbles.png');
    const map = await createReliefMap(renderer, heights, {wrapU: base !== 'plane', pyramid: view.pyramid});
    const albedoMap = view.albedo ? await loadAlbedo('../../assets/cobbles-albedo.png') : null;
    const material = kit.shadingMaterial({lightDirection: new THREE.Vector3(...normalizeFloat(view.light)), albedoMap, shadows: view.shadows});
    const relief = new Relief(map, {material, heightScale: view.heightScale, base, interpolation: view.interpolation, pixelError: view.pixelError});
    const scene = new THREE.Scene();
    scene.background = new THREE.Color().setRGB(0.11, 0.12, 0.14, THREE.LinearSRGBColorSpace);
    if (view.model) {
        relief.matrixAutoUpdate = false;
        relief.matrix.set(...view.model, 0, 0, 0, 1);
    }
    scene.add(relief);
    scene.updateMatrixWorld();
    // microrelief-render's depth range (Camera.cpp: resolveCamera), from the box's corners
    // placed by the model, about the model's translation (ReliefExtent.cpp: sceneRadius,
    // sceneCentre).
    const extent = reliefExtent(map.width, map.height, map.maxHeight, relief.heightScale, relief.base);
    const origin = new THREE.Vector3().setFromMatrixPosition(relief.matrixWorld);
    let radius = 0;
    for (let k = 0; k < 8; ++k) {
        const corner = new THREE.Vector3(...[0, 1, 2].map((a) => ((k >> a) & 1 ? extent.max[a] : extent.min[a]))).applyMatrix4(relief.matrixWorld).sub(origin);
        radius = Math.max(radius, Math.abs(corner.x), Math.abs(corner.y), Math.abs(corner.z));
    }
    radius *= 2;
    const centre = Math.hypot(view.eye[0] - origin.x, view.eye[1] - origin.y, view.eye[2] - origin.z);
    const far = centre + 2 * radius, near = Math.max(1e-4 * far, centre - 2 * radius);
    const camera = new THREE.PerspectiveCamera(view.fovy, canvas.width / canvas.height, near, far);
    camera.position.set(...view.eye);
    camera.up.set(...view.up);
    camera.lookAt(...view.target);
    return {renderer, scene, camera, relief, map};
}
