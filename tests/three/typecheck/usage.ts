// microrelief-three's declarations in use, checked by tsc --noEmit --strict (tests/three:
// ThreeTarball.TheDeclarationsTypecheckUnderStrict) in a project that installed the packed
// tarball, three and @types/three: a crater from a typed array, lit by three, picked. Each
// line marked as an expected error must be one: declarations that were `any` would pass them.
import * as THREE from 'three';
import * as WebGPU from 'three/webgpu';
import * as onWebGPU from 'microrelief-three/webgpu';
import {createReliefMap, heightsFromArray, HeightMapError, loadAlbedo, loadReliefMap, loadSceneChecks, readWindowLevel, Relief, ReliefGpuError,
        ReliefMapLoader, ReliefPhysicalMaterial, ReliefShadingMaterial, ReliefStandardMaterial, type ReliefHit, type TracedRays} from 'microrelief-three';

export async function crater(canvas: HTMLCanvasElement): Promise<ReliefHit | null> {
    const renderer = new THREE.WebGLRenderer({canvas});
    const size = 64, samples = new Float32Array(size * size);
    for (let k = 0; k < samples.length; ++k) samples[k] = Math.min(1, Math.hypot(k % size - 32, Math.floor(k / size) - 32) / 24);
    const heights = heightsFromArray(samples, size, size, {name: 'crater'});
    const map = await createReliefMap(renderer, heights, {pyramid: 'auto'});
    const relief = new Relief(map, {heightScale: 0.2, interpolation: 'biquadratic',
                                    material: new ReliefStandardMaterial({albedoMap: await loadAlbedo('albedo.png'), roughness: 0.6, selfShadow: true})});
    relief.pixelError = 0.5;
    relief.castShadow = relief.receiveShadow = true;
    const scene = new THREE.Scene();
    scene.add(relief, new THREE.DirectionalLight(0xffffff, 3));
    const camera = new THREE.PerspectiveCamera(45, canvas.width / canvas.height, 0.01, 20);
    renderer.render(scene, camera);
    const hits: THREE.Intersection[] = new THREE.Raycaster(camera.position, new THREE.Vector3(0, -1, 0)).intersectObject(relief);
    const rays: TracedRays = relief.traceRays([0, 1, 0], [0, -1, 0]);
    // Picks on the CPU twin (WebAssembly) or on the GPU.
    relief.pickWith = 'gpu';
    const onGpu: 'cpu' | 'gpu' = relief.traceRays([0, 1, 0], [0, -1, 0], [0, 2], {on: 'cpu'}).on;
    const twinHit = relief.trace(new THREE.Vector3(0, 1, 0), new THREE.Vector3(0, -1, 0), 0, 2, {on: 'auto'});
    const t: Float64Array = rays.t;
    console.log(onGpu, twinHit?.distance, t[0], map.twinBytes);
    const level: Float32Array = readWindowLevel(map, map.levelCount - 1);
    const sphere = new Relief(await loadReliefMap(renderer, 'globe.png', {wrapU: true}), {base: {kind: 'sphere', radius: 0.4},
                                                                                          material: new ReliefPhysicalMaterial({clearcoat: 1})});
    const loader = new ReliefMapLoader(renderer, new THREE.LoadingManager()).setPath('maps/').setOptions({pyramid: 'gpu', channel: 0});
    const loaded = await loader.loadAsync('cobbles.png', (event: ProgressEvent) => console.log(event.loaded));
    loader.load('cobbles.png', (m) => console.log(m.levelCount), undefined, (e: unknown) => console.error(e));
    const shaded = new Relief(loaded, {material: new ReliefShadingMaterial({shadows: 'hard', lightDirection: new THREE.Vector3(0, 1, 0)})});
    const refusal: string = (await loadSceneChecks()).refusal({eye: [1, 1, 1], target: [0, 0, 0]});
    const errors: Error[] = [new HeightMapError('a map'), new ReliefGpuError('a GPU')];
    console.log(hits.length, rays.point[0], level[0], sphere.base.kind, shaded.material.shadows, refusal, errors.length, map.builtOn, map.gpuBytes);

    // Relief and its materials as three's objects: options set later, a material assigned
    // later and shared, clone, toJSON and back.
    relief.heightScale = 0.15;
    relief.interpolation = 'bilinear';
    sphere.base = 'sphere';
    sphere.base = {kind: 'ellipsoid', radii: [0.5, 0.4, 0.3]};
    const radii: [number, number, number] | undefined = sphere.base.kind === 'ellipsoid' ? sphere.base.radii : undefined;
    const lit = new ReliefStandardMaterial().copy(new THREE.MeshStandardMaterial({roughness: 0.4}));
    relief.material = lit;
    const twin: Relief<ReliefStandardMaterial> = relief.clone();
    twin.material = lit;
    twin.copy(relief);
    const json: THREE.MeshJSON = relief.toJSON();
    const record = new THREE.ObjectLoader().parse(json);
    const again: Relief = Relief.fromMesh(record as THREE.Mesh, map, {albedoMap: null});
    console.log(radii, twin.options.heightScale, again.base.kind, lit.relief?.heightScale);
    // @ts-expect-error: a Relief draws with a relief material, not three's own
    relief.material = new THREE.MeshStandardMaterial();
    // @ts-expect-error: a base is a BaseSpec
    relief.base = 'torus';
    // @ts-expect-error: interpolation is 'bilinear' or 'biquadratic'
    new Relief(map, {interpolation: 'trilinear'});
    // @ts-expect-error: pyramid is 'auto', 'gpu' or 'cpu'
    void createReliefMap(renderer, heights, {pyramid: 'wasm'});
    // @ts-expect-error: the loader's options are createReliefMap's and the channel
    loader.setOptions({interpolation: 'bilinear'});
    // @ts-expect-error: picks are traced on 'auto', 'cpu' or 'gpu'
    relief.pickWith = 'wasm';
    // @ts-expect-error: selfShadow is a boolean
    new ReliefStandardMaterial({selfShadow: 'yes'});
    // @ts-expect-error: a Relief takes a ReliefMap, not the heights
    new Relief(heights);
    // @ts-expect-error: heightsFromArray takes typed arrays
    heightsFromArray([0, 1, 2, 3], 2, 2);
    // @ts-expect-error: a base's name is plane, cylinder, sphere or ellipsoid
    new Relief(map, {base: 'torus'});
    return relief.trace(new THREE.Vector3(0, 1, 0), new THREE.Vector3(0, -1, 0));
}

// The WebGPU entry ('microrelief-three/webgpu', docs/three.md): the same crater in a
// WebGPURenderer with the library's own shading.
export async function craterOnWebGPU(canvas: HTMLCanvasElement): Promise<number> {
    const renderer = new WebGPU.WebGPURenderer({canvas});
    const size = 64, samples = new Float32Array(size * size);
    for (let k = 0; k < samples.length; ++k) samples[k] = Math.min(1, Math.hypot(k % size - 32, Math.floor(k / size) - 32) / 24);
    const map = await onWebGPU.createReliefMap(renderer, onWebGPU.heightsFromArray(samples, size, size, {name: 'crater'}));
    const relief = new onWebGPU.Relief(map, {heightScale: 0.2, interpolation: 'biquadratic',
                                              material: new onWebGPU.ReliefShadingNodeMaterial({shadows: 'hard'})});
    const scene = new WebGPU.Scene();
    scene.add(relief);
    relief.base = 'plane';
    relief.heightScale = 0.1;
    // @ts-expect-error: a last level is bilinear or biquadratic
    relief.interpolation = 'bicubic';
    // @ts-expect-error: the WebGPU entry's Relief takes its own materials, not the WebGL entry's
    new onWebGPU.Relief(map, {material: new ReliefStandardMaterial()});
    // @ts-expect-error: createReliefMap takes a WebGPURenderer
    await onWebGPU.createReliefMap(new THREE.WebGLRenderer(), onWebGPU.heightsFromArray(samples, size, size));
    // Picks as in the WebGL entry, by the CPU twin.
    const camera = new WebGPU.PerspectiveCamera(45, canvas.width / canvas.height, 0.01, 20);
    const raycaster = new WebGPU.Raycaster();
    raycaster.setFromCamera(new WebGPU.Vector2(0.1, -0.2), camera);
    const hits: WebGPU.Intersection[] = raycaster.intersectObject(relief);
    const hit: onWebGPU.ReliefHit | null = relief.trace(new WebGPU.Vector3(0, 1, 0), new WebGPU.Vector3(0, -1, 0), 0, 2, {on: 'cpu'});
    const rays: onWebGPU.TracedRays = relief.traceRays([0, 1, 0], [0, -1, 0], [0, 2]);
    // @ts-expect-error: this entry's picks are the CPU twin's, not the GPU's
    relief.traceRays([0, 1, 0], [0, -1, 0], [0, 2], {on: 'gpu'});
    const twinBytes: number = map.twinBytes;
    // three's lights on the relief: MeshStandardNodeMaterial's parameters.
    const lit = new onWebGPU.Relief(map, {material: new onWebGPU.ReliefStandardNodeMaterial({color: 0xc8b8a0, roughness: 0.55, metalness: 0.15})});
    scene.add(lit, new WebGPU.DirectionalLight(0xffffff, 2), new WebGPU.PointLight(0x9fb8ff, 0.5), new WebGPU.AmbientLight(0x404850));
    lit.material.side = WebGPU.DoubleSide;
    // @ts-expect-error: the roughness is a number
    new onWebGPU.ReliefStandardNodeMaterial({roughness: 'rough'});
    // The map's colours in both materials.
    const albedoMap = await onWebGPU.loadAlbedo('cobbles-albedo.png');
    lit.material = new onWebGPU.ReliefStandardNodeMaterial({albedoMap, roughness: 0.85});
    relief.material = new onWebGPU.ReliefShadingNodeMaterial({albedoMap, shadows: 'hard'});
    // @ts-expect-error: an albedo map is a texture
    new onWebGPU.ReliefShadingNodeMaterial({albedoMap: 'cobbles-albedo.png'});
    return relief.heightScale + hits.length + (hit ? hit.distance : 0) + rays.t[0] + twinBytes;
}
