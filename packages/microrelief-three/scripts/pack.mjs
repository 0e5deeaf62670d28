#!/usr/bin/env node
// pack.mjs: the package's tarball, packed from a staged copy so that nothing is written into
// the source tree (`npm run tarball`; CMake's target microrelief-three-tarball; the test
// three.pack). The stage, OUT/microrelief-three/, holds what a consumer runs and nothing
// else: package.json (its scripts left out: they name build files the tarball does not
// ship), README.md, the repository's LICENSE, src/ (the modules and their .d.ts
// declarations) and generated/ (scripts/build.mjs: the GLSL, the PNG decoder, the scene
// checks and the pyramid in WebAssembly); `npm pack` of it writes
// OUT/microrelief-three-<version>.tgz.
//
// Without em++ on PATH (Debian package emscripten), or with --no-wasm, the package is
// packed without the WebAssembly: the CPU pyramid path and the scene checks then refuse at
// run time with one line, and this script says so when it packs.
//
// `npm pack` in the source folder itself is refused (its prepack runs this with
// --refuse-in-place): it would pack the build inputs and no generated/, or write generated/
// into the tree. An error is one line on stderr, exit status 2 for bad input, 1 for the
// environment (npm, a full disk).
//
// Usage: node scripts/pack.mjs [--out DIR] [--source DIR] [--no-wasm] [--no-wgsl]
//   --out DIR     where to stage and write the tarball (default: the repository's build/npm);
//                 never the package's folder or a folder holding it
//   --source DIR  the repository (default: MICRORELIEF_SOURCE_DIR, else ../.. of the package)
//   --no-wasm     pack without the WebAssembly even where em++ is there
//   --no-wgsl     pack without the library's WGSL (build.mjs --no-wgsl: no naga-wasm)
import {execFileSync} from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import {fileURLToPath} from 'node:url';

const packageDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const kProgram = 'microrelief-three pack';
const kBadInput = 2, kRuntime = 1;  // exit statuses, as scripts/build.mjs's

class PackError extends Error {
    constructor(status, message) {
        super(message);
        this.status = status;
    }
}

// Control characters written as escapes: a message stays one line.
const printable = (text) => String(text).replace(/[\x00-\x1f\x7f]/g, (c) => `\\x${c.charCodeAt(0).toString(16).padStart(2, '0')}`);
const firstLine = (e) => printable(String(e && e.message ? e.message : e).split('\n')[0]);

function parseArguments(argv) {
    const options = {source: process.env.MICRORELIEF_SOURCE_DIR || path.resolve(packageDir, '../..'), out: null, wasm: true, wgsl: true, refuse: false};
    for (let k = 0; k < argv.length; ++k) {
        const a = argv[k];
        if (a === '--out' && k + 1 < argv.length) options.out = path.resolve(argv[++k]);
        else if (a === '--source' && k + 1 < argv.length) options.source = path.resolve(argv[++k]);
        else if (a === '--no-wasm') options.wasm = false;
        else if (a === '--no-wgsl') options.wgsl = false;
        else if (a === '--refuse-in-place') options.refuse = true;
        else throw new PackError(kBadInput, `unknown argument '${printable(a)}' (see the header of scripts/pack.mjs)`);
    }
    options.source = path.resolve(options.source);
    options.out ??= path.join(options.source, 'build', 'npm');
    return options;
}

function findProgram(name) {
    for (const dir of (process.env.PATH || '').split(path.delimiter)) {
        const candidate = path.join(dir || '.', name);
        try {
            fs.accessSync(candidate, fs.constants.X_OK);
            if (fs.statSync(candidate).isFile()) return candidate;
        } catch {}
    }
    return null;
}

// `file` with its links resolved as far as it exists.
function realPath(file) {
    const tail = [];
    for (let head = path.resolve(file); ; head = path.dirname(head)) {
        try {
            return path.join(fs.realpathSync(head), ...tail);
        } catch {
            if (path.dirname(head) === head) return path.resolve(file);
            tail.unshift(path.basename(head));
        }
    }
}

const isWithin = (file, root) => {
    const relative = path.relative(root, file);
    return relative === '' || (relative !== '..' && !relative.startsWith(`..${path.sep}`) && !path.isAbsolute(relative));
};

// Runs a step, turning a file system failure into one line naming `what`.
function attempt(what, step) {
    try {
        return step();
    } catch (e) {
        if (e instanceof PackError) throw e;
        throw new PackError(kRuntime, `${printable(what)}: ${firstLine(e).replace(/^[A-Z]+: /, '')}`);
    }
}

// The stage, made fresh: a folder this script made before (its package.json names the
// package) is replaced; anything else there is refused, never deleted.
function freshStage(stage, name) {
    if (fs.existsSync(stage)) {
        let manifest = null;
        try {
            manifest = JSON.parse(fs.readFileSync(path.join(stage, 'package.json'), 'utf8'));
        } catch {}
        if (!manifest || manifest.name !== name || fs.existsSync(path.join(stage, 'scripts')))
            throw new PackError(kBadInput, `--out: ${printable(stage)} holds files this script did not stage: name another --out`);
        attempt(stage, () => fs.rmSync(stage, {recursive: true}));
    }
    attempt(stage, () => fs.mkdirSync(path.join(stage, 'src'), {recursive: true}));
}

function copy(from, to) {
    attempt(from, () => {
        if (!fs.statSync(from).isFile()) throw new PackError(kBadInput, `${printable(from)}: not a regular file`);
        fs.copyFileSync(from, to);
    });
}

// npm itself: the one running this script (npm run tarball), else npm on PATH.
function npm(args, cwd) {
    const [program, before] = process.env.npm_execpath && /\.[cm]?js$/.test(process.env.npm_execpath)
        ? [process.execPath, [process.env.npm_execpath]]
        : [findProgram('npm'), []];
    if (!program) throw new PackError(kRuntime, 'no npm on PATH (Debian package npm)');
    try {
        return execFileSync(program, [...before, ...args], {cwd, encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe']});
    } catch (e) {
        const said = String(e.stderr || '').split('\n').find((l) => /error/i.test(l)) || firstLine(e);
        throw new PackError(kRuntime, `npm ${args[0]} failed in ${printable(cwd)} (${printable(said.trim())})`);
    }
}

function pack(options) {
    if (options.refuse)
        throw new PackError(kBadInput, `npm pack of the source folder would ship its build inputs and no generated/: run \`npm run tarball\` (node scripts/pack.mjs), which packs a staged copy into ${printable(path.relative(process.cwd(), options.out) || '.')}`);
    const manifest = JSON.parse(fs.readFileSync(path.join(packageDir, 'package.json'), 'utf8'));
    const stage = path.join(options.out, manifest.name);
    const real = realPath(stage);
    if (isWithin(real, realPath(packageDir)) || isWithin(realPath(packageDir), real))
        throw new PackError(kBadInput, `--out ${printable(options.out)}: the stage ${printable(stage)} would be in the package's folder or hold it: name a folder outside it (the build folder)`);
    const licence = path.join(options.source, 'LICENSE');
    if (!fs.existsSync(licence))
        throw new PackError(kBadInput, `${printable(options.source)}: no LICENSE (not the microrelief repository? set MICRORELIEF_SOURCE_DIR or --source)`);

    freshStage(stage, manifest.name);
    const {scripts, ...shipped} = manifest;
    attempt(path.join(stage, 'package.json'), () => fs.writeFileSync(path.join(stage, 'package.json'), JSON.stringify(shipped, null, 2) + '\n'));
    copy(path.join(packageDir, 'README.md'), path.join(stage, 'README.md'));
    copy(licence, path.join(stage, 'LICENSE'));
    for (const file of fs.readdirSync(path.join(packageDir, 'src')).sort())
        if (/\.(js|d\.ts)$/.test(file)) copy(path.join(packageDir, 'src', file), path.join(stage, 'src', file));

    const wasm = options.wasm && findProgram('em++') !== null;
    if (options.wasm && !wasm)
        console.error(`${kProgram}: note: no em++ on PATH (Debian package emscripten): packing without the WebAssembly, so the CPU pyramid path and the scene checks refuse at run time`);
    try {
        execFileSync(process.execPath, [path.join(packageDir, 'scripts', 'build.mjs'), '--out', path.join(stage, 'generated'), '--source', options.source,
                                        ...(wasm ? [] : ['--no-wasm']), ...(options.wgsl ? [] : ['--no-wgsl'])], {stdio: ['ignore', 'ignore', 'inherit']});
    } catch (e) {
        // build.mjs said why, in one line of its own.
        throw new PackError(e.status === kBadInput ? kBadInput : kRuntime, 'scripts/build.mjs failed (above)');
    }
    const packed = JSON.parse(npm(['pack', '--ignore-scripts', '--json', '--pack-destination', options.out], stage));
    const tarball = path.join(options.out, packed[0].filename);
    const shown = path.relative(process.cwd(), tarball);
    console.log(`${kProgram}: ${shown.startsWith('..') ? tarball : shown} (${packed[0].entryCount} files${wasm ? '' : ', without the WebAssembly'})`);
}

try {
    pack(parseArguments(process.argv.slice(2)));
} catch (e) {
    console.error(`${kProgram}: error: ${e instanceof PackError ? printable(e.message) : firstLine(e)}`);
    process.exit(e instanceof PackError ? e.status : kRuntime);
}
