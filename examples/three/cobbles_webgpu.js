// cobbles.js on three's WebGPURenderer (renderer=webgpu): the same floor, sphere and knot,
// from microrelief-three/webgpu. What differs from cobbles.js is what moving a scene to
// WebGPU changes: the imports, the renderer (awaited), and the node material.
import * as THREE from 'three/webgpu';
import {OrbitControls} from 'three/addons/controls/OrbitControls.js';
import {createReliefMap, loadAlbedo, loadHeights, Relief, ReliefStandardNodeMaterial} from 'microrelief-three/webgpu';

export async function cobbles(canvas, {eye = [0.8, 0.5, 0.85], target = [0, -0.03, 0], fovy = 45} = {}) {
    const renderer = new THREE.WebGPURenderer({canvas, antialias: true, alpha: false});  // opaque, as a WebGLRenderer's canvas
    await renderer.init();
    renderer.shadowMap.enabled = true;
    const scene = new THREE.Scene();
    const camera = new THREE.PerspectiveCamera(fovy, canvas.width / canvas.height, 0.01, 20);
    camera.position.set(...eye);
    const sun = new THREE.DirectionalLight(0xfff4e0, 3);
    sun.position.set(-0.9, 1.6, -0.7);
    sun.castShadow = true;
    Object.assign(sun.shadow.camera, {left: -0.8, right: 0.8, bottom: -0.8, top: 0.8});
    scene.add(sun, new THREE.HemisphereLight(0xbfd4ff, 0x3b3025, 0.8));
    const [heights, albedoMap] = await Promise.all([loadHeights('../../assets/cobbles.png'), loadAlbedo('../../assets/cobbles-albedo.png')]);
    const map = await createReliefMap(renderer, heights);
    const floor = new Relief(map, {material: new ReliefStandardNodeMaterial({albedoMap, roughness: 0.85, selfShadow: true})});
    const ball = new THREE.Mesh(new THREE.SphereGeometry(0.1, 48, 24), new THREE.MeshStandardMaterial({color: 0xc8452b, roughness: 0.3}));
    const knot = new THREE.Mesh(new THREE.TorusKnotGeometry(0.06, 0.02, 128, 16), new THREE.MeshStandardMaterial({color: 0x3a7bd5, metalness: 0.5}));
    ball.position.set(0.15, 0.04, 0.12);
    knot.position.set(-0.2, 0.25, -0.05);
    for (const object of [floor, ball, knot]) object.castShadow = object.receiveShadow = true;
    scene.add(floor, ball, knot);
    const controls = new OrbitControls(camera, canvas);
    controls.target.set(...target);
    controls.addEventListener('change', () => renderer.render(scene, camera));
    controls.update();
    return {renderer, scene, camera, floor, ball, knot, controls, map};
}
