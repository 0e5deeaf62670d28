// shaders.js: the page-side measurements of ShaderSizeTest.cpp (suite ThreeShaders), made
// in examples/three's page once it is ready (sent as an `eval` step). Uses what the page
// exposes in window.microreliefThree (three, microrelief-three, the renderer, the map).
//
// sources(): every program the relief materials make, per material and base, as three hands
// them to WebGL, measured on a second renderer whose context compiles nothing (its
// compileShader, linkProgram and draws do nothing: no 7-11 s SwiftShader compile per
// variant); and how many programs reliefs of the same options share.
// warmUp(): renderer.compileAsync on a relief the page has not drawn, then one frame: the
// relief's pixels drawn.
window.threeShaders = (() => {
    const app = () => window.microreliefThree;

    // A WebGL 2 context on a canvas of its own that records each shader's source and
    // compiles, links and draws nothing; a renderer on it that checks no shader errors.
    function recordingRenderer() {
        const {THREE} = app();
        const canvas = document.createElement('canvas');
        Object.assign(canvas, {width: 64, height: 48});
        const gl = canvas.getContext('webgl2');
        const sources = new Map();
        const shaderSource = gl.shaderSource.bind(gl), getShaderParameter = gl.getShaderParameter.bind(gl),
              getProgramParameter = gl.getProgramParameter.bind(gl);
        gl.shaderSource = (shader, source) => {
            sources.set(shader, source);
            shaderSource(shader, '');
        };
        gl.compileShader = () => {};
        gl.linkProgram = () => {};
        gl.drawArrays = gl.drawElements = gl.drawArraysInstanced = gl.drawElementsInstanced = () => {};
        gl.getShaderParameter = (shader, name) => (name === gl.COMPILE_STATUS ? true : getShaderParameter(shader, name));
        gl.getProgramParameter = (program, name) =>
            name === gl.LINK_STATUS || name === 0x91B1 /* COMPLETION_STATUS_KHR */ ? true
            : name === gl.ACTIVE_UNIFORMS || name === gl.ACTIVE_ATTRIBUTES ? 0 : getProgramParameter(program, name);
        const renderer = new THREE.WebGLRenderer({canvas, context: gl, antialias: false});
        renderer.debug.checkShaderErrors = false;
        renderer.shadowMap.enabled = true;
        // The fragment source of each of three's programs, by its material's type.
        const fragments = () => renderer.info.programs.map((p) => {
            const shaders = gl.getAttachedShaders(p.program) || [];
            const fragment = shaders.find((s) => gl.getShaderParameter(s, gl.SHADER_TYPE) === gl.FRAGMENT_SHADER);
            return {name: p.name, cacheKey: p.cacheKey, length: sources.get(fragment)?.length ?? -1, source: sources.get(fragment) ?? ''};
        });
        return {renderer, fragments, sources};
    }

    // A scene of `reliefs` (each [base, Material]) lit by a shadow-casting directional and
    // point light, drawn once by `renderer` (its shadow maps too).
    function drawScene(renderer, maps, reliefs) {
        const {THREE, microrelief} = app();
        const scene = new THREE.Scene();
        const sun = new THREE.DirectionalLight(0xffffff, 2);
        sun.position.set(1, 2, 1);
        sun.castShadow = true;
        const lamp = new THREE.PointLight(0xffffff, 2);
        lamp.position.set(-1, 1, 0);
        lamp.castShadow = true;
        scene.add(sun, lamp);
        const made = reliefs.map(([base, Material, options = {}]) => {
            const relief = new microrelief.Relief(base === 'plane' ? maps.plane : maps.wrapped, {material: new Material(), base, ...options});
            relief.castShadow = relief.receiveShadow = true;
            scene.add(relief);
            return relief;
        });
        const camera = new THREE.PerspectiveCamera(45, 4 / 3, 0.1, 10);
        camera.position.set(0.8, 0.9, 1.1);
        camera.lookAt(0, 0, 0);
        renderer.render(scene, camera);
        return made;
    }

    async function maps() {
        const {microrelief, renderer} = app();
        const heights = await microrelief.loadHeights('../../assets/cobbles.png');
        return {plane: await microrelief.createReliefMap(renderer, heights), wrapped: await microrelief.createReliefMap(renderer, heights, {wrapU: true})};
    }

    // The relief functions (mr...) `source` calls that it neither defines nor has as a macro
    // or a struct: what a stripper that misread an #if branch would leave (the compile would
    // fail on that variant only), found without compiling.
    function undefinedCalls(source) {
        const defined = new Set();
        for (const m of source.matchAll(/\b[A-Za-z_]\w*(?:\s*\[[^\]]*\])?\s+(mr_?[A-Za-z]\w*)\s*\([^;{}]*\)\s*\{/g)) defined.add(m[1]);
        for (const m of source.matchAll(/^[ \t]*#[ \t]*define[ \t]+(mr_?[A-Za-z]\w*)/gim)) defined.add(m[1]);
        for (const m of source.matchAll(/\bstruct\s+(mr_?[A-Za-z]\w*)/g)) defined.add(m[1]);
        const missing = new Set();
        for (const m of source.matchAll(/\b(mr_?[A-Za-z]\w*)\s*\(/g)) if (!defined.has(m[1])) missing.add(m[1]);
        return [...missing].sort();
    }

    // Per base and material, the fragment shaders' lengths (the relief's programs: its
    // material, its depth and distance materials, the pick); the programs reliefs of the same
    // options share; whether the generated GLSL the package ships holds a comment.
    async function sources() {
        const {microrelief} = app();
        const both = await maps();
        const out = {sizes: {}, sharing: {}, undefined: {}};
        const kinds = {standard: microrelief.ReliefStandardMaterial, physical: microrelief.ReliefPhysicalMaterial, shading: microrelief.ReliefShadingMaterial};
        for (const base of ['plane', 'cylinder', 'sphere']) {
            for (const [kind, Material] of Object.entries(kinds)) {
                const {renderer, fragments} = recordingRenderer();
                const [relief] = drawScene(renderer, both, [[base, Material]]);
                const before = renderer.info.programs.length;
                // The pick, on this renderer: a map object whose renderer is this one.
                const pickMap = Object.create(relief.reliefMap, {renderer: {value: renderer}});
                const probe = new microrelief.Relief(pickMap, {material: new Material(), base});
                if ('pickWith' in probe) probe.pickWith = 'gpu';  // glsl/pick.frag, not the CPU twin
                try {
                    probe.trace(new (app().THREE.Vector3)(0, 1, 0), new (app().THREE.Vector3)(0, -1, 0));
                } catch (e) {
                    out.pickError = e.message;
                }
                // Each program by what made it: three's shader (its cache key's first field) or,
                // for a ShaderMaterial, the relief's own shading or the pick.
                fragments().forEach((p, k) => {
                    if (!/\bmr_?[A-Za-z]\w*\s*\(/.test(p.source)) return;  // not a relief's program
                    const id = p.cacheKey.split(',')[0];
                    const name = k >= before ? 'pick' : ['depth', 'distance'].includes(id) ? id : kind;
                    out.sizes[`${base} ${name}`] = p.length;
                    out.undefined[`${base} ${name}`] = undefinedCalls(p.source);
                });
                renderer.dispose();
            }
        }
        // Sharing: the programs of one relief, then of three more of the same options in the
        // same scene (their own materials, their own depth materials), and of two of another.
        for (const [kind, Material] of Object.entries(kinds)) {
            const one = recordingRenderer();
            drawScene(one.renderer, both, [['plane', Material]]);
            const four = recordingRenderer();
            drawScene(four.renderer, both, [['plane', Material], ['plane', Material], ['plane', Material], ['plane', Material]]);
            const mixed = recordingRenderer();
            drawScene(mixed.renderer, both, [['plane', Material], ['plane', Material], ['cylinder', Material], ['cylinder', Material]]);
            out.sharing[kind] = {one: one.renderer.info.programs.length, four: four.renderer.info.programs.length,
                                 mixed: mixed.renderer.info.programs.length};
            for (const r of [one, four, mixed]) r.renderer.dispose();
        }
        return out;
    }

    // The generated GLSL strings the package ships (generated/glsl.js): their lengths and the
    // first comment in any ('' when none).
    async function generated() {
        const glsl = await import('./node_modules/microrelief-three/generated/glsl.js');
        const texts = {library: glsl.library, ...Object.fromEntries(Object.entries(glsl.glue).map(([k, v]) => [`glue.${k}`, v])),
                       ...Object.fromEntries(Object.entries(glsl.pyramid).map(([k, v]) => [`pyramid.${k}`, v]))};
        const lengths = {};
        let comment = '';
        for (const [name, text] of Object.entries(texts)) {
            lengths[name] = text.length;
            const m = /\/\/.*|\/\*[\s\S]{0,60}/.exec(text);
            if (m && !comment) comment = `${name}: ${m[0].slice(0, 80)}`;
        }
        return {lengths, comment};
    }

    // renderer.compileAsync(scene, camera) on a scene whose relief (ReliefStandardMaterial,
    // lit, on the cylinder: a program the page has not made) was never drawn; then one frame.
    // Whether it resolved, the programs it made before the frame and after, and how many
    // pixels of the relief's box differ from the background.
    async function warmUp() {
        const {THREE, microrelief, renderer} = app();
        const {wrapped} = await maps();
        const scene = new THREE.Scene();
        scene.background = new THREE.Color(0, 0, 0);
        const sun = new THREE.DirectionalLight(0xffffff, 3);
        sun.position.set(1, 2, 1);
        scene.add(sun, new THREE.AmbientLight(0xffffff, 0.5));
        const relief = new microrelief.Relief(wrapped, {material: new microrelief.ReliefStandardMaterial({color: 0xffffff}), base: 'cylinder'});
        scene.add(relief);
        const camera = new THREE.PerspectiveCamera(50, renderer.domElement.width / renderer.domElement.height, 0.1, 10);
        camera.position.set(0, 0.2, 1.2);
        camera.lookAt(0, 0, 0);
        const programsBefore = renderer.info.programs.length;
        let resolved = false;
        await renderer.compileAsync(scene, camera).then(() => (resolved = true));
        const programsCompiled = renderer.info.programs.length;
        renderer.render(scene, camera);
        const programsAfterFrame = renderer.info.programs.length;
        const {width, height} = renderer.domElement;
        const gl = renderer.getContext(), bytes = new Uint8Array(4 * width * height);
        gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, bytes);
        let lit = 0;
        for (let k = 0; k < width * height; ++k) if (bytes[4 * k] + bytes[4 * k + 1] + bytes[4 * k + 2] > 30) ++lit;
        return {resolved, programsBefore, programsCompiled, programsAfterFrame, lit, pixels: width * height};
    }

    // For docs/perf (not a test: no timings in tests): the milliseconds of the first frame of
    // a relief of `kind` on `base` that the page's renderer has not drawn, lit by a
    // shadow-casting light, the readback waiting for the picture; its shaders compiled in it.
    async function firstFrame(kind, base) {
        const {THREE, microrelief, renderer} = app();
        const both = await maps();
        const Material = {standard: microrelief.ReliefStandardMaterial, physical: microrelief.ReliefPhysicalMaterial, shading: microrelief.ReliefShadingMaterial}[kind];
        renderer.shadowMap.enabled = true;
        const {width, height} = renderer.domElement;
        const gl = renderer.getContext();
        const start = performance.now();
        drawScene(renderer, both, [[base, Material]]);
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
        const first = performance.now() - start;
        const again = performance.now();
        drawScene(renderer, both, [[base, Material]]);
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
        return {first: Math.round(first), second: Math.round(performance.now() - again), width, height};
    }

    // For docs/perf: the vertex and fragment source of the main program of a relief of
    // `kind` on `base` in the lit scene of sources(), as three hands them to WebGL.
    async function programSources(kind, base) {
        const {microrelief} = app();
        const Material = {standard: microrelief.ReliefStandardMaterial, physical: microrelief.ReliefPhysicalMaterial, shading: microrelief.ReliefShadingMaterial}[kind];
        const {renderer, sources} = recordingRenderer();
        const gl = renderer.getContext();
        drawScene(renderer, await maps(), [[base, Material]]);
        const out = {};
        for (const p of renderer.info.programs) {
            const shaders = gl.getAttachedShaders(p.program);
            const text = shaders.map((sh) => sources.get(sh));
            const id = p.cacheKey.split(',')[0];
            const name = ['depth', 'distance'].includes(id) ? id : kind;
            out[name] = gl.getShaderParameter(shaders[0], gl.SHADER_TYPE) === gl.VERTEX_SHADER ? {vertex: text[0], fragment: text[1]} : {vertex: text[1], fragment: text[0]};
        }
        renderer.dispose();
        return out;
    }

    // For docs/perf: the milliseconds WebGL takes to compile, link and first draw each of `programs`
    // ({name: {vertex, fragment}}), `reps` times round, each compile made unique by a
    // #define after #version (no cache of the browser's serves it); the link status waited for.
    function compileTimes(programs, reps = 3) {
        const gl = app().renderer.getContext();
        const times = {};
        let nonce = 0;
        const unique = (source) => source.replace(/^(#version[^\n]*\n)?/, (v) => `${v}#define MR_NONCE_${Date.now()}_${++nonce}\n`);
        for (let r = 0; r < reps; ++r) {
            for (const [name, {vertex, fragment}] of Object.entries(programs)) {
                const start = performance.now();
                const program = gl.createProgram();
                for (const [type, source] of [[gl.VERTEX_SHADER, vertex], [gl.FRAGMENT_SHADER, fragment]]) {
                    const shader = gl.createShader(type);
                    gl.shaderSource(shader, unique(source));
                    gl.compileShader(shader);
                    gl.attachShader(program, shader);
                }
                gl.linkProgram(program);
                const ok = gl.getProgramParameter(program, gl.LINK_STATUS);
                // One draw (one pixel, the attributes' defaults): where SwiftShader makes the
                // pipeline, the most of the cost; the readback waits for it.
                if (ok) {
                    gl.useProgram(program);
                    gl.viewport(0, 0, 1, 1);
                    gl.drawArrays(gl.TRIANGLES, 0, 3);
                    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
                    gl.useProgram(null);
                }
                (times[name] ??= []).push(ok ? Math.round(performance.now() - start) : `failed: ${gl.getProgramInfoLog(program)}`);
                gl.deleteProgram(program);
            }
        }
        return times;
    }

    // sources() and generated() as lines for ShaderSizeTest.cpp: "size BASE PROGRAM BYTES",
    // "undefined BASE PROGRAM NAMES", "sharing MATERIAL ONE FOUR MIXED", "generated NAME
    // BYTES", "comment TEXT" (none: "comment -").
    async function report() {
        const s = await sources(), g = await generated();
        const lines = [];
        for (const [name, bytes] of Object.entries(s.sizes)) lines.push(`size ${name} ${bytes}`);
        for (const [name, missing] of Object.entries(s.undefined)) lines.push(`undefined ${name} ${missing.join(',') || '-'}`);
        for (const [kind, n] of Object.entries(s.sharing)) lines.push(`sharing ${kind} ${n.one} ${n.four} ${n.mixed}`);
        for (const [name, bytes] of Object.entries(g.lengths)) lines.push(`generated ${name} ${bytes}`);
        lines.push(`comment ${g.comment.replace(/\n/g, ' ') || '-'}`);
        return lines.join('\n');
    }

    return {report, sources, generated, warmUp, firstFrame, programSources, compileTimes, recordingRenderer, drawScene, maps};
})();
