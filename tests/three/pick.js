// pick.js: what tests/three/PickTest.cpp measures inside examples/three's page (sent as an
// `eval` step once the page is ready): the picks of the CPU twin compiled to WebAssembly
// (packages/microrelief-three/src/twin.js) against the native twin and against the GPU's
// picks (glsl/pick.frag), and the twin's memory. It uses only what the page exposes in
// window.microreliefThree.
window.threePick = (() => {
    const app = () => window.microreliefThree;

    // A small deterministic generator (the same sequence in every run).
    function generator(seed) {
        let state = seed >>> 0;
        return () => ((state = (Math.imul(state, 1664525) + 1013904223) >>> 0) / 4294967296);
    }

    // A rough map of `width` x `height` floats: ridges, pits and a plateau (16-bit steps).
    function roughHeights(width, height) {
        const samples = new Float32Array(width * height);
        for (let j = 0; j < height; ++j)
            for (let i = 0; i < width; ++i) {
                const wave = 0.5 + 0.25 * Math.sin(0.45 * i) * Math.cos(0.3 * j) + 0.2 * Math.sin(0.11 * (i + 2 * j));
                samples[j * width + i] = Math.round(65535 * Math.min(Math.max(wave, 0), 1) * ((i * 7 + j * 3) % 11 === 0 ? 0.4 : 1)) / 65535;
            }
        return samples;
    }

    // `count` world rays from an eye `distance` from the relief's centre (a direction of its
    // own per ray's group of 8, as a few cameras), towards random points of its box; every
    // fourth starts part of the way along (tMin > 0), every seventh stops short.
    function raysAt(relief, count, distance, random) {
        const {THREE} = app();
        relief.updateWorldMatrix(true, false);
        const origins = [], directions = [], ranges = [];
        const box = relief.box, eye = new THREE.Vector3(), target = new THREE.Vector3();
        const centre = box.getCenter(new THREE.Vector3()).applyMatrix4(relief.matrixWorld);
        for (let k = 0; k < count; ++k) {
            if (k % 8 === 0) {
                const z = 0.2 + 0.8 * random(), phi = 2 * Math.PI * random();
                eye.set(Math.sqrt(1 - z * z) * Math.cos(phi), z, Math.sqrt(1 - z * z) * Math.sin(phi)).multiplyScalar(distance).add(centre);
            }
            target.set(...['x', 'y', 'z'].map((a) => box.min[a] + random() * (box.max[a] - box.min[a]))).applyMatrix4(relief.matrixWorld);
            const direction = target.clone().sub(eye).normalize();
            origins.push(eye.x, eye.y, eye.z);
            directions.push(direction.x, direction.y, direction.z);
            ranges.push(k % 4 === 3 ? 0.5 * distance : 0, k % 7 === 6 ? distance : Infinity);
        }
        return {origins, directions, ranges};
    }

    // The cases: a map (the page's bundled one, or a small rough one), a relief of it and a
    // model transform.
    const kModel = [0.8, -0.3, 0, 0.05, 0.3, 0.8, 0, 0.02, 0, 0, 0.9, -0.03];
    const kTurned = [0.45, 0, 0.2, 0.3, 0.1, 0.5, 0, -0.1, -0.2, 0, 0.45, 0.2];
    const kFar = [1, 0, 0, 900000, 0, 1, 0, -400000, 0, 0, 1, 700000];
    const kCases = [
        {name: 'plane', options: {heightScale: 0.1}},
        {name: 'plane-biquadratic-model', options: {heightScale: 0.15, interpolation: 'biquadratic'}, model: kModel},
        {name: 'plane-far-from-the-origin', options: {heightScale: 0.1}, model: kFar},
        {name: 'cylinder-biquadratic', options: {base: {kind: 'cylinder', radius: 0.25, length: 0.9}, interpolation: 'biquadratic'}},
        {name: 'sphere-turned', options: {base: 'sphere', heightScale: 0.15}, model: kTurned},
        {name: 'ellipsoid', options: {base: {kind: 'ellipsoid', radii: [0.5, 0.3, 0.4]}, heightScale: 0.2}},
    ];

    async function reliefOf(map, c) {
        const {THREE, microrelief} = app();
        const relief = new microrelief.Relief(map, {material: new microrelief.ReliefShadingMaterial(), ...c.options});
        if (c.model) {
            relief.matrixAutoUpdate = false;
            relief.matrix.set(...c.model, 0, 0, 0, 1);
        }
        relief.updateMatrixWorld(true);
        return relief;
    }

    // Each case's map, relief and rays traced by the twin (on: 'cpu'), as numbers for the
    // native twin to trace again (PickTest.cpp): per case width height heightScale base a b
    // c interpolation, the model (16, column-major), n, the samples, origins, directions,
    // ranges, and the twin's 12 n values; the number of cases first.
    async function twinCases(count = 160) {
        const {renderer, microrelief} = app();
        const random = generator(48);
        const [width, height] = [61, 47];
        const heights = microrelief.heightsFromArray(roughHeights(width, height), width, height, {name: 'rough'});
        const maps = {};
        const out = [kCases.length];
        for (const c of kCases) {
            const wrapU = !!c.options.base && c.options.base !== 'plane';
            maps[wrapU] ??= await microrelief.createReliefMap(renderer, heights, {wrapU});
            const relief = await reliefOf(maps[wrapU], c);
            const rays = raysAt(relief, count, 1.2, random);
            const traced = relief.traceRays(rays.origins, rays.directions, rays.ranges, {on: 'cpu'});
            if (traced.on !== 'cpu') throw new Error(`${c.name}: traced on ${traced.on}`);
            // The base as its kind's own row takes it (PickTest.cpp finds the row by the kind's
            // MICRORELIEF_BASE): the kind's value, then its members' numbers in the shape's order
            // (baseShape writes them in its row's: radius, length; radii), with their count.
            const {kind, ...members} = relief.base;
            const sizes = Object.values(members).flat();
            out.push(width, height, relief.heightScale, {plane: 0, cylinder: 1, ellipsoid: 2}[kind], sizes.length, ...sizes,
                     relief.interpolation === 'biquadratic' ? 1 : 0, ...relief.matrixWorld.elements, count, ...heights.samples,
                     ...rays.origins, ...rays.directions, ...rays.ranges);
            for (let k = 0; k < count; ++k)
                out.push(traced.t[k], traced.kind[k], traced.exhausted[k], ...traced.point.subarray(3 * k, 3 * k + 3),
                         ...traced.normal.subarray(3 * k, 3 * k + 3), ...traced.uv.subarray(2 * k, 2 * k + 2), traced.iterations[k]);
        }
        for (const map of Object.values(maps)) map.dispose();
        return out.join(' ');
    }

    // The twin's picks against the GPU's, on the page's bundled map (a wrapU copy of it for
    // the curved bases), the cases above: one line a case, "name rays hits disagreements
    // beyond largestDistance largestNormalAngle largestUv onCpu onGpu" (hits where both hit
    // the surface or a face; beyond: hits more than `tolerance` apart; distances in world
    // units, the angle in radians, uv in uv units).
    async function againstGpu(count, tolerance) {
        const {renderer, map, microrelief} = app();
        const random = generator(4848);
        const wrapped = await microrelief.createReliefMap(renderer, await microrelief.loadHeights('../../assets/cobbles.png'), {wrapU: true});
        const lines = [];
        try {
            for (const c of kCases) {
                const curved = !!c.options.base && c.options.base !== 'plane';
                const relief = await reliefOf(curved ? wrapped : map, c);
                const rays = raysAt(relief, count, 1.3, random);
                const cpu = relief.traceRays(rays.origins, rays.directions, rays.ranges, {on: 'cpu'});
                const gpu = relief.traceRays(rays.origins, rays.directions, rays.ranges, {on: 'gpu'});
                let hits = 0, disagreements = 0, beyond = 0, distance = 0, angle = 0, uv = 0;
                for (let k = 0; k < count; ++k) {
                    const found = (r) => r.kind[k] !== 0 && !r.exhausted[k];
                    if (found(cpu) !== found(gpu)) {
                        ++disagreements;
                        continue;
                    }
                    if (!found(cpu)) continue;
                    ++hits;
                    const at = (r, f, size) => Array.from(r[f].slice(size * k, size * k + size));
                    const [p, q] = [at(cpu, 'point', 3), at(gpu, 'point', 3)];
                    const apart = Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
                    beyond += apart > tolerance;
                    distance = Math.max(distance, apart);
                    const [n, m] = [at(cpu, 'normal', 3), at(gpu, 'normal', 3)];
                    const dot = n[0] * m[0] + n[1] * m[1] + n[2] * m[2];
                    angle = Math.max(angle, Math.acos(Math.min(1, dot / Math.hypot(...n) / Math.hypot(...m))));
                    const [u, w] = [at(cpu, 'uv', 2), at(gpu, 'uv', 2)];
                    // u wraps round on a curved base: the nearer of the two ways.
                    const du = Math.abs(u[0] - w[0]);
                    uv = Math.max(uv, curved ? Math.min(du, 1 - du) : du, Math.abs(u[1] - w[1]));
                }
                lines.push([c.name, count, hits, disagreements, beyond, distance, angle, uv, cpu.on, gpu.on].join(' '));
                relief.dispose();
            }
        } finally {
            wrapped.dispose();
        }
        return lines.join('\n');
    }

    // The twin's memory and its release: a map of its own, two reliefs of it (two
    // configurations) picked, the bytes held, then the map disposed. Returns "before afterPick
    // bytes expectedBytes afterDispose pickWith defaultOn gpuOn refusal", the counts being
    // twins held by the module.
    async function memory() {
        const {THREE, renderer, microrelief} = app();
        const [width, height] = [61, 47];
        const map = await microrelief.createReliefMap(renderer, microrelief.heightsFromArray(roughHeights(width, height), width, height));
        // The package's own twin.js (the module index.js imported: the same URL).
        const twin = await import(new URL('./node_modules/microrelief-three/src/twin.js', location.href).href);
        const count = () => twin.twinCount();
        const before = count();
        const a = new microrelief.Relief(map, {heightScale: 0.1}), b = new microrelief.Relief(map, {heightScale: 0.2});
        const down = [new THREE.Vector3(0.01, 1, 0.02), new THREE.Vector3(0, -1, 0)];
        const picked = [a.trace(...down), b.trace(...down), a.trace(...down)];
        const afterPick = count();
        const bytes = map.twinBytes;
        // The samples and, per level, its blocks and windows: 4 bytes each, twice.
        const texels = map.levelSizes.reduce((sum, [w, h]) => sum + w * h, 0);
        const expected = 2 * (4 * width * height + 2 * 4 * texels);
        const defaultOn = a.traceRays([0, 1, 0], [0, -1, 0]).on;
        const gpuOn = a.traceRays([0, 1, 0], [0, -1, 0], [0, Infinity], {on: 'gpu'}).on;
        a.pickWith = 'gpu';
        const pickWithGpu = a.traceRays([0, 1, 0], [0, -1, 0]).on;
        let refusal = '';
        try {
            a.pickWith = 'wasm';
        } catch (e) {
            refusal = e.message;
        }
        map.dispose();
        return [before, afterPick, bytes, expected, count(), picked.every((h) => h && h.kind === 1) ? 1 : 0, defaultOn, gpuOn,
                pickWithGpu].join(' ') + '\n' + refusal;
    }

    // The time of one pick, ms: the page's camera through `picks` random pixels that show the
    // relief, three's Raycaster on it, each pick alone (as a pointer move asks for one), on the twin
    // and on the GPU, after a warm-up of each. Not a test: PickTest.cpp's DISABLED_ case
    // prints it (docs/three.md).
    function timePicks(picks = 200) {
        const {THREE, camera, relief, renderer} = app();
        const raycaster = new THREE.Raycaster(), random = generator(7);
        const {width, height} = renderer.domElement;
        // Pixels that show the relief (a miss of its box is no trace on either path).
        const pixels = [];
        relief.pickWith = 'cpu';
        while (pixels.length < picks) {
            const p = new THREE.Vector2(2 * random() - 1, 2 * random() - 1);
            raycaster.setFromCamera(p, camera);
            if (raycaster.intersectObject(relief, false).length) pixels.push(p);
        }
        const run = (on) => {
            relief.pickWith = on;
            let hits = 0;
            const start = performance.now();
            for (const p of pixels) {
                raycaster.setFromCamera(p, camera);
                hits += raycaster.intersectObject(relief, false).length;
            }
            return [(performance.now() - start) / picks, hits];
        };
        run('cpu');
        run('gpu');
        const [cpu, cpuHits] = run('cpu'), [gpu, gpuHits] = run('gpu');
        relief.pickWith = 'auto';
        return `${width}x${height} picks ${picks} cpu ${cpu.toFixed(4)} ms (${cpuHits} hits) gpu ${gpu.toFixed(4)} ms (${gpuHits} hits)`;
    }

    return {twinCases, againstGpu, memory, timePicks};
})();
