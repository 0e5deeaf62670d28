#!/usr/bin/env node
// webgl_entry_on_webgpu.mjs: microrelief-three's WebGL entry, given a WebGPURenderer, says in
// one line that it draws with a WebGLRenderer and names the WebGPU entry (issue 51: it used
// to refuse as "not a WebGLRenderer", and a relief drew as its white box, silently). Under
// node, no browser: a renderer is what three marks it (WebGPURenderer sets isWebGPURenderer,
// WebGLRenderer isWebGLRenderer), as tests/three/node_checks.mjs fakes one. One line a case,
// "ok NAME" or "FAILED NAME: why"; exit status 1 when one failed. ctest three.webgpu_renderer.
//
// Usage: node tests/webgpu/webgl_entry_on_webgpu.mjs PACKAGE_DIR (a built microrelief-three)
import * as fs from 'node:fs';
import * as path from 'node:path';
import {pathToFileURL} from 'node:url';

const entry = path.resolve(process.argv[2] ?? '', 'src', 'index.js');
if (!fs.existsSync(entry)) {
    console.error(`webgl_entry_on_webgpu.mjs: no ${entry} (usage: node webgl_entry_on_webgpu.mjs PACKAGE_DIR)`);
    process.exit(2);
}
const m = await import(pathToFileURL(entry).href);

const webgpu = {isWebGPURenderer: true, isRenderer: true, capabilities: {maxTextureSize: 4096}};
const heights = m.heightsFromArray(new Float32Array([0, 0.5, 0.25, 1]), 2, 2, {name: 'tiny'});
const map = {windows: {}, heights: {}, wrapU: false, width: 2, height: 2, maxHeight: 1, levelCount: 2};

// The one line: names the renderer and the entry to import instead.
function pointsAtWebGPUEntry(message) {
    const why = [];
    if (message.includes('\n')) why.push('more than one line');
    for (const part of ['WebGPURenderer', "import from 'microrelief-three/webgpu'", 'WebGLRenderer'])
        if (!message.includes(part)) why.push(`no '${part}'`);
    return why;
}

async function refusal(call) {
    try {
        await call();
    } catch (e) {
        return e;
    }
    return null;
}

const cases = {
    async createReliefMapNamesTheWebGPUEntry() {
        const e = await refusal(() => m.createReliefMap(webgpu, heights, {pyramid: 'cpu'}));
        if (!e) return ['createReliefMap took a WebGPURenderer'];
        return [...(e instanceof TypeError ? [] : [`a ${e.constructor.name}, not a TypeError`]), ...pointsAtWebGPUEntry(e.message)];
    },
    async otherRenderersAreStillNotAWebGLRenderer() {
        const e = await refusal(() => m.createReliefMap({}, heights, {pyramid: 'cpu'}));
        if (!e) return ['createReliefMap took {}'];
        return /must be a THREE\.WebGLRenderer/.test(e.message) && !/webgpu/i.test(e.message) ? [] : [`'${e.message}'`];
    },
    async aReliefDrawnByAWebGPURendererSaysSoOnce() {
        const relief = new m.Relief(map);
        const said = [];
        const error = console.error;
        console.error = (...a) => said.push(a.join(' '));
        try {
            for (let frame = 0; frame < 3; ++frame) relief.onBeforeRender(webgpu, null, null, null, relief.material, null);
            new m.Relief(map).onBeforeRender(webgpu, null, null, null, null, null);  // once a renderer, not a relief
        } catch (e) {
            return [`onBeforeRender threw ${e.constructor.name}: ${e.message}`];
        } finally {
            console.error = error;
        }
        if (said.length !== 1) return [`${said.length} messages in 3 frames of 2 reliefs, not 1: ${JSON.stringify(said)}`];
        return [...(said[0].startsWith('Relief: ') ? [] : ['not "Relief: ..."']), ...pointsAtWebGPUEntry(said[0])];
    },
};

let failed = 0;
for (const [name, check] of Object.entries(cases)) {
    const why = await check();
    if (why.length) ++failed;
    console.log(why.length ? `FAILED ${name}: ${why.join('; ')}` : `ok ${name}`);
}
process.exit(failed ? 1 : 0);
