// pyramid.js: a height map's textures as the library reads them (docs/engine.md,
// "Textures"): the samples (R32F, W x H, nearest; u repeating on a curved base) and the
// windows pyramid (R16F, GL's mip sizes of W x H down to 1 x 1, nearest mipmaps, each texel
// a bound of the surface divided by 2^S, exactly a half), built one of two ways, texel for
// texel the same:
//  * on the GPU, with three's own renderer: the passes of shaders/pyramid/ as they stand
//    (window_finest.frag, then window_level.frag for each coarser level), each level drawn
//    into a WebGLRenderTarget of its own and copied into its mip level of the windows
//    texture (copyTextureToTexture: a blit); the top read back as its float's bits through
//    an RGBA8 target, and S settled as the C++ builder settles it (PyramidBuilder::
//    settleScale, in generated/relief_core.js). Rendering into R16F needs
//    EXT_color_buffer_float. Every draw goes through three (render targets, materials,
//    renderer.render), and the renderer's render target is put back: three's state stays
//    three's.
//  * on the CPU: the C++ MaxPyramid itself (src/core/heightmap/MaxPyramid.cpp), compiled to
//    WebAssembly (generated/pyramid_wasm.js), uploaded as halves.
import * as THREE from 'three';

import {glue, pyramid as passes} from '../generated/glsl.js';
import * as core from '../generated/relief_core.js';
import {requireSupportedThree, requireWebGLRenderer} from './three_version.js';
import {checkHeightMap, largestSample, windowLevelsOnCpu} from './map_host.js';
import {loadTwin, releaseTwins, twinBytes} from './twin.js';

// A WebGL that cannot do what was asked (an extension missing, a texture too large).
export class ReliefGpuError extends Error {
    constructor(message) {
        super(message);
        this.name = 'ReliefGpuError';
    }
}

// GL's mip sizes of W x H down to 1 x 1 (MaxPyramid's windowLevelSizes): relief_core.js's.
export const windowLevelSizes = core.windowLevelSizes;

// The map's textures and the numbers mr_ReliefMap takes. Built by createReliefMap.
export class ReliefMap {
    constructor({renderer, heights, windows, width, height, levelSizes, maxHeight, maxSample, scaleExponent, wrapU, builtOn, name}) {
        Object.assign(this, {renderer, heights, windows, width, height, levelSizes, maxHeight, maxSample, scaleExponent, wrapU, builtOn, name});
        this.levelCount = levelSizes.length;
    }

    // GPU memory of the textures, bytes: 4 a sample, 2 a window texel (6.7 a map texel).
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

function samplesTexture(map, wrapU) {
    const texture = new THREE.DataTexture(map.samples, map.width, map.height, THREE.RedFormat, THREE.FloatType);
    texture.internalFormat = 'R32F';
    texture.minFilter = texture.magFilter = THREE.NearestFilter;
    texture.wrapS = wrapU ? THREE.RepeatWrapping : THREE.ClampToEdgeWrapping;
    texture.wrapT = THREE.ClampToEdgeWrapping;
    texture.generateMipmaps = false;
    texture.flipY = false;
    texture.unpackAlignment = 4;
    texture.needsUpdate = true;
    return texture;
}

// An R16F texture with one mip level a window level, filled with `levels` (Uint16Array of
// half bits each) or zeros (to be drawn into).
function windowsTexture(levelSizes, levels = null) {
    const mipmaps = levelSizes.map(([w, h], k) => ({data: levels ? levels[k] : new Uint16Array(w * h), width: w, height: h}));
    const texture = new THREE.DataTexture(null, levelSizes[0][0], levelSizes[0][1], THREE.RedFormat, THREE.HalfFloatType);
    texture.internalFormat = 'R16F';
    texture.mipmaps = mipmaps;
    texture.minFilter = THREE.NearestMipmapNearestFilter;
    texture.magFilter = THREE.NearestFilter;
    texture.wrapS = texture.wrapT = THREE.ClampToEdgeWrapping;
    texture.generateMipmaps = false;
    texture.flipY = false;
    texture.unpackAlignment = 2;
    texture.needsUpdate = true;
    // Once on the GPU the levels are the GPU's: drop the arrays (they would be uploaded
    // again only if someone set needsUpdate).
    texture.onUpdate = () => {
        for (const m of texture.mipmaps) m.data = null;
        texture.onUpdate = null;
    };
    return texture;
}

// ---- the GPU builder ----

function passMaterial(fragment, uniforms) {
    return new THREE.RawShaderMaterial({
        glslVersion: THREE.GLSL3,
        vertexShader: 'precision highp float;\nprecision highp int;\n' + passes.pass,
        fragmentShader: fragment,
        uniforms,
        depthTest: false,
        depthWrite: false,
    });
}

function levelTarget(width, height) {
    const target = new THREE.WebGLRenderTarget(width, height, {
        type: THREE.HalfFloatType, format: THREE.RedFormat, internalFormat: 'R16F',
        minFilter: THREE.NearestFilter, magFilter: THREE.NearestFilter,
        depthBuffer: false, stencilBuffer: false, generateMipmaps: false,
    });
    target.texture.internalFormat = 'R16F';
    return target;
}

// Draws full-viewport passes of shaders/pyramid/ with three's renderer.
class GpuPyramidBuilder {
    constructor(renderer) {
        this.renderer = renderer;
        this.finest = passMaterial(passes.windowFinest, {
            heights: {value: null}, mapSize: {value: new THREE.Vector2()}, wrapU: {value: 0}, scaleExponent: {value: 0},
        });
        this.level = passMaterial(passes.windowLevel, {windows: {value: null}, level: {value: 0}});
        this.readback = passMaterial(glue.pyramidReadback, {source: {value: null}, level: {value: 0}});
        // pass.vert makes its triangle from gl_VertexID: three draws three vertices.
        const geometry = new THREE.BufferGeometry();
        geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(9), 3));
        this.quad = new THREE.Mesh(geometry, this.finest);
        this.quad.frustumCulled = false;
        // A camera three can turn to reversed depth (a renderer with reversedDepthBuffer calls
        // its updateProjectionMatrix, which THREE.Camera lacks); pass.vert ignores it.
        this.camera = new THREE.OrthographicCamera();
    }

    draw(material, target) {
        this.quad.material = material;
        this.renderer.setRenderTarget(target);
        this.renderer.render(this.quad, this.camera);
    }

    // The texels of `texture`'s level `level` (width x height) as floats, through their bits.
    readFloats(texture, level, width, height) {
        const target = new THREE.WebGLRenderTarget(width, height, {depthBuffer: false, generateMipmaps: false});
        try {
            this.readback.uniforms.source.value = texture;
            this.readback.uniforms.level.value = level;
            this.draw(this.readback, target);
            const bytes = new Uint8Array(4 * width * height);
            this.renderer.readRenderTargetPixels(target, 0, 0, width, height, bytes);
            return new Float32Array(bytes.buffer);
        } finally {
            target.dispose();
        }
    }

    // Every level of the windows of `heights` with S = scaleExponent, as render targets.
    drawLevels(heights, width, height, wrapU, scaleExponent, levelSizes) {
        const targets = [];
        try {
            for (let k = 0; k < levelSizes.length; ++k) {
                const target = levelTarget(...levelSizes[k]);
                targets.push(target);
                if (k === 0) {
                    const u = this.finest.uniforms;
                    u.heights.value = heights;
                    u.wrapU.value = wrapU ? 1 : 0;
                    u.scaleExponent.value = scaleExponent;
                    u.mapSize.value.set(width, height);
                    this.draw(this.finest, target);
                } else {
                    // A level of its own, read whole (level 0 of the texture below it): no
                    // texture is read while it is drawn into.
                    this.level.uniforms.windows.value = targets[k - 1].texture;
                    this.level.uniforms.level.value = 0;
                    this.draw(this.level, target);
                }
            }
            return targets;
        } catch (e) {
            for (const t of targets) t.dispose();
            throw e;
        }
    }

    build(map, wrapU) {
        const renderer = this.renderer;
        const previous = [renderer.getRenderTarget(), renderer.getActiveCubeFace(), renderer.getActiveMipmapLevel()];
        const heights = samplesTexture(map, wrapU);
        const levelSizes = core.windowLevelSizes(map.width, map.height);
        let targets = [];
        try {
            // As PyramidBuilder::settleScale (relief_core.js): where the top lies in another
            // binade than S was chosen for, every texel again with the S it asks for.
            const {scaleExponent, maxHeight} = core.settleScale(core.initialScaleExponent(map.maxSample), (s) => {
                for (const t of targets) t.dispose();
                targets = [];  // none held while drawLevels runs (it disposes its own where it throws)
                targets = this.drawLevels(heights, map.width, map.height, wrapU, s, levelSizes);
                return this.readFloats(targets[targets.length - 1].texture, 0, 1, 1)[0];
            });
            const windows = windowsTexture(levelSizes);
            for (let k = 0; k < targets.length; ++k) renderer.copyTextureToTexture(targets[k].texture, windows, null, null, 0, k);
            return {heights, windows, levelSizes, maxHeight, scaleExponent};
        } catch (e) {
            heights.dispose();
            throw e;
        } finally {
            for (const t of targets) t.dispose();
            renderer.setRenderTarget(...previous);
        }
    }

    dispose() {
        for (const m of [this.finest, this.level, this.readback]) m.dispose();
        this.quad.geometry.dispose();
    }
}

const builders = new WeakMap();
function gpuBuilder(renderer) {
    if (!builders.has(renderer)) builders.set(renderer, new GpuPyramidBuilder(renderer));
    return builders.get(renderer);
}

// The red channel of level `level` of `texture` (width x height texels: R16F, R32F, a depth
// texture, ...) as floats, read back exactly through their bits (an RGBA8 target), with
// `renderer`'s render target put back: for tests and tools.
export function readTextureFloats(renderer, texture, level, width, height) {
    const previous = [renderer.getRenderTarget(), renderer.getActiveCubeFace(), renderer.getActiveMipmapLevel()];
    try {
        return gpuBuilder(renderer).readFloats(texture, level, width, height);
    } finally {
        renderer.setRenderTarget(...previous);
    }
}

// The texels of level `level` of a ReliefMap's windows, as floats (bound / 2^S).
export function readWindowLevel(reliefMap, level) {
    const [w, h] = reliefMap.levelSizes[level];
    return readTextureFloats(reliefMap.renderer, reliefMap.windows, level, w, h);
}

// ---- the CPU builder: the C++ MaxPyramid in WebAssembly (map_host.js, shared with the WebGPU entry) ----

async function buildOnCpu(map, wrapU) {
    const {levels, levelSizes, maxHeight, scaleExponent} = await windowLevelsOnCpu(map, wrapU);
    return {heights: samplesTexture(map, wrapU), windows: windowsTexture(levelSizes, levels), levelSizes, maxHeight, scaleExponent};
}

// The textures of `map` ({width, height, samples, name}: heights.js) for `renderer`.
// options: wrapU (true for the curved bases: their u wraps round, and the pyramid's seam
// with it), pyramid: 'auto' (the GPU where WebGL 2 renders into R16F, else the CPU),
// 'gpu' or 'cpu'.
export async function createReliefMap(renderer, map, {wrapU = false, pyramid = 'auto'} = {}) {
    requireSupportedThree();
    requireWebGLRenderer(renderer, 'createReliefMap');
    if (!['auto', 'gpu', 'cpu'].includes(pyramid)) throw new TypeError(`createReliefMap: pyramid '${pyramid}' (expected auto, gpu or cpu)`);
    checkHeightMap(map, 'createReliefMap');
    const name = map.name || 'height map';
    const maxSize = renderer.capabilities.maxTextureSize;
    if (map.width > maxSize || map.height > maxSize)
        throw new ReliefGpuError(`${name}: ${map.width} x ${map.height} is larger than this GPU's MAX_TEXTURE_SIZE (${maxSize})`);
    const maxSample = largestSample(map);
    const renderable = renderer.extensions.has('EXT_color_buffer_float');
    if (pyramid === 'gpu' && !renderable)
        throw new ReliefGpuError('this WebGL 2 has no EXT_color_buffer_float, so it cannot render the max pyramid into R16F textures; pyramid: \'cpu\' (or \'auto\') builds it in WebAssembly instead');
    const onGpu = pyramid === 'gpu' || (pyramid === 'auto' && renderable);
    const twin = loadTwin();  // the picks' CPU twin, where the package has it (twin.js); never rejects
    let built;
    try {
        built = onGpu ? gpuBuilder(renderer).build({...map, maxSample}, wrapU) : await buildOnCpu({...map, name}, wrapU);
    } finally {
        // Settled either way before this returns or throws: a pick after a refused map knows
        // whether the package has a twin, rather than finding it still loading.
        await twin;
    }
    return new ReliefMap({renderer, ...built, width: map.width, height: map.height, maxSample, wrapU, builtOn: onGpu ? 'gpu' : 'cpu', name});
}
