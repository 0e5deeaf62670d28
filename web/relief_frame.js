// relief_frame.js: what the page's two drawing hosts (relief_gl.js, WebGL 2; relief_gpu.js,
// WebGPU) hand the library for one picture, written once and free of either API: the proxy
// box's corners (ReliefRenderer::uploadBox), which of its faces to draw (front faces from
// outside the box grown by a margin, back faces from inside), the camera
// (HeadlessRenderer::render's depth range from the samples' maximum) and the members of
// MicroreliefParameters (ReliefRenderer::parameters) by name, as relief_layout.js's
// writeParameters takes them. A host changes only what its API asks (relief_gpu.js: the clip
// transform for WebGPU's framebuffer and depth range) and writes the buffer.
import {defineValue, kBaseKindValues, kDebugViewValues, kInterpolationValues, kMethodValues, kShadowModeValues} from './relief_layout.js';
import * as core from './relief_core.js';
import * as scene from './scene.js';

// The #defines of relief.frag's variant `c` ({method, base, interpolation, shadows,
// albedoMap}), each value by its name from the GLSL's own table (variants.glsl, through the
// generated relief_layout.js): what both hosts compile, WebGL 2 as GLSL ES and WebGPU as
// naga's WGSL of it. No depth layout (WebGL 2 has no conservative depth, and the page draws
// the relief alone) and no tiling.
export function reliefDefines(c) {
    return [
        ['MICRORELIEF_METHOD', defineValue(kMethodValues, c.method, 'MICRORELIEF_METHOD')],
        ['MICRORELIEF_BASE', defineValue(kBaseKindValues, c.base, 'MICRORELIEF_BASE')],
        ['MICRORELIEF_INTERPOLATION', defineValue(kInterpolationValues, c.interpolation, 'MICRORELIEF_INTERPOLATION')],
        ['MICRORELIEF_DEPTH_LAYOUT', '0'],
        ['MICRORELIEF_SHADOWS', defineValue(kShadowModeValues, c.shadows, 'MICRORELIEF_SHADOWS')],
        ['MICRORELIEF_ALBEDO_MAP', c.albedoMap ? '1' : '0'],
        ['MICRORELIEF_TILING', '0'],
    ];
}

// `view` (scene.js's) drawn at `pixels` ([W, H]) over a map whose textures' `shape`
// (ReliefTextures.shape: size, pyramidSize, levelCount, maxHeight) and largest sample
// `maxSample` are given: {corners (Float32Array, 8 x 3), outside (the eye outside the box),
// values (MicroreliefParameters' members by name)}.
export function reliefFrame(view, shape, maxSample, pixels) {
    const base = scene.viewBase(view);
    const heightScale = view.heightScale;

    // The box, from the windows' top (ReliefRenderer::uploadBox), in floats.
    const boxExtent = core.reliefExtent(shape.size[0], shape.size[1], shape.maxHeight, heightScale, base);
    const margin = Math.fround(1e-3);
    const lo = boxExtent.min.map((c) => Math.fround(Math.fround(c) - margin));
    const hi = boxExtent.max.map((c) => Math.fround(Math.fround(c) + margin));
    const corners = new Float32Array([lo[0], lo[1], lo[2], hi[0], lo[1], lo[2], hi[0], lo[1], hi[2], lo[0], lo[1], hi[2],
                                      lo[0], hi[1], lo[2], hi[0], hi[1], lo[2], hi[0], hi[1], hi[2], lo[0], hi[1], hi[2]]);

    // The camera's depth range from the samples' maximum (HeadlessRenderer::render).
    const radius = scene.sceneRadius(core.reliefExtent(shape.size[0], shape.size[1], maxSample, heightScale, base));
    const camera = scene.resolveCamera(view, pixels[0], pixels[1], radius);

    // Front faces from outside the box grown by a margin, back faces from inside.
    const eye = view.eye;
    const grow = [0, 1, 2].map((k) => 1e-4 * (hi[k] - lo[k]) + 1e-6);
    const outside = [0, 1, 2].some((k) => eye[k] < lo[k] - grow[k] || eye[k] > hi[k] + grow[k]);

    return {corners, outside, values: parameterValues(view, camera, shape, base, pixels)};
}

// MicroreliefParameters' members (ReliefRenderer::parameters), for relief_layout.js's
// writeParameters (generated from shaders/relief_parameters.glsl), which refuses a member
// left out.
function parameterValues(view, camera, shape, base, pixels) {
    const extent = core.reliefExtent(shape.size[0], shape.size[1], shape.maxHeight, view.heightScale, base);
    // Traced relative to the eye, as ReliefRenderer::parameters does: the page places
    // the relief at the origin, so the model is the move by minus the eye, its inverse
    // the move back, and the clip transform takes the eye-relative world (its last
    // column VP (eye, 1), in double).
    const [x, y, z] = camera.eye, vp = camera.viewProjection;
    const viewProjection = vp.slice(0, 12).concat([0, 1, 2, 3].map((r) => vp[r] * x + vp[4 + r] * y + vp[8 + r] * z + vp[12 + r]));
    return {
        viewProjection,
        objectToWorld: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -x, -y, -z, 1],
        worldToObject: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, x, y, z, 1],
        eye: [0, 0, 0],
        pixelErrorTolerance: view.pixelError,
        cameraRight: camera.right,
        heightScale: view.heightScale,
        cameraUp: camera.up,
        reliefMaxHeight: shape.maxHeight,
        cameraForward: camera.forward,
        tMin: 0,
        frameScale: core.frameScale(base),
        tMax: 3.4e38,
        reliefBoxMin: extent.min,
        pyramidLevels: shape.levelCount,
        reliefBoxMax: extent.max,
        maxIterations: core.traversalBudget(shape.size[0], shape.size[1]),
        lightDirection: scene.normalizeFloat(view.light),
        debugView: Number(defineValue(kDebugViewValues, view.view, 'debugView')),
        albedo: scene.toFloat([0.6, 0.58, 0.55]),  // ShadingOptions::albedo, without a texture
        methodSteps: view.steps,
        reliefSize: shape.size,
        pyramidSize: shape.pyramidSize,
        viewportSize: pixels,
        tileOrigin: [0, 0],  // the whole picture
        methodMinSteps: scene.minSteps(view.steps),
        methodRefineSteps: 8,  // relief mapping's binary steps
        depthZeroToOne: 0,  // WebGL's clip depth is [-1, 1]
        blockPadding: 0,  // std140 padding before lightPosition
        lightPosition: [0, 0, 0, 0],  // a directional light
        lightTanRadius: Math.tan(0.5 * view.lightSize * 0.01745329251994329576923690768489),
        albedoFinest: 0,  // filtered over the pixel's footprint
        reliefTiles: [1, 1],
    };
}
