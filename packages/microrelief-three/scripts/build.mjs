#!/usr/bin/env node
// build.mjs: makes generated/ from the microrelief repository the package lives in, so that
// nothing of the library is kept in the package by hand (npm runs it before `npm pack`;
// CMake runs it into the build tree for the example and the tests):
//  * generated/glsl.js: the GLSL library (shaders/microrelief/) spliced into one string for
//    the tracer, the shading, the shadow ray and the albedo, each #include "..." resolved
//    against the including file's folder and then shaders/ and spliced once, as the
//    library's own resolver and microrelief-glsl-bundle do; the pyramid builder's passes
//    (shaders/pyramid/) the same way; and the package's own glue (glsl/*), the files as
//    they are;
//  * generated/png.js: web/png.js, the page's PNG decoder (16-bit maps keep their low byte);
//  * generated/pyramid_wasm.js: the C++ max pyramid (src/core/heightmap/MaxPyramid.cpp,
//    HeightMap.cpp, and core/Error.cpp with core/scene/SceneFields.cpp, which its errors use)
//    compiled to WebAssembly by emscripten (em++ on PATH), one ES module with the wasm
//    inside: the CPU path where WebGL 2 cannot render into R16F.
//  * generated/manifest.json: every source file read and its SHA-256.
//
// Usage: node scripts/build.mjs [--out DIR] [--source DIR] [--no-wasm]
//   --out DIR     where to write (default: generated/ beside this folder)
//   --source DIR  the repository (default: MICRORELIEF_SOURCE_DIR, else ../.. of the package)
//   --no-wasm     no emscripten: the CPU pyramid path then refuses with a clear message
import {execFileSync} from 'node:child_process';
import {createHash} from 'node:crypto';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import {fileURLToPath} from 'node:url';

const packageDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');

function fail(message) {
    console.error(`microrelief-three build: error: ${message}`);
    process.exit(1);
}

function parseArguments(argv) {
    const options = {out: path.join(packageDir, 'generated'), source: process.env.MICRORELIEF_SOURCE_DIR || path.resolve(packageDir, '../..'), wasm: true};
    for (let k = 0; k < argv.length; ++k) {
        const a = argv[k];
        if (a === '--out' && k + 1 < argv.length) options.out = path.resolve(argv[++k]);
        else if (a === '--source' && k + 1 < argv.length) options.source = path.resolve(argv[++k]);
        else if (a === '--no-wasm') options.wasm = false;
        else fail(`unknown argument '${a}' (see the header of scripts/build.mjs)`);
    }
    return options;
}

const options = parseArguments(process.argv.slice(2));
const shaderRoot = path.join(options.source, 'shaders');
if (!fs.existsSync(path.join(shaderRoot, 'microrelief', 'multilevel_trace.glsl')))
    fail(`${options.source}: not the microrelief repository (no shaders/microrelief/multilevel_trace.glsl); set MICRORELIEF_SOURCE_DIR or --source`);

const manifest = {};
function read(file) {
    const text = fs.readFileSync(file, 'utf8');
    manifest[path.relative(options.source, file)] = createHash('sha256').update(text).digest('hex');
    return text;
}

// ---- GLSL: #include "..." spliced once each (src/gl/ShaderSource.cpp's rule) ----

const kInclude = /^\s*#\s*include\s+"([^"]+)"\s*$/;

function resolveInclude(from, name) {
    for (const base of [path.dirname(from), shaderRoot]) {
        const candidate = path.resolve(base, name);
        if (fs.existsSync(candidate)) return candidate;
    }
    return null;
}

// The files of `entries` (paths under shaders/) with their includes spliced where each is
// first included, every file once; each marked by a comment naming it.
function bundle(entries) {
    const seen = new Set();
    let text = '';
    const splice = (file, depth) => {
        if (depth > 32) fail(`${file}: #include nested too deeply (a cycle?)`);
        seen.add(file);
        text += `// ---- microrelief: ${path.relative(options.source, file)} ----\n`;
        const lines = read(file).split('\n');
        if (lines.length && lines[lines.length - 1] === '') lines.pop();
        lines.forEach((line, index) => {
            const match = kInclude.exec(line.replace(/\r$/, ''));
            if (!match) {
                text += line.replace(/\r$/, '') + '\n';
                return;
            }
            const target = resolveInclude(file, match[1]);
            if (!target) fail(`${path.relative(options.source, file)}:${index + 1}: #include "${match[1]}" not found`);
            if (!seen.has(target)) splice(target, depth + 1);
        });
    };
    for (const entry of entries) {
        const file = path.join(shaderRoot, entry);
        if (!seen.has(file)) splice(file, 0);
    }
    return text;
}

const library = bundle(['microrelief/multilevel_trace.glsl', 'microrelief/map_space.glsl',
                        'microrelief/shading.glsl', 'microrelief/shadow.glsl', 'microrelief/albedo.glsl']);
const pyramid = {
    pass: bundle(['pyramid/pass.vert']),
    windowFinest: bundle(['pyramid/window_finest.frag']),
    windowLevel: bundle(['pyramid/window_level.frag']),
};
// The package's own GLSL (glsl/): the glue between three.js and the library.
const glueDir = path.join(packageDir, 'glsl');
const glue = {};
for (const file of fs.readdirSync(glueDir).sort()) {
    const key = file.replace(/\.\w+$/, '').replace(/_(\w)/g, (_, c) => c.toUpperCase());
    glue[key] = `// ---- microrelief-three: glsl/${file} ----\n` + fs.readFileSync(path.join(glueDir, file), 'utf8');
}

fs.mkdirSync(options.out, {recursive: true});
const header = '// Generated by microrelief-three scripts/build.mjs from the microrelief repository; do not edit.\n';
fs.writeFileSync(path.join(options.out, 'glsl.js'), header +
    `export const library = ${JSON.stringify(library)};\n` +
    `export const pyramid = ${JSON.stringify(pyramid, null, 1)};\n` +
    `export const glue = ${JSON.stringify(glue, null, 1)};\n`);

// ---- the page's PNG decoder ----
const png = read(path.join(options.source, 'web', 'png.js'));
fs.writeFileSync(path.join(options.out, 'png.js'), header.replace('; do not edit', ' (web/png.js); do not edit') + png);

// ---- the C++ pyramid as WebAssembly ----
function findProgram(name) {
    for (const dir of (process.env.PATH || '').split(path.delimiter)) {
        const candidate = path.join(dir, name);
        try {
            fs.accessSync(candidate, fs.constants.X_OK);
            return candidate;
        } catch {}
    }
    return null;
}

function buildWasm() {
    const emxx = findProgram('em++');
    if (!emxx) fail('no em++ on PATH (Debian package emscripten; bash scripts/setup.sh installs it), or --no-wasm for a package without the CPU pyramid path');
    const glm = process.env.MICRORELIEF_GLM_INCLUDE || '/usr/include';
    if (!fs.existsSync(path.join(glm, 'glm', 'glm.hpp'))) fail(`${glm}/glm/glm.hpp: no GLM (Debian package libglm-dev), or set MICRORELIEF_GLM_INCLUDE`);
    // GLM alone on the include path: the system's own C headers must not shadow emscripten's.
    const scratch = fs.mkdtempSync(path.join(os.tmpdir(), 'microrelief-three-'));
    try {
        fs.symlinkSync(path.join(glm, 'glm'), path.join(scratch, 'glm'));
        const sources = ['src/core/heightmap/MaxPyramid.cpp', 'src/core/heightmap/HeightMap.cpp', 'src/core/ParallelRows.cpp', 'src/core/Error.cpp', 'src/core/scene/SceneFields.cpp'].map((f) => path.join(options.source, f));
        for (const f of sources) read(f);
        const glue = path.join(packageDir, 'wasm', 'pyramid_wasm.cpp');
        const shim = path.join(packageDir, 'wasm', 'bit_cast.h');
        // Debian's emscripten runs its JavaScript tools with the system's node; Debian keeps
        // their modules (acorn) in /usr/share/nodejs, which a node from elsewhere does not search.
        const env = {...process.env, NODE_PATH: [process.env.NODE_PATH, '/usr/share/nodejs'].filter(Boolean).join(path.delimiter)};
        execFileSync(emxx, ['-std=c++20', '-O2', '-fexceptions', '-include', shim,
                            '-I', path.join(options.source, 'include'), '-isystem', scratch,
                            ...sources, glue, '-o', path.join(options.out, 'pyramid_wasm.js'),
                            '-sMODULARIZE', '-sEXPORT_ES6', '-sSINGLE_FILE', '-sENVIRONMENT=web,worker',
                            '-sALLOW_MEMORY_GROWTH', '-sMAXIMUM_MEMORY=4GB', '-sEXPORT_NAME=createPyramidModule',
                            '-sEXPORTED_FUNCTIONS=_mr_build_windows,_mr_level_count,_mr_level_size,_mr_copy_level,_mr_max_height,_mr_scale_exponent,_mr_release,_mr_last_error,_malloc,_free',
                            '-sEXPORTED_RUNTIME_METHODS=UTF8ToString'],
                     {stdio: ['ignore', 'inherit', 'inherit'], env});
    } catch (e) {
        fail(`em++ failed (${e.message.split('\n')[0]})`);
    } finally {
        fs.rmSync(scratch, {recursive: true, force: true});
    }
}

if (options.wasm) {
    buildWasm();
} else {
    fs.writeFileSync(path.join(options.out, 'pyramid_wasm.js'), header +
        'export default async function createPyramidModule() {\n' +
        '    throw new Error(\'this build of microrelief-three has no WebAssembly pyramid (built with --no-wasm): the CPU path is unavailable\');\n}\n');
}
fs.writeFileSync(path.join(options.out, 'manifest.json'), JSON.stringify({source: 'microrelief', files: manifest}, null, 1) + '\n');
console.log(`microrelief-three build: ${path.relative(process.cwd(), options.out) || '.'}: glsl.js, png.js, pyramid_wasm.js${options.wasm ? '' : ' (stub)'}, manifest.json`);
