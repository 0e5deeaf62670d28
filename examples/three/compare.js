// shading=microrelief: the relief alone, drawn by ReliefShadingMaterial (the library's own
// shading, one directional light, the bundled map's colours), with microrelief-render's
// camera, background and light, so that the picture can be held against
// microrelief-render's of the same flags (tests/three).
import * as THREE from 'three';
import {createReliefMap, loadAlbedo, loadHeights, Relief, reliefExtent, ReliefShadingMaterial} from 'microrelief-three';

import {viewBase} from './view.js';

export async function compare(canvas, view) {
    const renderer = new THREE.WebGLRenderer({canvas, antialias: false, preserveDrawingBuffer: true});
    const base = viewBase(view);
    const heights = await loadHeights('../../assets/cobbles.png');
    const map = await createReliefMap(renderer, heights, {wrapU: base !== 'plane', pyramid: view.pyramid});
    const albedoMap = view.albedo ? await loadAlbedo('../../assets/cobbles-albedo.png') : null;
    const material = new ReliefShadingMaterial({lightDirection: new THREE.Vector3(...view.light), albedoMap, shadows: view.shadows});
    const relief = new Relief(map, {material, heightScale: view.heightScale, base, interpolation: view.interpolation, pixelError: view.pixelError});
    const scene = new THREE.Scene();
    scene.background = new THREE.Color().setRGB(0.11, 0.12, 0.14, THREE.LinearSRGBColorSpace);
    scene.add(relief);
    // microrelief-render's depth range (Camera.cpp: resolveCamera), from the samples' box.
    const extent = reliefExtent(map.width, map.height, map.maxSample, relief.heightScale, relief.base);
    const radius = 2 * Math.max(...extent.min.map(Math.abs), ...extent.max.map(Math.abs));
    const centre = Math.hypot(...view.eye);
    const far = centre + 2 * radius, near = Math.max(1e-4 * far, centre - 2 * radius);
    const camera = new THREE.PerspectiveCamera(view.fovy, canvas.width / canvas.height, near, far);
    camera.position.set(...view.eye);
    camera.up.set(...view.up);
    camera.lookAt(...view.target);
    return {renderer, scene, camera, relief, map};
}
