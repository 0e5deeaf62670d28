#!/usr/bin/env node
// wgsl_generated.mjs: the package's WGSL is the translator's, not edited by hand (issue 51).
// Builds microrelief-three's generated/ again from the repository (scripts/build.mjs
// --no-wasm into a scratch folder: the same bundling, stripping and translation through
// scripts/wgsl.mjs) and compares its wgsl.js, and the glsl.js it is translated from, with a
// built generated/ byte for byte; a module that differs is named with its first differing
// line. Each module must also hold what the WebGPU entry will call (kCalled) and the
// package's variants must be the ones listed (every base, both last levels). ctest
// web.wgsl.generated (tests/webgpu/CMakeLists.txt), on the staged package.
//
// Usage: node tests/webgpu/wgsl_generated.mjs GENERATED_DIR
// Exit status 0: equal; 1: a difference or a build failure (one line each on stdout); 2: bad
// arguments; 77: no naga-wasm and MICRORELIEF_ALLOW_MISSING_BROWSER=1 (as web.wgsl skips).
import {spawnSync} from 'node:child_process';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import {fileURLToPath, pathToFileURL} from 'node:url';

const repo = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const scripts = path.join(repo, 'packages/microrelief-three/scripts');
const built = process.argv[2] ? path.resolve(process.argv[2]) : null;
if (!built || process.argv.length !== 3 || !fs.existsSync(path.join(built, 'wgsl.js'))) {
    console.error(`wgsl_generated.mjs: no wgsl.js in '${process.argv[2] ?? ''}' (usage: node wgsl_generated.mjs GENERATED_DIR, a built microrelief-three's generated/)`);
    process.exit(2);
}
// The library functions the WebGPU entry calls, as the WebGL entry's glue does, and the glue
// naga translates with them (glsl/relief_three.glsl's shared part, glsl/webgpu_shading.glsl's
// mrShadePixel and mrTraceHit, which src/webgpu.js calls).
const kCalled = ['mr_traceMultilevel', 'mr_hardShadow', 'mr_surfaceAlbedo', 'mr_shadeRelief', 'mr_reliefWorldNormal', 'mr_baseMapPoint',
                 'mrNdcOf', 'mrTraceRay', 'mrShadeHit', 'mrShadePixel', 'mrTraceHit'];
// Every kind of the table of bases (the staged package's relief_layout.js: kBaseKindValues,
// generated from variants.glsl's MR_BASE_*), each last level.
const {kBaseKindValues} = await import(pathToFileURL(path.join(built, 'relief_layout.js')).href);
const kVariants = Object.keys(kBaseKindValues).flatMap((b) => [`${b}_bilinear`, `${b}_biquadratic`]);

const {loadNaga} = await import(pathToFileURL(path.join(scripts, 'wgsl.mjs')).href);
try {
    await loadNaga();
} catch (e) {
    if (process.env.MICRORELIEF_ALLOW_MISSING_BROWSER === '1') {
        console.log(`SKIPPED: ${e.message}`);
        process.exit(77);
    }
    console.log(`FAILED: ${e.message}`);
    process.exit(1);
}

const problems = [];
const scratch = fs.mkdtempSync(path.join(os.tmpdir(), 'wgsl-generated-'));
// The fresh build's modules are ES modules, as in the package (its package.json says so):
// Debian's node 18 reads a .js file outside such a folder as CommonJS.
fs.writeFileSync(path.join(scratch, 'package.json'), '{"type": "module"}\n');
try {
    const fresh = path.join(scratch, 'generated');
    const run = spawnSync(process.execPath, [path.join(scripts, 'build.mjs'), '--no-wasm', '--source', repo, '--out', fresh], {encoding: 'utf8'});
    if (run.status !== 0) {
        console.log(`FAILED: scripts/build.mjs: ${run.stderr.trim()}`);
        process.exit(1);
    }
    const load = async (folder) => import(pathToFileURL(path.join(folder, 'wgsl.js')).href);
    const [now, then] = [await load(fresh), await load(built)];
    if (then.unavailable) problems.push(`${built}/wgsl.js: ${then.unavailable}`);
    const names = Object.keys(now.wgsl);
    if (names.join(' ') !== kVariants.join(' ')) problems.push(`the build makes the variants ${names.join(', ')}, not ${kVariants.join(', ')}`);
    if (Object.keys(then.wgsl).join(' ') !== names.join(' ')) problems.push(`built wgsl.js holds ${Object.keys(then.wgsl).join(', ') || 'no module'}, a build now ${names.join(', ')}`);
    for (const name of names) {
        const missing = kCalled.filter((f) => !new RegExp(`^fn ${f}\\(`, 'm').test(now.wgsl[name]));
        if (missing.length) problems.push(`${name}: no fn ${missing.join(', ')}`);
        if (!(name in then.wgsl) || then.wgsl[name] === now.wgsl[name]) continue;
        const [a, b] = [then.wgsl[name].split('\n'), now.wgsl[name].split('\n')];
        const k = a.findIndex((line, i) => line !== b[i]);
        problems.push(`${name}: the built module differs from naga's at line ${k + 1}: '${(a[k] ?? '(end)').slice(0, 100)}', translated '${(b[k] ?? '(end)').slice(0, 100)}'`);
    }
    // The rest of the file (its header, naga's version, the variants' table) and its input.
    const moduleDiffers = problems.some((p) => /differs from naga's/.test(p));
    for (const file of ['wgsl.js', 'glsl.js'])
        if (!(file === 'wgsl.js' && moduleDiffers) && !fs.readFileSync(path.join(fresh, file)).equals(fs.readFileSync(path.join(built, file))))
            problems.push(`${file}: the built file is not what scripts/build.mjs makes now (built from other sources, or edited)`);
} finally {
    fs.rmSync(scratch, {recursive: true, force: true});
}
for (const p of problems) console.log(`FAILED: ${p}`);
if (!problems.length) console.log(`wgsl.js: the ${kVariants.length} modules are naga's translation of the library and the glue, as built`);
process.exit(problems.length ? 1 : 0);
