// relief_gl.js: the relief in WebGL 2, following the contract an engine follows
// (docs/engine.md) the way src/ follows it for the C++ renderer:
//  * ReliefTextures: the samples R32F (nearest, clamped; repeating in s on a curved base),
//    the windows R16F at GL's mip sizes of W x H, maxmip's aligned levels only where
//    maxmip runs, and the cone map of cone or rcsm only where that method runs: RG16F,
//    linear, clamped: cone's drawn on the GPU (PyramidBuilder.buildConeMap), rcsm's made
//    by the C++ build in WebAssembly (cone_maps.js) (src/gl/ReliefTextures.cpp);
//  * PyramidBuilder: both pyramids built on the GPU by the passes of shaders/pyramid/ as
//    they stand (GLSL ES 3.00), texel for texel what the C++ builder makes
//    (src/gl/PyramidBuilder.cpp): the finest windows in bands of 64 rows through a scratch
//    texture on maps of 256 rows or more, else from the 4 x 4 samples at once; coarser
//    levels from the level below with the sampled range ending there; the top read back
//    and S settled; and cone's conservative cone map from maxmip's quadtree, in bands of
//    32 rows (shaders/pyramid/cone_map.frag);
//  * ReliefRenderer: relief_box.vert and relief.frag (the method, base, interpolation,
//    shadows and albedo as the C++ renderer's #defines), the uniform block
//    MicroreliefParameters filled through relief_layout.js (generated at build time from
//    shaders/relief_parameters.glsl, beside this file in the build tree and an install),
//    the proxy box drawn
//    with front faces from outside and back faces from inside (src/gl/ReliefRenderer.cpp);
//    into an SRGB8_ALPHA8 target as OffscreenTarget's (the GL encodes the linear colour and
//    the background), then shown on the canvas by shaders/web/present.frag.
//
// WebGL 2 renders into R16F only with EXT_color_buffer_float (the builder's passes need it,
// and reading the top back as floats); without it there is no pyramid and the page says so.
import {ShaderFiles, mapCompilerLog} from './shader_source.js';
import {kParametersSize, writeParameters} from './relief_layout.js';
import * as core from './relief_core.js';
import {reliefDefines, reliefFrame} from './relief_frame.js';
import * as scene from './scene.js';

const kBandRows = 64, kBandsFrom = 4 * kBandRows;
// Rows a draw of the cone map (PyramidBuilder::buildConeMap's kConeBandRows): each fragment
// walks a quadtree, thousands of reads where the map is rough, and a long draw can lose
// the context to the browser's GPU watchdog.
const kConeBandRows = 32;
const kUnits = {maxPyramid: 0, heightSamples: 1, windowPyramid: 2, albedoMap: 3, coneMap: 4};
const kParametersBinding = 0;

export class GlError extends Error {}

// Compiles and links; a failure names the stage and the file and line (the log mapped).
function compile(gl, type, source, what) {
    const shader = gl.createShader(type);
    gl.shaderSource(shader, source.text);
    gl.compileShader(shader);
    if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) {
        const log = mapCompilerLog(gl.getShaderInfoLog(shader) || '', source.files);
        gl.deleteShader(shader);
        throw new GlError(`${what}: the ${type === gl.VERTEX_SHADER ? 'vertex' : 'fragment'} shader does not compile as GLSL ${source.version}:\n${log}`);
    }
    const log = gl.getShaderInfoLog(shader);
    if (log && log.trim()) console.warn(`${what}: ${mapCompilerLog(log, source.files)}`);
    return shader;
}

function link(gl, vertex, fragment, what) {
    const program = gl.createProgram();
    gl.attachShader(program, vertex);
    gl.attachShader(program, fragment);
    gl.linkProgram(program);
    if (!gl.getProgramParameter(program, gl.LINK_STATUS)) {
        const log = gl.getProgramInfoLog(program);
        gl.deleteProgram(program);
        throw new GlError(`${what}: the program does not link:\n${log}`);
    }
    return program;
}

// The map's textures (src/gl/ReliefTextures.cpp) for `samples` (W x H floats, row 0 first).
export class ReliefTextures {
    constructor(gl, samples, width, height, wrapU) {
        const maxSize = gl.getParameter(gl.MAX_TEXTURE_SIZE);
        if (width > maxSize || height > maxSize)
            throw new GlError(`${width}x${height} is larger than this GPU's MAX_TEXTURE_SIZE (${maxSize})`);
        this.gl = gl;
        this.size = [width, height];
        this.wrapU = wrapU;
        this.levelSizes = core.windowLevelSizes(width, height);
        this.maxHeight = 0;
        let largest = 0;
        for (const h of samples) largest = Math.max(largest, h);
        this.maxSample = largest;
        this.scaleExponent = core.initialScaleExponent(largest);

        gl.activeTexture(gl.TEXTURE0);
        gl.pixelStorei(gl.UNPACK_ALIGNMENT, 4);
        this.windows = ReliefTextures.pyramid(gl, this.levelSizes);
        this.samples = gl.createTexture();
        gl.bindTexture(gl.TEXTURE_2D, this.samples);
        gl.texImage2D(gl.TEXTURE_2D, 0, gl.R32F, width, height, 0, gl.RED, gl.FLOAT, samples);
        ReliefTextures.samplerState(gl, gl.NEAREST, 0, wrapU);
        this.aligned = null;
        this.cones = {conservative: null, relaxed: null};  // by scene.methodConeMap's kind
    }

    // An empty R16F pyramid of `sizes` (GL's mip chain of its first size).
    static pyramid(gl, sizes) {
        const texture = gl.createTexture();
        gl.bindTexture(gl.TEXTURE_2D, texture);
        gl.texStorage2D(gl.TEXTURE_2D, sizes.length, gl.R16F, sizes[0][0], sizes[0][1]);
        ReliefTextures.samplerState(gl, gl.NEAREST_MIPMAP_NEAREST, sizes.length - 1, false);
        return texture;
    }

    static samplerState(gl, minFilter, maxLevel, repeatS) {
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, minFilter);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, repeatS ? gl.REPEAT : gl.CLAMP_TO_EDGE);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_BASE_LEVEL, 0);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAX_LEVEL, maxLevel);
    }

    alignedSizes() {
        return core.maxMipLevelSizes(this.size[0], this.size[1]);
    }

    // mr_ReliefMap's numbers for the multilevel method's windows, or maxmip's quadtree.
    shape(maxMip) {
        const sizes = maxMip ? this.alignedSizes() : this.levelSizes;
        return {size: this.size, pyramidSize: sizes[0], levelCount: sizes.length, maxHeight: this.maxHeight};
    }

    // An RG16F cone map texture of the map's size (ReliefTextures::allocateConeMap):
    // linear, clamped; `texels` its halves (apex, ratio) per texel, row 0 first, as
    // coneMapHalfTexels lays them out, or null to leave it for the GPU to draw.
    static coneMap(gl, width, height, texels) {
        const texture = gl.createTexture();
        gl.activeTexture(gl.TEXTURE0);
        gl.bindTexture(gl.TEXTURE_2D, texture);
        gl.pixelStorei(gl.UNPACK_ALIGNMENT, 4);
        gl.texImage2D(gl.TEXTURE_2D, 0, gl.RG16F, width, height, 0, gl.RG, gl.HALF_FLOAT, texels);
        ReliefTextures.samplerState(gl, gl.LINEAR, 0, false);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
        return texture;
    }

    // The cone map of `kind` the relief draws with (ReliefTextures::addConeMap): `texture`,
    // one of coneMap's; the one before is deleted.
    setConeMap(kind, texture) {
        if (this.cones[kind]) this.gl.deleteTexture(this.cones[kind]);
        this.cones[kind] = texture;
    }

    // A cone map made on the CPU: `texels` as coneMap takes them.
    uploadConeMap(kind, texels) {
        const [width, height] = this.size;
        if (texels.length !== 2 * width * height) throw new GlError(`the ${kind} cone map has ${texels.length / 2} texels, not ${width} x ${height}`);
        this.setConeMap(kind, ReliefTextures.coneMap(this.gl, width, height, texels));
    }

    // A cone map's texels as the GPU holds them, read back (RG16F renders with
    // EXT_color_buffer_float): [apex, ratio] per texel as floats, row 0 first. For tests.
    readConeMap(kind) {
        const gl = this.gl, [width, height] = this.size;
        if (!this.cones[kind]) return null;
        const framebuffer = gl.createFramebuffer();
        gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
        gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, this.cones[kind], 0);
        const rgba = new Float32Array(4 * width * height);
        gl.readPixels(0, 0, width, height, gl.RGBA, gl.FLOAT, rgba);
        gl.bindFramebuffer(gl.FRAMEBUFFER, null);
        gl.deleteFramebuffer(framebuffer);
        const texels = new Float32Array(2 * width * height);
        for (let k = 0; k < width * height; ++k) {
            texels[2 * k] = rgba[4 * k];
            texels[2 * k + 1] = rgba[4 * k + 1];
        }
        return texels;
    }

    // Deletes the textures; the object holds none after.
    dispose() {
        for (const t of [this.samples, this.windows, this.aligned, this.cones.conservative, this.cones.relaxed])
            if (t) this.gl.deleteTexture(t);
        this.samples = this.windows = this.aligned = null;
        this.cones = {conservative: null, relaxed: null};
    }
}

// The pyramids built on the GPU (src/gl/PyramidBuilder.cpp), from shaders/pyramid/.
export class PyramidBuilder {
    static async create(gl, files, shaderRoot) {
        const builder = new PyramidBuilder(gl, files, shaderRoot);
        builder.vertex = compile(gl, gl.VERTEX_SHADER, await files.assemble(shaderRoot + 'pyramid/pass.vert', '300 es'),
                                 'pyramid (pass)');
        builder.windowFinest = await builder.pass('window_finest.frag', 'pyramid (finest windows)');
        builder.windowBlocks = await builder.pass('window_blocks.frag', 'pyramid (windows of bounds)');
        builder.windowLevel = await builder.pass('window_level.frag', 'pyramid (windows)');
        builder.alignedFinest = await builder.pass('finest_level.frag', 'pyramid (finest aligned)');
        builder.alignedLevel = await builder.pass('aligned_level.frag', 'pyramid (aligned)');
        const u = (program, name) => gl.getUniformLocation(program, name);
        builder.finest = [builder.windowFinest, builder.alignedFinest].map((p) => ({
            program: p, mapSize: u(p, 'mapSize'), wrapU: u(p, 'wrapU'), scaleExponent: u(p, 'scaleExponent'),
        }));
        builder.alignedOrigin = u(builder.alignedFinest, 'texelOrigin');
        builder.blocksMapSize = u(builder.windowBlocks, 'mapSize');
        builder.blocksFirstRow = u(builder.windowBlocks, 'firstRow');
        builder.windowsLevel = u(builder.windowLevel, 'level');
        for (const [p, name] of [[builder.windowFinest, 'heights'], [builder.alignedFinest, 'heights'],
                                 [builder.windowLevel, 'windows'], [builder.windowBlocks, 'bounds'],
                                 [builder.alignedLevel, 'aligned']]) {
            gl.useProgram(p);
            gl.uniform1i(u(p, name), 0);
        }
        builder.vertexArray = gl.createVertexArray();
        builder.framebuffer = gl.createFramebuffer();
        return builder;
    }

    constructor(gl, files, shaderRoot) {
        this.gl = gl;
        this.files = files;
        this.shaderRoot = shaderRoot;
        this.vertex = null;  // the passes' vertex shader, compiled once
        this.scratch = null;
        this.scratchWidth = 0;
        this.conePass = null;  // a promise of cone's map pass (coneProgram)
    }

    // The pass shaders/pyramid/`file` linked with the shared vertex shader (`what` names it
    // in errors).
    async pass(file, what) {
        const root = this.shaderRoot;
        const source = await this.files.assemble(root + 'pyramid/' + file, '300 es', [], [root]);
        return link(this.gl, this.vertex, compile(this.gl, this.gl.FRAGMENT_SHADER, source, what), what);
    }

    // Cone's map pass, linked when first asked for (most pages never draw cone): one
    // promise, however many ask while its source is fetched; asked again after a failure.
    coneProgram() {
        const gl = this.gl;
        const u = (program, name) => gl.getUniformLocation(program, name);
        this.conePass ??= this.pass('cone_map.frag', 'cone map').then((program) => {
            gl.useProgram(program);
            gl.uniform1i(u(program, 'heights'), 0);
            gl.uniform1i(u(program, 'aligned'), 1);
            return {program, mapSize: u(program, 'mapSize'), levelCount: u(program, 'levelCount'),
                    scaleExponent: u(program, 'scaleExponent')};
        }, (e) => {
            this.conePass = null;
            throw e;
        });
        return this.conePass;
    }

    // Every texel of the pyramids of `textures`, then its top and S, settled as
    // PyramidBuilder::settleScale settles it (relief_core.js): where the top asks for another
    // S than the texels were drawn with, every texel again with that S.
    build(textures) {
        const settled = core.settleScale(textures.scaleExponent, (s) => {
            textures.scaleExponent = s;
            this.drawAll(textures);
            return this.readTop(textures);
        });
        textures.scaleExponent = settled.scaleExponent;
        textures.maxHeight = settled.maxHeight;
    }

    // maxmip's aligned pyramid, made and built (with the windows' S).
    addAligned(textures) {
        if (textures.aligned) return;
        const gl = this.gl;
        gl.activeTexture(gl.TEXTURE0);
        textures.aligned = ReliefTextures.pyramid(gl, textures.alignedSizes());
        this.begin();
        this.drawAligned(textures);
        this.end();
    }

    // Cone's conservative cone map of `textures` (PyramidBuilder::buildConeMap), drawn from
    // maxmip's quadtree (made for it and dropped after where the page had none): the CPU
    // build's walk per texel, every rounding towards narrower cones (cone_map.frag), so no
    // ratio above the C++ build's. `cone`: the pass, as coneProgram gives it. Returns the
    // RG16F texture, its draws queued, not done (`finished` says when).
    buildConeMap(textures, cone) {
        const gl = this.gl, [width, height] = textures.size;
        // The walk's stack holds 22 levels: past any browser's textures, but said.
        if (Math.max(width, height) > 2 ** 21) throw new GlError('a cone map is built on the GPU for maps of at most 2^21 a side');
        const hadQuadtree = Boolean(textures.aligned);
        this.addAligned(textures);
        const cones = ReliefTextures.coneMap(gl, width, height, null);
        this.begin();
        this.attach(cones, 0);
        if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE) {
            this.end();
            gl.deleteTexture(cones);
            throw new GlError('this WebGL cannot render into the RG16F cone map (incomplete framebuffer)');
        }
        gl.useProgram(cone.program);
        gl.uniform2i(cone.mapSize, width, height);
        gl.uniform1i(cone.levelCount, textures.alignedSizes().length);
        gl.uniform1i(cone.scaleExponent, textures.scaleExponent);
        gl.activeTexture(gl.TEXTURE1);
        gl.bindTexture(gl.TEXTURE_2D, textures.aligned);
        gl.activeTexture(gl.TEXTURE0);
        gl.bindTexture(gl.TEXTURE_2D, textures.samples);
        for (let row = 0; row < height; row += kConeBandRows) this.draw(0, row, width, Math.min(row + kConeBandRows, height));
        this.attach(null, 0);
        gl.activeTexture(gl.TEXTURE1);
        gl.bindTexture(gl.TEXTURE_2D, null);
        gl.activeTexture(gl.TEXTURE0);
        this.end();
        if (!hadQuadtree) {
            gl.deleteTexture(textures.aligned);  // the GL keeps it till the draws are done
            textures.aligned = null;
        }
        return cones;
    }

    // A promise that resolves once the GL has done what was queued so far (a fence, polled
    // between tasks, so the page keeps answering while the GPU works); rejects with GlError
    // where the context was lost meanwhile (the fence's status is then null, also after
    // the context is restored).
    finished() {
        const gl = this.gl, fence = gl.fenceSync(gl.SYNC_GPU_COMMANDS_COMPLETE, 0);
        gl.flush();
        return new Promise((resolve, reject) => {
            const poll = () => {
                const status = gl.isContextLost() ? null : gl.getSyncParameter(fence, gl.SYNC_STATUS);
                if (status === null) {
                    reject(new GlError('the WebGL context was lost'));
                } else if (status === gl.SIGNALED) {
                    gl.deleteSync(fence);
                    resolve();
                } else {
                    setTimeout(poll, 5);
                }
            };
            poll();
        });
    }

    begin() {
        const gl = this.gl;
        gl.bindFramebuffer(gl.FRAMEBUFFER, this.framebuffer);
        gl.bindVertexArray(this.vertexArray);
        gl.activeTexture(gl.TEXTURE0);
        gl.disable(gl.CULL_FACE);
        gl.disable(gl.DEPTH_TEST);
    }

    end() {
        const gl = this.gl;
        gl.bindFramebuffer(gl.FRAMEBUFFER, null);
        gl.bindVertexArray(null);
    }

    drawAll(textures) {
        this.begin();
        this.drawWindows(textures);
        if (textures.aligned) this.drawAligned(textures);
        this.end();
    }

    attach(texture, level) {
        const gl = this.gl;
        gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, texture, level);
    }

    // The viewport is the rectangle [x0, x1) x [y0, y1): gl_FragCoord names the texels.
    draw(x0, y0, x1, y1) {
        this.gl.viewport(x0, y0, x1 - x0, y1 - y0);
        this.gl.drawArrays(this.gl.TRIANGLES, 0, 3);
    }

    useFinest(k, textures) {
        const gl = this.gl, f = this.finest[k];
        gl.useProgram(f.program);
        gl.uniform2i(f.mapSize, textures.size[0], textures.size[1]);
        gl.uniform1i(f.wrapU, textures.wrapU ? 1 : 0);
        gl.uniform1i(f.scaleExponent, textures.scaleExponent);
        gl.bindTexture(gl.TEXTURE_2D, textures.samples);
    }

    drawWindowBands(textures) {
        const gl = this.gl;
        const [width, height] = textures.size;
        if (!this.scratch || this.scratchWidth !== width) {
            if (this.scratch) gl.deleteTexture(this.scratch);
            this.scratch = gl.createTexture();
            gl.bindTexture(gl.TEXTURE_2D, this.scratch);
            gl.texStorage2D(gl.TEXTURE_2D, 1, gl.R16F, width, kBandRows + 1);
            gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
            gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
            gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAX_LEVEL, 0);
            this.scratchWidth = width;
        }
        for (let row = 0; row < height; row += kBandRows) {
            const rows = Math.min(kBandRows, height - row);
            this.attach(this.scratch, 0);
            this.useFinest(1, textures);
            gl.uniform2i(this.alignedOrigin, 0, row);
            this.draw(0, 0, width, rows + 1);
            this.attach(textures.windows, 0);
            gl.useProgram(this.windowBlocks);
            gl.uniform2i(this.blocksMapSize, width, height);
            gl.uniform1i(this.blocksFirstRow, row);
            gl.bindTexture(gl.TEXTURE_2D, this.scratch);
            this.draw(0, row, width, row + rows);
        }
        gl.useProgram(this.alignedFinest);
        gl.uniform2i(this.alignedOrigin, 0, 0);
    }

    drawWindows(textures) {
        const gl = this.gl;
        const sizes = textures.levelSizes;
        for (let level = 0; level < sizes.length; ++level) {
            this.attach(textures.windows, level);
            if (level === 0) {
                if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE)
                    throw new GlError('this WebGL cannot render into the R16F max pyramid (incomplete framebuffer)');
                if (textures.size[1] >= kBandsFrom) {
                    this.drawWindowBands(textures);
                    continue;
                }
                this.useFinest(0, textures);
            } else {
                gl.useProgram(this.windowLevel);
                gl.uniform1i(this.windowsLevel, level - 1);
                gl.bindTexture(gl.TEXTURE_2D, textures.windows);
                // Read level k - 1, write level k: only the level read is sampled.
                gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_BASE_LEVEL, 0);
                gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAX_LEVEL, level - 1);
            }
            this.draw(0, 0, sizes[level][0], sizes[level][1]);
        }
        gl.bindTexture(gl.TEXTURE_2D, textures.windows);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAX_LEVEL, sizes.length - 1);
    }

    drawAligned(textures) {
        const gl = this.gl;
        const sizes = textures.alignedSizes();
        for (let level = 0; level < sizes.length; ++level) {
            this.attach(textures.aligned, level);
            if (level === 0) {
                this.useFinest(1, textures);
            } else {
                gl.useProgram(this.alignedLevel);
                gl.bindTexture(gl.TEXTURE_2D, textures.aligned);
                gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_BASE_LEVEL, level - 1);
                gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAX_LEVEL, level - 1);
            }
            this.draw(0, 0, sizes[level][0], sizes[level][1]);
        }
        gl.bindTexture(gl.TEXTURE_2D, textures.aligned);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_BASE_LEVEL, 0);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAX_LEVEL, sizes.length - 1);
    }

    // The top texel, read back as a float (the bound divided by 2^S).
    readTop(textures) {
        const gl = this.gl;
        gl.bindFramebuffer(gl.FRAMEBUFFER, this.framebuffer);
        this.attach(textures.windows, textures.levelSizes.length - 1);
        const top = new Float32Array(4);
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.FLOAT, top);
        this.attach(null, 0);
        gl.bindFramebuffer(gl.FRAMEBUFFER, null);
        return top[0];
    }
}

// The relief program's variants and their draw (src/gl/ReliefShader.cpp,
// src/gl/ReliefRenderer.cpp), and the picture's target and presentation.
export class ReliefRenderer {
    static async create(gl, shaderRoot) {
        if (!gl.getExtension('EXT_color_buffer_float'))
            throw new GlError('this browser\'s WebGL 2 has no EXT_color_buffer_float: the max pyramid is built on the GPU into R16F textures, which WebGL 2 can render into only with it');
        const r = new ReliefRenderer(gl, shaderRoot);
        r.depthClamp = gl.getExtension('EXT_depth_clamp');
        r.builder = await PyramidBuilder.create(gl, r.files, shaderRoot);
        const version = '300 es';
        const vertex = compile(gl, gl.VERTEX_SHADER, await r.files.assemble(shaderRoot + 'pyramid/pass.vert', version), 'present');
        const fragment = compile(gl, gl.FRAGMENT_SHADER,
                                 await r.files.assemble(shaderRoot + 'web/present.frag', version, [], [shaderRoot]), 'present');
        r.present = link(gl, vertex, fragment, 'present');
        gl.useProgram(r.present);
        gl.uniform1i(gl.getUniformLocation(r.present, 'picture'), 0);
        r.emptyArray = gl.createVertexArray();
        r.parameterBuffer = gl.createBuffer();
        r.boxArray = gl.createVertexArray();
        r.boxVertices = gl.createBuffer();
        r.boxIndices = gl.createBuffer();
        // Outward-facing counter-clockwise triangles, two per face (ReliefRenderer::uploadBox).
        gl.bindVertexArray(r.boxArray);
        gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, r.boxIndices);
        gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, new Uint16Array([0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6, 0, 4, 5, 0, 5, 1,
                                                                1, 5, 6, 1, 6, 2, 2, 6, 7, 2, 7, 3, 3, 7, 4, 3, 4, 0]), gl.STATIC_DRAW);
        gl.bindBuffer(gl.ARRAY_BUFFER, r.boxVertices);
        gl.bufferData(gl.ARRAY_BUFFER, 24 * 4, gl.DYNAMIC_DRAW);
        gl.enableVertexAttribArray(0);
        gl.vertexAttribPointer(0, 3, gl.FLOAT, false, 12, 0);
        gl.bindVertexArray(null);
        return r;
    }

    constructor(gl, shaderRoot) {
        this.gl = gl;
        this.shaderRoot = shaderRoot;
        this.files = new ShaderFiles();
        this.programs = new Map();
        this.textures = null;
        this.albedo = null;
        this.target = null;
    }

    // The variant of relief.frag for `config` {method, base, interpolation, shadows,
    // albedoMap}, compiled once (ReliefShader's constructor).
    async program(config) {
        const key = JSON.stringify(config);
        if (!this.programs.has(key)) this.programs.set(key, this.compileProgram(config));
        try {
            return await this.programs.get(key);
        } catch (e) {
            this.programs.delete(key);  // a later call tries again (a shader fixed meanwhile)
            throw e;
        }
    }

    async compileProgram(c) {
        const gl = this.gl, version = '300 es';
        const what = `relief (${c.method}, ${c.base}, ${c.interpolation})`;
        const defines = reliefDefines(c);
        const vertex = compile(gl, gl.VERTEX_SHADER, await this.files.assemble(this.shaderRoot + 'relief_box.vert', version), what);
        const fragment = compile(gl, gl.FRAGMENT_SHADER, await this.files.assemble(this.shaderRoot + 'relief.frag', version, defines), what);
        const program = link(gl, vertex, fragment, what);
        gl.useProgram(program);
        for (const [name, unit] of Object.entries(kUnits)) gl.uniform1i(gl.getUniformLocation(program, name), unit);
        const block = gl.getUniformBlockIndex(program, 'MicroreliefParameters');
        if (block === gl.INVALID_INDEX) throw new GlError(`${what}: the program has no MicroreliefParameters block`);
        gl.uniformBlockBinding(program, block, kParametersBinding);
        const size = gl.getActiveUniformBlockParameter(program, block, gl.UNIFORM_BLOCK_DATA_SIZE);
        if (size !== kParametersSize) throw new GlError(`${what}: MicroreliefParameters is ${size} bytes, not the ${kParametersSize} the page fills`);
        return program;
    }

    // A new map (W x H samples): its textures and pyramids, replacing the old ones only
    // once they are made. `maxMip`: maxmip's pyramid too.
    setMap(samples, width, height, wrapU, maxMip) {
        const textures = new ReliefTextures(this.gl, samples, width, height, wrapU);
        try {
            this.builder.build(textures);
            if (maxMip) this.builder.addAligned(textures);
        } catch (e) {
            textures.dispose();
            throw e;
        }
        if (this.textures) this.textures.dispose();
        this.textures = textures;
    }

    // Cone's conservative cone map of the current map, drawn on the GPU: a promise of true
    // once it is done and in the map's textures (at once where it is there), of false where
    // another map came meanwhile. One build at a time for a map: the caller's to keep.
    async addConservativeConeMap() {
        const textures = this.textures;
        if (textures.cones.conservative) return true;
        const cone = await this.builder.coneProgram();  // fetched first: another map may come meanwhile
        if (this.textures !== textures) return false;
        const texture = this.builder.buildConeMap(textures, cone);
        try {
            await this.builder.finished();
        } catch (e) {
            this.gl.deleteTexture(texture);
            throw e;
        }
        if (this.textures !== textures) {
            this.gl.deleteTexture(texture);
            return false;
        }
        textures.setConeMap('conservative', texture);
        return true;
    }

    ensureMaxMip() {
        if (this.textures && !this.textures.aligned) this.builder.addAligned(this.textures);
    }

    // An 8-bit sRGB albedo (RGBA bytes, row 0 at v = 0), or null (AlbedoTexture).
    setAlbedo(image) {
        const gl = this.gl;
        if (this.albedo) gl.deleteTexture(this.albedo);
        this.albedo = null;
        if (!image) return;
        this.albedo = gl.createTexture();
        gl.activeTexture(gl.TEXTURE0);
        gl.bindTexture(gl.TEXTURE_2D, this.albedo);
        gl.pixelStorei(gl.UNPACK_ALIGNMENT, 4);
        gl.texImage2D(gl.TEXTURE_2D, 0, gl.SRGB8_ALPHA8, image.width, image.height, 0, gl.RGBA, gl.UNSIGNED_BYTE, image.rgba);
        gl.generateMipmap(gl.TEXTURE_2D);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR_MIPMAP_LINEAR);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.REPEAT);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.REPEAT);
    }

    // The picture's target: an SRGB8_ALPHA8 texture of the drawing buffer's size.
    ensureTarget(width, height) {
        const gl = this.gl;
        if (this.target && this.target.width === width && this.target.height === height) return;
        if (this.target) {
            gl.deleteTexture(this.target.texture);
            gl.deleteFramebuffer(this.target.framebuffer);
        }
        const texture = gl.createTexture();
        gl.bindTexture(gl.TEXTURE_2D, texture);
        gl.texStorage2D(gl.TEXTURE_2D, 1, gl.SRGB8_ALPHA8, width, height);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
        const framebuffer = gl.createFramebuffer();
        gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
        gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, texture, 0);
        const status = gl.checkFramebufferStatus(gl.FRAMEBUFFER);
        gl.bindFramebuffer(gl.FRAMEBUFFER, null);
        if (status !== gl.FRAMEBUFFER_COMPLETE) throw new GlError(`the picture's framebuffer is incomplete (status 0x${status.toString(16)})`);
        this.target = {texture, framebuffer, width, height};
    }

    // Draws `view` (scene.js's view) with `program` into the target, then onto the canvas.
    // `pixels` is the drawing buffer's [W, H].
    draw(program, view, pixels) {
        const gl = this.gl, t = this.textures;
        const maxMip = scene.methodReadsMaxPyramid(view.method);
        // The box, its faces, the camera and the parameters (relief_frame.js, shared with
        // relief_gpu.js).
        const {corners, outside, values} = reliefFrame(view, t.shape(maxMip), t.maxSample, pixels);
        const p = writeParameters(values);
        gl.bindBuffer(gl.UNIFORM_BUFFER, this.parameterBuffer);
        gl.bufferData(gl.UNIFORM_BUFFER, p, gl.STREAM_DRAW);
        gl.bindBuffer(gl.ARRAY_BUFFER, this.boxVertices);
        gl.bufferSubData(gl.ARRAY_BUFFER, 0, corners);

        this.ensureTarget(pixels[0], pixels[1]);
        gl.bindFramebuffer(gl.FRAMEBUFFER, this.target.framebuffer);
        gl.viewport(0, 0, pixels[0], pixels[1]);
        // The linear background, encoded by the GL as the target is sRGB (OffscreenTarget::clear).
        gl.clearBufferfv(gl.COLOR, 0, new Float32Array([...view.background, 1]));

        gl.useProgram(program);
        gl.bindBufferBase(gl.UNIFORM_BUFFER, kParametersBinding, this.parameterBuffer);
        const bind = (unit, texture) => {
            gl.activeTexture(gl.TEXTURE0 + unit);
            gl.bindTexture(gl.TEXTURE_2D, texture);
        };
        bind(kUnits.maxPyramid, t.aligned);
        bind(kUnits.heightSamples, t.samples);
        bind(kUnits.windowPyramid, t.windows);
        bind(kUnits.albedoMap, this.albedo);
        const cones = scene.methodConeMap(view.method);
        bind(kUnits.coneMap, cones ? t.cones[cones] : null);
        gl.enable(gl.CULL_FACE);
        gl.frontFace(gl.CCW);
        gl.cullFace(outside ? gl.BACK : gl.FRONT);
        gl.disable(gl.DEPTH_TEST);  // one convex box, one face a pixel: nothing to test against
        if (this.depthClamp) gl.enable(this.depthClamp.DEPTH_CLAMP_EXT);
        gl.bindVertexArray(this.boxArray);
        gl.drawElements(gl.TRIANGLES, 36, gl.UNSIGNED_SHORT, 0);
        gl.disable(gl.CULL_FACE);

        // Onto the canvas: the target read back linear, encoded again (8-bit values come
        // back exactly: decoding and encoding in float move them by far less than a level).
        gl.bindFramebuffer(gl.FRAMEBUFFER, null);
        gl.viewport(0, 0, pixels[0], pixels[1]);
        gl.useProgram(this.present);
        bind(0, this.target.texture);
        gl.bindVertexArray(this.emptyArray);
        gl.drawArrays(gl.TRIANGLES, 0, 3);
        gl.bindVertexArray(null);
        for (let unit = kUnits.coneMap; unit >= 0; --unit) bind(unit, null);
    }
}
