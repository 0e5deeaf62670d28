#!/usr/bin/env node
// wgsl.mjs: the library's GLSL as WGSL, through naga's GLSL front end (the npm package
// naga-wasm, a devDependency of this package): the one place that runs the translator, for
// the package's build (scripts/build.mjs: generated/wgsl.js) and for the tests
// (tests/webgpu/translate.mjs, glsl_wgsl_equal.py, wgsl_generated.mjs). docs/webgpu.md says
// why naga and what it needs of the GLSL.
//
// naga reads a whole Vulkan GLSL (4.50) shader, preprocessor included (the #defines of a
// variant are resolved there, at translation: WGSL has no preprocessor), and writes one WGSL
// module; it needs an entry point (`main`) and keeps every function of the source.
//
// use:   const naga = await loadNaga();
//        const wgsl = translate(naga, glsl, 'what');   // throws WgslError, one line
//        const modules = libraryWgsl(naga, library, glue, wgslVariants(Object.keys(kBaseKindValues)));
//                                                              // {plane_bilinear: wgsl, ...}
// as a program: node scripts/wgsl.mjs --version  prints naga's version, or one line saying
//        why there is no translator (exit status 1): the tests ask it whether they can run.
import {fileURLToPath} from 'node:url';

// One line: the message of every failure here.
export class WgslError extends Error {}

// Control characters written as escapes: a message stays one line.
const oneLine = (text) => String(text).replace(/[\x00-\x1f\x7f]/g, (c) => (c === '\n' ? ' | ' : `\\x${c.charCodeAt(0).toString(16).padStart(2, '0')}`));

// naga-wasm's node build, as this package's node_modules has it (`npm ci` here). Throws
// WgslError saying what to do where it is missing.
export async function loadNaga() {
    try {
        return await import('naga-wasm');
    } catch (e) {
        if (e && e.code === 'ERR_MODULE_NOT_FOUND' && /naga-wasm/.test(e.message))
            throw new WgslError('no naga-wasm (the GLSL to WGSL translator, a devDependency of microrelief-three): run npm ci in packages/microrelief-three');
        throw new WgslError(`naga-wasm does not load (${oneLine(e && e.message ? e.message : e).slice(0, 300)})`);
    }
}

// The WGSL of `glsl`, a whole fragment shader in Vulkan GLSL (#version 450, an entry point
// `main`), validated by naga. `what` names the source in an error: "what: naga parse error:
// its first lines".
export function translate(naga, glsl, what) {
    try {
        const module = naga.parseGlsl(glsl, {stage: 'fragment'});
        return naga.writeWgsl(module, naga.validate(module));
    } catch (e) {
        const report = String(e.formatted || e.message || e).split('\n').filter((l) => l.trim()).slice(0, 6).join('\n');
        throw new WgslError(`${what}: naga ${e.kind || 'error'}: ${oneLine(report)}`);
    }
}

// The package's variants for the base kinds `kinds` (relief_layout.js's kBaseKindValues' keys,
// generated from variants.glsl's MR_BASE_*: scripts/build.mjs gives them): each kind and each
// last level (relief_map.glsl's MICRORELIEF_BASE, relief_patch.glsl's MICRORELIEF_INTERPOLATION),
// traced by the multilevel method, the one
// microrelief-three offers. The shadows are no variant of the library: MICRORELIEF_SHADOWS
// chooses which library function the glue calls (glsl/microrelief_shading.frag), and every
// module holds mr_hardShadow, as the WebGL entry's library does (the package's library has no
// soft shadow: scripts/strip_glsl.mjs drops it, as nothing of the package calls it).
export const wgslVariants = (kinds) => kinds.flatMap((base) =>
    ['bilinear', 'biquadratic'].map((interpolation) => ({name: `${base}_${interpolation}`, base, interpolation, method: 'multilevel'})));

// What a WebGPU host sets before the library (texture_reads.glsl's and albedo.glsl's hooks):
// WGSL has no combined texture-samplers. The heights and the pyramid are read by texelFetch on
// a texture2D, no sampler (GL_EXT_samplerless_texture_functions; WGSL's textureLoad): the
// same texels as the defaults read, so the library's functions name no module-scope binding
// for them. The cell's four samples are four reads (no gather: it needs a sampler). The
// albedo is filtered (textureGrad), so it is sampled through mrAlbedoSampler, declared here
// as a binding (group 0, binding 0) for naga, which libraryWgsl then makes a parameter of the
// functions that use it (samplerAsParameter).
export const kWebGpuHooks = `#extension GL_EXT_samplerless_texture_functions : require
#define MICRORELIEF_SAMPLER texture2D
#define MICRORELIEF_TEXTURE_GATHER 0
#define MICRORELIEF_READ_SAMPLE(heights, texel) texelFetch(heights, texel, 0).r
#define MICRORELIEF_READ_PYRAMID(pyramid, texel, level, levelSize) texelFetch(pyramid, texel, level).r
layout(set = 0, binding = 0) uniform sampler mrAlbedoSampler;
#define MICRORELIEF_ALBEDO_TEXTURE texture2D
#define MICRORELIEF_ALBEDO_SAMPLED(t) sampler2D(t, mrAlbedoSampler)
`;

// The package's glue (glsl/, as scripts/build.mjs's glue of generated/glsl.js names each
// file) that each module holds after the library, in this order: relief_three.glsl's part in
// parameters only (MICRORELIEF_THREE_PARAMETERS_ONLY: its uniforms and the functions that
// read them left out) and webgpu_shading.glsl's mrShadePixel, which calls it: the WebGPU
// entry's pixel from the GLSL the WebGL entry's pixel runs (docs/webgpu.md).
export const kWgslGlue = ['reliefThree', 'webgpuShading'];

// The GLSL naga reads for `variant` of `library` (the package's library: scripts/build.mjs's
// bundle of shaders/microrelief/, stripped) and `glue` ({reliefThree, webgpuShading}: the
// texts of kWgslGlue): #version, the variant's #defines by the names variants.glsl gives them
// (MR_BASE_PLANE ...; a name the library does not define is refused here, since #if would
// take it as 0, the plane, silently), the hooks, the library, the glue, and an empty main
// (naga needs an entry point; the WGSL keeps it, `fn main`).
export function libraryEntry(library, variant, glue) {
    const defines = [['MICRORELIEF_BASE', `MR_BASE_${variant.base.toUpperCase()}`],
                     ['MICRORELIEF_INTERPOLATION', `MR_INTERPOLATION_${variant.interpolation.toUpperCase()}`]];
    for (const [, value] of defines)
        if (!new RegExp(`^\\s*#\\s*define\\s+${value}\\b`, 'm').test(library))
            throw new WgslError(`WGSL variant ${variant.name}: the library defines no ${value} (shaders/microrelief/variants.glsl)`);
    for (const key of kWgslGlue)
        if (typeof glue?.[key] !== 'string') throw new WgslError(`WGSL variant ${variant.name}: no glue ${key} (the package's glsl/)`);
    return '#version 450\n' + defines.map(([name, value]) => `#define ${name} ${value}\n`).join('') + kWebGpuHooks + library +
        '\n#define MICRORELIEF_THREE_PARAMETERS_ONLY\n' + kWgslGlue.map((key) => glue[key] + '\n').join('') + 'void main() {}\n';
}

// The albedo's sampler as a parameter rather than a module-scope binding: a node material
// (three's WebGPURenderer) cannot hold a binding of the module's own beside three's, but can
// pass three's sampler of the albedo texture to the function it calls. naga's output mended,
// at the build, by text: the binding (`@group(0) @binding(0)` and `var mrAlbedoSampler:
// sampler;`, naga's two lines) is dropped, and every function that names mrAlbedoSampler, or
// calls one that does, takes it as its first parameter (`fn f(mrAlbedoSampler: sampler, ...`)
// and passes it first to each such call (`f(mrAlbedoSampler, ...`), until none is left
// (mr_filteredAlbedo, mr_surfaceAlbedo, the glue's pixels). Throws WgslError where the
// module is not what this was written for (no binding, or a function of no parameters).
export function samplerAsParameter(module, what) {
    const binding = /^@group\(0\) @binding\(0\) *\nvar mrAlbedoSampler: sampler;\n/m;
    if (!binding.test(module)) throw new WgslError(`${what}: no module-scope mrAlbedoSampler binding where naga writes it`);
    let text = module.replace(binding, '');
    const functions = () => [...text.matchAll(/^fn (\w+)\(([^)]*)\)[^\n]*\{\n[\s\S]*?^\}$/gm)];
    const threaded = new Set();
    for (;;) {
        const next = functions().filter((f) => !threaded.has(f[1]) && (/\bmrAlbedoSampler\b/.test(f[0]) ||
                                                  [...threaded].some((name) => new RegExp(`\\b${name}\\(`).test(f[0].slice(f[0].indexOf('{'))))));
        if (next.length === 0) break;
        for (const f of next) {
            if (f[2].trim() === '') throw new WgslError(`${what}: ${f[1]} takes no parameter (the sampler cannot be threaded)`);
            threaded.add(f[1]);
        }
        for (const f of next) {
            text = text.replace(new RegExp(`^fn ${f[1]}\\(`, 'm'), `fn ${f[1]}(mrAlbedoSampler: sampler, `);
            text = text.replace(new RegExp(`([^\\w])${f[1]}\\((?!mrAlbedoSampler: )`, 'g'), (m, before) => `${before}${f[1]}(mrAlbedoSampler, `);
        }
    }
    return text;
}

// Every variant's WGSL (`variants`: wgslVariants'): {name: text}, each with a header naming naga's version and the
// variant, the albedo's sampler a parameter (samplerAsParameter). Throws WgslError naming the first variant that fails.
export function libraryWgsl(naga, library, glue, variants) {
    const modules = {};
    for (const variant of variants) {
        const what = `WGSL variant ${variant.name}`;
        modules[variant.name] = `// naga ${naga.nagaVersion}: microrelief's library and microrelief-three's glue (${kWgslGlue.join(', ')}), ${variant.base} base, ${variant.interpolation} last level, ${variant.method}; the albedo's sampler a parameter\n` +
            samplerAsParameter(translate(naga, libraryEntry(library, variant, glue), what), what);
    }
    return modules;
}

if (process.argv[1] && fileURLToPath(import.meta.url) === process.argv[1]) {
    if (process.argv.slice(2).join(' ') !== '--version') {
        console.error('wgsl.mjs: usage: node scripts/wgsl.mjs --version (the build runs the translation: scripts/build.mjs)');
        process.exit(2);
    }
    try {
        console.log((await loadNaga()).nagaVersion);
    } catch (e) {
        console.error(`wgsl.mjs: ${e.message}`);
        process.exit(1);
    }
}
