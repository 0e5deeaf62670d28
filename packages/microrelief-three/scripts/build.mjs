#!/usr/bin/env node
// build.mjs: makes generated/ from the microrelief repository the package lives in, so that
// nothing of the library is kept in the package by hand (npm runs it before `npm pack`;
// CMake runs it into the build tree for the example and the tests):
//  * generated/glsl.js: the GLSL library (shaders/microrelief/) spliced into one string for
//    the tracer, the shading, the shadow ray and the albedo, each #include "..." resolved
//    against the including file's folder and then shaders/ and spliced once, by the rules
//    of the library's own resolver and microrelief-glsl-bundle (src/gl/ShaderSource.cpp):
//    the same include forms, regular files only (a FIFO, a device or a folder is refused
//    before it is read, never waited on), of at most kMaxShaderFileBytes, whose real paths
//    (links followed) lie inside shaders/; the same messages, "file:line: #include ...:
//    reason" (tests/bundler holds both tools to one table of cases); the pyramid builder's
//    passes (shaders/pyramid/) the same way; and the package's own glue (glsl/*), the files
//    as they are; all of it stripped of comments, of the functions no shader can call and
//    of blank space (scripts/strip_glsl.mjs says how, conservatively, under every #if);
//  * generated/relief_layout.js: the ES module cmake/generate_contracts.py makes (python3)
//    from the GLSL, the page's own: the uniform block's layout, the shared constants and
//    the enumerations whose values the package's #defines take by name (kBaseKindValues
//    ..., written in shaders/microrelief/variants.glsl), with the lists of
//    cmake/Contracts.cmake;
//  * generated/relief_core.js: web/relief_core.js, the host core the page and the package
//    share (the table of bases, the pyramids' level sizes and scale, the traversal's budget),
//    which imports relief_layout.js beside it;
//  * generated/png.js: web/png.js, the page's PNG decoder (16-bit maps keep their low byte);
//  * generated/scene_checks.js: web/scene_checks.js, the programs' checks of a scene in the
//    pages' words, and generated/scene_checks_wasm.js: the C++ checks it drives (the files
//    web/wasm/scene_checks_sources.txt lists) compiled to WebAssembly (src/checks.js);
//  * generated/pyramid_wasm.js: the C++ max pyramid (src/core/heightmap/MaxPyramid.cpp,
//    HeightMap.cpp, and core/Error.cpp with core/scene/SceneFields.cpp, which its errors use)
//    compiled to WebAssembly by emscripten (em++ on PATH), one ES module with the wasm
//    inside: the CPU path where WebGL 2 cannot render into R16F.
//  * generated/twin_wasm.js: the CPU twin of the traversal (src/core/trace/
//    MultilevelTracer.cpp with the base surfaces, the surface patches, the pyramid and
//    ModelTransform.cpp) behind wasm/twin_wasm.cpp, compiled the same way: the picks
//    (src/twin.js; without emscripten a stub, and the picks are traced on the GPU).
//  * generated/wgsl.js: the library of glsl.js (stripped, as the WebGL entry has it) in WGSL
//    with the glue both entries share (glue.reliefThree's functions in parameters only) and
//    the WebGPU entry's pixel that calls it (glue.webgpuShading's mrShadePixel), one module
//    per variant the WebGPU entry needs (each base, each last level; the
//    multilevel method), translated by naga through scripts/wgsl.mjs (naga-wasm, a
//    devDependency: `npm ci` here): `wgsl.plane_bilinear` ...; a variant naga refuses fails the
//    build, named in its one line. Not edited by hand: tests/webgpu/wgsl_generated.mjs
//    translates again and compares (ctest web.wgsl.generated);
//  * generated/manifest.json: every source file read and its SHA-256.
//
// generated/ is made whole in a temporary folder beside it and then put in its place: a run
// that fails leaves the last one as it was, and a file the last run made and this one does
// not is gone. --out must be such a folder, an empty one or a new one (never one of the
// sources' folders: its files would be replaced). An error is one line on stderr and exit
// status 2 for bad input (an include, an argument), 1 for the environment (a full disk,
// em++).
//
// Usage: node scripts/build.mjs [--out DIR] [--source DIR] [--no-wasm] [--no-wgsl]
//   --out DIR     where to write (default: generated/ beside this folder)
//   --source DIR  the repository (default: MICRORELIEF_SOURCE_DIR, else ../.. of the package)
//   --no-wasm     no emscripten: the CPU pyramid path, the CPU twin's picks and the scene
//                 checks then refuse with a clear message (picks go to the GPU)
//   --no-wgsl     no naga-wasm: wgsl.js says so (`unavailable`) and holds no module
import {execFileSync} from 'node:child_process';
import {createHash} from 'node:crypto';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import {fileURLToPath} from 'node:url';

const packageDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const kProgram = 'microrelief-three build';
// The most bytes a shader source may have (include/microrelief/gl/ShaderSource.h).
const kMaxShaderFileBytes = 4 * 1024 * 1024;
const kMaxIncludeDepth = 32;
const kBadInput = 2, kRuntime = 1;  // exit statuses, as the programs' (core/Error.h)
const kOutputs = ['glsl.js', 'wgsl.js', 'relief_layout.js', 'relief_core.js', 'png.js', 'scene_checks.js', 'scene_checks_wasm.js', 'pyramid_wasm.js', 'twin_wasm.js', 'manifest.json'];

class BuildError extends Error {
    constructor(status, message) {
        super(message);
        this.status = status;
    }
}
const badInput = (message) => new BuildError(kBadInput, message);

// Control characters written as escapes (core/Text.h: printable): a message stays one line.
function printable(text) {
    return String(text).replace(/[\x00-\x1f\x7f]/g, (c) =>
        c === '\r' ? '\\r' : c === '\n' ? '\\n' : c === '\t' ? '\\t' : `\\x${c.charCodeAt(0).toString(16).toUpperCase().padStart(2, '0')}`);
}

// An errno's text as strerror has it (libuv's, its first letter capitalised): "File too large".
function reason(e) {
    const text = (e && e.message ? e.message : String(e)).replace(/^[A-Z0-9_]+: /, '').replace(/, \w+( '.*')?$/, '');
    return text.charAt(0).toUpperCase() + text.slice(1);
}

function parseArguments(argv) {
    const options = {out: path.join(packageDir, 'generated'), source: process.env.MICRORELIEF_SOURCE_DIR || path.resolve(packageDir, '../..'), wasm: true, wgsl: true};
    for (let k = 0; k < argv.length; ++k) {
        const a = argv[k];
        if (a === '--out' && k + 1 < argv.length) options.out = path.resolve(argv[++k]);
        else if (a === '--source' && k + 1 < argv.length) options.source = path.resolve(argv[++k]);
        else if (a === '--no-wasm') options.wasm = false;
        else if (a === '--no-wgsl') options.wgsl = false;
        else throw badInput(`unknown argument '${printable(a)}' (see the header of scripts/build.mjs)`);
    }
    return options;
}

// ---- reading: regular files only, never waited on ----

// The whole text of a regular file of at most kMaxShaderFileBytes (ShaderSource.cpp:
// readShaderFile): its type checked before it is opened, and again on the descriptor (opened
// without blocking), so a FIFO or a device is refused, never read or waited on. Throws
// BuildError with the reason alone; the caller names the file.
function readRegularFile(file) {
    let info;
    try {
        info = fs.statSync(file);
    } catch (e) {
        throw badInput(`cannot open (${reason(e)})`);
    }
    const refuseType = (stat) => {
        if (stat.isDirectory()) throw badInput('a folder, not a file');
        if (!stat.isFile()) throw badInput('not a regular file (a FIFO, socket or device)');
        if (stat.size > kMaxShaderFileBytes)
            throw badInput(`${stat.size} bytes, more than the ${kMaxShaderFileBytes} bytes a shader source may have (ShaderSource.h)`);
    };
    refuseType(info);
    let fd;
    try {
        fd = fs.openSync(file, fs.constants.O_RDONLY | fs.constants.O_NONBLOCK);
    } catch (e) {
        throw badInput(`cannot open (${reason(e)})`);
    }
    try {
        refuseType(fs.fstatSync(fd));  // the file opened is the one checked
        const buffer = Buffer.alloc(Math.min(fs.fstatSync(fd).size, kMaxShaderFileBytes) + 1);
        let used = 0;
        for (;;) {
            const got = fs.readSync(fd, buffer, used, buffer.length - used, null);
            if (got === 0) break;
            used += got;
            if (used === buffer.length) break;
        }
        if (used > kMaxShaderFileBytes) throw badInput(`grew past the ${kMaxShaderFileBytes} bytes a shader source may have while read`);
        return buffer.subarray(0, used).toString('utf8');
    } catch (e) {
        if (e instanceof BuildError) throw e;
        throw badInput(`cannot read (${reason(e)})`);
    } finally {
        fs.closeSync(fd);
    }
}

// ---- GLSL: #include "..." spliced once each (src/gl/ShaderSource.cpp's rules) ----

// An #include line's file name, or why the line is no include the resolver takes.
function parseInclude(line) {
    const directive = /^\s*#\s*include\b([\s\S]*)$/.exec(line);
    if (!directive) return null;
    const rest = directive[1];
    const quoted = /^\s*"([^"]*)"\s*$/.exec(rest);
    const first = rest.search(/[^ \t]/);
    if (quoted) return quoted[1] === '' ? {problem: 'an empty file name'} : {name: quoted[1]};
    if (first >= 0 && rest[first] === '<') return {problem: '#include <...> is not resolved here; write #include "..."'};
    if (first >= 0 && rest[first] === '"' && rest.indexOf('"', first + 1) < 0) return {problem: "the file name's quote is not closed"};
    if (first >= 0 && rest[first] === '"') return {problem: 'text after the file name (#include "file" stands alone on its line)'};
    return {problem: 'expected #include "file"'};
}

// `file` with its links and ".." resolved as far as it exists (std::filesystem::weakly_canonical).
function realPath(file) {
    let head = path.resolve(file);
    const tail = [];
    for (;;) {
        try {
            return path.join(fs.realpathSync(head), ...tail);
        } catch {
            const parent = path.dirname(head);
            if (parent === head) return path.resolve(file);
            tail.unshift(path.basename(head));
            head = parent;
        }
    }
}

// `file` is `root` or lies inside it, both real paths (ShaderSource.cpp: isWithin).
const isWithin = (file, root) => {
    const relative = path.relative(root, file);
    return relative !== '..' && !relative.startsWith(`..${path.sep}`) && !path.isAbsolute(relative);
};

// The GLSL of `entries` (paths under the shader root) spliced as one text, each file once,
// where it is first included, marked by a comment naming it.
class Bundler {
    constructor(shaderRoot, source, read) {
        this.shaderRoot = shaderRoot;
        this.root = realPath(shaderRoot);
        this.source = source;
        this.read = read;  // reads a file (recording it), or throws BuildError
    }

    name(file) {
        return printable(path.relative(this.source, file));
    }

    bundle(entries) {
        this.seen = new Set();
        this.text = '';
        for (const entry of entries) {
            const file = path.join(this.shaderRoot, entry);
            if (this.seen.has(file)) continue;
            let text;
            try {
                text = this.read(file);
            } catch (e) {
                throw new BuildError(e.status ?? kBadInput, `${this.name(file)}: ${e.message}`);
            }
            this.splice(file, text, 0);
        }
        return this.text;
    }

    splice(file, text, depth) {
        if (depth > kMaxIncludeDepth) throw badInput(`${this.name(file)}: #include nested too deeply (a cycle?)`);
        this.seen.add(file);
        this.text += `// ---- microrelief: ${path.relative(this.source, file)} ----\n`;
        const lines = text.split('\n');
        if (lines.length && lines[lines.length - 1] === '') lines.pop();
        lines.forEach((raw, index) => {
            const line = raw.replace(/\r$/, '');
            const include = parseInclude(line);
            if (!include) {
                this.text += line + '\n';
                return;
            }
            // "file:line: #include "name": reason", one line whatever the file holds.
            const refuse = (why, status = kBadInput) => {
                throw new BuildError(status, `${this.name(file)}:${index + 1}: ${printable(line.slice(line.indexOf('#')))}: ${why}`);
            };
            if (include.problem) refuse(include.problem);
            const target = this.resolve(file, include.name, refuse);
            if (this.seen.has(target)) return;
            let included;
            try {
                included = this.read(target);
            } catch (e) {
                refuse(e.message, e.status);
            }
            this.splice(target, included, depth + 1);
        });
    }

    // The including file's folder first, then the shader root: the first that holds
    // `name`. A name that is absolute, or that leads out of the root (through ".." or a
    // link), is refused, not looked up further.
    resolve(from, name, refuse) {
        if (/[\x00-\x1f\x7f\\]/.test(name)) refuse('control characters or a backslash in the file name');
        if (path.isAbsolute(name)) refuse('an absolute path (a name is relative to the including file\'s folder or a search folder)');
        const folders = [path.dirname(from), this.shaderRoot];
        for (const folder of folders) {
            const candidate = path.normalize(path.join(folder, name));
            if (!fs.existsSync(candidate)) continue;
            const real = realPath(candidate);
            if (!isWithin(real, this.root)) refuse(`${printable(real)} is outside the shader folders (${printable(this.root)})`);
            return candidate;
        }
        refuse(`not found (looked in ${folders.map(printable).join(', ')})`);
    }
}

// ---- the C++ in WebAssembly ----

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

// The em++ runs' shared part: GLM alone on the include path (the system's own C headers
// must not shadow emscripten's), Debian's node modules for its JavaScript tools.
function emscripten(scratch) {
    const emxx = findProgram('em++');
    if (!emxx) throw new BuildError(kRuntime, 'no em++ on PATH (Debian package emscripten; bash scripts/setup.sh installs it), or --no-wasm for a package without the CPU pyramid path and the scene checks');
    const glm = process.env.MICRORELIEF_GLM_INCLUDE || '/usr/include';
    if (!fs.existsSync(path.join(glm, 'glm', 'glm.hpp'))) throw new BuildError(kRuntime, `${glm}/glm/glm.hpp: no GLM (Debian package libglm-dev), or set MICRORELIEF_GLM_INCLUDE`);
    fs.symlinkSync(path.join(glm, 'glm'), path.join(scratch, 'glm'));
    // Debian's emscripten runs its JavaScript tools with the system's node; Debian keeps
    // their modules (acorn) in /usr/share/nodejs, which a node from elsewhere does not search.
    const env = {...process.env, NODE_PATH: [process.env.NODE_PATH, '/usr/share/nodejs'].filter(Boolean).join(path.delimiter)};
    return (args) => {
        try {
            execFileSync(emxx, ['-std=c++20', '-O2', '-fexceptions', '-include', path.join(packageDir, 'wasm', 'bit_cast.h'), '-isystem', scratch, ...args,
                                '-sMODULARIZE', '-sEXPORT_ES6', '-sSINGLE_FILE', '-sENVIRONMENT=web,worker'],
                         {stdio: ['ignore', 'inherit', 'inherit'], env});
        } catch (e) {
            throw new BuildError(kRuntime, `em++ failed (${printable(e.message.split('\n')[0])})`);
        }
    };
}

// What C++, JavaScript and GLSL share, made as the CMake build makes it: cmake/
// generate_contracts.py with the lists cmake/Contracts.cmake gives (python3, which emscripten
// itself runs on): the ES module's text (its stdout; written into --out with the rest) and,
// with `scratch`, the headers the C++ in WebAssembly includes (core/GlslConstants.h) in the
// folder returned as `include`.
function generateContracts(source, scratch, read) {
    const contracts = read(path.join(source, 'cmake', 'Contracts.cmake'));
    const list = (name) => {
        const found = new RegExp(`set\\(${name}\\s+([^)]*)\\)`).exec(contracts);
        if (!found) throw new BuildError(kRuntime, `cmake/Contracts.cmake: no ${name} list to generate the contracts from`);
        return found[1].trim().split(/\s+/);
    };
    const include = scratch ? path.join(scratch, 'include') : null;
    const script = path.join(source, 'cmake', 'generate_contracts.py');
    const shaders = path.join(source, 'shaders', 'microrelief');
    const block = path.join(source, 'shaders', 'relief_parameters.glsl');
    const constants = list('MICRORELIEF_SHARED_CONSTANTS'), enums = list('MICRORELIEF_SHARED_ENUMS');
    // The files it reads, in the manifest.
    for (const file of [script, block, ...new Set([...constants, ...enums].map((spec) => path.join(shaders, spec.split(':')[0])))]) read(file);
    const headers = include ? ['--struct', path.join(include, 'microrelief', 'gl', 'ReliefParameters.h'),
                               '--constants-header', path.join(include, 'microrelief', 'core', 'GlslConstants.h')] : [];
    try {
        const layout = execFileSync('python3', [script, '--block', block, '--shaders', shaders, '--constants', ...constants, '--enums', ...enums,
                                                ...headers, '--js', '-'],
                                    {stdio: ['ignore', 'pipe', 'inherit'], encoding: 'utf8'});
        return {include, layout};
    } catch (e) {
        throw new BuildError(kRuntime, `cmake/generate_contracts.py failed (${printable(e.message.split('\n')[0])})`);
    }
}

function buildWasm(options, into, read, constants) {
    const scratch = fs.mkdtempSync(path.join(os.tmpdir(), 'microrelief-three-'));
    try {
        const emxx = emscripten(scratch);
        // A '*' in a file name stands for any characters: the files of its folder that match,
        // in name order (web/wasm/scene_checks_sources.txt's rule, which CMake reads alike).
        const from = (files) => files.flatMap((f) => {
            if (!f.includes('*')) return [path.join(options.source, f)];
            const folder = path.join(options.source, path.dirname(f));
            const name = new RegExp(`^${path.basename(f).split('*').map((p) => p.replace(/[.+?^${}()|[\]\\]/g, '\\$&')).join('.*')}$`);
            return fs.readdirSync(folder).filter((n) => name.test(n)).sort().map((n) => path.join(folder, n));
        });
        const pyramid = from(['src/core/heightmap/MaxPyramid.cpp', 'src/core/heightmap/HeightMap.cpp', 'src/core/ParallelRows.cpp', 'src/core/Error.cpp', 'src/core/scene/SceneFields.cpp']);
        for (const f of pyramid) read(f);
        emxx(['-I', path.join(options.source, 'include'), ...pyramid, path.join(packageDir, 'wasm', 'pyramid_wasm.cpp'), '-o', path.join(into, 'pyramid_wasm.js'),
              '-sALLOW_MEMORY_GROWTH', '-sMAXIMUM_MEMORY=4GB', '-sEXPORT_NAME=createPyramidModule',
              '-sEXPORTED_FUNCTIONS=_mr_build_windows,_mr_level_count,_mr_level_size,_mr_copy_level,_mr_max_height,_mr_scale_exponent,_mr_release,_mr_last_error,_malloc,_free',
              '-sEXPORTED_RUNTIME_METHODS=UTF8ToString']);
        // The CPU twin of the traversal, for the picks (wasm/twin_wasm.cpp).
        const twin = from(['src/core/trace/MultilevelTracer.cpp', 'src/core/base/BaseShape.cpp', 'src/core/base/BaseTable.cpp',
                           'src/core/base/*Surface.cpp', 'src/core/heightmap/HeightMap.cpp', 'src/core/heightmap/SurfacePatch.cpp',
                           'src/core/heightmap/MaxPyramid.cpp', 'src/core/ParallelRows.cpp', 'src/core/Error.cpp',
                           'src/core/scene/SceneFields.cpp', 'src/core/scene/ModelTransform.cpp',
                           'src/core/Text.cpp']);  // the table's refusal of a base's name lists the names
        for (const f of twin) read(f);
        emxx(['-I', path.join(options.source, 'include'), '-I', path.join(options.source, 'src'), '-I', constants,
              ...twin, path.join(packageDir, 'wasm', 'twin_wasm.cpp'), '-o', path.join(into, 'twin_wasm.js'),
              '-sALLOW_MEMORY_GROWTH', '-sMAXIMUM_MEMORY=4GB', '-sEXPORT_NAME=createTwinModule',
              '-sEXPORTED_FUNCTIONS=_mr_twin_create,_mr_twin_bytes,_mr_twin_trace,_mr_twin_release,_mr_twin_count,_mr_twin_last_error,_malloc,_free',
              '-sEXPORTED_RUNTIME_METHODS=UTF8ToString']);
        // The scene checks: the page's build of them (web/wasm/CMakeLists.txt), from the same list.
        const list = read(path.join(options.source, 'web', 'wasm', 'scene_checks_sources.txt'));
        const checks = from(list.split('\n').map((l) => l.trim()).filter((l) => l && !l.startsWith('#')));
        for (const f of checks) read(f);
        const cmake = read(path.join(options.source, 'web', 'wasm', 'CMakeLists.txt'));
        const exports = /set\(MICRORELIEF_SCENE_CHECKS_EXPORTS "([^"]*)"\)/.exec(cmake);
        if (!exports) throw new BuildError(kRuntime, 'web/wasm/CMakeLists.txt: no MICRORELIEF_SCENE_CHECKS_EXPORTS to export');
        emxx(['-I', path.join(options.source, 'include'), '-I', path.join(options.source, 'src'), '-I', constants,
              ...checks, '-o', path.join(into, 'scene_checks_wasm.js'), '-sEXPORT_NAME=createSceneChecksModule',
              `-sEXPORTED_FUNCTIONS=${exports[1].replace(/\\\s*/g, '')}`, '-sEXPORTED_RUNTIME_METHODS=cwrap,UTF8ToString']);
    } finally {
        fs.rmSync(scratch, {recursive: true, force: true});
    }
}

// ---- writing: a whole folder, or none ----

// Refuses an --out that is not a folder this script may replace: a file, one of the
// sources' folders (or above one), or a folder of other files.
function checkOut(out, inputs) {
    const real = realPath(out);
    for (const input of inputs) {
        const file = realPath(input);
        if (isWithin(file, real))
            throw badInput(`--out ${printable(out)}: holds ${printable(input)}, which this run reads; writing there would replace it (name another folder)`);
    }
    let info;
    try {
        info = fs.statSync(out);
    } catch {
        return;  // a new folder
    }
    if (!info.isDirectory()) throw badInput(`--out ${printable(out)}: not a folder`);
    const entries = fs.readdirSync(out);
    if (entries.length === 0) return;
    let manifest = null;
    try {
        manifest = JSON.parse(fs.readFileSync(path.join(out, 'manifest.json'), 'utf8'));
    } catch {}
    if (!manifest || manifest.source !== 'microrelief')
        throw badInput(`--out ${printable(out)}: holds files this script did not make (no manifest.json of its own): name an empty folder, a new one, or one it made`);
}

// `write(folder)` fills a new folder beside `out`, which then replaces `out` whole.
function replaceFolder(out, write) {
    const parent = path.dirname(out), base = path.basename(out);
    try {
        fs.mkdirSync(parent, {recursive: true});
    } catch (e) {
        throw new BuildError(kRuntime, `${printable(parent)}: cannot make the folder (${reason(e)})`);
    }
    let staged;
    try {
        staged = fs.mkdtempSync(path.join(parent, `.${base}.new-`));
        fs.chmodSync(staged, 0o755);  // a folder to publish, not mkdtemp's private one
    } catch (e) {
        throw new BuildError(kRuntime, `${printable(parent)}: cannot write (${reason(e)})`);
    }
    let old = null;
    try {
        write(staged);
        if (fs.existsSync(out)) {
            old = `${staged.replace(/\.new-(\w+)$/, '.old-$1')}`;
            fs.renameSync(out, old);
        }
        try {
            fs.renameSync(staged, out);
        } catch (e) {
            if (old) fs.renameSync(old, out);
            old = null;
            throw new BuildError(kRuntime, `${printable(out)}: cannot replace the folder (${reason(e)})`);
        }
    } finally {
        fs.rmSync(staged, {recursive: true, force: true});
        if (old) fs.rmSync(old, {recursive: true, force: true});
    }
}

// `text` as `name` in `folder`; a failed write (a full disk) names the file as it will be
// in --out.
function writeText(folder, out, name, text) {
    try {
        fs.writeFileSync(path.join(folder, name), text);
    } catch (e) {
        throw new BuildError(kRuntime, `${printable(path.join(out, name))}: cannot write (${reason(e)})`);
    }
}

// ---- the build ----

import {strip} from './strip_glsl.mjs';
import {libraryWgsl, loadNaga, wgslVariants, WgslError} from './wgsl.mjs';

// The library's WGSL, each variant (scripts/wgsl.mjs), or null under --no-wgsl. No translator
// is the environment's fault (status 1); a variant naga refuses, the source's (2).
async function translateLibrary(options, library, glue, variants) {
    if (!options.wgsl) return null;
    try {
        const naga = await loadNaga();
        return {naga: naga.nagaVersion, modules: libraryWgsl(naga, library, glue, variants)};
    } catch (e) {
        if (!(e instanceof WgslError)) throw e;
        throw new BuildError(/^no naga-wasm|^naga-wasm does not load/.test(e.message) ? kRuntime : kBadInput,
                             /^no naga-wasm/.test(e.message) ? `${e.message}, or --no-wgsl for a package without the WGSL` : e.message);
    }
}

// Every identifier of the package's JavaScript (src/*.js): the GLSL names it splices into
// three's shaders or replaces, kept by the stripper whatever the GLSL says.
function identifiersOfTheJavaScript(read) {
    const roots = new Set();
    const src = path.join(packageDir, 'src');
    for (const file of fs.readdirSync(src).sort().filter((f) => f.endsWith('.js')))
        for (const m of read(path.join(src, file)).matchAll(/[A-Za-z_]\w*/g)) roots.add(m[0]);
    return roots;
}

async function build(options) {
    const shaderRoot = path.join(options.source, 'shaders');
    if (!fs.existsSync(path.join(shaderRoot, 'microrelief', 'multilevel_trace.glsl')))
        throw badInput(`${printable(options.source)}: not the microrelief repository (no shaders/microrelief/multilevel_trace.glsl); set MICRORELIEF_SOURCE_DIR or --source`);

    const manifest = {};
    const inputs = [];
    const read = (file) => {
        const text = readRegularFile(file);
        inputs.push(file);
        manifest[path.relative(options.source, file)] = createHash('sha256').update(text).digest('hex');
        return text;
    };
    // A file of the repository or the package, named in its error.
    const readNamed = (file) => {
        try {
            return read(file);
        } catch (e) {
            throw new BuildError(e.status ?? kBadInput, `${printable(file)}: ${e.message}`);
        }
    };

    const bundler = new Bundler(shaderRoot, options.source, read);
    let library = bundler.bundle(['microrelief/multilevel_trace.glsl', 'microrelief/map_space.glsl',
                                    'microrelief/shading.glsl', 'microrelief/shadow.glsl', 'microrelief/albedo.glsl']);
    const pyramid = {
        pass: bundler.bundle(['pyramid/pass.vert']),
        windowFinest: bundler.bundle(['pyramid/window_finest.frag']),
        windowLevel: bundler.bundle(['pyramid/window_level.frag']),
    };
    // The package's own GLSL (glsl/): the glue between three.js and the library.
    const glueDir = path.join(packageDir, 'glsl');
    const glue = {};
    for (const file of fs.readdirSync(glueDir).sort()) {
        const key = file.replace(/\.\w+$/, '').replace(/_(\w)/g, (_, c) => c.toUpperCase());
        glue[key] = `// ---- microrelief-three: glsl/${file} ----\n` + readNamed(path.join(glueDir, file));
    }
    // Stripped together: the library with the glue (joined at run time in any combination),
    // the pyramid's passes with each other.
    const roots = identifiersOfTheJavaScript(readNamed);
    try {
        const shaders = strip({library, ...Object.fromEntries(Object.entries(glue).map(([k, v]) => [`glue.${k}`, v]))}, roots).texts;
        library = shaders.library;
        for (const key of Object.keys(glue)) glue[key] = shaders[`glue.${key}`];
        Object.assign(pyramid, strip(pyramid, roots).texts);
    } catch (e) {
        throw badInput(e.message);
    }
    const core = readNamed(path.join(options.source, 'web', 'relief_core.js'));
    const png = readNamed(path.join(options.source, 'web', 'png.js'));
    const checks = readNamed(path.join(options.source, 'web', 'scene_checks.js'));
    // The headers only for the C++ in WebAssembly: a build without it writes no file but --out.
    const scratch = options.wasm ? fs.mkdtempSync(path.join(os.tmpdir(), 'microrelief-three-contracts-')) : null;
    try {
        const contracts = generateContracts(options.source, scratch, readNamed);
        // The WGSL's variants: one a base kind of the generated layout (kBaseKindValues).
        const layout = await import(`data:text/javascript;base64,${Buffer.from(contracts.layout).toString('base64')}`);
        const variants = wgslVariants(Object.keys(layout.kBaseKindValues));
        const wgsl = await translateLibrary(options, library, glue, variants);
        checkOut(options.out, inputs);
        writeGenerated(options, {library, pyramid, glue, wgsl, variants, core, png, checks, contracts}, manifest, readNamed);
    } finally {
        if (scratch) fs.rmSync(scratch, {recursive: true, force: true});
    }
    const stubs = [options.wasm ? '' : 'the WebAssembly ones stubs', options.wgsl ? '' : 'wgsl.js without WGSL'].filter(Boolean);
    console.log(`${kProgram}: ${path.relative(process.cwd(), options.out) || '.'}: ${kOutputs.join(', ')}${stubs.length ? ` (${stubs.join(', ')})` : ''}`);
}

// generated/, whole: the texts made above, the WebAssembly (or its stubs) and the manifest.
function writeGenerated(options, {library, pyramid, glue, wgsl, variants: variantList, core, png, checks, contracts}, manifest, readNamed) {
    const header = '// Generated by microrelief-three scripts/build.mjs from the microrelief repository; do not edit.\n';
    const from = (file) => header.replace('; do not edit', ` (${file}); do not edit`);
    replaceFolder(options.out, (folder) => {
        writeText(folder, options.out, 'glsl.js', header +
            `export const library = ${JSON.stringify(library)};\n` +
            `export const pyramid = ${JSON.stringify(pyramid, null, 1)};\n` +
            `export const glue = ${JSON.stringify(glue, null, 1)};\n`);
        // The variants' WGSL (scripts/wgsl.mjs says what each holds), or none and why.
        const variants = Object.fromEntries(variantList.map(({name, ...v}) => [name, v]));
        writeText(folder, options.out, 'wgsl.js', header.replace('; do not edit', ' (the library of glsl.js through naga: scripts/wgsl.mjs); do not edit') + (wgsl ?
            `export const naga = ${JSON.stringify(wgsl.naga)};\n` +
            'export const unavailable = null;\n' +
            `export const variants = ${JSON.stringify(variants, null, 1)};\n` +
            `export const wgsl = ${JSON.stringify(wgsl.modules, null, 1)};\n` :
            'export const naga = null;\n' +
            'export const unavailable = \'microrelief-three: no WGSL in this package (built without naga-wasm, --no-wgsl)\';\n' +
            'export const variants = {};\nexport const wgsl = {};\n'));
        writeText(folder, options.out, 'relief_layout.js', contracts.layout);
        writeText(folder, options.out, 'relief_core.js', from('web/relief_core.js') + core);
        writeText(folder, options.out, 'png.js', from('web/png.js') + png);
        writeText(folder, options.out, 'scene_checks.js', from('web/scene_checks.js') + checks);
        if (options.wasm) {
            buildWasm(options, folder, readNamed, contracts.include);
        } else {
            writeText(folder, options.out, 'pyramid_wasm.js', header +
                'export default async function createPyramidModule() {\n' +
                '    throw new Error("microrelief-three: no WebAssembly pyramid in this package (packed without emscripten, --no-wasm): pyramid \'cpu\' is unavailable; \'gpu\' needs EXT_color_buffer_float");\n}\n');
            writeText(folder, options.out, 'twin_wasm.js', header +
                'export default async function createTwinModule() {\n' +
                '    throw new Error("microrelief-three: no WebAssembly twin in this package (packed without emscripten, --no-wasm): picks are traced on the GPU; pickWith \'cpu\' is unavailable");\n}\n');
            writeText(folder, options.out, 'scene_checks_wasm.js', header +
                'export default async function createSceneChecksModule() {\n' +
                '    throw new Error(\'microrelief-three: no WebAssembly scene checks in this package (packed without emscripten, --no-wasm): loadSceneChecks is unavailable\');\n}\n');
        }
        writeText(folder, options.out, 'manifest.json', JSON.stringify({source: 'microrelief', files: manifest}, null, 1) + '\n');
        const made = fs.readdirSync(folder).sort().join(', ');
        if (made !== [...kOutputs].sort().join(', ')) throw new BuildError(kRuntime, `${printable(options.out)}: made ${made}, not the ${kOutputs.length} files expected`);
    });
}

try {
    await build(parseArguments(process.argv.slice(2)));
} catch (e) {
    // One line, never a stack trace: the cause of anything unforeseen, as the environment's.
    const status = e instanceof BuildError ? e.status : kRuntime;
    console.error(`${kProgram}: error: ${printable(e instanceof BuildError ? e.message : reason(e))}`);
    process.exit(status);
}
