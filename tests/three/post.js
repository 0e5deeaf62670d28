// post.js: tests/three's post-processing measurements (PostTest.cpp), evaluated in
// examples/three's page once it is ready (shading=microrelief: the relief alone in its
// scene). Everything is drawn with a copy of the page's camera whose depth range is
// [0.25, 4], into targets of the canvas's size, and compared at every `step`-th pixel with
// the relief's own hits: Relief.traceRays of the pixels' centre rays (the library's GLSL).
// Each function returns a line of numbers for the C++ side.
window.postChecks = (() => {
    const app = () => window.microreliefThree;

    function camera() {
        const copy = app().camera.clone();
        Object.assign(copy, {near: 0.25, far: 4});
        copy.updateProjectionMatrix();
        copy.updateMatrixWorld();
        return copy;
    }

    // Pixels (column, row; row 0 the top) every `step`, and the relief's hit through each
    // centre: {pixels, kind, point (world), normal (world)}.
    function traced(view, step) {
        const {THREE, renderer, relief, scene} = app();
        const {width, height} = renderer.domElement;
        const pixels = [], origins = [], directions = [];
        const raycaster = new THREE.Raycaster();
        for (let row = Math.floor(step / 2); row < height; row += step) {
            for (let column = Math.floor(step / 2); column < width; column += step) {
                pixels.push([column, row]);
                raycaster.setFromCamera(new THREE.Vector2(((column + 0.5) / width) * 2 - 1, 1 - ((row + 0.5) / height) * 2), view);
                origins.push(...raycaster.ray.origin.toArray());
                directions.push(...raycaster.ray.direction.toArray());
            }
        }
        scene.updateMatrixWorld();
        const hits = relief.traceRays(origins, directions, [0, 100]);
        return {pixels, kind: hits.kind, exhausted: hits.exhausted, point: hits.point, normal: hits.normal};
    }

    // The scene drawn with `override` as scene.overrideMaterial into a target of `type`
    // (with a float depth texture), cleared to 0; its colour and depth read back.
    function drawOverride(view, override, type) {
        const {THREE, renderer, scene} = app();
        const {width, height} = renderer.domElement;
        const target = new THREE.WebGLRenderTarget(width, height, {type, depthBuffer: true});
        target.depthTexture = new THREE.DepthTexture(width, height, THREE.FloatType);
        const background = scene.background, clear = renderer.getClearColor(new THREE.Color()), alpha = renderer.getClearAlpha();
        const colour = type === THREE.FloatType ? new Float32Array(4 * width * height) : new Uint8Array(4 * width * height);
        try {
            scene.background = null;
            scene.overrideMaterial = override;
            renderer.setClearColor(0x000000, 0);
            renderer.setRenderTarget(target);
            renderer.clear();
            renderer.render(scene, view);
            renderer.readRenderTargetPixels(target, 0, 0, width, height, colour);
        } finally {
            scene.overrideMaterial = null;
            scene.background = background;
            renderer.setClearColor(clear, alpha);
            renderer.setRenderTarget(null);
        }
        const depth = app().microrelief.readTextureFloats(renderer, target.depthTexture, 0, width, height);
        target.dispose();
        return {colour, depth, width, height};
    }

    const at = (read, [column, row]) => (read.height - 1 - row) * read.width + column;  // GL's rows run bottom up

    // scene.overrideMaterial = MeshNormalMaterial (flatShading off), a float target: per
    // pixel the relief's hit or not, drawn or not, and the angle (radians) between the
    // normal read back and the hit's normal in the camera's view space.
    // Returns: samples, hits, drawn, drawn hits, hits within `angle`, the largest angle
    // over the hits drawn, drawn misses.
    function normals(step, angle) {
        const {THREE} = app();
        const view = camera(), rays = traced(view, step);
        const override = new THREE.MeshNormalMaterial();
        const read = drawOverride(view, override, THREE.FloatType);
        override.dispose();
        const toView = new THREE.Matrix3().setFromMatrix4(view.matrixWorldInverse);
        let hits = 0, drawn = 0, drawnHits = 0, within = 0, largest = 0, drawnMisses = 0;
        rays.pixels.forEach((pixel, k) => {
            const i = 4 * at(read, pixel), hit = rays.kind[k] !== 0 && !rays.exhausted[k];
            const seen = read.colour[i + 3] > 0;
            hits += hit;
            drawn += seen;
            if (seen && !hit) drawnMisses += 1;
            if (!hit || !seen) return;
            drawnHits += 1;
            const expected = new THREE.Vector3().fromArray(rays.normal, 3 * k).applyMatrix3(toView).normalize();
            const got = new THREE.Vector3(read.colour[i] * 2 - 1, read.colour[i + 1] * 2 - 1, read.colour[i + 2] * 2 - 1).normalize();
            const a = got.angleTo(expected);
            largest = Math.max(largest, a);
            within += a <= angle;
        });
        return [rays.pixels.length, hits, drawn, drawnHits, within, largest, drawnMisses].join(' ');
    }

    // scene.overrideMaterial = MeshDepthMaterial with `packing` ('basic': a float target,
    // 1 - depth in red; 'rgba': an 8-bit target, three's packDepthToRGBA), and the target's
    // depth texture: per hit drawn, the depth the colour gives and the depth buffer holds
    // against the hit's window depth (projected in double). Returns: hits, hits drawn, the
    // largest colour error, the largest depth-buffer error, drawn misses.
    function depths(step, packing) {
        const {THREE} = app();
        const view = camera(), rays = traced(view, step);
        const rgba = packing === 'rgba';
        const override = new THREE.MeshDepthMaterial({depthPacking: rgba ? THREE.RGBADepthPacking : THREE.BasicDepthPacking});
        const read = drawOverride(view, override, rgba ? THREE.UnsignedByteType : THREE.FloatType);
        override.dispose();
        // three's unpackRGBAToDepth (packing.glsl.js): UnpackFactors4 on the bytes / 255.
        const factors = [255 / 256, 255 / 256 / 256, 255 / 256 / 65536, 1 / 16777216];
        let hits = 0, drawnHits = 0, colourError = 0, bufferError = 0, drawnMisses = 0;
        rays.pixels.forEach((pixel, k) => {
            const p = at(read, pixel), i = 4 * p, hit = rays.kind[k] !== 0 && !rays.exhausted[k];
            const seen = read.depth[p] < 1;
            hits += hit;
            if (seen && !hit) drawnMisses += 1;
            if (!hit || !seen) return;
            drawnHits += 1;
            const expected = 0.5 + 0.5 * new THREE.Vector3().fromArray(rays.point, 3 * k).project(view).z;
            const fromColour = rgba ? factors.reduce((sum, f, c) => sum + (read.colour[i + c] / 255) * f, 0) : 1 - read.colour[i];
            colourError = Math.max(colourError, Math.abs(fromColour - expected));
            bufferError = Math.max(bufferError, Math.abs(read.depth[p] - expected));
        });
        return [hits, drawnHits, colourError, bufferError, drawnMisses].join(' ');
    }

    // scene.overrideMaterial = MeshDistanceMaterial, a float target: three (0.182 on) takes
    // its reference point and range from the point light whose shadow map it draws
    // (renderer.properties), so a point light at the camera with a [0.25, 4] shadow camera is
    // recorded for it, as WebGLShadowMap records one. Per hit drawn, the distance read back
    // against the hit's ((|hit - light| - near) / (far - near), in double). Returns: hits,
    // hits drawn, the largest error, drawn misses.
    function distances(step) {
        const {THREE, renderer} = app();
        const view = camera(), rays = traced(view, step);
        const override = new THREE.MeshDistanceMaterial();
        const light = new THREE.PointLight();
        light.position.copy(view.position);
        light.updateMatrixWorld();
        Object.assign(light.shadow.camera, {near: 0.25, far: 4});
        renderer.properties.get(override).light = light;
        const read = drawOverride(view, override, THREE.FloatType);
        override.dispose();
        let hits = 0, drawnHits = 0, error = 0, drawnMisses = 0;
        rays.pixels.forEach((pixel, k) => {
            const p = at(read, pixel), hit = rays.kind[k] !== 0 && !rays.exhausted[k];
            const seen = read.depth[p] < 1;
            hits += hit;
            if (seen && !hit) drawnMisses += 1;
            if (!hit || !seen) return;
            drawnHits += 1;
            const expected = (new THREE.Vector3().fromArray(rays.point, 3 * k).distanceTo(light.position) - 0.25) / 3.75;
            error = Math.max(error, Math.abs(read.colour[4 * p] - expected));
        });
        return [hits, drawnHits, error, drawnMisses].join(' ');
    }

    // How open the relief is at each surface hit, as its own geometry says: the fraction of
    // `count` rays (a fixed cosine-weighted spiral about the hit's normal, from 1e-4 above
    // it) that leave without meeting the surface within `radius` (Relief.traceRays).
    function openness(rays, samples, radius, count) {
        const {THREE, relief} = app();
        const origins = [], directions = [];
        const n = new THREE.Vector3(), t = new THREE.Vector3(), b = new THREE.Vector3(), d = new THREE.Vector3();
        for (const k of samples) {
            n.fromArray(rays.normal, 3 * k);
            t.set(Math.abs(n.x) < 0.9 ? 1 : 0, Math.abs(n.x) < 0.9 ? 0 : 1, 0).cross(n).normalize();
            b.crossVectors(n, t);
            const from = new THREE.Vector3().fromArray(rays.point, 3 * k).addScaledVector(n, 1e-4);
            for (let j = 0; j < count; ++j) {
                const r = Math.sqrt((j + 0.5) / count), phi = j * 2.399963229728653;
                d.copy(t).multiplyScalar(r * Math.cos(phi)).addScaledVector(b, r * Math.sin(phi)).addScaledVector(n, Math.sqrt(1 - r * r));
                origins.push(from.x, from.y, from.z);
                directions.push(d.x, d.y, d.z);
            }
        }
        const hits = relief.traceRays(origins, directions, [0, radius]);
        return samples.map((k, s) => {
            let open = 0;
            for (let j = 0; j < count; ++j) open += hits.kind[s * count + j] !== 1;
            return open / count;
        });
    }

    // An ambient-occlusion pass (`kind` 'gtao': GTAOPass, its raw AO buffer; 'ssao':
    // SSAOPass, its blurred buffer) run on the scene, its buffer copied out (red: 1 open, 0
    // occluded), read at the relief's surface hits, which are classed by their openness
    // within `radius` (32 rays): crevices (under `low`) and open tops (at least `high`).
    // Returns: crevice samples, top samples, the crevices' mean AO, the tops' mean AO, the
    // fraction of crevice samples darker than the tops' mean by more than `margin`. Leaves
    // the buffer on the canvas (grey), for a screenshot.
    async function ambientOcclusion(kind, step, radius, low, high, margin) {
        const {THREE, renderer, scene} = app();
        const view = camera(), rays = traced(view, step);
        const {width, height} = renderer.domElement;
        const background = scene.background;
        scene.background = null;
        let pass;
        if (kind === 'gtao') {
            const {GTAOPass} = await import('three/addons/postprocessing/GTAOPass.js');
            pass = new GTAOPass(scene, view, width, height);
            pass.updateGtaoMaterial({radius, thickness: 1, distanceExponent: 1, scale: 1});
            pass.output = GTAOPass.OUTPUT.AO;
        } else {
            const {SSAOPass} = await import('three/addons/postprocessing/SSAOPass.js');
            pass = new SSAOPass(scene, view, width, height, 32);
            Object.assign(pass, {kernelRadius: radius, minDistance: 0.00002, maxDistance: 0.03});
            pass.output = SSAOPass.OUTPUT.Blur;
        }
        const write = new THREE.WebGLRenderTarget(width, height), readBuffer = new THREE.WebGLRenderTarget(width, height);
        const bytes = new Uint8Array(4 * width * height);
        try {
            pass.render(renderer, write, readBuffer);
            // GTAOPass writes its output to the write buffer, SSAOPass (needsSwap false) to the read one.
            renderer.readRenderTargetPixels(kind === 'gtao' ? write : readBuffer, 0, 0, width, height, bytes);
            pass.renderToScreen = true;
            pass.render(renderer, null, readBuffer);  // the canvas shows the buffer
        } finally {
            scene.background = background;
            renderer.setRenderTarget(null);
            pass.dispose();
            write.dispose();
            readBuffer.dispose();
        }
        const samples = [];
        rays.pixels.forEach((pixel, k) => {
            if (rays.kind[k] === 1 && !rays.exhausted[k]) samples.push(k);
        });
        const open = openness(rays, samples, radius, 32);
        const crevices = [], tops = [];
        samples.forEach((k, s) => {
            const [column, row] = rays.pixels[k];
            const ao = bytes[4 * ((height - 1 - row) * width + column)] / 255;
            if (open[s] < low) crevices.push(ao);
            else if (open[s] >= high) tops.push(ao);
        });
        const mean = (values) => values.reduce((a, b) => a + b, 0) / Math.max(values.length, 1);
        const topMean = mean(tops);
        const darker = crevices.filter((ao) => ao < topMean - margin).length / Math.max(crevices.length, 1);
        return [crevices.length, tops.length, mean(crevices), topMean, darker].join(' ');
    }

    return {normals, depths, distances, ambientOcclusion};
})();
