// compare.js: one map's scenes (a view, a last level, a base) drawn by microrelief-three's
// WebGL entry (WebGLRenderer, ReliefShadingMaterial) and by its WebGPU entry (WebGPURenderer,
// ReliefShadingNodeMaterial), each into a W x H RGBA8 render target, read back and compared
// pixel by pixel (three_webgpu_equal.py serves this folder with three and the staged package
// beside it, and judges). A box of three's own crosses the plane's relief in both pictures:
// the relief's depth decides which shows where (the picture composes with other meshes only if
// it is right). Writes document.documentElement.dataset.api = 'webgpu' once the WebGPU entry's
// first frame is drawn. compareEntries(view, interpolation, base) -> JSON {stats, png}; png:
// WebGL | WebGPU | differing pixels. comparePicks: the two entries' Raycaster hits through
// every pixel, against each other and against the WebGPU picture.
import * as THREE from 'three';
import * as GPU from 'three/webgpu';
import * as gl from 'microrelief-three';
import * as wg from 'microrelief-three/webgpu';

const W = 128, H = 96;  // a multiple of 64 wide: WebGPU's 256-byte rows need no padding

// Waves and one-texel spikes, 64 x 48 (deterministic).
function heights() {
    const w = 64, h = 48, samples = new Float32Array(w * h);
    for (let y = 0; y < h; ++y)
        for (let x = 0; x < w; ++x)
            samples[y * w + x] = 0.5 + 0.25 * Math.sin(x * 0.37) * Math.cos(y * 0.29) + ((x * 7 + y * 13) % 23 === 0 ? 0.4 : 0);
    return {w, h, samples};
}

const kViews = {
    oblique: {eye: [0.55, 0.45, 0.7], target: [0, 0.02, 0]},
    low: {eye: [-0.7, 0.16, 0.35], target: [0.05, 0.03, 0]},
    round: {eye: [0.9, 0.5, 1.0], target: [0, 0, 0]},
    // `low` again, the WebGPU relief drawn first (into the target: a first frame into the
    // OffscreenCanvas lost SwiftShader's WebGPU device) with another map, height scale and last
    // level, then given the view's: its options live, its program made again.
    lowLive: {eye: [-0.7, 0.16, 0.35], target: [0.05, 0.03, 0], live: true},
    ortho: {eye: [0.6, 0.7, 0.5], target: [0, 0.02, 0], orthographic: true},  // a directional light's kind of camera
    // Drawn into part of the target (x, y from the bottom, width, height): the NDC from the viewport.
    corner: {eye: [0.55, 0.45, 0.7], target: [0, 0.02, 0], viewport: [16, 8, 96, 64]},
    // `oblique` and `ortho` under each renderer's logarithmic depth buffer: the box of three's
    // own writes three's logarithmic depth, the relief must too (orthographic: its linear one).
    logDepth: {eye: [0.55, 0.45, 0.7], target: [0, 0.02, 0], logarithmic: true},
    logOrtho: {eye: [0.6, 0.7, 0.5], target: [0, 0.02, 0], orthographic: true, logarithmic: true},
};

function setUp(T, view, relief, {withBox = true} = {}) {
    const scene = new T.Scene();
    scene.add(relief);
    if (relief.isLit) addLights(T, scene, relief.raking, relief.casting);
    if (relief.casting === 'ground' || relief.casting === 'off') {  // three's own square through the relief, which casts its shadow on it
        const ground = new T.Mesh(new T.PlaneGeometry(1, 0.75).rotateX(-Math.PI / 2), new T.MeshStandardMaterial({color: 0xa0a0a0, roughness: 1}));
        ground.position.y = 0.045;
        ground.receiveShadow = true;
        relief.castShadow = relief.casting !== 'off';
        scene.add(ground);
    } else if (relief.casting) {  // 'self', 'unreceived': the relief casts; a ball of three's own too, low over it
        const ball = new T.Mesh(new T.SphereGeometry(0.04, 24, 12), new T.MeshStandardMaterial({color: 0x30a050, roughness: 1}));
        ball.position.set(0.25, 0.09, 0);
        ball.castShadow = true;
        relief.castShadow = true;
        relief.receiveShadow = relief.casting === 'self';  // the relief receives the map: its own shadows and the ball's
        scene.add(ball);
    }
    if (withBox) {
        const box = new T.Mesh(new T.BoxGeometry(0.1, 0.1, 0.1), new T.MeshBasicMaterial({color: 0x3366cc}));
        box.position.set(0.0, 0.02, 0.05);  // half buried: the relief's depth draws the line between them
        scene.add(box);
    }
    const [, , vw, vh] = kViews[view].viewport ?? [0, 0, W, H];
    const camera = kViews[view].orthographic ? new T.OrthographicCamera(-0.6, 0.6, 0.45, -0.45, 0.05, 10)
                                             : new T.PerspectiveCamera(45, vw / vh, 0.05, 10);
    camera.position.set(...kViews[view].eye);
    camera.lookAt(...kViews[view].target);
    camera.updateMatrixWorld();
    return {scene, camera};
}

// The two renderers, with logarithmic depth buffers where `logarithmicDepthBuffer` (made at
// the first view that asks).
const made = {};
async function renderers(logarithmicDepthBuffer = false) {
    if (!made[logarithmicDepthBuffer]) {
        const webgl = new THREE.WebGLRenderer({canvas: new OffscreenCanvas(W, H), logarithmicDepthBuffer});
        webgl.setSize(W, H, false);
        const webgpu = new GPU.WebGPURenderer({canvas: new OffscreenCanvas(W, H), logarithmicDepthBuffer});
        webgpu.setSize(W, H, false);
        await webgpu.init();
        made[logarithmicDepthBuffer] = {webgl, webgpu};
    }
    return made[logarithmicDepthBuffer];
}

const light = new THREE.Vector3(-0.45, 0.8, -0.35).normalize();

// The lit scenes (`lit`: the relief in each entry's standard material; `mesh`: the same
// height map as three's own triangle mesh, displaced, in three's MeshStandardMaterial, the
// measure of how three's WebGL and WebGPU lighting differ on a surface whose normal turns as
// fast, from pixel to pixel, as the relief's): three's directional, point and ambient lights;
// `raking` adds a second directional light that grazes the relief where the camera sees it
// (the self-shadow's scenes: long shadows): on the plane 12 degrees above it, on the cylinder
// (`raking` 'cylinder': its axis is y) from 20 degrees off its axis, towards the camera.
const kLit = {color: 0xc8b8a0, roughness: 0.55, metalness: 0.15};
function addLights(T, scene, raking = null, casting = false) {
    const sun = new T.DirectionalLight(0xfff4e0, 2.5);
    sun.position.set(-0.9, 1.6, -0.7);
    const lamp = new T.PointLight(0x9fb8ff, 0.06, 0, 2);
    lamp.position.set(0.2, 0.16, 0.25);
    scene.add(sun, sun.target, lamp, new T.AmbientLight(0x404850, 1.2));
    if (raking) {
        const low = new T.DirectionalLight(0xffd0a0, 2);
        if (raking === 'cylinder') low.position.set(0.93, 0.1, -0.37);
        else low.position.set(0.95, 0.21, 0.2);
        scene.add(low, low.target);
        if (casting) {  // its shadow map (BasicShadowMap: nearest texel, no filter of three's own), bright enough to see
            low.castShadow = true;
            low.intensity = 8;
            Object.assign(low.shadow.camera, {left: -0.7, right: 0.7, bottom: -0.7, top: 0.7, near: 0.05, far: 3});
            low.shadow.mapSize.set(512, 512);
        }
        if (casting === 'self' || casting === 'unreceived') {  // the lamp's cube map too, brighter, and a spot light's
            lamp.castShadow = true;
            lamp.intensity = 0.3;
            Object.assign(lamp.shadow.camera, {near: 0.01, far: 2});
            lamp.shadow.mapSize.set(256, 256);
            const spot = new T.SpotLight(0xa0ffb0, 1.2, 0, 0.45, 0.2, 2);
            spot.position.set(-0.35, 0.3, 0.3);
            spot.castShadow = true;
            Object.assign(spot.shadow.camera, {near: 0.05, far: 2});
            spot.shadow.mapSize.set(256, 256);
            scene.add(spot, spot.target);
        }
    }
}

function displacedMesh(T, roughness) {
    const {w, h, samples} = heights();
    const geometry = new T.PlaneGeometry(1, h / w, w - 1, h - 1).rotateX(-Math.PI / 2);
    const position = geometry.attributes.position;
    for (let k = 0; k < position.count; ++k) position.setY(k, 0.08 * samples[k]);
    geometry.computeVertexNormals();
    const mesh = new T.Mesh(geometry, new T.MeshStandardMaterial({...kLit, roughness}));
    mesh.isLit = true;
    return mesh;
}

// The map's colours for entry `E`'s materials (as loadAlbedo makes them: sRGB, flipY false,
// repeating, mipmapped): 64 x 48 stripes and checks of several colours, so that the footprint
// filter and the tiling show.
function albedoMap(T) {
    const w = 64, h = 48, data = new Uint8Array(4 * w * h);
    for (let y = 0; y < h; ++y)
        for (let x = 0; x < w; ++x)
            data.set([(x * 37) % 256, ((x >> 2) + (y >> 2)) % 2 ? 220 : 40, (y * 23 + x * 5) % 256, 255], 4 * (y * w + x));
    const texture = new T.DataTexture(data, w, h, T.RGBAFormat, T.UnsignedByteType);
    texture.colorSpace = T.SRGBColorSpace;
    texture.flipY = false;
    texture.wrapS = texture.wrapT = T.RepeatWrapping;
    texture.minFilter = T.LinearMipmapLinearFilter;
    texture.magFilter = T.LinearFilter;
    texture.generateMipmaps = true;
    texture.needsUpdate = true;
    return texture;
}

// What a picture of `kind` shows of an entry `E` (gl or wg): 'shading', the relief in the
// library's own shading; 'lit', in the entry's standard material under three's lights;
// 'mesh', no relief (displacedMesh under the same lights); 'shadingAlbedo' and 'litAlbedo'
// as 'shading' and 'lit' with the map's colours (albedoMap); 'litShadow' as 'lit' with the
// library's self-shadow (selfShadow), 'litShadow' and 'litRaking' (without it) with the raking
// light too (addLights); 'litFog' as 'lit' in three's Fog (drawWebGL, drawWebGPU: near the
// camera clear, then towards a dark blue); `roughness` the standard materials'.
function reliefMaterial(E, kind, roughness) {
    const T = E === gl ? THREE : GPU, map = kind.endsWith('Albedo') ? {albedoMap: albedoMap(T)} : {};
    if (['lit', 'cast', 'receive'].some((k) => kind.startsWith(k)))
        return new (E === gl ? gl.ReliefStandardMaterial : wg.ReliefStandardNodeMaterial)({...kLit, roughness, ...map, selfShadow: kind === 'litShadow'});
    return new (E === gl ? gl.ReliefShadingMaterial : wg.ReliefShadingNodeMaterial)({lightDirection: light, shadows: 'hard', ...map});
}

// The relief's height scale: 0.08, but for the self-shadow's scenes on a curved base, whose heights
// are radial in units of its radius (0.3 by default, so 0.08 raises a bump 0.012 over texels 0.03
// wide: too flat to shadow anything but near the terminator), 0.4.
const heightScaleOf = (base, kind) => (kind.startsWith('litShadow') || kind === 'litRaking') && base !== 'plane' ? 0.4 : 0.08;

// What a picture of `kind` shows (reliefMaterial): the relief, or for 'mesh' and 'castMesh' three's
// own mesh of the map, lit where `kind` asks, with the raking light, casting its shadow ('cast',
// 'castMesh': the raking light's shadow map on three's square through the relief, setUp;
// 'castOff': the same scene with the relief not casting; 'receive', 'receiveMesh': the relief
// or the mesh casting and receiving that map, with a ball of three's own casting too;
// 'receiveOff': the relief not receiving it).
function subject(T, relief, kind, base, roughness) {
    const shown = ['mesh', 'castMesh', 'receiveMesh'].includes(kind) ? displacedMesh(T, roughness) : relief;
    shown.isLit = ['lit', 'mesh', 'cast', 'receive'].some((k) => kind.startsWith(k));
    shown.raking = ['litShadow', 'litRaking', 'cast', 'castMesh', 'castOff', 'receive', 'receiveMesh', 'receiveOff'].includes(kind) ? base : null;
    shown.casting = {cast: 'ground', castMesh: 'ground', castOff: 'off', receive: 'self', receiveMesh: 'self', receiveOff: 'unreceived'}[kind] ?? null;
    return shown;
}

async function drawWebGL(view, interpolation, base = 'plane', kind = 'shading', roughness = kLit.roughness) {
    const {webgl: renderer} = await renderers(!!kViews[view].logarithmic);
    const {w, h, samples} = heights();
    const map = await gl.createReliefMap(renderer, gl.heightsFromArray(samples, w, h, {name: 'waves'}), {pyramid: 'cpu', wrapU: base !== 'plane'});
    const relief = new gl.Relief(map, {heightScale: heightScaleOf(base, kind), interpolation, base, material: reliefMaterial(gl, kind, roughness)});
    const {scene, camera} = setUp(THREE, view, subject(THREE, relief, kind, base, roughness), {withBox: !['mesh', 'cast', 'receive'].some((k) => kind.startsWith(k))});
    if (kind === 'litFog') scene.fog = new THREE.Fog(0x101418, 0.7, 1.5);  // three's fog, by its own nodes or chunks
    renderer.shadowMap.enabled = kind.startsWith('cast') || kind.startsWith('receive');
    renderer.shadowMap.type = THREE.BasicShadowMap;
    const target = new THREE.WebGLRenderTarget(W, H);
    if (kViews[view].viewport) target.viewport.set(...kViews[view].viewport);  // GL's y from the bottom
    renderer.setRenderTarget(target);
    renderer.setClearColor(0x000000, 0);
    renderer.clear();
    renderer.render(scene, camera);
    renderer.shadowMap.enabled = false;
    renderer.setRenderTarget(null);
    const pixels = new Uint8Array(4 * W * H);
    renderer.readRenderTargetPixels(target, 0, 0, W, H, pixels);  // rows from the bottom
    target.dispose();
    map.dispose();
    return pixels;
}

async function drawWebGPU(view, interpolation, base = 'plane', kind = 'shading', roughness = kLit.roughness) {
    const {webgpu: renderer} = await renderers(!!kViews[view].logarithmic);
    const {w, h, samples} = heights();
    const map = await wg.createReliefMap(renderer, wg.heightsFromArray(samples, w, h, {name: 'waves'}), {wrapU: base !== 'plane'});
    const relief = new wg.Relief(map, {heightScale: heightScaleOf(base, kind), interpolation, base, material: reliefMaterial(wg, kind, roughness)});
    const {scene, camera} = setUp(GPU, view, subject(GPU, relief, kind, base, roughness), {withBox: !['mesh', 'cast', 'receive'].some((k) => kind.startsWith(k))});
    if (kind === 'litFog') scene.fog = new GPU.Fog(0x101418, 0.7, 1.5);  // three's fog, by its own nodes or chunks
    renderer.shadowMap.enabled = kind.startsWith('cast') || kind.startsWith('receive');
    renderer.shadowMap.type = GPU.BasicShadowMap;
    const target = new GPU.RenderTarget(W, H);
    if (kViews[view].viewport) {  // the same pixels: WebGPU's y from the top
        const [x, y, w, h] = kViews[view].viewport;
        target.viewport.set(x, H - y - h, w, h);
    }
    if (kind === 'litShadow' && base === 'plane') {  // selfShadow set live: drawn without it first, its program made again
        relief.material.selfShadow = false;
        renderer.setRenderTarget(target);
        renderer.render(scene, camera);
        relief.material.selfShadow = true;
    }
    if (kViews[view].live) {
        const flat = await wg.createReliefMap(renderer, wg.heightsFromArray(samples.map((x) => 0.5 * x), w, h, {name: 'half'}));
        relief.reliefMap = flat;
        relief.heightScale = 0.05;
        relief.interpolation = interpolation === 'bilinear' ? 'biquadratic' : 'bilinear';
        renderer.setRenderTarget(target);
        renderer.render(scene, camera);
        [relief.reliefMap, relief.heightScale, relief.interpolation] = [map, 0.08, interpolation];
        flat.dispose();
    }
    renderer.setRenderTarget(target);
    renderer.setClearColor(0x000000, 0);
    renderer.clear();
    renderer.render(scene, camera);
    renderer.shadowMap.enabled = false;
    const read = await renderer.readRenderTargetPixelsAsync(target, 0, 0, W, H);  // rows from the top
    renderer.setRenderTarget(null);
    document.documentElement.dataset.api = 'webgpu';
    const pixels = new Uint8Array(4 * W * H);
    for (let y = 0; y < H; ++y) pixels.set(new Uint8Array(read.buffer, read.byteOffset + 4 * W * (H - 1 - y), 4 * W), 4 * W * y);
    target.dispose();
    map.dispose();
    return pixels;
}

// The pictures of `view` with last level `interpolation` on `base`, of `kind` (reliefMaterial), compared: per pixel the largest channel difference (of 255), hit
// (alpha) agreement, and a PNG strip (bottom row first in the data, drawn upright).
async function compareEntries(view, interpolation, base, kind = 'shading', roughness = kLit.roughness) {
    const a = await drawWebGL(view, interpolation, base, kind, roughness), b = await drawWebGPU(view, interpolation, base, kind, roughness);
    let sum = 0, max = 0, differing = 0, hitsGl = 0, hitsGpu = 0, hitDisagree = 0, reliefGl = 0;
    const canvas = new OffscreenCanvas(3 * W, H), ctx = canvas.getContext('2d'), image = ctx.createImageData(3 * W, H);
    for (let y = 0; y < H; ++y)
        for (let x = 0; x < W; ++x) {
            const k = 4 * (y * W + x);
            let d = 0;
            for (let c = 0; c < 3; ++c) d = Math.max(d, Math.abs(a[k + c] - b[k + c]));
            const hitA = a[k + 3] > 0, hitB = b[k + 3] > 0;
            hitsGl += hitA;
            hitsGpu += hitB;
            if (hitA !== hitB) ++hitDisagree;
            if (hitA && !(a[k + 2] > 150 && a[k] < 100)) ++reliefGl;  // not the blue box
            sum += d;
            max = Math.max(max, d);
            if (d > 2 || hitA !== hitB) ++differing;
            const row = H - 1 - y;
            for (const [panel, src] of [[0, a], [1, b]])
                image.data.set([src[k], src[k + 1], src[k + 2], 255], 4 * (row * 3 * W + panel * W + x));
            const v = d > 2 || hitA !== hitB ? 255 : 0;
            image.data.set([v, v, v, 255], 4 * (row * 3 * W + 2 * W + x));
        }
    ctx.putImageData(image, 0, 0);
    // The shadows' scenes: the pixels the shadow darkens (by more than 8 in a channel) in the
    // WebGL picture, against the same without it (the self-shadow, the relief's casting): the
    // scene tests the shadow only where there are many.
    let shadowed;
    const without = {litShadow: 'litRaking', cast: 'castOff', receive: 'receiveOff', litFog: 'lit'}[kind];
    if (without) {
        const c = await drawWebGL(view, interpolation, base, without, roughness);
        shadowed = 0;
        for (let k = 0; k < a.length; k += 4) shadowed += Math.max(c[k] - a[k], c[k + 1] - a[k + 1], c[k + 2] - a[k + 2]) > 8;
    }
    const blob = await canvas.convertToBlob({type: 'image/png'});
    const png = btoa(String.fromCharCode(...new Uint8Array(await blob.arrayBuffer())));
    const n = W * H;
    return JSON.stringify({stats: {pixels: n, meanDiff: sum / n, maxDiff: max, differingFraction: differing / n,
                                   hitsGl, hitsGpu, hitDisagree, reliefGl, shadowed}, png});
}

// The picks (three's Raycaster) of `view`'s scene, the relief alone, through every pixel's
// centre: on the WebGPU entry's Relief against the WebGL entry's Relief of the same map and
// options (both the CPU twin's, through relief_host.js), and against the WebGPU picture's
// hit/miss (its alpha). `model`: the relief turned, scaled and moved (its matrixWorld).
// -> JSON {pixels, picksGpu, picksGl, hitsPicture, pickDisagree (WebGPU's picks against the
// WebGL's: hit/miss), maxDistance, maxPoint, maxNormal, maxUv (largest differences where both
// hit), pictureDisagree (picks against the picture: hit/miss), maxPictureApart and
// meanPictureApart (the pick's point against the picture's, the pixel centre unprojected at
// its depth, where both hit: bothHit pixels), pictureApart (pixels where those are more than
// kPictureApart apart), twinBytes (the WebGPU map's,
// after the picks), twinBytesDisposed (after its dispose), exactDiffer (values of traceRays
// of the same rays that differ between the entries)}.
const kPictureApart = 1e-4;  // world units: a pick this far from the picture's point counts (pictureApart)
async function comparePicks(view, interpolation, base, model) {
    const {webgl: glRenderer, webgpu: renderer} = await renderers();
    const {w, h, samples} = heights();
    const options = {heightScale: 0.08, interpolation, base};
    const glMap = await gl.createReliefMap(glRenderer, gl.heightsFromArray(samples, w, h, {name: 'waves'}), {pyramid: 'cpu', wrapU: base !== 'plane'});
    const glRelief = new gl.Relief(glMap, {...options, material: new gl.ReliefShadingMaterial({lightDirection: light, shadows: 'hard'})});
    const map = await wg.createReliefMap(renderer, wg.heightsFromArray(samples, w, h, {name: 'waves'}), {wrapU: base !== 'plane'});
    const relief = new wg.Relief(map, {...options, material: new wg.ReliefShadingNodeMaterial({lightDirection: light, shadows: 'hard'})});
    for (const r of [glRelief, relief])
        if (model) {
            r.rotation.set(0.3, -0.5, 0.2);
            r.scale.set(1.2, 0.9, 1.1);
            r.position.set(0.05, -0.03, 0.02);
        }
    const glScene = setUp(THREE, view, glRelief, {withBox: false});
    const {scene, camera} = setUp(GPU, view, relief, {withBox: false});
    // The picture and its depth (depth32float, which WebGPU copies to a buffer: three's
    // backend's copyTextureToBuffer, as readRenderTargetPixelsAsync reads a colour texture).
    const depthTexture = new GPU.DepthTexture(W, H);
    depthTexture.type = GPU.FloatType;
    const target = new GPU.RenderTarget(W, H, {depthTexture});
    renderer.setRenderTarget(target);
    renderer.setClearColor(0x000000, 0);
    renderer.clear();
    renderer.render(scene, camera);
    const read = await renderer.readRenderTargetPixelsAsync(target, 0, 0, W, H);  // rows from the top
    const depth = new Float32Array((await renderer.backend.copyTextureToBuffer(depthTexture, 0, 0, W, H, 0)).buffer);
    renderer.setRenderTarget(null);
    target.dispose();
    glScene.scene.updateMatrixWorld();
    const raycaster = new THREE.Raycaster(), ndc = new THREE.Vector2(), _p = new THREE.Vector3();
    const s = {pixels: W * H, picksGpu: 0, picksGl: 0, hitsPicture: 0, pickDisagree: 0, pictureDisagree: 0,
               maxDistance: 0, maxPoint: 0, maxNormal: 0, maxUv: 0, maxPictureApart: 0, meanPictureApart: 0, bothHit: 0, pictureApart: 0};
    for (let row = 0; row < H; ++row)
        for (let x = 0; x < W; ++x) {
            ndc.set(((x + 0.5) / W) * 2 - 1, 1 - ((row + 0.5) / H) * 2);  // row 0 at the top, as read
            raycaster.setFromCamera(ndc, camera);
            const [a] = raycaster.intersectObject(relief, false);
            raycaster.setFromCamera(ndc, glScene.camera);
            const [b] = raycaster.intersectObject(glRelief, false);
            const shown = read[4 * (row * W + x) + 3] > 0;
            s.picksGpu += !!a;
            s.picksGl += !!b;
            s.hitsPicture += shown;
            if (!!a !== !!b) ++s.pickDisagree;
            if (!!a !== shown) ++s.pictureDisagree;
            if (a && b) {  // a field missing (not the relief's own hit) counts as far apart
                const apart = (p, q) => (p && q ? p.distanceTo(q) : Number.MAX_VALUE);
                s.maxDistance = Math.max(s.maxDistance, Math.abs(a.distance - b.distance));
                s.maxPoint = Math.max(s.maxPoint, apart(a.point, b.point));
                s.maxNormal = Math.max(s.maxNormal, apart(a.normal, b.normal), apart(a.worldNormal, b.worldNormal));
                s.maxUv = Math.max(s.maxUv, apart(a.uv, b.uv));
            }
            if (a && shown) {  // the picture's point: the pixel centre at its depth, unprojected
                const seen = _p.set(ndc.x, ndc.y, depth[row * W + x]).unproject(camera);
                const d = seen.distanceTo(a.point);
                s.maxPictureApart = Math.max(s.maxPictureApart, d);
                s.meanPictureApart += d;
                s.bothHit += 1;
                s.pictureApart += d > kPictureApart;
            }
        }
    // The same rays (the WebGL camera's, every pixel's) through both entries' traceRays: the
    // same twin on the same doubles, so every value the same to the bit (exactDiffer counts
    // those that are not).
    const origins = [], directions = [];
    for (let row = 0; row < H; ++row)
        for (let x = 0; x < W; ++x) {
            raycaster.setFromCamera(ndc.set(((x + 0.5) / W) * 2 - 1, 1 - ((row + 0.5) / H) * 2), glScene.camera);
            origins.push(...raycaster.ray.origin.toArray());
            directions.push(...raycaster.ray.direction.toArray());
        }
    const [ta, tb] = [relief.traceRays(origins, directions), glRelief.traceRays(origins, directions, [0, Infinity], {on: 'cpu'})];
    s.meanPictureApart /= Math.max(s.bothHit, 1);
    s.exactDiffer = 0;
    for (const field of ['t', 'kind', 'exhausted', 'point', 'normal', 'uv', 'iterations'])
        ta[field].forEach((v, k) => (s.exactDiffer += !Object.is(v, tb[field][k])));
    s.twinBytes = map.twinBytes;
    map.dispose();
    s.twinBytesDisposed = map.twinBytes;
    glMap.dispose();
    return JSON.stringify(s);
}

// What the WebGPU entry says where it cannot draw: given a WebGLRenderer, given a
// WebGPURenderer without a WebGPU adapter (forceWebGL: three's fallback to WebGL 2, as where
// the browser has no adapter), a map wider than the device's maxTextureDimension2D, and its
// Relief drawn by a WebGLRenderer. -> JSON {[case]: {name, message}} (no name: nothing thrown).
async function refusals() {
    const {w, h, samples} = heights();
    const map = wg.heightsFromArray(samples, w, h, {name: 'waves'});
    const said = {};
    const attempt = async (what, call) => {
        try {
            await call();
            said[what] = {name: '', message: ''};
        } catch (e) {
            said[what] = {name: e.name, message: e.message};
        }
    };
    const fallback = new GPU.WebGPURenderer({canvas: new OffscreenCanvas(8, 8), forceWebGL: true});
    await attempt('webglRenderer', () => wg.createReliefMap(new THREE.WebGLRenderer({canvas: new OffscreenCanvas(8, 8)}), map));
    await attempt('noAdapter', () => wg.createReliefMap(fallback, map));
    fallback.dispose();
    // A map one texel wider than the device takes; the map after it is made and drawn below
    // (the scene goes on).
    const {webgl: glRenderer, webgpu: gpuRenderer} = await renderers();
    const wide = gpuRenderer.backend.device.limits.maxTextureDimension2D + 1;
    await attempt('tooLarge', () => wg.createReliefMap(gpuRenderer, wg.heightsFromArray(new Float32Array(wide), wide, 1, {name: 'wide'})));
    // This entry's Relief in a WebGLRenderer's scene.
    const relief = new wg.Relief(await wg.createReliefMap(gpuRenderer, map));
    const scene = new THREE.Scene();
    scene.add(relief);
    await attempt('drawnByWebGL', () => glRenderer.render(scene, new THREE.PerspectiveCamera()));
    // Its picks on the GPU: this entry has none (the CPU twin traces them).
    await attempt('gpuPicks', () => relief.traceRays([0, 1, 0], [0, -1, 0], [0, 2], {on: 'gpu'}));
    relief.reliefMap.dispose();
    // An albedo map three's WebGPU cannot filter (NearestFilter both ways: no sampler).
    const nearest = albedoMap(GPU);
    nearest.minFilter = nearest.magFilter = GPU.NearestFilter;
    await attempt('nearestAlbedo', () => new wg.ReliefStandardNodeMaterial({albedoMap: nearest}));
    return JSON.stringify(said);
}

window.refusals = refusals;
window.comparePicks = comparePicks;
window.compareEntries = compareEntries;
document.documentElement.dataset.state = 'ready';
