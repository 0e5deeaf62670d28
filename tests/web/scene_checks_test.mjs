// The browser front ends refuse what microrelief-render refuses, in its words (issue 47,
// "one validation for every front end"): each view below, set in a page's URL (the web
// page's scene.js, examples/three's view.js) and checked by web/scene_checks.js (the C++
// checks compiled to WebAssembly) over the bundled map at a picture's size, is refused with
// exactly the message microrelief-render prints for the same flags at that --size, its
// flags written as the page's URL keys; a view the program draws passes. No browser: node
// runs the pages' own modules as staged in the build tree (the browser tests show the pages
// act on it: tests/web, tests/three). And the page's parameter block (relief_layout.js's
// writeParameters) refuses a member left out. One line a case on stdout; exit status 1 when
// one failed.
//
// node tests/web/scene_checks_test.mjs RENDER STAGED_SHARE   (STAGED_SHARE: share/microrelief)
import {spawnSync} from 'node:child_process';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import {pathToFileURL} from 'node:url';

const [render, share] = process.argv.slice(2);
if (!render || !share || !fs.existsSync(path.join(share, 'web', 'scene_checks.js'))) {
    console.error('usage: node scene_checks_test.mjs RENDER STAGED_SHARE (the build tree\'s share/microrelief)');
    process.exit(2);
}

// The pages' modules in a scratch folder marked as ES modules (node before 22 reads a .js
// file as CommonJS unless a package.json says otherwise).
const scratch = fs.mkdtempSync(path.join(os.tmpdir(), 'scene-checks-'));
process.on('exit', () => fs.rmSync(scratch, {recursive: true, force: true}));
// examples/three is staged where the build stages microrelief-three (MICRORELIEF_BUILD_THREE).
const withThree = fs.existsSync(path.join(share, 'web', 'three', 'view.js'));
// examples/three's view.js reads the table of bases from the package beside it (its package.json
// too: node takes a package's module type from it, not from above node_modules).
const threePackage = 'three/node_modules/microrelief-three';
const modules = ['scene.js', 'relief_core.js', 'relief_layout.js', 'scene_checks.js', 'png.js', 'generated/scene_checks_wasm.js',
                 ...(withThree ? ['three/view.js', ...['package.json', 'generated/relief_core.js', 'generated/relief_layout.js'].map((f) => `${threePackage}/${f}`)] : [])];
for (const file of modules) {
    fs.mkdirSync(path.dirname(path.join(scratch, file)), {recursive: true});
    fs.copyFileSync(path.join(share, 'web', file), path.join(scratch, file));
}
fs.writeFileSync(path.join(scratch, 'package.json'), '{"type": "module"}\n');
const load = (file) => import(pathToFileURL(path.join(scratch, file)).href);
const scene = await load('scene.js');
const threeView = withThree ? await load('three/view.js') : null;
if (!withThree) console.log('scene_checks_test: examples/three is not staged in this build: its cases are not run');
const {SceneChecks, kFieldNames, largestSample} = await load('scene_checks.js');
const {decodePng, heightsFromPng} = await load('png.js');
const checks = await SceneChecks.load((await load('generated/scene_checks_wasm.js')).default);

// The bundled map, as the pages read it.
const asset = path.resolve(share, 'assets', 'cobbles.png');
const png = await decodePng(new Uint8Array(fs.readFileSync(asset)));
const samples = heightsFromPng(png, 0);
const cobbles = {width: png.width, height: png.height, maxHeight: largestSample(samples), name: 'cobbles.png'};

// microrelief-render's message, its flags written as the page's names for them (a key, or
// the flag itself where the page has no key for the field: kFieldNames) and the bundled map
// named as the pages name it.
const names = new Set([...Object.values(kFieldNames), 'radius', 'length', 'radii']);
function inThePagesWords(message) {
    return message.split(asset).join('cobbles.png').replace(/--([a-z][a-z-]*)/g, (flag, key) => {
        if (names.has(key)) return key;
        if (names.has(flag)) return flag;
        throw new Error(`${flag}: a flag the pages have no name for (scene_checks.js: kFieldNames)`);
    });
}

function renderMessage(flags, [width, height]) {
    const r = spawnSync(render, ['--quiet', '--size', `${width}x${height}`, ...flags, '--out', path.join(scratch, 'x.png')], {encoding: 'utf8'});
    if (r.status === 0) return '';
    const prefix = 'microrelief-render: error: ';
    if (r.status !== 2 || !r.stderr.startsWith(prefix)) throw new Error(`microrelief-render ${flags.join(' ')}: status ${r.status}: ${r.stderr}`);
    return inThePagesWords(r.stderr.slice(prefix.length).trim());
}

// Each view as a page's URL and as microrelief-render's flags, at a picture's size.
const cases = [
    // Drawn by both.
    {page: 'web', query: 'eye=1,0.6,0.9&fovy=30', flags: ['--eye', '1,0.6,0.9', '--fovy', '30']},
    {page: 'three', query: 'shading=microrelief&base=cylinder&radius=0.4', flags: ['--base', 'cylinder', '--radius', '0.4']},
    // The issue's: a blank canvas called "ready" on the page.
    {page: 'web', query: 'fovy=1e-37', flags: ['--fovy', '1e-37']},
    {page: 'web', query: 'height-scale=1e30', flags: ['--height-scale', '1e30']},
    {page: 'web', query: 'base=cylinder&length=1e8', flags: ['--base', 'cylinder', '--length', '1e8']},
    {page: 'three', query: 'model=1,0,0,0,0,1,0,0,0,0,0,0', flags: ['--model', '1,0,0,0,0,1,0,0,0,0,0,0']},
    {page: 'three', query: 'fovy=1e-37', flags: ['--fovy', '1e-37']},
    {page: 'three', query: 'eye=0.5,0.5,0.5&target=0.5,0.5,0.5', flags: ['--eye', '0.5,0.5,0.5', '--target', '0.5,0.5,0.5']},
    // And what else the checks hold: the field of view at this picture's height, a model
    // that shrinks the relief past float's normals, a base size the base has not, the
    // method and the base, the light.
    {page: 'web', query: 'fovy=0.001', flags: ['--fovy', '0.001'], pixels: [64, 480]},
    {page: 'three', query: 'model=1e-25,0,0,0,0,1e-25,0,0,0,0,1e-25,0', flags: ['--model', '1e-25,0,0,0,0,1e-25,0,0,0,0,1e-25,0']},
    {page: 'web', query: 'base=sphere&length=2', flags: ['--base', 'sphere', '--length', '2']},
    {page: 'web', query: 'base=cylinder&method=steep', flags: ['--base', 'cylinder', '--method', 'steep']},
    {page: 'three', query: 'light=0,0,0', flags: ['--light', '0,0,0']},
    {page: 'web', query: 'steps=0&method=pom', flags: ['--steps', '0', '--method', 'pom']},
];

let failed = 0;
const report = (name, problem) => {
    failed += problem ? 1 : 0;
    console.log(problem ? `FAILED ${name}: ${problem}` : `ok ${name}`);
};
for (const c of cases.filter((c) => c.page === 'web' || withThree)) {
    const pixels = c.pixels ?? [64, 48];
    const name = `${c.page}?${c.query} at ${pixels.join('x')}`;
    try {
        const view = c.page === 'web' ? scene.viewFromQuery(`?${c.query}`) : threeView.viewFromUrl(`?${c.query}`);
        const page = checks.refusal(view, cobbles, pixels);
        const program = renderMessage(c.flags, pixels);
        report(name, page === program ? '' : `the page says\n    '${page}'\n  microrelief-render says\n    '${program}'`);
    } catch (e) {
        report(name, e.message);
    }
}
// Every field a message may name has a name on the pages, but map.samples (no text sets it)
// and mesh.file (the mesh base is microrelief-render's alone so far: issue 50).
const unnamed = checks.unnamedFields();
report('every field has a name', JSON.stringify(unnamed) === '["map.samples","mesh.file"]' ? '' : `no names for ${unnamed}`);
// The page fills the parameter block through relief_layout.js (generated from
// shaders/relief_parameters.glsl): a member left out, a name that is not a member, or a wrong
// count is refused, and a block with every member given is written whole.
const layout = await load('relief_layout.js');
const everyMember = Object.fromEntries(Object.entries(layout.kParameters).map(([name, m]) => [name, m.count === 1 ? 1 : new Array(m.count).fill(1)]));
const refusedWith = (values) => {
    try {
        layout.writeParameters(values);
        return '';
    } catch (e) {
        return e.message;
    }
};
const [firstMember] = Object.keys(layout.kParameters);
const {[firstMember]: _left, ...allButFirst} = everyMember;
const writes = [
    ['every member given', refusedWith(everyMember), ''],
    ['a member left out', refusedWith(allButFirst), `${layout.kParametersBlock}: no value for ${firstMember}`],
    ['an unknown member', refusedWith({...everyMember, noSuchMember: 1}), `${layout.kParametersBlock} has no member noSuchMember`],
];
for (const [name, got, want] of writes) report(`writeParameters: ${name}`, got === want ? '' : `'${got}', not '${want}'`);
const run = cases.filter((c) => c.page === 'web' || withThree).length + 1 + writes.length;
console.log(`scene_checks_test: ${run - failed} of ${run} passed`);
process.exit(failed ? 1 : 0);
