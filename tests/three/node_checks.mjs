// The installed microrelief-three under node, no browser (tests/three: ThreeTarball.*): run in
// a project folder, it imports the package as that project resolves it and prints one line
// per case, "case: ok" or "case: <error class>: <message>" (a message's line breaks kept as
// \n, so a two-line message shows).
//   node node_checks.mjs revision   the calls that make a relief, on whatever three is installed
//   node node_checks.mjs base       a base and a map that disagree on wrapU
//   node node_checks.mjs wasm       the WebAssembly's uses (loadSceneChecks, pyramid 'cpu', the picks' twin)
import {createRequire} from 'node:module';
import * as path from 'node:path';
import {pathToFileURL} from 'node:url';

const entry = createRequire(path.join(process.cwd(), 'package.json')).resolve('microrelief-three');
const m = await import(pathToFileURL(entry));

// A renderer as far as createReliefMap looks before it builds (no WebGL under node).
const renderer = {isWebGLRenderer: true, capabilities: {maxTextureSize: 4096}, extensions: {has: () => false}};
const heights = m.heightsFromArray(new Float32Array([0, 0.5, 0.25, 1]), 2, 2, {name: 'tiny'});
// A ReliefMap as far as the Relief looks before it draws.
const map = (wrapU) => ({windows: {}, heights: {}, wrapU, width: 2, height: 2, maxHeight: 1, levelCount: 2});

const cases = {
    revision: {
        material: () => new m.ReliefStandardMaterial(),
        physical: () => new m.ReliefPhysicalMaterial(),
        shading: () => new m.ReliefShadingMaterial(),
        relief: () => new m.Relief(map(false)),
        map: () => m.createReliefMap(renderer, heights, {pyramid: 'cpu'}).then(() => {}, (e) => {
            if (/WebAssembly/.test(e.message)) return;  // got past the revision (this package may have no wasm)
            throw e;
        }),
    },
    base: {
        ellipsoid: () => new m.Relief(map(false), {base: 'ellipsoid'}),
        sphere: () => new m.Relief(map(false), {base: {kind: 'sphere', radius: 0.4}}),
        cylinder: () => new m.Relief(map(false), {base: 'cylinder'}),
        plane: () => new m.Relief(map(true), {base: 'plane'}),
    },
    wasm: {
        checks: () => m.loadSceneChecks(),
        cpu: () => m.createReliefMap(renderer, heights, {pyramid: 'cpu'}),
        // A pick on the CPU twin (createReliefMap, just above, loaded it where there is one).
        pick: () => {
            const relief = new m.Relief({...map(false), heights: {image: {data: heights.samples}}, name: 'tiny'});
            const rays = relief.traceRays([0, 1, 0], [0, -1, 0], [0, 2], {on: 'cpu'});
            if (rays.kind[0] !== 1 || rays.on !== 'cpu') throw new Error(`kind ${rays.kind[0]} on ${rays.on}`);
        },
    },
};

const which = cases[process.argv[2]];
if (!which) {
    console.error(`node_checks.mjs: unknown case list '${process.argv[2]}' (${Object.keys(cases).join(', ')})`);
    process.exit(2);
}
for (const [name, call] of Object.entries(which)) {
    try {
        await call();
        console.log(`${name}: ok`);
    } catch (e) {
        console.log(`${name}: ${e.constructor.name}: ${String(e.message).replace(/\n/g, '\\n')}`);
    }
}
