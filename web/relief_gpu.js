// relief_gpu.js: the relief in WebGPU, from the same GLSL as relief_gl.js draws in WebGL 2:
// shaders/relief_box.vert and shaders/relief.frag assembled by shader_source.js as the WebGL
// path assembles them (the same #defines), then translated to WGSL in the page by naga's
// GLSL front end (naga-wasm, staged by the build into web/generated/naga/ from
// microrelief-three's `npm ci`; docs/webgpu.md says why naga). No WGSL is written by hand:
// what WGSL needs of the GLSL is set before it or mended in its text (wgslSource, below):
//  * the library's read hooks (texture_reads.glsl, albedo.glsl, relaxed_cone_step.glsl) for
//    separate textures and samplers, as microrelief-three's WGSL sets them: the heights and
//    the pyramid read by texelFetch on a texture2D without a sampler (WGSL's textureLoad);
//  * relief.frag's `uniform sampler2D NAME;` lines as texture2D bindings, the uniform block
//    given its binding (group 0, binding 0), gl_DepthRange as a constant ([0, 1]: WebGPU's);
//  * shaders/web/present.frag's read of the target turned upside down (below).
// The page's frame (the box, its faces, the camera, the parameters) is relief_frame.js's, as
// the WebGL path's. The pyramids are the WebGL path's: built by relief_gl.js's PyramidBuilder
// (the passes of shaders/pyramid/, on the page's WebGL 2 context) and read back into WebGPU
// textures, texel for texel; the albedo's levels likewise (WebGPU makes no mipmaps).
//
// WebGPU's framebuffer counts rows from the top, GL's from the bottom, and relief.frag makes
// each pixel's ray from gl_FragCoord. To cast every pixel's ray bit for bit as the WebGL path
// does, the relief is drawn upside down into its target (the clip transform's y row negated:
// the fragment shader reads viewProjection only for the depth, its z and w rows), so that a
// pixel's gl_FragCoord is GL's, and the present pass reads the target upside down. The clip
// depth is taken from GL's [-1, 1] to WebGPU's [0, 1] (z' = (z + w) / 2, depthZeroToOne 1), so
// the same box is clipped (unclipped where the adapter offers depth-clip-control, as the WebGL
// path uses EXT_depth_clamp where offered).
//
// What this path draws (gpuRefusal): the multilevel method, on every base, with both last
// levels, every debug view, shadows off, hard or soft, with or without the albedo. The peers
// (their cone maps and maxmip's quadtree are WebGL's alone so far) are refused in one line.
import {ShaderFiles, mapCompilerLog} from './shader_source.js';
import {kParametersSize, writeParameters} from './relief_layout.js';
import {reliefDefines, reliefFrame} from './relief_frame.js';
import * as scene from './scene.js';

export class GpuError extends Error {}

// Why this path cannot draw `view`, in one line, or '' where it can.
export function gpuRefusal(view) {
    if (view.method !== 'multilevel')
        return `the page's WebGPU path draws the multilevel method only, not method=${view.method} (drawn in WebGL 2: api=webgl2, or no api key)`;
    return '';
}

// The bindings of group 0, as wgslSource declares them.
const kBinding = {parameters: 0, windowPyramid: 1, heightSamples: 2, maxPyramid: 3, albedoMap: 4, coneMap: 5,
                  albedoSampler: 6, coneSampler: 7, coarseStart: 8 /* under MICRORELIEF_COARSE_TILE: never here */,
                  picture: 1 /* present.frag's: the relief's target */};

// What goes before the library (after #version 450): the hooks for separate textures and
// samplers (microrelief-three's scripts/wgsl.mjs sets the same reads: kWebGpuHooks), and
// gl_DepthRange, which naga does not know, as WebGPU's (viewport depth [0, 1]).
const kPrelude = `#extension GL_EXT_samplerless_texture_functions : require
#define MICRORELIEF_SAMPLER texture2D
#define MICRORELIEF_TEXTURE_GATHER 0
#define MICRORELIEF_READ_SAMPLE(heights, texel) texelFetch(heights, texel, 0).r
#define MICRORELIEF_READ_PYRAMID(pyramid, texel, level, levelSize) texelFetch(pyramid, texel, level).r
layout(set = 0, binding = ${kBinding.albedoSampler}) uniform sampler mrAlbedoSampler;
layout(set = 0, binding = ${kBinding.coneSampler}) uniform sampler mrConeSampler;
#define MICRORELIEF_ALBEDO_TEXTURE texture2D
#define MICRORELIEF_ALBEDO_SAMPLED(t) sampler2D(t, mrAlbedoSampler)
#define MICRORELIEF_READ_RELAXED_CONE(cones, p, size) textureLod(sampler2D(cones, mrConeSampler), (p) / (size), 0.0).rg
struct mr_DepthRangeParameters { float near; float far; float diff; };
const mr_DepthRangeParameters mrDepthRange = mr_DepthRangeParameters(0.0, 1.0, 1.0);
#define gl_DepthRange mrDepthRange
#define gl_VertexID gl_VertexIndex
`;

// present.frag's read of the target, turned upside down (the relief is drawn so: above). A
// function-like macro is not expanded again inside its own expansion, so the inner
// texelFetch is GLSL's.
const kPresentPrelude = `#define texelFetch(t, p, l) texelFetch(t, ivec2((p).x, textureSize(t, 0).y - 1 - (p).y), l)
`;

// `source` (a ShaderSource assembled for '450') as naga takes it: the prelude after
// #version, each `uniform sampler2D NAME;` a texture2D at its binding, the uniform block at
// binding 0. Throws GpuError where a line it mends is not there (the GLSL changed).
export function wgslSource(source, prelude = '') {
    const lines = source.text.split('\n');
    if (!/^#version 450$/.test(lines[0])) throw new GpuError(`expected #version 450 first, not '${lines[0]}'`);
    let text = [lines[0], kPrelude + prelude, ...lines.slice(1)].join('\n');
    text = text.replace(/^uniform sampler2D (\w+);/gm, (line, name) => {
        const binding = kBinding[name];
        if (binding === undefined) throw new GpuError(`no WebGPU binding for the texture ${name}`);
        return `layout(set = 0, binding = ${binding}) uniform texture2D ${name};`;
    });
    return text.replace(/^layout\(std140\) uniform MicroreliefParameters/m,
                        `layout(set = 0, binding = ${kBinding.parameters}, std140) uniform MicroreliefParameters`);
}

// naga's WGSL of `glsl` for `stage` ('vertex', 'fragment'); `what` and `files` name it in
// an error (naga's first lines, the assembled file and line mapped back).
function translate(naga, glsl, stage, what, files) {
    try {
        const module = naga.parseGlsl(glsl, {stage});
        try {
            const info = naga.validate(module);
            try {
                return naga.writeWgsl(module, info);
            } finally {
                info.free();
            }
        } finally {
            module.free();
        }
    } catch (e) {
        const report = String(e.formatted || e.message || e).split('\n').filter((l) => l.trim()).slice(0, 8).join('\n');
        throw new GpuError(`${what}: naga cannot translate the ${stage} shader to WGSL (${e.kind || 'error'}):\n${mapCompilerLog(report, files)}`);
    }
}

// The WebGPU device, or why there is none (one line): {adapter, device} or {why}.
export async function requestGpu() {
    if (!navigator.gpu) return {why: 'this browser has no WebGPU (navigator.gpu)'};
    let adapter;
    try {
        adapter = await navigator.gpu.requestAdapter();
    } catch (e) {
        return {why: `this browser's WebGPU gives no adapter (${e.message})`};
    }
    if (!adapter) return {why: 'this browser\'s WebGPU gives no adapter'};
    const features = adapter.features.has('depth-clip-control') ? ['depth-clip-control'] : [];
    try {
        // The adapter's largest textures, as the WebGL path has GL's MAX_TEXTURE_SIZE (the
        // default device stops at 8192 a side).
        const requiredLimits = {maxTextureDimension2D: adapter.limits.maxTextureDimension2D};
        return {adapter, device: await adapter.requestDevice({requiredFeatures: features, requiredLimits})};
    } catch (e) {
        return {why: `this browser's WebGPU adapter gives no device (${e.message})`};
    }
}

// A GL texture's `level` read back (w x h): Float32Array of its red channel (`float`), or
// the RGBA bytes.
function readGlLevel(gl, texture, level, w, h, float) {
    const framebuffer = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, texture, level);
    const status = gl.checkFramebufferStatus(gl.FRAMEBUFFER);
    let out = null;
    if (status === gl.FRAMEBUFFER_COMPLETE) {
        if (float) {
            const rgba = new Float32Array(4 * w * h);
            gl.readPixels(0, 0, w, h, gl.RGBA, gl.FLOAT, rgba);
            out = new Float32Array(w * h);
            for (let k = 0; k < w * h; ++k) out[k] = rgba[4 * k];
        } else {
            out = new Uint8Array(4 * w * h);
            gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, out);
        }
    }
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.deleteFramebuffer(framebuffer);
    if (!out) throw new GpuError(`cannot read a texture back from WebGL (framebuffer status 0x${status.toString(16)})`);
    return out;
}

const levelSizes = (w, h) => {
    const sizes = [[w, h]];
    while (w > 1 || h > 1) sizes.push([(w = Math.max(1, w >> 1)), (h = Math.max(1, h >> 1))]);
    return sizes;
};

export class GpuReliefRenderer {
    // A renderer on `canvas` with `gpu` (requestGpu's) and the page's WebGL renderer `glRenderer`
    // (relief_gl.js: its map textures, pyramids and albedo are read from it).
    static async create(canvas, gpu, glRenderer, shaderRoot) {
        const r = new GpuReliefRenderer(canvas, gpu, glRenderer, shaderRoot);
        let naga;
        try {
            naga = await import('./generated/naga/index.js');
            await naga.init();
        } catch (e) {
            throw new GpuError(`the page's WebGPU path needs naga-wasm (the GLSL to WGSL translator, staged from microrelief-three's npm ci): ${e.message}`);
        }
        r.naga = naga;
        r.context = canvas.getContext('webgpu');
        if (!r.context) throw new GpuError('this canvas gives no WebGPU context');
        r.format = navigator.gpu.getPreferredCanvasFormat();
        r.context.configure({device: r.device, format: r.format, alphaMode: 'opaque'});
        const device = r.device;
        device.lost.then((info) => r.onLost?.(info.message));
        const texture = (sampleType, visibility = GPUShaderStage.FRAGMENT) => ({visibility, texture: {sampleType}});
        r.layout = device.createBindGroupLayout({entries: [
            {binding: kBinding.parameters, visibility: GPUShaderStage.VERTEX | GPUShaderStage.FRAGMENT, buffer: {type: 'uniform'}},
            {binding: kBinding.windowPyramid, ...texture('unfilterable-float')},
            {binding: kBinding.heightSamples, ...texture('unfilterable-float')},
            {binding: kBinding.maxPyramid, ...texture('unfilterable-float')},
            {binding: kBinding.albedoMap, ...texture('float')},
            {binding: kBinding.coneMap, ...texture('float')},
            {binding: kBinding.albedoSampler, visibility: GPUShaderStage.FRAGMENT, sampler: {type: 'filtering'}},
            {binding: kBinding.coneSampler, visibility: GPUShaderStage.FRAGMENT, sampler: {type: 'filtering'}},
        ]});
        r.parameterBuffer = device.createBuffer({size: kParametersSize, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST});
        r.boxVertices = device.createBuffer({size: 24 * 4, usage: GPUBufferUsage.VERTEX | GPUBufferUsage.COPY_DST});
        // Outward-facing counter-clockwise triangles, two per face (ReliefRenderer::uploadBox).
        const indices = new Uint16Array([0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6, 0, 4, 5, 0, 5, 1,
                                         1, 5, 6, 1, 6, 2, 2, 6, 7, 2, 7, 3, 3, 7, 4, 3, 4, 0]);
        r.boxIndices = device.createBuffer({size: indices.byteLength, usage: GPUBufferUsage.INDEX | GPUBufferUsage.COPY_DST});
        device.queue.writeBuffer(r.boxIndices, 0, indices);
        // The albedo trilinear and repeating (AlbedoTexture's sampler state), the cone map linear, clamped.
        r.albedoSampler = device.createSampler({magFilter: 'linear', minFilter: 'linear', mipmapFilter: 'linear',
                                                addressModeU: 'repeat', addressModeV: 'repeat'});
        r.coneSampler = device.createSampler({magFilter: 'linear', minFilter: 'linear'});
        // What a variant binds where it reads nothing (maxmip's quadtree, the cone map, no albedo).
        r.unused = {
            float: device.createTexture({size: [1, 1], format: 'r32float', usage: GPUTextureUsage.TEXTURE_BINDING}),
            colour: device.createTexture({size: [1, 1], format: 'rgba8unorm', usage: GPUTextureUsage.TEXTURE_BINDING}),
        };
        r.present = await r.presentPipeline();
        return r;
    }

    constructor(canvas, gpu, glRenderer, shaderRoot) {
        this.canvas = canvas;
        this.device = gpu.device;
        this.depthClip = gpu.device.features.has('depth-clip-control');
        this.gl = glRenderer;
        this.shaderRoot = shaderRoot;
        this.files = new ShaderFiles();
        this.programs = new Map();
        this.mapTextures = null;  // {from: the GL ReliefTextures read, samples, windows}
        this.albedoTexture = null;  // {from: the GL albedo texture read, texture}
        this.target = null;
        this.onLost = null;
    }

    // A shader module of `file` (under shaders/) for `stage`, its GLSL assembled with `defines`
    // and translated by naga; Chromium's compiler's messages are errors too.
    async module(file, stage, defines, what, prelude = '') {
        const source = await this.files.assemble(this.shaderRoot + file, '450', defines, [this.shaderRoot]);
        const wgsl = translate(this.naga, wgslSource(source, prelude), stage, what, source.files);
        const module = this.device.createShaderModule({code: wgsl, label: `${what} (${stage})`});
        const info = await module.getCompilationInfo();
        const errors = info.messages.filter((m) => m.type === 'error');
        if (errors.length)
            throw new GpuError(`${what}: WebGPU does not compile naga's WGSL of the ${stage} shader: ${errors.slice(0, 3).map((m) => `${m.lineNum}:${m.linePos} ${m.message}`).join('; ')}`);
        return module;
    }

    async presentPipeline() {
        const device = this.device;
        const vertex = await this.module('pyramid/pass.vert', 'vertex', [], 'present');
        const fragment = await this.module('web/present.frag', 'fragment', [], 'present', kPresentPrelude);
        const layout = device.createBindGroupLayout({entries: [
            {binding: kBinding.picture, visibility: GPUShaderStage.FRAGMENT, texture: {sampleType: 'unfilterable-float'}},
        ]});
        return {
            layout,
            pipeline: await device.createRenderPipelineAsync({
                layout: device.createPipelineLayout({bindGroupLayouts: [layout]}),
                vertex: {module: vertex, entryPoint: 'main'},
                fragment: {module: fragment, entryPoint: 'main', targets: [{format: this.format}]},
                primitive: {topology: 'triangle-list'},
            }),
        };
    }

    // The pipeline of relief.frag's variant for `config` (relief_gl.js's program: the same
    // #defines), made once.
    async program(config) {
        const key = JSON.stringify(config);
        if (!this.programs.has(key)) this.programs.set(key, this.makeProgram(config));
        try {
            return await this.programs.get(key);
        } catch (e) {
            this.programs.delete(key);
            throw e;
        }
    }

    async makeProgram(c) {
        const what = `relief in WebGPU (${c.method}, ${c.base}, ${c.interpolation})`;
        const defines = reliefDefines(c);
        const vertex = await this.module('relief_box.vert', 'vertex', defines, what);
        const fragment = await this.module('relief.frag', 'fragment', defines, what);
        const pipeline = (cullMode) => this.device.createRenderPipelineAsync({
            layout: this.device.createPipelineLayout({bindGroupLayouts: [this.layout]}),
            vertex: {module: vertex, entryPoint: 'main',
                     buffers: [{arrayStride: 12, attributes: [{shaderLocation: 0, offset: 0, format: 'float32x3'}]}]},
            // relief.frag's other outputs (position, statistics, shadow) have no target here.
            fragment: {module: fragment, entryPoint: 'main', targets: [{format: 'rgba8unorm-srgb'}]},
            // The box drawn upside down: its counter-clockwise faces are clockwise on the target.
            primitive: {topology: 'triangle-list', frontFace: 'cw', cullMode, ...(this.depthClip ? {unclippedDepth: true} : {})},
            // WebGPU wants a depth target where the shader writes the depth; the page draws the
            // relief alone, so nothing is tested (the WebGL path disables the depth test).
            depthStencil: {format: 'depth32float', depthWriteEnabled: false, depthCompare: 'always'},
        });
        const [outside, inside] = await Promise.all([pipeline('back'), pipeline('front')]);
        return {outside, inside};
    }

    // The GL renderer's map (samples, windows) as WebGPU textures, read back once a map.
    mapFrom(glTextures) {
        if (this.mapTextures?.from === glTextures) return this.mapTextures;
        const gl = this.gl.gl, device = this.device, [w, h] = glTextures.size;
        const most = device.limits.maxTextureDimension2D;
        if (w > most || h > most) throw new GpuError(`${w}x${h} is larger than this WebGPU device's textures (${most} a side)`);
        const upload = (data, size, level, texture) =>
            device.queue.writeTexture({texture, mipLevel: level}, data, {bytesPerRow: 4 * size[0]}, size);
        const samples = device.createTexture({size: [w, h], format: 'r32float',
                                              usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST});
        upload(readGlLevel(gl, glTextures.samples, 0, w, h, true), [w, h], 0, samples);
        const sizes = glTextures.levelSizes;
        const windows = device.createTexture({size: sizes[0], mipLevelCount: sizes.length, format: 'r32float',
                                              usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST});
        sizes.forEach((size, level) => upload(readGlLevel(gl, glTextures.windows, level, size[0], size[1], true), size, level, windows));
        if (this.mapTextures) {
            this.mapTextures.samples.destroy();
            this.mapTextures.windows.destroy();
        }
        this.mapTextures = {from: glTextures, samples, windows};
        return this.mapTextures;
    }

    // The GL renderer's albedo and its mipmaps (generateMipmap's) as a WebGPU texture, or null.
    albedoFrom(glAlbedo, image) {
        if (!glAlbedo) return null;
        if (this.albedoTexture?.from === glAlbedo) return this.albedoTexture.texture;
        const gl = this.gl.gl, sizes = levelSizes(image.width, image.height);
        const texture = this.device.createTexture({size: sizes[0], mipLevelCount: sizes.length, format: 'rgba8unorm-srgb',
                                                   usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST});
        sizes.forEach((size, level) => this.device.queue.writeTexture({texture, mipLevel: level}, readGlLevel(gl, glAlbedo, level, size[0], size[1], false),
                                                                      {bytesPerRow: 4 * size[0]}, size));
        this.albedoTexture?.texture.destroy();
        this.albedoTexture = {from: glAlbedo, texture};
        return texture;
    }

    ensureTarget(width, height) {
        if (this.target && this.target.width === width && this.target.height === height) return;
        this.target?.texture.destroy();
        this.target?.depth.destroy();
        const texture = this.device.createTexture({size: [width, height], format: 'rgba8unorm-srgb',
                                                   usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.TEXTURE_BINDING});
        const depth = this.device.createTexture({size: [width, height], format: 'depth32float', usage: GPUTextureUsage.RENDER_ATTACHMENT});
        this.target = {texture, depth, width, height,
                       present: this.device.createBindGroup({layout: this.present.layout, entries: [
                           {binding: kBinding.picture, resource: texture.createView()},
                       ]})};
    }

    // Draws `view` with `program` (program's) into the target, then onto the canvas; `pixels`
    // the canvas's [W, H]; `albedoImage` the albedo's image where the GL renderer has one.
    // Resolves once the GPU is done.
    async draw(program, view, pixels, albedoImage) {
        const device = this.device, glTextures = this.gl.textures;
        device.pushErrorScope('validation');
        const map = this.mapFrom(glTextures);
        const albedo = this.albedoFrom(this.gl.albedo, albedoImage);
        const {corners, outside, values} = reliefFrame(view, glTextures.shape(false), glTextures.maxSample, pixels);
        // The clip transform for WebGPU (above): y negated, z from [-w, w] to [0, w].
        const vp = values.viewProjection.slice();
        for (let c = 0; c < 4; ++c) {
            vp[4 * c + 1] = -vp[4 * c + 1];
            vp[4 * c + 2] = 0.5 * (vp[4 * c + 2] + vp[4 * c + 3]);
        }
        device.queue.writeBuffer(this.parameterBuffer, 0, writeParameters({...values, viewProjection: vp, depthZeroToOne: 1}));
        device.queue.writeBuffer(this.boxVertices, 0, corners);
        this.ensureTarget(pixels[0], pixels[1]);
        const bindings = device.createBindGroup({layout: this.layout, entries: [
            {binding: kBinding.parameters, resource: {buffer: this.parameterBuffer}},
            {binding: kBinding.windowPyramid, resource: map.windows.createView()},
            {binding: kBinding.heightSamples, resource: map.samples.createView()},
            {binding: kBinding.maxPyramid, resource: this.unused.float.createView()},
            {binding: kBinding.albedoMap, resource: (albedo ?? this.unused.colour).createView()},
            {binding: kBinding.coneMap, resource: this.unused.colour.createView()},
            {binding: kBinding.albedoSampler, resource: this.albedoSampler},
            {binding: kBinding.coneSampler, resource: this.coneSampler},
        ]});
        const encoder = device.createCommandEncoder();
        const [r, g, b] = view.background;
        const relief = encoder.beginRenderPass({colorAttachments: [{
            view: this.target.texture.createView(), loadOp: 'clear', storeOp: 'store', clearValue: {r, g, b, a: 1},
        }], depthStencilAttachment: {view: this.target.depth.createView(), depthLoadOp: 'clear', depthClearValue: 1, depthStoreOp: 'discard'}});
        relief.setPipeline(outside ? program.outside : program.inside);
        relief.setBindGroup(0, bindings);
        relief.setVertexBuffer(0, this.boxVertices);
        relief.setIndexBuffer(this.boxIndices, 'uint16');
        relief.drawIndexed(36);
        relief.end();
        const present = encoder.beginRenderPass({colorAttachments: [{
            view: this.context.getCurrentTexture().createView(), loadOp: 'clear', storeOp: 'store', clearValue: {r: 0, g: 0, b: 0, a: 1},
        }]});
        present.setPipeline(this.present.pipeline);
        present.setBindGroup(0, this.target.present);
        present.draw(3);
        present.end();
        device.queue.submit([encoder.finish()]);
        const error = await device.popErrorScope();
        if (error) throw new GpuError(`WebGPU: ${error.message}`);
        await device.queue.onSubmittedWorkDone();
    }
}
