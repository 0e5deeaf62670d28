// main.js: the page around the example. Reads the URL (view.js), sizes the canvas, runs
// cobbles.js (the three-lit scene; cobbles_webgpu.js with renderer=webgpu) or, with
// shading=microrelief, compare.js (the library's own shading, to hold against
// microrelief-render) on the renderer the URL asks for (renderers.js), and reports its state
// as the web page does (<html data-state="loading|ready|error">, #error, and once the first
// frame is drawn data-api="webgl2|webgpu") for the tests, which find the scene's objects in
// window.microreliefThree. The URL's view is held to the programs' own checks first
// (microrelief-three's loadSceneChecks: the C++ in WebAssembly), and over the map at the
// canvas's size before it is drawn: one they refuse is an error in their words, with this
// page's keys for their flags.
import * as microrelief from 'microrelief-three';

import {kApiOf, rendererKit} from './renderers.js';
import {viewFromUrl} from './view.js';

const root = document.documentElement;

function fail(message) {
    document.getElementById('error').textContent = message;
    root.dataset.state = 'error';
}

async function start() {
    let view, checks;
    try {
        checks = await microrelief.loadSceneChecks();
    } catch (e) {
        fail(`the scene checks: ${e.message}`);
        return;
    }
    try {
        view = viewFromUrl(location.search);
        const why = checks.refusal(view);
        if (why) throw new Error(why);
    } catch (e) {
        fail(`the URL: ${e.message}`);
        return;
    }
    root.classList.toggle('clean', view.clean);
    const canvas = document.getElementById('canvas');
    const size = () => view.size ?? [Math.max(1, innerWidth), Math.max(1, innerHeight)];
    const [width, height] = size();
    Object.assign(canvas.style, {width: `${width}px`, height: `${height}px`});
    Object.assign(canvas, {width, height});
    let app, kit;
    try {
        kit = await rendererKit(view.renderer);
        const scene = view.shading === 'microrelief' ? (await import('./compare.js')).compare
                                                     : (await import(view.renderer === 'webgpu' ? './cobbles_webgpu.js' : './cobbles.js')).cobbles;
        app = await scene(canvas, view, kit);
    } catch (e) {
        console.error(e);
        fail(e.message);
        return;
    }
    // The float limits need the map and the picture: checked before the first draw.
    const why = checks.refusal(view, {width: app.map.width, height: app.map.height, maxHeight: app.map.maxSample, name: 'cobbles.png'}, [width, height]);
    if (why) {
        fail(`the URL: ${why}`);
        return;
    }
    const render = async () => {
        app.renderer.render(app.scene, app.camera);
        await kit.finish(app.renderer);  // waits for the picture
    };
    // A shader three cannot compile is this page's error (three itself only logs it).
    if (app.renderer.isWebGLRenderer) app.renderer.debug.onShaderError = (gl, program, vertex, fragment) => {
        const report = [vertex, fragment].map((shader) => {
            const log = (gl.getShaderInfoLog(shader) || '').trim();
            const line = /ERROR: \d+:(\d+)/.exec(log);
            if (!line) return log;
            const lines = gl.getShaderSource(shader).split('\n'), at = Number(line[1]);
            return `${log}\n${lines.slice(Math.max(0, at - 3), at + 2).map((l, k) => `${Math.max(1, at - 2) + k}: ${l}`).join('\n')}`;
        });
        fail(`a shader does not compile:\n${report.join('\n').trim() || gl.getProgramInfoLog(program)}`);
    };
    window.microreliefThree = {...app, view, THREE: kit.THREE, microrelief: kit.relief, render};
    if (!view.size) {
        addEventListener('resize', () => {
            const [w, h] = size();
            Object.assign(canvas.style, {width: `${w}px`, height: `${h}px`});
            app.renderer.setSize(w, h, false);
            app.camera.aspect = w / h;
            app.camera.updateProjectionMatrix();
            render();
        });
    }
    try {
        await render();
    } catch (e) {
        fail(`drawing failed: ${e.message}`);
        return;
    }
    root.dataset.api = kApiOf[view.renderer];
    requestAnimationFrame(() => requestAnimationFrame(() => {
        if (root.dataset.state !== 'error') root.dataset.state = 'ready';
    }));
}

start();
