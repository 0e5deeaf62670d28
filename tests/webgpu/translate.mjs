#!/usr/bin/env node
// translate.mjs: a GLSL entry and the library it includes, assembled as the page assembles its
// shaders (web/shader_source.js: #version, the #defines, each #include "..." spliced once),
// written as GLSL or translated to WGSL by naga's GLSL front end through
// packages/microrelief-three/scripts/wgsl.mjs, as the package's build translates
// (docs/webgpu.md says why naga and what it needs of the GLSL). For WGSL the entry is assembled as GLSL 4.50 with VULKAN defined (separate textures
// and samplers: tests/webgpu/entry.frag sets the library's read hooks for them).
//
// Usage: node tests/webgpu/translate.mjs --entry FILE --out FILE [--shaders DIR]
//            [--version '300 es' | --wgsl] [--define NAME=VALUE ...]
//   --shaders DIR  the folder whose microrelief/ the entry includes (default: the repository's)
//   --wgsl         translate (else write the assembled GLSL for --version, default '300 es')
// An error is one line on stderr and exit status 2 (bad arguments, a missing file, no naga-wasm)
// or 1 (naga refused the source: its first lines, with the assembled line it names).
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import {fileURLToPath, pathToFileURL} from 'node:url';

const repo = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const fail = (status, message) => {
    process.stderr.write(`translate.mjs: ${message}\n`);
    process.exit(status);
};

const options = {
    shaders: path.join(repo, 'shaders'),
    version: '300 es',
    wgsl: false,
    defines: []
};
const argv = process.argv.slice(2);
for (let k = 0; k < argv.length; ++k) {
    const a = argv[k], value = () => (k + 1 < argv.length ? argv[++k] : fail(2, `${a} needs a value`));
    if (a === '--entry')
        options.entry = path.resolve(value());
    else if (a === '--out')
        options.out = path.resolve(value());
    else if (a === '--shaders')
        options.shaders = path.resolve(value());
    else if (a === '--version')
        options.version = value();
    else if (a === '--wgsl')
        options.wgsl = true;
    else if (a === '--define') {
        const [name, ...rest] = value().split('=');
        options.defines.push([name, rest.join('=')]);
    } else
        fail(2, `unknown argument '${a}' (see the header of tests/webgpu/translate.mjs)`);
}
if (!options.entry || !options.out) fail(2, '--entry and --out are required');

// The page's own assembler, reading files: fetch and document.baseURI as the page has them.
globalThis.document = {
    baseURI: pathToFileURL(options.entry).href
};
globalThis.fetch = async (url) => {
    const file = fileURLToPath(url);
    if (!fs.existsSync(file) || !fs.statSync(file).isFile()) return {status: 404, ok: false};
    return {status: 200, ok: true, text: async () => fs.readFileSync(file, 'utf8')};
};
// Copied into a scratch folder marked as ES modules: node before 22 (Debian 12's is 18)
// reads a .js file as CommonJS unless a package.json says otherwise.
const scratch = fs.mkdtempSync(path.join(os.tmpdir(), 'translate-'));
process.on('exit', () => fs.rmSync(scratch, {recursive: true, force: true}));
fs.copyFileSync(path.join(repo, 'web/shader_source.js'), path.join(scratch, 'shader_source.js'));
fs.writeFileSync(path.join(scratch, 'package.json'), '{"type": "module"}\n');
const {ShaderFiles} = await import(pathToFileURL(path.join(scratch, 'shader_source.js')).href);
const version = options.wgsl ? '450' : options.version;
const defines = options.wgsl ? [['VULKAN', ''], ...options.defines] : options.defines;
let source;
try {
    source = await new ShaderFiles().assemble(
        pathToFileURL(options.entry).href, version, defines, [pathToFileURL(options.shaders).href + '/']);
} catch (e) {
    fail(2, e.message);
}
if (!options.wgsl) {
    fs.writeFileSync(options.out, source.text);
    process.exit(0);
}
// The translator as the package's build runs it (packages/microrelief-three/scripts/wgsl.mjs).
const {loadNaga, translate, WgslError} = await import(pathToFileURL(path.join(repo, 'packages/microrelief-three/scripts/wgsl.mjs')).href);
try {
    const naga = await loadNaga();
    fs.writeFileSync(options.out, `// naga ${naga.nagaVersion} from ${path.relative(repo, options.entry)}\n` +
                                      translate(naga, source.text, path.relative(repo, options.entry)));
} catch (e) {
    if (!(e instanceof WgslError)) throw e;
    fail(/^no naga-wasm/.test(e.message) ? 2 : 1, e.message);
}
