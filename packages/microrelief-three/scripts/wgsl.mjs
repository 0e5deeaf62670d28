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
// albedo is filtered (textureGrad), so it is sampled through mrAlbedoSampler, the one
// binding of the module (group 0, binding 0; docs/webgpu.md's plan: a parameter later).
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

// Every variant's WGSL (`variants`: wgslVariants'): {name: text}, each with a header naming naga's version and the
// variant. Throws WgslError naming the first variant that fails.
export function libraryWgsl(naga, library, glue, variants) {
    const modules = {};
    for (const variant of variants)
        modules[variant.name] = `// naga ${naga.nagaVersion}: microrelief's library and microrelief-three's glue (${kWgslGlue.join(', ')}), ${variant.base} base, ${variant.interpolation} last level, ${variant.method}\n` +
            translate(naga, libraryEntry(library, variant, glue), `WGSL variant ${variant.name}`);
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
