// equal.js: tests/webgpu/entry.frag's GLSL in WebGL 2 and naga's WGSL of it in WebGPU, the
// same rays through the same map, every answer compared pixel by pixel (glsl_wgsl_equal.py
// serves this folder with CASE.es.frag, CASE.wgsl and map.json beside it, and judges).
// runCase(name, base) -> JSON {stats, png}: png shows the WebGL 2 colour, the WebGPU colour
// and, in white, the pixels where any output differs in any bit.
const Wv = 160, Hv = 120;  // viewport
let data = null;
async function loadData() {
    if (!data) data = await (await fetch('map.json', {cache: 'no-store'})).json();
    return data;
}
const text = async (f) => {
    const r = await fetch(f, {cache: 'no-store'});
    if (!r.ok) throw new Error(`${f}: ${r.status}`);
    return r.text();
};
const sub = (a, b) => a.map((x, i) => x - b[i]);
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => {
    const l = Math.hypot(...a);
    return a.map((x) => x / l);
};
const scale = (a, s) => a.map((x) => x * s);

// The scene for a base: frame scale, height scale, camera.
function scene(base) {
    const d = data, cam = {plane: [0.6, 0.5, 0.75], cylinder: [1.1, 0.5, 0.9], ellipsoid: [1.0, 0.7, 0.8]}[base];
    const frame = {plane: [1, 1, 1], cylinder: [0.45, 0.5, 0.45], ellipsoid: [0.5, 0.4, 0.45]}[base];
    const target = base === 'plane' ? [0, 0.03, 0] : [0, 0, 0];
    const f = norm(sub(target, cam)), r = norm(cross(f, [0, 1, 0])), u = cross(r, f);
    const tanHalf = Math.tan(0.5 * 45 * Math.PI / 180), aspect = Wv / Hv;
    const pyr = base === 'plane' ? d.flat : d.wrapped;
    const buf = new ArrayBuffer(320), fl = new Float32Array(buf), it = new Int32Array(buf);
    for (const o of [0, 16])
        for (let k = 0; k < 4; ++k) fl[o + 5 * k] = 1;  // identity matrices
    fl.set([...frame, 0.03], 32);
    fl.set([d.W, d.H, pyr.maxHeight, 0], 36);
    it.set([d.W, d.H, pyr.levels.length, 0], 40);
    const heightToObject = base === 'plane' ? 0.03 : 0.03 * (frame[0] + frame[1] + frame[2]) / 3;
    fl.set([0.01, 100, 0.03, heightToObject], 44);
    fl.set([...norm([0.8, 0.35, 0.3]), 0], 48);
    fl.set([...cam, 0], 52);
    fl.set([0, 0, 0, 0], 56);
    fl.set([0, 0, 0, 0], 60);
    fl.set([...f, 0], 64);
    fl.set([...scale(r, tanHalf * aspect), 0], 68);
    fl.set([...scale(u, tanHalf), 0], 72);
    fl.set([Wv, Hv, 0, 0], 76);
    return {buf, pyr};
}

function albedoTexels() {
    const n = 16, px = new Uint8Array(n * n * 4);
    for (let y = 0; y < n; ++y)
        for (let x = 0; x < n; ++x) {
            const o = 4 * (y * n + x), c = ((x >> 2) + (y >> 2)) & 1;
            px.set([c ? 220 : 60 + 10 * x, 120 + 8 * y, c ? 40 : 200, 255], o);
        }
    return {n, px};
}

async function renderWebGL(esSource, sc) {
    const canvas = new OffscreenCanvas(Wv, Hv), gl = canvas.getContext('webgl2');
    if (!gl.getExtension('EXT_color_buffer_float')) throw new Error('no EXT_color_buffer_float');
    const sh = (type, src) => {
        const s = gl.createShader(type);
        gl.shaderSource(s, src);
        gl.compileShader(s);
        if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error('GLSL: ' + gl.getShaderInfoLog(s));
        return s;
    };
    const prog = gl.createProgram();
    gl.attachShader(
        prog,
        sh(gl.VERTEX_SHADER,
           '#version 300 es\nvoid main() { vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2); gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0); }'));
    gl.attachShader(prog, sh(gl.FRAGMENT_SHADER, esSource));
    gl.linkProgram(prog);
    if (!gl.getProgramParameter(prog, gl.LINK_STATUS)) throw new Error('link: ' + gl.getProgramInfoLog(prog));
    gl.useProgram(prog);
    const block = gl.getUniformBlockIndex(prog, 'Params');
    const size = gl.getActiveUniformBlockParameter(prog, block, gl.UNIFORM_BLOCK_DATA_SIZE);
    if (size !== 320) throw new Error(`Params is ${size} bytes`);
    gl.uniformBlockBinding(prog, block, 0);
    const ubo = gl.createBuffer();
    gl.bindBuffer(gl.UNIFORM_BUFFER, ubo);
    gl.bufferData(gl.UNIFORM_BUFFER, sc.buf, gl.STATIC_DRAW);
    gl.bindBufferBase(gl.UNIFORM_BUFFER, 0, ubo);
    const tex = (unit, name) => {
        const t = gl.createTexture();
        gl.activeTexture(gl.TEXTURE0 + unit);
        gl.bindTexture(gl.TEXTURE_2D, t);
        gl.uniform1i(gl.getUniformLocation(prog, name), unit);
        return t;
    };
    tex(0, 'mrHeights');
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.R32F, data.W, data.H, 0, gl.RED, gl.FLOAT, new Float32Array(data.samples));
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    tex(1, 'mrWindows');
    sc.pyr.levels.forEach(
        (l, k) =>
            gl.texImage2D(gl.TEXTURE_2D, k, gl.R16F, l.w, l.h, 0, gl.RED, gl.HALF_FLOAT, new Uint16Array(l.halves)));
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAX_LEVEL, sc.pyr.levels.length - 1);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST_MIPMAP_NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    tex(2, 'mrAlbedo');
    const a = albedoTexels();
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA8, a.n, a.n, 0, gl.RGBA, gl.UNSIGNED_BYTE, a.px);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.REPEAT);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.REPEAT);
    const fb = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
    for (let i = 0; i < 4; ++i) {
        const t = gl.createTexture();
        gl.activeTexture(gl.TEXTURE7);
        gl.bindTexture(gl.TEXTURE_2D, t);
        gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, Wv, Hv);
        gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0 + i, gl.TEXTURE_2D, t, 0);
    }
    gl.drawBuffers([0, 1, 2, 3].map((i) => gl.COLOR_ATTACHMENT0 + i));
    gl.viewport(0, 0, Wv, Hv);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    const out = [];
    for (let i = 0; i < 4; ++i) {
        const px = new Float32Array(Wv * Hv * 4);
        gl.readBuffer(gl.COLOR_ATTACHMENT0 + i);
        gl.readPixels(0, 0, Wv, Hv, gl.RGBA, gl.FLOAT, px);
        out.push(px);
    }
    const e = gl.getError();
    if (e) throw new Error('GL error ' + e);
    return out;
}

let device = null;
async function webgpuDevice() {
    if (!device) {
        const ad = await navigator.gpu.requestAdapter();
        device = await ad.requestDevice({requiredLimits: {maxColorAttachmentBytesPerSample: 64}});
    }
    return device;
}

async function renderWebGPU(wgsl, sc) {
    await webgpuDevice();
    device.pushErrorScope('validation');
    const module = device.createShaderModule({code: wgsl});
    const info = await module.getCompilationInfo();
    const errors = info.messages.filter((m) => m.type === 'error');
    if (errors.length)
        throw new Error('WGSL: ' + errors.map((m) => `${m.lineNum}:${m.linePos} ${m.message}`).join('; '));
    const vs = device.createShaderModule({
        code:
            '@vertex fn main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f { let p = vec2f(f32((i << 1u) & 2u), f32(i & 2u)); return vec4f(p * 2.0 - 1.0, 0.0, 1.0); }'
    });
    const F = GPUShaderStage.FRAGMENT;
    const bgl = device.createBindGroupLayout({
        entries: [
            {binding: 0, visibility: F, texture: {sampleType: 'unfilterable-float'}},
            {binding: 1, visibility: F, texture: {sampleType: 'unfilterable-float'}},
            {binding: 2, visibility: F, texture: {sampleType: 'float'}},
            {binding: 3, visibility: F, buffer: {type: 'uniform'}},
            {binding: 4, visibility: F, sampler: {type: 'non-filtering'}},
            {binding: 5, visibility: F, sampler: {type: 'filtering'}}
        ]
    });
    const pipeline = device.createRenderPipeline({
        layout: device.createPipelineLayout({bindGroupLayouts: [bgl]}),
        vertex: {module: vs, entryPoint: 'main'},
        fragment: {module, entryPoint: 'main', targets: [0, 1, 2, 3].map(() => ({format: 'rgba32float'}))}
    });
    const heights = device.createTexture({
        size: [data.W, data.H],
        format: 'r32float',
        usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST
    });
    device.queue.writeTexture(
        {texture: heights}, new Float32Array(data.samples), {bytesPerRow: 4 * data.W}, [data.W, data.H]);
    const windows = device.createTexture({
        size: [data.W, data.H],
        mipLevelCount: sc.pyr.levels.length,
        format: 'r16float',
        usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST
    });
    sc.pyr.levels.forEach(
        (l, k) => device.queue.writeTexture(
            {texture: windows, mipLevel: k}, new Uint16Array(l.halves), {bytesPerRow: 2 * l.w}, [l.w, l.h]));
    const a = albedoTexels();
    const albedo = device.createTexture(
        {size: [a.n, a.n], format: 'rgba8unorm', usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST});
    device.queue.writeTexture({texture: albedo}, a.px, {bytesPerRow: 4 * a.n}, [a.n, a.n]);
    const ubo = device.createBuffer({size: 320, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST});
    device.queue.writeBuffer(ubo, 0, sc.buf);
    const bind = device.createBindGroup({
        layout: bgl,
        entries: [
            {binding: 0, resource: heights.createView()}, {binding: 1, resource: windows.createView()},
            {binding: 2, resource: albedo.createView()}, {binding: 3, resource: {buffer: ubo}}, {
                binding: 4,
                resource: device.createSampler({magFilter: 'nearest', minFilter: 'nearest', mipmapFilter: 'nearest'})
            },
            {
                binding: 5,
                resource: device.createSampler(
                    {magFilter: 'linear', minFilter: 'linear', addressModeU: 'repeat', addressModeV: 'repeat'})
            }
        ]
    });
    const targets = [0, 1, 2, 3].map(() => device.createTexture({
        size: [Wv, Hv],
        format: 'rgba32float',
        usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.COPY_SRC
    }));
    const enc = device.createCommandEncoder();
    const pass = enc.beginRenderPass({
        colorAttachments:
            targets.map((t) => ({view: t.createView(), loadOp: 'clear', storeOp: 'store', clearValue: [0, 0, 0, 0]}))
    });
    pass.setPipeline(pipeline);
    pass.setBindGroup(0, bind);
    pass.draw(3);
    pass.end();
    const reads = targets.map((t) => {
        const b = device.createBuffer({size: Wv * Hv * 16, usage: GPUBufferUsage.COPY_DST | GPUBufferUsage.MAP_READ});
        enc.copyTextureToBuffer({texture: t}, {buffer: b, bytesPerRow: Wv * 16}, [Wv, Hv]);
        return b;
    });
    device.queue.submit([enc.finish()]);
    const err = await device.popErrorScope();
    if (err) throw new Error('WebGPU: ' + err.message);
    const out = [];
    for (const b of reads) {
        await b.mapAsync(GPUMapMode.READ);
        out.push(new Float32Array(b.getMappedRange().slice(0)));
        b.unmap();
    }
    return out;
}

function compare(g, w) {
    const s = {
        pixels: Wv * Hv,
        hitsGl: 0,
        hitsGpu: 0,
        kindDiffer: 0,
        exhaustedGl: 0,
        exhaustedGpu: 0,
        tMaxRel: 0,
        tDiffer: 0,
        normalMax: 0,
        hardDiffer: 0,
        softMax: 0,
        colorMax: 0,
        iterationsDiffer: 0,
        stopLevelDiffer: 0,
        positionMax: 0,
        bitIdentical: 0,
        shadowedGl: 0,
        penumbraGl: 0
    };
    for (let p = 0; p < Wv * Hv; ++p) {
        const o = 4 * p, kg = g[0][o + 1], kw = w[0][o + 1];
        let same = true;
        for (let i = 0; i < 4; ++i)
            for (let c = 0; c < 4; ++c)
                if (!Object.is(g[i][o + c], w[i][o + c])) same = false;
        if (same) s.bitIdentical++;
        if (kg) s.hitsGl++;
        if (kw) s.hitsGpu++;
        if (g[0][o + 2]) s.exhaustedGl++;
        if (w[0][o + 2]) s.exhaustedGpu++;
        if (g[3][o] !== w[3][o]) s.iterationsDiffer++;
        if (g[3][o + 1] !== w[3][o + 1]) s.stopLevelDiffer++;
        if (kg !== kw) {
            s.kindDiffer++;
            continue;
        }
        if (!kg) continue;
        const tg = g[0][o], tw = w[0][o], rel = Math.abs(tg - tw) / Math.abs(tg);
        if (tg !== tw) s.tDiffer++;
        s.tMaxRel = Math.max(s.tMaxRel, rel);
        if (g[0][o + 3] !== w[0][o + 3]) s.hardDiffer++;
        if (g[0][o + 3] === 0) s.shadowedGl++;
        if (g[1][o + 3] > 0 && g[1][o + 3] < 1) s.penumbraGl++;
        for (let c = 0; c < 3; ++c) s.normalMax = Math.max(s.normalMax, Math.abs(g[1][o + c] - w[1][o + c]));
        s.softMax = Math.max(s.softMax, Math.abs(g[1][o + 3] - w[1][o + 3]));
        for (let c = 0; c < 4; ++c) s.colorMax = Math.max(s.colorMax, Math.abs(g[2][o + c] - w[2][o + c]));
        for (let c = 2; c < 4; ++c) s.positionMax = Math.max(s.positionMax, Math.abs(g[3][o + c] - w[3][o + c]));
    }
    return s;
}

// Both colours side by side (rows as stored: WebGL's from the bottom, WebGPU's from the top), then
// the pixels that differ at all in white.
function picture(g, w) {
    const c = new OffscreenCanvas(3 * Wv, Hv), ctx = c.getContext('2d'), img = ctx.createImageData(3 * Wv, Hv);
    const enc = (x) => Math.round(255 * Math.min(1, Math.max(0, x)) ** (1 / 2.2));
    for (let y = 0; y < Hv; ++y)
        for (let x = 0; x < Wv; ++x) {
            const o = 4 * (y * Wv + x), row = Hv - 1 - y;
            for (const [k, src] of [[0, g], [1, w]]) {
                const d = 4 * (row * 3 * Wv + k * Wv + x);
                const miss = !src[0][o + 1];
                img.data.set(
                    miss ? [30, 30, 40, 255] : [enc(src[2][o]), enc(src[2][o + 1]), enc(src[2][o + 2]), 255], d);
            }
            let same = true;
            for (let i = 0; i < 4; ++i)
                for (let ch = 0; ch < 4; ++ch)
                    if (!Object.is(g[i][o + ch], w[i][o + ch])) same = false;
            img.data.set(same ? [0, 0, 0, 255] : [255, 255, 255, 255], 4 * (row * 3 * Wv + 2 * Wv + x));
        }
    ctx.putImageData(img, 0, 0);
    return c.convertToBlob()
        .then((b) => b.arrayBuffer())
        .then((ab) => btoa(String.fromCharCode(...new Uint8Array(ab))));
}

globalThis.runCase = async (name, base) => {
    await loadData();
    const sc = scene(base);
    const g = await renderWebGL(await text(`${name}.es.frag`), sc);
    const w = await renderWebGPU(await text(`${name}.wgsl`), sc);
    return JSON.stringify({stats: compare(g, w), png: await picture(g, w)});
};

// The messages Chromium's WebGPU (Tint) gives for the WGSL module in `file`, each
// "type line:column text": the package's built variants compile without one.
globalThis.compileWgsl = async (file) => {
    const module = (await webgpuDevice()).createShaderModule({code: await text(file)});
    const info = await module.getCompilationInfo();
    return JSON.stringify(info.messages.map((m) => `${m.type} ${m.lineNum}:${m.linePos} ${m.message}`));
};
