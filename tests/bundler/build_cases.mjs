// microrelief-three's scripts/build.mjs held to the bundlers' table of cases
// (tests/bundler/cases.txt, which microrelief-glsl-bundle is held to as well:
// BundlerCasesTest.cpp), and to what only it does: it writes a folder (generated/), made
// fresh each run, never over a folder of other files; an error is one line, never a stack
// trace. One line a case on stdout ("ok NAME" or "FAILED NAME: why"); exit status 1 when one
// failed.
//
// node tests/bundler/build_cases.mjs packages/microrelief-three/scripts/build.mjs
import {spawnSync} from 'node:child_process';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import {fileURLToPath} from 'node:url';

const script = path.resolve(process.argv[2] ?? '');
if (!fs.existsSync(script)) {
    console.error(`build_cases: no build.mjs at '${process.argv[2] ?? ''}' (usage: node build_cases.mjs BUILD_MJS)`);
    process.exit(2);
}
const here = path.dirname(fileURLToPath(import.meta.url));
const kProgram = 'microrelief-three build';

// ---- the table (cases.txt's format: see its header) ----

function unescape(text) {
    return text.replace(/\\(x[0-9A-Fa-f]{2}|.)/g, (_, c) =>
        c === 'n' ? '\n' : c === 'r' ? '\r' : c === 't' ? '\t' : c.length === 3 ? String.fromCharCode(parseInt(c.slice(1), 16)) : c);
}

function readTable() {
    const blocks = [];
    let open = false;
    for (const line of fs.readFileSync(path.join(here, 'cases.txt'), 'utf8').split('\n')) {
        if (line === '') {
            open = false;
            continue;
        }
        if (line.startsWith('#')) continue;
        const space = line.indexOf(' ');
        const key = space < 0 ? line : line.slice(0, space);
        const value = space < 0 ? '' : unescape(line.slice(space + 1));
        if (!open) {
            blocks.push({name: key === 'case' ? value : key, keys: []});
            open = true;
        } else {
            blocks[blocks.length - 1].keys.push([key, value]);
        }
    }
    const all = (block, key) => block.keys.filter(([k]) => k === key).map(([, v]) => v);
    return blocks.map((b) => ({...b, all: (key) => all(b, key), get: (key, otherwise = '') => all(b, key)[0] ?? otherwise}));
}

const table = readTable();
const tree = table.find((b) => b.name === 'tree');

function makeTree(root) {
    for (const [kind, value] of tree.keys) {
        const space = value.indexOf(' ');
        const file = path.join(root, space < 0 ? value : value.slice(0, space));
        const rest = space < 0 ? '' : value.slice(space + 1);
        fs.mkdirSync(path.dirname(file), {recursive: true});
        if (kind === 'file') fs.writeFileSync(file, rest);
        else if (kind === 'link') fs.symlinkSync(rest, file);
        else if (kind === 'fifo') {
            if (spawnSync('mkfifo', [file]).status !== 0) throw new Error(`mkfifo ${file} failed`);
        } else if (kind === 'sparse') fs.truncateSync((fs.writeFileSync(file, ''), file), Number(rest));
        else throw new Error(`cases.txt: unknown tree entry '${kind}'`);
    }
    copyContracts(root);
}

// build.mjs makes generated/relief_layout.js with cmake/generate_contracts.py from the lists
// of cmake/Contracts.cmake: those, and the GLSL files they name, as the repository has them.
function copyContracts(root) {
    const repository = path.resolve(here, '..', '..');
    const contracts = fs.readFileSync(path.join(repository, 'cmake', 'Contracts.cmake'), 'utf8');
    const specs = ['MICRORELIEF_SHARED_CONSTANTS', 'MICRORELIEF_SHARED_ENUMS'].flatMap((name) =>
        new RegExp(`set\\(${name}\\s+([^)]*)\\)`).exec(contracts)[1].trim().split(/\s+/));
    const files = ['cmake/Contracts.cmake', 'cmake/generate_contracts.py', 'shaders/relief_parameters.glsl',
                   ...specs.map((spec) => `shaders/microrelief/${spec.split(':')[0]}`)];
    for (const file of new Set(files)) {
        fs.mkdirSync(path.dirname(path.join(root, file)), {recursive: true});
        fs.copyFileSync(path.join(repository, file), path.join(root, file));
    }
}

// ---- running build.mjs ----

// build.mjs under a 20 s limit (a FIFO waited on fails, not stalls), under a file size limit
// of `limit` bytes where given (SIGXFSZ ignored: a write past it fails with EFBIG, as on a
// full disk). --no-wgsl: the trees here are bundling cases, no library naga could translate
// (tests/webgpu/wgsl_generated.mjs holds the WGSL step).
function run(args, limit = 0) {
    const command = ['timeout', '20', ...(limit ? ['prlimit', `--fsize=${limit}`] : []), process.execPath, script, ...args, '--no-wgsl'];
    const r = spawnSync('sh', ['-c', `trap '' XFSZ; exec "$@"`, 'sh', ...command], {encoding: 'utf8'});
    return {status: r.status, out: r.stdout, err: r.stderr};
}

class CaseFailed extends Error {}
const expect = (condition, why) => {
    if (!condition) throw new CaseFailed(why);
};

function expectOneLineFailure(r, status, mentions) {
    const lines = r.err.split('\n').filter(Boolean);
    expect(r.status === status, `exit status ${r.status}, not ${status}: ${r.err}`);
    expect(lines.length === 1, `${lines.length} lines on stderr, not one: ${r.err}`);
    expect(lines[0]?.startsWith(`${kProgram}: error: `), `not "${kProgram}: error: ...": ${r.err}`);
    expect(r.err.includes(mentions), `the error does not mention '${mentions}': ${r.err}`);
}

const hiddenFilesIn = (folder) => (fs.existsSync(folder) ? fs.readdirSync(folder).filter((f) => f.startsWith('.')) : []);
const count = (text, part) => text.split(part).length - 1;
const listing = (folder) => fs.readdirSync(folder).sort().map((f) => [f, fs.readFileSync(path.join(folder, f), 'latin1')]);

function runCase(c, dir) {
    makeTree(dir);
    let text = `// main\n${c.get('include')}\n`;
    if (c.get('padding')) text += `#define MICRORELIEF_PADDING ${'.'.repeat(Number(c.get('padding')))}\n`;
    fs.writeFileSync(path.join(dir, 'shaders/microrelief/multilevel_trace.glsl'), `${text}void main() {${c.get('main')}}\n`);
    const out = path.join(dir, c.get('out.build', 'out/generated'));
    fs.mkdirSync(path.dirname(out), {recursive: true});
    const args = ['--source', dir, '--out', out, '--no-wasm'];
    const before = new Map(c.all('unchanged').map((f) => [f, fs.readFileSync(path.join(dir, f))]));
    const status = Number(c.get('status', '0'));
    let r, last = null;
    const limit = Number(c.get('file-size-limit', '0'));
    if (limit) {
        const whole = run(args);
        expect(whole.status === 0, `the run without a limit failed: ${whole.err}`);
        expect(fs.statSync(path.join(out, 'glsl.js')).size > limit, 'glsl.js is no larger than the limit: the case proves nothing');
        last = listing(out);
        r = run(args, limit);
    } else {
        r = run(args);
    }
    if (status === 0) {
        expect(r.status === 0, `exit status ${r.status}: ${r.err}`);
        const glsl = fs.readFileSync(path.join(out, 'glsl.js'), 'utf8');
        for (const part of c.all('contains')) expect(glsl.includes(part), `glsl.js does not hold '${part}'`);
        for (const part of c.all('once')) expect(count(glsl, part) === 1, `glsl.js holds '${part}' ${count(glsl, part)} times, not once`);
        for (const part of c.all('stripped')) expect(!glsl.includes(part), `glsl.js still holds '${part}'`);
        const library = JSON.parse(/^export const library = (.*);$/m.exec(glsl)[1]).split('\n');
        for (const spec of c.all('line')) {
            const [, n, text] = /^(\d+) (.*)$/s.exec(spec);
            expect(library[Number(n) - 1] === text, `the library's line ${n} is '${library[Number(n) - 1]}', not '${text}'`);
        }
    } else {
        expectOneLineFailure(r, status, c.get('reason'));
        if (c.get('at')) expect(r.err.includes(c.get('at')), `the error does not say where ('${c.get('at')}'): ${r.err}`);
        expect(!r.err.includes('\r') && !r.err.includes('\x01'), `a raw control character in the message: ${JSON.stringify(r.err)}`);
        if (last) expect(JSON.stringify(listing(out)) === JSON.stringify(last), 'the last output changed');
        else if (!c.all('unchanged').length) expect(!fs.existsSync(out), `a refused run made ${out}`);
        expect(hiddenFilesIn(path.dirname(out)).length === 0, `temporaries left: ${hiddenFilesIn(path.dirname(out))}`);
    }
    for (const [file, bytes] of before) expect(bytes.equals(fs.readFileSync(path.join(dir, file))), `${file} changed`);
}

// ---- what only build.mjs does: a folder ----

// generated/ is made fresh: a file the last run left that this one does not make is gone
// (a stale file would be published by npm pack), and what the last run made is replaced.
function staleFilesGo(dir) {
    makeTree(dir);
    fs.writeFileSync(path.join(dir, 'shaders/microrelief/multilevel_trace.glsl'), '// main\nvoid main() {}\n');
    const out = path.join(dir, 'generated');
    const first = run(['--source', dir, '--out', out, '--no-wasm']);
    expect(first.status === 0, first.err);
    fs.writeFileSync(path.join(out, 'stale.js'), 'export const old = 1;\n');
    fs.writeFileSync(path.join(out, 'png.js'), 'tampered\n');
    const again = run(['--source', dir, '--out', out, '--no-wasm']);
    expect(again.status === 0, again.err);
    expect(!fs.existsSync(path.join(out, 'stale.js')), 'stale.js survived the run');
    expect(fs.readFileSync(path.join(out, 'png.js'), 'utf8').includes('// png.js'), 'png.js was not made again');
    expect(JSON.stringify(fs.readdirSync(out).sort()) ===
               JSON.stringify(['glsl.js', 'manifest.json', 'png.js', 'pyramid_wasm.js', 'relief_core.js', 'relief_layout.js', 'scene_checks.js', 'scene_checks_wasm.js', 'twin_wasm.js', 'wgsl.js']),
           `generated/ holds ${fs.readdirSync(out)}`);
    expect(hiddenFilesIn(dir).length === 0, `temporaries left: ${hiddenFilesIn(dir)}`);
}

// A folder of other files (a home folder, the repository) is not replaced; nor is a file.
function otherFoldersAreNotReplaced(dir) {
    makeTree(dir);
    fs.writeFileSync(path.join(dir, 'shaders/microrelief/multilevel_trace.glsl'), '// main\nvoid main() {}\n');
    const mine = path.join(dir, 'mine');
    fs.mkdirSync(mine);
    fs.writeFileSync(path.join(mine, 'notes.txt'), 'mine\n');
    const r = run(['--source', dir, '--out', mine, '--no-wasm']);
    expectOneLineFailure(r, 2, 'holds files this script did not make');
    expect(fs.readFileSync(path.join(mine, 'notes.txt'), 'utf8') === 'mine\n', 'notes.txt changed');
    expect(fs.readdirSync(mine).length === 1, `mine/ holds ${fs.readdirSync(mine)}`);
    const file = path.join(dir, 'a-file');
    fs.writeFileSync(file, 'x');
    expectOneLineFailure(run(['--source', dir, '--out', file, '--no-wasm']), 2, 'not a folder');
    expectOneLineFailure(run(['--source', dir, '--out', dir, '--no-wasm']), 2, 'which this run reads');
    expect(hiddenFilesIn(dir).length === 0, `temporaries left: ${hiddenFilesIn(dir)}`);
}

// Bad arguments: one line, status 2.
function badArguments(dir) {
    expectOneLineFailure(run(['--frobnicate']), 2, "unknown argument '--frobnicate'");
    expectOneLineFailure(run(['--source', path.join(dir, 'nowhere'), '--out', path.join(dir, 'g')]), 2, 'not the microrelief repository');
}

const checks = [
    ...table.filter((b) => b.name !== 'tree').map((c) => [c.name, (dir) => runCase(c, dir)]),
    ['GeneratedIsMadeFreshEachRun', staleFilesGo],
    ['AFolderOfOtherFilesIsNotReplaced', otherFoldersAreNotReplaced],
    ['BadArgumentsAreOneLine', badArguments],
];
let failed = 0;
for (const [name, check] of checks) {
    const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'build-cases-'));
    try {
        check(dir);
        console.log(`ok ${name}`);
    } catch (e) {
        ++failed;
        console.log(`FAILED ${name}: ${e instanceof CaseFailed ? e.message : e.stack}`);
    } finally {
        fs.rmSync(dir, {recursive: true, force: true});
    }
}
console.log(`build_cases: ${checks.length - failed} of ${checks.length} passed`);
if (checks.length < 28) {
    console.log('build_cases: fewer checks than the table had when written: is cases.txt read?');
    failed = failed || 1;
}
process.exit(failed ? 1 : 0);
