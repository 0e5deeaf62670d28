// microrelief-three/webgpu: exact microrelief in three.js's WebGPURenderer (docs/three.md,
// docs/webgpu.md). The first slice: the library's own shading (ReliefShadingNodeMaterial,
// as the WebGL entry's ReliefShadingMaterial draws it) and three's lights
// (ReliefStandardNodeMaterial, as the WebGL entry's ReliefStandardMaterial) on every base,
// both last levels; the windows pyramid built by the C++ MaxPyramid in WebAssembly.
//
//   import {WebGPURenderer} from 'three/webgpu';
//   import {createReliefMap, loadHeights, Relief, ReliefShadingNodeMaterial} from 'microrelief-three/webgpu';
//   const map = await createReliefMap(renderer, await loadHeights('cobbles.png'));
//   scene.add(new Relief(map, {material: new ReliefShadingNodeMaterial()}));
//
// The relief is the WebGL entry's: the same host code (relief_host.js: the base, the box,
// the option checks, each draw's rays and matrices, the picks by the CPU twin of twin.js;
// map_host.js: the map's checks and its pyramid), the same library (naga's WGSL of
// shaders/microrelief/, generated/wgsl.js, the functions the WebGL entry calls in GLSL) and
// the same glue (naga's WGSL of the package's glsl/relief_three.glsl, the pixel's ray, trace
// and shading the WebGL entry runs, and of glsl/webgpu_shading.glsl's mrShadePixel, which
// calls them), called from a node material by wgslFn. What is WebGPU's own is here: the
// textures (read by textureLoad, no sampler) and three's nodes passed to the glue's pixels.
import * as THREE from 'three/webgpu';
import * as TSL from 'three/tsl';
import {cameraFar, cameraNear, cameraWorldMatrix, code, context, diffuseColor, Discard, float, Fn, frontFacing, If, lightShadowMatrix, lightViewPosition, normalViewGeometry,
        normalWorld, positionView, positionWorld, property, reference, sampler, screenCoordinate, select, texture, uniform, vec4, viewport, viewZToLogarithmicDepth,
        wgslFn} from 'three/tsl';

import {unavailable as wgslUnavailable, wgsl as wgslModules} from '../generated/wgsl.js';
import * as core from '../generated/relief_core.js';
import {kBaseKindValues} from '../generated/relief_layout.js';
import {checkHeightMap, largestSample, windowLevelsOnCpu} from './map_host.js';
import {baseShape, boxFaces, checkBaseForMap, checkHeightScale, checkInterpolation, checkPixelError, checkRays, defineReliefOptions, raycastRelief, reliefFrame,
        reliefMapUniforms, reliefUniforms, traceOne, traceRaysOnTwin, updateReliefBox} from './relief_host.js';
import {requireSupportedThree} from './three_version.js';
import {loadTwin, releaseTwins, twinBytes} from './twin.js';

export {albedoFromBytes, loadAlbedo} from './albedo.js';
export {HeightMapError, heightsFromArray, heightsFromBytes, heightsFromImage, heightsFromPng, kMaxMapSide, loadHeights} from './heights.js';
export {baseShape, cameraRays, reliefExtent} from './relief_host.js';

// The bases this entry draws, by kind (a base outside them is refused in one line naming it):
// every kind of the table of bases (relief_layout.js's kBaseKindValues, MICRORELIEF_BASE's
// values), each a WGSL variant per last level (scripts/wgsl.mjs: wgslVariants).
export const kWebGPUBases = Object.freeze(Object.keys(kBaseKindValues));

// A WebGPU that cannot do what was asked (no adapter, a map past the device's limits).
export class ReliefGpuError extends Error {
    constructor(message) {
        super(message);
        this.name = 'ReliefGpuError';
    }
}

// The one line a WebGLRenderer gets here.
export const kWebGLRendererHere = "microrelief-three/webgpu draws with three's WebGPURenderer; a WebGLRenderer takes the WebGL entry: import from 'microrelief-three'";

function requireWebGPURenderer(renderer, what) {
    if (renderer && renderer.isWebGLRenderer) throw new TypeError(`${what}: ${kWebGLRendererHere}`);
    if (!renderer || !renderer.isWebGPURenderer) throw new TypeError(`${what}: the first argument must be a WebGPURenderer (three/webgpu)`);
}

// ---- the library's WGSL, as a node material includes it ----

// The top-level items of a naga module: {name, text}. naga writes each item from column 0:
// `struct` and `fn` up to a `}` line, `const` and `var` in one statement, attributes (`@...`)
// on lines of their own before their item; its comments (the module's header) are dropped.
// Anything else is refused: the module is then not what this reader was written for.
export function wgslItems(module) {
    const lines = module.split('\n'), items = [];
    let attributes = '';
    for (let k = 0; k < lines.length; ++k) {
        const line = lines[k];
        if (line.trim() === '' || line.startsWith('//')) continue;
        if (line.startsWith('@') && !/\b(fn|var)\b/.test(line)) {
            attributes += line + '\n';
            continue;
        }
        const head = /^(?:@\S+\s+)*(struct|fn|const|var(?:<[^>]*>)?)\s+([A-Za-z_][A-Za-z0-9_]*)/.exec(line);
        if (!head) throw new Error(`microrelief-three/webgpu: a WGSL line this reader does not know: '${line.slice(0, 80)}'`);
        let text = attributes + line;
        attributes = '';
        if (head[1] === 'struct' || head[1] === 'fn') {
            if (!/\{\s*\}\s*$/.test(line)) while (lines[k] !== '}' && k + 1 < lines.length) text += '\n' + lines[++k];
        } else {
            while (!/;\s*$/.test(lines[k]) && k + 1 < lines.length) text += '\n' + lines[++k];
        }
        items.push({name: head[2], text});
    }
    return items;
}

// The items of `module` that `roots` reach (by name, through every identifier each item's
// text holds), in the module's order: what a node material includes. The module's empty
// entry point (`fn main`) and the albedo's sampler (a binding of its own, which a node
// material cannot hold beside three's) are reached by none of the functions the glue calls.
export function reachableWgsl(module, roots) {
    const items = wgslItems(module);
    const byName = new Map(items.map((item) => [item.name, item]));
    const kept = new Set(), stack = [...roots];
    while (stack.length) {
        const name = stack.pop();
        if (kept.has(name)) continue;
        if (!byName.has(name)) throw new Error(`microrelief-three/webgpu: the library's WGSL has no ${name}`);
        kept.add(name);
        for (const word of byName.get(name).text.match(/[A-Za-z_][A-Za-z0-9_]*/g))
            if (byName.has(word) && !kept.has(word)) stack.push(word);
    }
    return items.filter((item) => kept.has(item.name)).map((item) => item.text).join('\n');
}

// The glue's functions: glsl/webgpu_shading.glsl's mrShadePixel (ReliefShadingNodeMaterial's:
// returns (colour, depth), depth -1 where the pixel shows nothing), mrTraceHit
// (ReliefStandardNodeMaterial's: the hit in view space for three's lighting) and mrSelfShadow
// (its selfShadow: the hard shadow from mrTraceHit's hit towards one of three's lights) and
// mrShadowTexelSize (its shadow lookups' bias: a shadow-map texel's world size), which
// run relief_three.glsl's functions the WebGL entry's pixel runs (mrNdcOf, mrTraceRay,
// mrShadeHit) and the library's, translated with the library into each variant's module by
// naga (scripts/wgsl.mjs).
const kGlueEntries = ['mrShadePixel', 'mrTraceHit', 'mrSelfShadow', 'mrShadowTexelSize'];

// The glue functions `entryNames` of a variant (`base`_`interpolation`), called together from
// one node material: {name: {fn, parameters}}, fn the module's function as a wgslFn, parameters
// its GLSL parameter names in order (naga may add a suffix _N to a name; the suffix is dropped
// here). What they reach (the library, the glue's module-scope variables: mrTraceHit leaves its
// pixel there for mrSelfShadow) is one include they share, so that the shader holds each item
// once. Made once a variant and set of entries. No WGSL is written here: the call passes
// three's nodes by position (glue below).
const _glues = new Map();
function glueFunctions(variant, entryNames) {
    const key = `${variant}:${entryNames.join(',')}`;
    if (!_glues.has(key)) {
        if (wgslUnavailable) throw new Error(`microrelief-three/webgpu: this package was built without its WGSL (${wgslUnavailable})`);
        const module = wgslModules[variant];
        if (!module) throw new Error(`microrelief-three/webgpu: no WGSL variant ${variant}`);
        const items = wgslItems(module);
        // What the entries reach, in the module's order, without the entries themselves (each
        // its wgslFn's own text); an entry another reaches would be in the shader twice.
        const reached = wgslItems(reachableWgsl(module, entryNames));
        for (const name of entryNames)
            if (wgslItems(reachableWgsl(module, entryNames.filter((other) => other !== name))).some((item) => item.name === name))
                throw new Error(`microrelief-three/webgpu: the glue function ${name} is called by another of ${entryNames.join(', ')}`);
        const include = code(reached.filter((item) => !entryNames.includes(item.name)).map((item) => item.text).join('\n'));
        const functions = {};
        for (const name of entryNames) {
            const entry = items.find((item) => item.name === name);
            if (!entry) throw new Error(`microrelief-three/webgpu: the WGSL variant ${variant} has no ${name}`);
            const head = /^fn\s+\w+\(([^)]*)\)/.exec(entry.text);
            const parameters = head[1].split(',').map((p) => p.trim().split(':')[0].trim().replace(/_\d+$/, ''));
            functions[name] = {fn: wgslFn(entry.text, [include]), parameters};
        }
        _glues.set(key, functions);
    }
    return _glues.get(key);
}

// The glue function `entryName` (kGlueEntries) of `variant` called with `inputs` ({name:
// node}, by its GLSL parameter names): each one given, none left over. `entries`: every glue
// function the material calls (glueFunctions: they share their include).
function glue(variant, entryName, inputs, entries = [entryName]) {
    if (!kGlueEntries.includes(entryName) || !entries.includes(entryName)) throw new Error(`microrelief-three/webgpu: no glue function ${entryName}`);
    const {fn, parameters} = glueFunctions(variant, entries)[entryName];
    const extra = Object.keys(inputs).filter((name) => !parameters.includes(name));
    const missing = parameters.filter((name) => !(name in inputs));
    if (extra.length || missing.length)
        throw new Error(`microrelief-three/webgpu: ${entryName} of ${variant} takes ${parameters.join(', ')} (missing ${missing.join(', ') || 'none'}, extra ${extra.join(', ') || 'none'})`);
    return fn(parameters.map((name) => inputs[name]));
}

// ---- the map ----

// A height map's textures for a WebGPURenderer: the samples (r32float, W x H) and the
// windows pyramid (r16float, GL's mip sizes of W x H, one mip level a window level), both
// read by textureLoad (no sampler, no filtering: the texels the library asks for).
export class ReliefMap {
    constructor({renderer, heights, windows, width, height, levelSizes, maxHeight, maxSample, scaleExponent, wrapU, name}) {
        Object.assign(this, {renderer, heights, windows, width, height, levelSizes, maxHeight, maxSample, scaleExponent, wrapU, name});
        this.levelCount = levelSizes.length;
        this.builtOn = 'cpu';
    }

    // GPU memory of the textures, bytes: 4 a sample, 2 a window texel.
    get gpuBytes() {
        return 4 * this.width * this.height + 2 * this.levelSizes.reduce((sum, [w, h]) => sum + w * h, 0);
    }

    // WebAssembly memory of the CPU twins the picks built (twin.js), bytes: 0 before the first.
    get twinBytes() {
        return twinBytes(this);
    }

    dispose() {
        this.heights.dispose();
        this.windows.dispose();
        releaseTwins(this);
    }
}

function readTexture(texture) {
    texture.minFilter = texture.magFilter = THREE.NearestFilter;
    texture.wrapS = texture.wrapT = THREE.ClampToEdgeWrapping;
    texture.generateMipmaps = false;
    texture.flipY = false;
    texture.needsUpdate = true;
    return texture;
}

// Waits for the renderer's backend; throws ReliefGpuError where it is not WebGPU (no
// adapter: three falls back to WebGL 2, where the WGSL cannot run).
async function requireWebGPUBackend(renderer, what) {
    if (renderer.init) await renderer.init();
    if (!renderer.backend || !renderer.backend.isWebGPUBackend)
        throw new ReliefGpuError(`${what}: this WebGPURenderer has no WebGPU adapter (three fell back to WebGL 2, where microrelief-three/webgpu cannot draw); draw with a WebGLRenderer and 'microrelief-three' instead`);
}

// The textures of `map` ({width, height, samples, name}: heights.js) for `renderer`, a
// WebGPURenderer (awaited: init). options: wrapU (true for the curved bases: their u wraps
// round, and the pyramid's seam with it).
export async function createReliefMap(renderer, map, {wrapU = false} = {}) {
    requireSupportedThree();
    requireWebGPURenderer(renderer, 'createReliefMap');
    checkHeightMap(map, 'createReliefMap');
    await requireWebGPUBackend(renderer, 'createReliefMap');
    const name = map.name || 'height map';
    const maxSize = renderer.backend.device.limits.maxTextureDimension2D;
    if (map.width > maxSize || map.height > maxSize)
        throw new ReliefGpuError(`${name}: ${map.width} x ${map.height} is larger than this WebGPU device's maxTextureDimension2D (${maxSize})`);
    const maxSample = largestSample(map);
    const twin = loadTwin();  // the picks' CPU twin (twin.js), as the WebGL entry's createReliefMap; never rejects
    let built;
    try {
        built = await windowLevelsOnCpu({...map, name}, wrapU);
    } finally {
        await twin;  // settled either way: a pick knows whether the package has a twin
    }
    const {levels, levelSizes, maxHeight, scaleExponent} = built;
    const heights = readTexture(new THREE.DataTexture(map.samples, map.width, map.height, THREE.RedFormat, THREE.FloatType));
    const windows = readTexture(new THREE.DataTexture(null, levelSizes[0][0], levelSizes[0][1], THREE.RedFormat, THREE.HalfFloatType));
    windows.mipmaps = levelSizes.map(([w, h], k) => ({data: levels[k], width: w, height: h}));
    windows.image = windows.mipmaps[0];
    return new ReliefMap({renderer, heights, windows, width: map.width, height: map.height, levelSizes, maxHeight, maxSample, scaleExponent, wrapU, name});
}

// ---- the material and the relief ----

// A relief uniform the node material reads per draw from the relief drawn, for the draw's
// camera (Relief.uniformsFor).
function reliefUniform(name, value) {
    return uniform(value).onObjectUpdate(({object, camera, renderId}) => object.uniformsFor(camera, renderId)[name].value);
}

// The Relief a relief material is built for (three builds a node material for its object).
function drawnRelief(builder, name) {
    const relief = builder.object;
    if (!relief || !relief.isRelief) throw new Error(`microrelief-three/webgpu: a ${name} draws only on a Relief (new Relief(map, {material}))`);
    return relief;
}

// The WGSL variant a relief draws with (generated/wgsl.js's name).
const variantOf = (relief) => `${relief.base.kind}_${relief.interpolation}`;

// The albedo texture bound where a material has no albedoMap (the glue's pixels take one
// always; useAlbedoMap 0 leaves it unread): one white texel.
let _noAlbedo = null;
function noAlbedo() {
    if (!_noAlbedo) {
        _noAlbedo = new THREE.DataTexture(new Uint8Array([255, 255, 255, 255]), 1, 1, THREE.RGBAFormat, THREE.UnsignedByteType);
        _noAlbedo.minFilter = _noAlbedo.magFilter = THREE.LinearFilter;  // filterable: three gives it a sampler
        _noAlbedo.needsUpdate = true;
    }
    return _noAlbedo;
}

// The map's colours as the glue's pixels take them (mrPixelAlbedo): the texture, its
// sampler (the WGSL's first parameter: scripts/wgsl.mjs's samplerAsParameter), whether to
// read it. `albedoMap` a texture as loadAlbedo makes it (flipY false, sRGB, mipmapped), or
// null.
// three gives a texture no sampler where it cannot filter it (nearest both ways): refused, by
// the materials' constructors and again when the program is made (for one set later).
function checkAlbedoMap(albedoMap, what) {
    if (albedoMap && albedoMap.minFilter === THREE.NearestFilter && albedoMap.magFilter === THREE.NearestFilter)
        throw new TypeError(`${what}: albedoMap is filtered over each pixel's footprint, and a texture with NearestFilter both ways has no sampler in three's WebGPU (loadAlbedo's is mipmapped, linear)`);
}

function albedoInputs(albedoMap) {
    checkAlbedoMap(albedoMap, 'microrelief-three/webgpu');
    const node = texture(albedoMap ?? noAlbedo());
    return {albedoMap: node, mrAlbedoSampler: sampler(node), useAlbedoMap: uniform(albedoMap ? 1 : 0)};
}

// The parameters both glue pixels take (webgpu_shading.glsl's mrTraceFragment): the relief's
// textures and uniforms, the fragment's position, the viewport, the face; the matrix the
// depth is made with (mrDepthMatrix under a logarithmic depth buffer: tracedDepth).
function traceInputs(builder, relief) {
    const u = (name) => reliefUniform(name, relief.uniforms[name].value);
    const logarithmic = builder.renderer.logarithmicDepthBuffer === true;
    return {
        heights: texture(relief.reliefMap.heights), windows: texture(relief.reliefMap.windows),
        fragCoord: screenCoordinate, viewport, front: frontFacing, faces: u('mrFaces'),
        mapSize: u('mrMapSize'), pyramidSize: u('mrPyramidSize'), levelCount: u('mrLevelCount'), maxHeight: u('mrMaxHeight'),
        objectToWorld: u('mrObjectToWorld'), worldToObject: u('mrWorldToObject'), heightScale: u('mrHeightScale'),
        frameScale: u('mrFrameScale'), pixelError: u('mrPixelError'),
        rayOrigin: u('mrRayOrigin'), rayOriginDx: u('mrRayOriginDx'), rayOriginDy: u('mrRayOriginDy'),
        rayDir: u('mrRayDir'), rayDirDx: u('mrRayDirDx'), rayDirDy: u('mrRayDirDy'), range: u('mrRange'),
        viewProjection: u(logarithmic ? 'mrDepthMatrix' : 'mrViewProjection'),
    };
}

// The depth three's other meshes write, from the glue's `depth` (-1: nothing shown): the
// traced clip z / w; under a logarithmic depth buffer (NodeMaterial.setupDepth's) three's
// logarithmic depth of the hit's view z for a perspective camera, which mrDepthMatrix hands
// the glue as -z / far (a float's relative precision at any distance, as the buffer means to
// keep), and the traced clip z / w (its orthographic depth) for any other.
function tracedDepth(builder, relief, depth) {
    const clamped = depth.max(0);
    if (builder.renderer.logarithmicDepthBuffer !== true) return clamped;
    const perspective = reliefUniform('mrPerspective', relief.uniforms.mrPerspective.value);
    return select(perspective.equal(1), viewZToLogarithmicDepth(clamped.mul(cameraFar).negate(), cameraNear, cameraFar), clamped);
}

// The relief's depth as `material`'s depthNode: in the material's own pass `material._mrDepth`
// (its setup's, from the trace of its pixel), in any other (three's shadow pass: its depth
// material, isShadowPassMaterial, draws each caster with the caster material's depthNode,
// Renderer._getShadowNodes) the relief traced again from that pass's camera (castDepth).
function reliefDepth(material) {
    return Fn((builder) => (builder.material === material ? material._mrDepth : castDepth(builder)))();
}

// The relief in three's shadow pass for a light (a directional or spot light's camera, a point
// light's cube faces), as the WebGL entry's ReliefDepthMaterial and ReliefDistanceMaterial
// draw it: each shadow-map texel's ray from the light's camera traced (mrTraceHit: the relief's
// uniforms are that camera's, Relief.uniformsFor; the map's colours not read), the
// texel discarded where it shows nothing or where the traversal ran out of its budget (no
// shadow from a ray that did not finish, three_material.glsl's MR_SHADOW_PASS), its depth
// the hit's, as the relief's own pass writes it (tracedDepth).
function castDepth(builder) {
    const relief = drawnRelief(builder, 'relief material');
    const hit = glue(variantOf(relief), 'mrTraceHit', {...traceInputs(builder, relief), ...albedoInputs(null),
                                                        worldToCamera: reliefUniform('mrWorldToCamera', relief.uniforms.mrWorldToCamera.value)}).toVar('mrCast');
    If(hit.element(0).w.lessThan(0).or(hit.element(1).w.greaterThan(0.5)), () => {
        Discard();
    });
    return tracedDepth(builder, relief, hit.element(0).w);
}

// The library's own shading, as microrelief-render draws it and as the WebGL entry's
// ReliefShadingMaterial does: one directional light (`lightDirection`, world, towards the
// light), the map's colours (`albedoMap`, loadAlbedo's) or a grey `albedo` (linear), the hard
// self-shadow with `shadows: 'hard'`; not lit
// by three's lights; three's output conversion applies (toneMapped false). A node material
// (MeshBasicNodeMaterial) whose colour and depth are the traced pixel's (the depth
// logarithmic where the renderer's depth buffer is, as three's meshes write it). In this slice one
// material draws one relief (the textures are bound when its program is built).
export class ReliefShadingNodeMaterial extends THREE.MeshBasicNodeMaterial {
    constructor({lightDirection = new THREE.Vector3(-0.45, 0.8, -0.35).normalize(), albedoMap = null, albedo = new THREE.Color(0.6, 0.58, 0.55),
                 shadows = 'off'} = {}) {
        requireSupportedThree();
        if (!['off', 'hard'].includes(shadows)) throw new TypeError(`ReliefShadingNodeMaterial: shadows '${shadows}' (expected off or hard)`);
        checkAlbedoMap(albedoMap, 'ReliefShadingNodeMaterial');
        super();
        this.isReliefMaterial = true;
        this.relief = null;
        this.side = THREE.DoubleSide;  // the faces that run are chosen per draw (mrFaces)
        this.toneMapped = false;
        this.fog = false;
        this.shadows = shadows;
        this.lightDirection = uniform(lightDirection.clone());
        this.albedo = uniform(new THREE.Color().copy(albedo));
        this.albedoMap = albedoMap;
    }

    customProgramCacheKey() {
        // The variant, the map and the albedo (the program binds its textures: others, another program).
        const relief = this.relief;
        return `microrelief-webgpu:${relief ? `${relief.base.kind}:${relief.interpolation}:${relief.reliefMap.heights.id}` : ''}:${this.shadows}:${albedoKey(this.albedoMap)}`;
    }

    setup(builder) {
        const relief = drawnRelief(builder, 'ReliefShadingNodeMaterial');
        const traced = glue(variantOf(relief), 'mrShadePixel', {
            ...traceInputs(builder, relief), lightDirection: this.lightDirection, albedo: this.albedo,
            shadows: uniform(this.shadows === 'hard' ? 1 : 0), ...albedoInputs(this.albedoMap),
        }).toVar('mrTraced');
        this.depthNode = tracedDepth(builder, relief, traced.w);
        this.colorNode = Fn(() => {
            If(traced.w.lessThan(0), () => {
                Discard();
            });
            return vec4(traced.xyz, 1);
        })();
        return super.setup(builder);
    }

    copy(source) {
        super.copy(source);
        this.shadows = source.shadows;
        if (source.lightDirection) this.lightDirection.value.copy(source.lightDirection.value);
        if (source.albedo) this.albedo.value.copy(source.albedo.value);
        this.albedoMap = source.albedoMap ?? null;
        return this;
    }
}

// A material's albedo in its program's key: the texture binds with the program.
const albedoKey = (albedoMap) => (albedoMap ? `albedo${albedoMap.id}` : 'grey');

// ReliefStandardNodeMaterial's traced pixel (mrTraceHit's columns), one a fragment.
const kHit = property('mat4', 'mrHit');

// three's MeshStandardNodeMaterial on the relief: three's lights (directional, point, spot,
// hemisphere, ambient, ...), environment maps, fog and tone mapping evaluated at the traced
// hit, as the WebGL entry's ReliefStandardMaterial evaluates three's MeshStandardMaterial
// there. Its parameters are MeshStandardNodeMaterial's (color, roughness, metalness, ...). The
// glue's mrTraceHit (webgpu_shading.glsl) traces the pixel once and gives the hit in the
// camera's view space and its unit normal there, as three_material.glsl's mrBeginPixel gives
// them to three's WebGL shaders; this material hands them to three's lighting as the
// fragment's surface: the normal as `normalNode`, the position by three's overrideNodes
// (r187: positionView, positionWorld and normalViewGeometry, the nodes three's lights, BRDFs,
// fog and shadow lookups read, replaced in the fragment stage; its contextNode), the depth as `depthNode` (logarithmic as ReliefShadingNodeMaterial's). Misses
// and faces that do not run are discarded; an exhausted traversal is magenta, as in WebGL.
// `albedoMap` (loadAlbedo's texture) multiplies three's diffuse colour by the map's colours,
// filtered over the pixel's footprint as in WebGL. `selfShadow`: the library's exact hard
// shadow of the relief on itself towards each of three's directional, point and spot lights
// (ReliefLightingModel below), on top of three's shadow maps, as the WebGL entry's. It casts
// into three's shadow maps (depthNode: reliefDepth) and receives them, each lookup moved off
// the surface by the map's texel as in WebGL (receivedShadow; docs/three.md, "Shadow acne").
export class ReliefStandardNodeMaterial extends THREE.MeshStandardNodeMaterial {
    constructor(parameters = {}) {
        requireSupportedThree();
        if (typeof TSL.overrideNodes !== 'function')
            throw new Error("ReliefStandardNodeMaterial: this three has no overrideNodes (three/tsl, r187 and newer), which hands three's lighting the traced hit");
        const {albedoMap = null, selfShadow = false, ...rest} = parameters;
        checkAlbedoMap(albedoMap, 'ReliefStandardNodeMaterial');
        super(rest);
        this.albedoMap = albedoMap;
        this._selfShadow = !!selfShadow;
        this.isReliefMaterial = true;
        this.relief = null;
        this.side = THREE.DoubleSide;  // the faces that run are chosen per draw (mrFaces)
        this.shadowSide = THREE.DoubleSide;  // in three's shadow passes too (castDepth)
        // The depth: this material's pass's (the trace of kHit, setup below) or, in three's
        // shadow pass, the relief traced from the light's camera (castDepth).
        this.depthNode = reliefDepth(this);
        // The surface three lights is the hit (kHit, traced by setupClipping below), in the
        // fragment stage: its view position (three's positionViewDirection follows from it:
        // normalize(-position), or (0, 0, 1) for an orthographic camera, as three's WebGL
        // shaders have it), three's world position (the camera's matrixWorld of the view
        // position: what shadow-map lookups and projected lights read; not tested yet) and
        // the geometry's normal (whose screen derivatives roughen the specular where the
        // normal turns fast: three's getGeometryRoughness, as WebGL's lights_physical_fragment
        // does with the hit's normal). Set here, not in setup: three reads a material's
        // contextNode before it sets the material up (set there, the first program three
        // made lit the box, measured).
        const view = kHit.element(0).xyz;
        this.contextNode = TSL.overrideNodes([
            [positionView, view],
            [positionWorld, cameraWorldMatrix.mul(vec4(view, 1)).xyz],
            [normalViewGeometry, kHit.element(1).xyz],
        ], null, 'fragment');
        // three's shadow lookups for each light (its context's getShadow, which three's
        // AnalyticLightNode asks for the light's shadowed colour): at the hit moved off the
        // surface by what the map's texel asks for (receivedShadow, of the material being built:
        // a copy shares this context).
        this.contextNode.value.getShadow = (lightNode, builder) => builder.material.receivedShadow(lightNode);
    }

    // The self-shadow's rays are in the program: another value, another program.
    get selfShadow() {
        return this._selfShadow;
    }

    set selfShadow(value) {
        if (!!value !== this._selfShadow) this.needsUpdate = true;
        this._selfShadow = !!value;
    }

    customProgramCacheKey() {
        const relief = this.relief;
        return `microrelief-webgpu-standard:${relief ? `${relief.base.kind}:${relief.interpolation}:${relief.reliefMap.heights.id}` : ''}:${albedoKey(this.albedoMap)}:${this.selfShadow ? 'self' : ''}`;
    }

    setup(builder) {
        const relief = drawnRelief(builder, 'ReliefStandardNodeMaterial');
        const u = (name) => reliefUniform(name, relief.uniforms[name].value);
        const variant = variantOf(relief), entries = ['mrTraceHit', 'mrShadowTexelSize', ...(this.selfShadow ? ['mrSelfShadow'] : [])];
        this._mrTexelSize = (inputs) => glue(variant, 'mrShadowTexelSize', inputs, entries);
        this._mrBasicShadows = builder.renderer.shadowMap.type === THREE.BasicShadowMap;
        const inputs = traceInputs(builder, relief);
        // The trace, once a pixel, into a property of its own (kHit): three builds the
        // overrides in a context of their own, where a variable of the trace would be
        // declared (and traced) a second time.
        this._mrTrace = glue(variant, 'mrTraceHit', {...inputs, worldToCamera: u('mrWorldToCamera'), ...albedoInputs(this.albedoMap)}, entries);
        // selfShadow: the shadow ray from that hit towards a light (mrSelfShadow reads the pixel
        // mrTraceHit left), the same textures' nodes (one binding each).
        this._mrSelfShadow = this.selfShadow ?
            (light) => glue(variant, 'mrSelfShadow', {heights: inputs.heights, windows: inputs.windows, cameraToWorld: u('mrCameraToWorld'), light}, entries) : null;
        this._mrDepth = tracedDepth(builder, relief, kHit.element(0).w);
        this.normalNode = kHit.element(1).xyz;
        return super.setup(builder);
    }

    // three's shadow of `lightNode`'s light at the hit (the light's colour times its shadow map's
    // lookup, AnalyticLightNode's shadowColorNode), looked up at the hit moved along its normal
    // by the map's reach times its texel's world size there, as the WebGL entry's
    // three_material.glsl moves vDirectionalShadowCoord, vSpotLightCoord and vPointShadowCoord
    // (docs/three.md, "Shadow acne"): half a texel's diagonal for BasicShadowMap's nearest
    // texel, three's PCF radius (shadow.radius) plus a diagonal for its filtered lookups. How:
    // three's ShadowNode looks up at its context's shadowPositionWorld where there is one
    // (ShadowBaseNode.setupShadowPosition), to which it adds the light's normalBias as on any
    // mesh; the light's shadowed colour is built in a context that gives it, per light.
    receivedShadow(lightNode) {
        const light = lightNode.light, shadow = light.shadow;
        const reach = this._mrBasicShadows ? float(Math.SQRT1_2) : reference('radius', 'float', shadow).add(Math.SQRT2);
        const texel = this._mrTexelSize({m: lightShadowMatrix(light), p: positionWorld, mapSize: reference('mapSize', 'vec2', shadow),
                                         point: float(light.isPointLight ? 1 : 0)});
        return context(lightNode.shadowColorNode, {shadowPositionWorld: positionWorld.add(normalWorld.mul(reach.mul(texel)))});
    }

    // three's physical lighting, each direct light dimmed by the self-shadow (selfShadow).
    setupLightingModel(builder) {
        return this._mrSelfShadow ? new ReliefLightingModel(this._mrSelfShadow) : super.setupLightingModel(builder);
    }

    // The first step of three's fragment stage (NodeMaterial.setup): the pixel traced into
    // kHit, and discarded where it shows nothing (a discarded fragment lights nothing).
    setupClipping(builder) {
        kHit.assign(this._mrTrace).toStack();
        If(kHit.element(0).w.lessThan(0), () => {
            Discard();
        });
        return super.setupClipping(builder);
    }

    // The map's colours (albedoMap) multiply three's diffuse colour, as three_material.glsl's
    // MR_ALBEDO_MAP does right after three sets it.
    setupDiffuseColor(builder) {
        super.setupDiffuseColor(builder);
        if (this.albedoMap) diffuseColor.assign(vec4(diffuseColor.rgb.mul(kHit.element(2).xyz), diffuseColor.a));
    }

    // Never silent: an exhausted traversal shows magenta (three_material.glsl's last line).
    setupOutput(builder, outputNode) {
        return select(kHit.element(1).w.greaterThan(0.5), vec4(1, 0, 1, 1), super.setupOutput(builder, outputNode));
    }

    copy(source) {
        super.copy(source);
        this.albedoMap = source.albedoMap ?? null;
        this.selfShadow = source.selfShadow ?? false;
        return this;
    }
}

// three's PhysicalLightingModel (MeshStandardNodeMaterial's) with the library's hard self-shadow
// on each direct light, as the WebGL entry's patch multiplies three's directLight.color by
// mrSelfShadowDirection or mrSelfShadowPoint right after three's getDirectionalLightInfo,
// getPointLightInfo or getSpotLightInfo (materials.js): the light's colour, three's shadow
// map already in it, times `selfShadow(light)` (mrSelfShadow: 1 lit, 0 shadowed) for a
// directional light (the unit direction towards it three lights with, view space, w 0) and a
// point or spot light (its view position, w 1). Other lights (rect area: directRectArea, not
// direct) as three lights them.
class ReliefLightingModel extends THREE.PhysicalLightingModel {
    constructor(selfShadow) {
        super();
        this.mrSelfShadow = selfShadow;
    }

    direct(data, builder) {
        const light = data.lightNode && data.lightNode.light;
        let toLight = null;
        if (light && light.isDirectionalLight) toLight = vec4(data.lightDirection, 0);
        else if (light && (light.isPointLight || light.isSpotLight)) toLight = vec4(lightViewPosition(light), 1);
        const lightColor = toLight ? data.lightColor.mul(this.mrSelfShadow(toLight).toVar()) : data.lightColor;
        super.direct({...data, lightColor}, builder);
    }
}

// The matrix the glue's depth is made with under a logarithmic depth buffer (u.mrDepthMatrix,
// after reliefFrame): for a perspective camera its clip z / w is the camera-relative world
// point's view depth over the far plane, -z / far (in [0, 1] up to the far plane, as the
// glue's clamp keeps it), its clip w 1; for another camera the view-projection itself.
function depthMatrix(u, camera, perspective) {
    const m = u.mrDepthMatrix.value;
    if (!perspective) return m.copy(u.mrViewProjection.value);
    _toDepth.makeScale(1, 1, -1 / camera.far);
    return m.multiplyMatrices(_toDepth, u.mrWorldToCamera.value);
}
const _toDepth = new THREE.Matrix4();

// A map this entry made (the WebGL entry's textures are its renderer's).
function checkReliefMap(reliefMap, what) {
    if (!(reliefMap instanceof ReliefMap))
        throw new TypeError(`Relief: ${what} must be a ReliefMap of microrelief-three/webgpu's createReliefMap${reliefMap && reliefMap.windows ? ' (this one is the WebGL entry\'s)' : ''}`);
}

// A base this entry draws, as baseShape makes it.
function drawnBase(base) {
    const shape = baseShape(base);
    if (!kWebGPUBases.includes(shape.kind))
        throw new TypeError(`Relief: microrelief-three/webgpu draws the ${kWebGPUBases.join(', ')} bases, not the ${shape.kind}`);
    return shape;
}

// The relief as a three.js object: a THREE.Mesh whose geometry is its proxy box and whose
// material traces it in every pixel the box covers (relief.js's Relief, for a
// WebGPURenderer). Options as there: material (a ReliefShadingNodeMaterial), heightScale,
// base (a row's name, core.kBaseNames: 'plane', 'sphere', ...; or a shape), interpolation ('bilinear'
// or 'biquadratic'), pixelError; each a property too, settable at any time. Its picks
// (raycast, trace, traceRays) are the WebGL entry's: the CPU twin's, by the same host code.
export class Relief extends THREE.Mesh {
    constructor(reliefMap, {material = null, heightScale = 0.1, base = 'plane', interpolation = 'bilinear', pixelError = 0} = {}) {
        requireSupportedThree();
        checkReliefMap(reliefMap, 'the first argument');
        checkHeightScale(heightScale);
        checkInterpolation(interpolation);
        checkPixelError(pixelError);
        const shape = drawnBase(base);
        checkBaseForMap(shape, base, reliefMap);
        if (material !== null && !(material instanceof ReliefShadingNodeMaterial) && !(material instanceof ReliefStandardNodeMaterial))
            throw new TypeError('Relief: the material must be a ReliefShadingNodeMaterial or a ReliefStandardNodeMaterial (microrelief-three/webgpu)');
        super(new THREE.BufferGeometry(), material ?? new ReliefShadingNodeMaterial());
        if (this.material.relief && this.material.relief !== this)
            throw new TypeError('Relief: this material draws another relief (one material a relief in microrelief-three/webgpu so far)');
        this.material.relief = this;
        this.isRelief = true;
        this.type = 'Relief';
        this.uniforms = reliefUniforms(pixelError);
        this.uniforms.mrDepthMatrix = {value: new THREE.Matrix4()};  // depthMatrix's
        this.uniforms.mrHeightScale.value = Math.fround(heightScale);
        this._interpolation = interpolation;
        this.setMapAndBase(reliefMap, shape);
        this.onBeforeRender = (renderer, scene, camera) => {
            // A WebGLRenderer cannot compile a node material (three's own error then says
            // nothing of why): this one line instead, thrown out of its render.
            if (renderer.isWebGLRenderer) throw new TypeError(`Relief: ${kWebGLRendererHere}`);
        };
    }

    // The uniforms for a draw with `camera` in render call `renderId` (three's NodeFrame's):
    // the rays, the camera-relative matrices, the faces that run, the depth's matrix
    // (reliefFrame, boxFaces, depthMatrix), made once a camera and render call, when the
    // uniforms are read for a draw (reliefUniform), not in onBeforeRender: three's WebGPU
    // renderer renders the shadow maps a receiving object's lights need after its
    // onBeforeRender and before its uniforms are read (its lights' updateBefore), and the
    // relief is drawn there too, with each light's camera.
    uniformsFor(camera, renderId) {
        if (this._framedCamera !== camera || this._framedRender !== renderId) {
            const rays = reliefFrame(this, camera, this.uniforms);
            this.uniforms.mrFaces.value = boxFaces(this.box, this.matrixWorld, camera, rays.range);
            depthMatrix(this.uniforms, camera, rays.perspective);
            this._framedCamera = camera;
            this._framedRender = renderId;
        }
        return this.uniforms;
    }

    // The map's and the base's uniforms, the box; the material's program again where the
    // textures or the variant changed (its program binds them).
    setMapAndBase(reliefMap, shape) {
        const rebuild = this._reliefMap !== undefined && (this._reliefMap !== reliefMap || this._base.kind !== shape.kind);
        this._reliefMap = reliefMap;
        this._base = Object.freeze(shape);
        reliefMapUniforms(reliefMap, this.uniforms);
        this.uniforms.mrFrameScale.value.set(...core.frameScale(shape));
        this.updateBox();
        if (rebuild) this.material.needsUpdate = true;
    }

    // The box: relief_host.js's updateReliefBox, as the WebGL entry's.
    updateBox() {
        updateReliefBox(this);
    }

    // Each option is a property too, settable at any time, as in the WebGL entry: the map here,
    // heightScale, pixelError, interpolation and base by relief_host.js (below).
    get reliefMap() {
        return this._reliefMap;
    }

    set reliefMap(reliefMap) {
        checkReliefMap(reliefMap, 'reliefMap');
        checkBaseForMap(this._base, this._base.kind, reliefMap);
        this.setMapAndBase(reliefMap, this._base);
    }

    // three's Raycaster: the relief's own hit, {distance, point, uv (three's convention),
    // normal (object space, as three's Mesh gives it), worldNormal, kind, iterations,
    // object}, traced by the CPU twin in double (twin.js), as the WebGL entry's picks are
    // (relief_host.js: raycastRelief, traceOne, traceRaysOnTwin, both entries' code).
    raycast(raycaster, intersects) {
        raycastRelief(this, raycaster, intersects);
    }

    // The first hit of the world ray origin + t direction (direction unit), t in [near, far],
    // or null for a miss: the WebGL entry's Relief.trace.
    trace(origin, direction, near = 0, far = Infinity, options = {}) {
        return traceOne(this, origin, direction, near, far, options);
    }

    // Many world rays at once, as the WebGL entry's Relief.traceRays takes and returns them;
    // options.on 'auto' or 'cpu' (the CPU twin: this entry has no GPU picks).
    traceRays(origins, directions, ranges = [0, Infinity], {on = 'auto'} = {}) {
        checkRays(origins, directions, ranges, on, ['auto', 'cpu']);
        return traceRaysOnTwin(this, origins, directions, ranges);
    }

    dispose() {
        this.geometry.dispose();
    }

    // heightScale, pixelError, interpolation and base as properties: relief_host.js's, both
    // entries' (a base this entry draws; a new variant: the material's program made again).
    static {
        defineReliefOptions(this.prototype, {shapeOf: drawnBase, variantChanged: (relief) => {
            relief.material.needsUpdate = true;
        }});
    }
}
