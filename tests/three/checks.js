// checks.js: the measurements tests/three makes inside examples/three's page, evaluated there
// once the page is ready (ThreeTest.cpp sends this text as a script). It uses only what the
// page exposes in window.microreliefThree: three, microrelief-three, its renderer, scene,
// camera and relief (in the three-lit example: its floor, ball and knot). Pixels are
// (column, row), row 0 the top, as in microrelief-render's AOV.
window.threeChecks = (() => {
    const app = () => window.microreliefThree;
    // The three-lit example's sun: its one directional light.
    const exampleSun = () => app().scene.children.find((object) => object.isDirectionalLight);

    // The NDC of pixel (column, row)'s centre.
    function pixelNdc(column, row) {
        const {width, height} = app().renderer.domElement;
        return new (app().THREE.Vector2)(((column + 0.5) / width) * 2 - 1, 1 - ((row + 0.5) / height) * 2);
    }

    // The canvas's RGBA bytes as GL reads them (row 0 the bottom).
    function readPixels(renderer, width, height) {
        const gl = renderer.getContext(), bytes = new Uint8Array(4 * width * height);
        gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, bytes);
        return bytes;
    }

    // three's Raycaster through each pixel's centre against the relief: the first hit's world
    // point and uv, or null.
    function pick(pixels) {
        const {THREE, camera, relief} = app();
        const raycaster = new THREE.Raycaster();
        return pixels.map(([column, row]) => {
            raycaster.setFromCamera(pixelNdc(column, row), camera);
            const hits = raycaster.intersectObject(relief, false);
            return hits.length ? {point: hits[0].point.toArray(), uv: hits[0].uv.toArray(), distance: hits[0].distance} : null;
        });
    }

    // A square of 2 x 2 world units (MeshBasicMaterial, both sides) through `point`, normal `normal`, added
    // to the scene; then the scene drawn into a target with a 32-bit float depth texture
    // and its depths read back at `pixels` through their bits. For each pixel: the depth
    // three wrote, the plane's own window depth there (its pixel ray met analytically,
    // projected by the camera, in double), and `reliefPoints[k]`'s (the relief's hit from
    // microrelief-render's AOV, or null) projected the same way; whether the pixel is within 0.01 of the square's edge. The camera's depth range
    // is set to [near, far] first (its rays stay the pixels' own; only their t range moves).
    // measureDepth does it for a renderer, scene, camera and a world point's expected depth.
    function depth(pixels, reliefPoints, point, normal, near, far) {
        const {THREE, renderer, scene, camera} = app();
        return measureDepth(renderer, scene, camera, pixels, reliefPoints, point, normal, near, far,
                            (world) => 0.5 + 0.5 * world.clone().project(camera).z);
    }

    // The same with three's logarithmic depth buffer: a second renderer on a canvas of its own
    // (logarithmicDepthBuffer is a renderer's constructor option), its own ReliefMap of the
    // page's heights, the relief (ReliefShadingMaterial, the page's height scale and model)
    // and a copy of the page's camera. The depth expected where a world point is seen is the
    // one three's logdepthbuf chunks write: log2(1 + w) / log2(far + 1), w its view depth.
    async function depthLogarithmic(pixels, reliefPoints, point, normal, near, far) {
        const {THREE, renderer: pageRenderer, camera: pageCamera, relief: pageRelief, microrelief} = app();
        const {width, height} = pageRenderer.domElement;
        const canvas = document.createElement('canvas');
        Object.assign(canvas, {width, height});
        const renderer = new THREE.WebGLRenderer({canvas, antialias: false, logarithmicDepthBuffer: true});
        try {
            const map = await microrelief.createReliefMap(renderer, await microrelief.loadHeights('../../assets/cobbles.png'));
            const relief = new microrelief.Relief(map, {material: new microrelief.ReliefShadingMaterial(), heightScale: pageRelief.heightScale});
            relief.matrixAutoUpdate = false;
            relief.matrix.copy(pageRelief.matrix);
            const scene = new THREE.Scene();
            scene.add(relief);
            const camera = pageCamera.clone();
            Object.assign(camera, {near, far});
            camera.updateProjectionMatrix();
            camera.updateMatrixWorld();
            const logDepth = (world) => Math.log2(1 + -world.clone().applyMatrix4(camera.matrixWorldInverse).z) / Math.log2(far + 1);
            return measureDepth(renderer, scene, camera, pixels, reliefPoints, point, normal, near, far, logDepth);
        } finally {
            renderer.dispose();
        }
    }

    function measureDepth(renderer, scene, camera, pixels, reliefPoints, point, normal, near, far, windowDepth) {
        const {THREE, microrelief} = app();
        const side = 2;
        Object.assign(camera, {near, far});
        camera.updateProjectionMatrix();
        const {width, height} = renderer.domElement;
        const plane = new THREE.Mesh(new THREE.PlaneGeometry(side, side), new THREE.MeshBasicMaterial({color: 0x20a040, side: THREE.DoubleSide}));
        plane.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), new THREE.Vector3(...normal).normalize());
        plane.position.set(...point);
        scene.add(plane);
        const target = new THREE.WebGLRenderTarget(width, height, {depthBuffer: true});
        target.depthTexture = new THREE.DepthTexture(width, height, THREE.FloatType);
        try {
            renderer.setRenderTarget(target);
            renderer.render(scene, camera);
        } finally {
            renderer.setRenderTarget(null);
        }
        const depths = microrelief.readTextureFloats(renderer, target.depthTexture, 0, width, height);
        renderer.render(scene, camera);  // the canvas shows the crossing too, for a screenshot
        scene.remove(plane);
        target.dispose();
        const mathPlane = new THREE.Plane().setFromNormalAndCoplanarPoint(new THREE.Vector3(...normal).normalize(), new THREE.Vector3(...point));
        const raycaster = new THREE.Raycaster();
        return pixels.map(([column, row], k) => {
            raycaster.setFromCamera(pixelNdc(column, row), camera);
            let onPlane = raycaster.ray.intersectPlane(mathPlane, new THREE.Vector3()), edge = false;
            if (onPlane) {
                const local = plane.worldToLocal(onPlane.clone());
                const fromEdge = side / 2 - Math.max(Math.abs(local.x), Math.abs(local.y));
                edge = Math.abs(fromEdge) < 0.01;  // the rasteriser's coverage may differ there
                if (fromEdge < 0) onPlane = null;  // beside the square
            }
            return {
                read: depths[(height - 1 - row) * width + column],  // GL's rows run bottom up
                plane: onPlane ? windowDepth(onPlane) : null,
                relief: reliefPoints[k] ? windowDepth(new THREE.Vector3(...reliefPoints[k])) : null,
                edge,
            };
        });
    }

    // three's shadow maps and the relief, in a scene of its own drawn with the page's camera
    // and map: a white ReliefStandardMaterial relief, an ambient light and a `kind` light
    // ('directional': towards `light`, a 2048-texel orthographic shadow map over
    // [-0.8, 0.8]^2; 'spot': at `light`, aimed at the origin, a cone of 0.8 rad and a
    // 2048-texel perspective shadow map; 'point': at `light`, a cube shadow map of 1024 texels
    // a face; the last two without decay, so that they light as much everywhere), and either
    // (`what` 'receive') a sphere of radius 0.12 at `sphere`, casting but not drawn, onto the
    // relief, or ('cast') the relief casting onto a ground square at y = -0.0005. The scene is
    // drawn three times: the light off, the caster not casting, casting (what the canvas keeps). At each of
    // `pixels` the hit point (the relief's: Relief.traceRays; the ground's: its plane met
    // analytically where the relief is missed) and whether the drawing shows it shadowed
    // (darker with the caster casting by more than half of what the light adds), and what the
    // geometry says: the ray from the point towards the light (up to it, for a spot or point
    // light) meets the sphere (analytically) or the relief (traceRays). `margin`: a point whose
    // answer changes within that distance (the sphere's outline, or the same ray from points
    // moved by margin along x and z) is left out, as is one the light barely reaches (it adds
    // under 24 levels). Returns [expected, seen] per pixel: 1 shadowed, 0 lit, -1 left out.
    function shadows(what, pixels, light, sphereCentre, margin, kind = 'directional') {
        const {THREE, renderer, camera, map, microrelief} = app();
        const {width, height} = renderer.domElement;
        const scene = new THREE.Scene();
        const relief = new microrelief.Relief(map, {material: new microrelief.ReliefStandardMaterial({color: 0xffffff, roughness: 1})});
        let sun;
        if (kind === 'directional') {
            sun = new THREE.DirectionalLight(0xffffff, 2.5);
            sun.position.set(...light).normalize().multiplyScalar(2);
            sun.shadow.mapSize.set(2048, 2048);
            Object.assign(sun.shadow.camera, {left: -0.8, right: 0.8, bottom: -0.8, top: 0.8, near: 0.5, far: 4});
        } else if (kind === 'spot') {
            sun = new THREE.SpotLight(0xffffff, 2.5, 0, 0.8, 0, 0);
            sun.position.set(...light);
            sun.shadow.mapSize.set(2048, 2048);
            Object.assign(sun.shadow.camera, {near: 0.5, far: 4});
        } else {
            sun = new THREE.PointLight(0xffffff, 2.5, 0, 0);
            sun.position.set(...light);
            sun.shadow.mapSize.set(1024, 1024);
            Object.assign(sun.shadow.camera, {near: 0.5, far: 4});
        }
        sun.castShadow = true;
        scene.add(sun, new THREE.AmbientLight(0xffffff, 0.4), relief);
        if (sun.target) scene.add(sun.target);
        // From a point towards the light: a direction, or the segment up to the light (t in [0, 1]).
        const towardsLight = (p) => (kind === 'directional' ? new THREE.Vector3(...light).normalize() : new THREE.Vector3(...light).sub(p));
        const tMax = kind === 'directional' ? 100 : 1;
        const radius = 0.12;
        const sphere = new THREE.Mesh(new THREE.SphereGeometry(radius, 96, 48), new THREE.MeshBasicMaterial({colorWrite: false, depthWrite: false}));
        sphere.position.set(...sphereCentre);
        const ground = new THREE.Mesh(new THREE.PlaneGeometry(4, 4).rotateX(-Math.PI / 2), new THREE.MeshStandardMaterial({color: 0xffffff, roughness: 1}));
        ground.position.y = -0.0005;
        const caster = what === 'receive' ? sphere : relief;
        if (what === 'receive') {
            scene.add(sphere);
            relief.receiveShadow = true;
        } else {
            scene.add(ground);
            ground.receiveShadow = true;
        }
        const wasEnabled = renderer.shadowMap.enabled;
        renderer.shadowMap.enabled = true;
        const draw = (casting, intensity) => {
            caster.castShadow = casting;
            sun.intensity = intensity;
            renderer.render(scene, camera);
            return readPixels(renderer, width, height);
        };
        const [dark, lit, shadowed] = [draw(false, 0), draw(false, 2.5), draw(true, 2.5)];  // the canvas keeps the last
        renderer.shadowMap.enabled = wasEnabled;
        // The camera's rays through the pixels, and where they meet the relief.
        const raycaster = new THREE.Raycaster(), origins = [], directions = [];
        for (const [column, row] of pixels) {
            raycaster.setFromCamera(pixelNdc(column, row), camera);
            origins.push(...raycaster.ray.origin.toArray());
            directions.push(...raycaster.ray.direction.toArray());
        }
        scene.updateMatrixWorld();
        const seen = relief.traceRays(origins, directions, [0, 100]);
        const points = pixels.map((pixel, k) => {
            if (what === 'receive') return seen.kind[k] === 1 ? new THREE.Vector3().fromArray(seen.point, 3 * k) : null;
            if (seen.kind[k] !== 0) return null;
            const ray = new THREE.Ray(new THREE.Vector3().fromArray(origins, 3 * k), new THREE.Vector3().fromArray(directions, 3 * k));
            return ray.intersectPlane(new THREE.Plane(new THREE.Vector3(0, 1, 0), 0.0005), new THREE.Vector3());
        });
        // The geometry's answer at each point and at the points moved by margin.
        let expected;
        if (what === 'receive') {
            expected = points.map((p) => {
                if (!p) return -1;
                const towards = towardsLight(p);
                const segment = new THREE.Ray(p, towards.clone().normalize());
                // The distance from the sphere's centre to the ray (or to the segment up to the light).
                const along = segment.direction.dot(sphere.position.clone().sub(p));
                const d = kind !== 'directional' && along > towards.length() ? sphere.position.distanceTo(sun.position) : segment.distanceToPoint(sphere.position);
                return Math.abs(d - radius) < margin ? -1 : Number(d < radius);
            });
        } else {
            const offsets = [[0, 0], [margin, 0], [-margin, 0], [0, margin], [0, -margin]];
            const from = [], towards = [];
            for (const p of points)
                for (const [dx, dz] of offsets) {
                    const q = p ? new THREE.Vector3(p.x + dx, p.y + 0.0005, p.z + dz) : new THREE.Vector3(0, -10, 0);
                    from.push(...q.toArray());
                    towards.push(...towardsLight(q).toArray());
                }
            const blocked = relief.traceRays(from, towards, [0, tMax]).kind;
            expected = points.map((p, k) => {
                if (!p) return -1;
                const answers = offsets.map((o, j) => Number(blocked[5 * k + j] !== 0));
                return answers.every((a) => a === answers[0]) ? answers[0] : -1;
            });
        }
        return pixels.map(([column, row], k) => {
            const at = 4 * ((height - 1 - row) * width + column);
            const added = lit[at] - dark[at];
            if (expected[k] === -1 || added < 24) return [-1, -1];
            return [expected[k], Number(lit[at] - shadowed[at] > added / 2)];
        });
    }

    // The library's exact self-shadow (ReliefStandardMaterial's selfShadow) in a scene of
    // its own with the page's camera and map: a white relief, an ambient light and a
    // directional light towards `light`, no shadow maps, drawn with the light off, lit
    // without selfShadow and lit with it. Returns, for every pixel (row 0 the top, row by
    // row), -1 where the light adds under 24 levels (or nothing is drawn), else 1 where
    // selfShadow takes more than half of what the light adds, 0 where it does not.
    function selfShadow(light) {
        const {THREE, renderer, camera, map, microrelief} = app();
        const {width, height} = renderer.domElement;
        const scene = new THREE.Scene();
        const material = new microrelief.ReliefStandardMaterial({color: 0xffffff, roughness: 1});
        const relief = new microrelief.Relief(map, {material});
        const sun = new THREE.DirectionalLight(0xffffff, 2.5);
        sun.position.set(...light).normalize().multiplyScalar(2);
        scene.add(sun, new THREE.AmbientLight(0xffffff, 0.4), relief);
        const draw = (on, exact) => {
            sun.intensity = on ? 2.5 : 0;
            material.selfShadow = exact;
            material.needsUpdate = true;
            renderer.render(scene, camera);
            return readPixels(renderer, width, height);
        };
        const [dark, lit, shadowed] = [draw(false, false), draw(true, false), draw(true, true)];
        const out = [];
        for (let row = 0; row < height; ++row)
            for (let column = 0; column < width; ++column) {
                const at = 4 * ((height - 1 - row) * width + column);
                const added = lit[at] - dark[at];
                out.push(added < 24 ? -1 : Number(lit[at] - shadowed[at] > added / 2));
            }
        return out;
    }

    // The three-lit example's scene (examples/three/cobbles.js, the page opened without
    // shading=microrelief) drawn with its sun's shadow.normalBias set to `normalBias` (null:
    // the example's own), the floor in three's shadow map or not, shown or hidden, the sun on
    // or off; its pixels read back, and every setting put back as the example made it.
    function drawExample({normalBias = null, floorInShadowMap = true, floorShown = true, sunOn = true}) {
        const {renderer, scene, camera, floor} = app();
        const {width, height} = renderer.domElement;
        const sun = exampleSun();
        const made = {normalBias: sun.shadow.normalBias, intensity: sun.intensity, castShadow: floor.castShadow, visible: floor.visible};
        sun.shadow.normalBias = normalBias ?? made.normalBias;
        sun.intensity = sunOn ? made.intensity : 0;
        floor.castShadow = floorInShadowMap;
        floor.visible = floorShown;
        try {
            renderer.render(scene, camera);
            return readPixels(renderer, width, height);
        } finally {
            sun.shadow.normalBias = made.normalBias;
            sun.intensity = made.intensity;
            Object.assign(floor, {castShadow: made.castShadow, visible: made.visible});
        }
    }

    // Shadow acne on the example's floor: it is in three's shadow map and receives from it,
    // so where it meets its own depth there its lit stones darken in stripes. The scene is
    // drawn (drawExample, with `normalBias`) as it is (A) and with the floor left out of the
    // shadow map (B: the ball and the knot still cast, the relief's self-shadow is still
    // traced by its material), so that the floor's own depth in the map is the one
    // difference; also with the floor hidden and with the sun off. The floor's pixels are
    // those that change when it is hidden; the lit ones, those where the sun adds at least 24
    // levels a channel in B (as the checks above); a lit one is darker in A where A loses more
    // than a quarter of what the sun adds (three's PCF filter averages acne's stripes over
    // its taps: they take a part of the light, not all of it). Returns [the normalBias drawn,
    // floor pixels, lit, darker in A]; the canvas keeps A.
    function shadowAcne(normalBias) {
        const hidden = drawExample({normalBias, floorInShadowMap: false, floorShown: false});
        const dark = drawExample({normalBias, floorInShadowMap: false, sunOn: false});
        const b = drawExample({normalBias, floorInShadowMap: false}), a = drawExample({normalBias});
        const sum = (p, at) => p[at] + p[at + 1] + p[at + 2];
        let floorPixels = 0, lit = 0, darker = 0;
        for (let at = 0; at < a.length; at += 4) {
            if ([0, 1, 2].every((c) => hidden[at + c] === b[at + c])) continue;
            ++floorPixels;
            const added = sum(b, at) - sum(dark, at);
            if (added < 3 * 24) continue;
            ++lit;
            darker += sum(b, at) - sum(a, at) > added / 4;
        }
        return [normalBias ?? exampleSun().shadow.normalBias, floorPixels, lit, darker];
    }

    // shadowAcne's B alone, for a picture of it: the canvas keeps it.
    function withoutFloorInShadowMap(normalBias) {
        drawExample({normalBias, floorInShadowMap: false});
        return 'drawn';
    }

    // The windows pyramid built on the GPU (shaders/pyramid/'s passes) and by the C++
    // MaxPyramid in WebAssembly, for the bundled map and an odd-sized map of its own (37 x 23,
    // heights over three octaves), each with and without wrapU: every level read back
    // through its bits. Returns one line a case: "name levels texels differing sameScale",
    // differing the texels whose 32 bits differ, sameScale 1 where the scale exponent S and
    // the max height agree.
    async function pyramids() {
        const {renderer, microrelief} = app();
        const cobbles = await microrelief.loadHeights('../../assets/cobbles.png');
        const [w, h] = [37, 23], samples = new Float32Array(w * h);
        for (let k = 0; k < samples.length; ++k) samples[k] = Math.fround(0.05 + 6.5 * (0.5 + 0.5 * Math.sin(0.7 * k)) * (1 + (k % 7)));
        const odd = microrelief.heightsFromArray(samples, w, h, {name: 'odd'});
        const lines = [];
        for (const [name, heights, wrapU] of [['cobbles', cobbles, false], ['cobbles-wrapU', cobbles, true], ['odd', odd, false], ['odd-wrapU', odd, true]]) {
            const gpu = await microrelief.createReliefMap(renderer, heights, {wrapU, pyramid: 'gpu'});
            const cpu = await microrelief.createReliefMap(renderer, heights, {wrapU, pyramid: 'cpu'});
            let texels = 0, differing = 0;
            const levels = Math.min(gpu.levelSizes.length, cpu.levelSizes.length);
            for (let level = 0; level < levels; ++level) {
                const a = new Uint32Array(microrelief.readWindowLevel(gpu, level).buffer);
                const b = new Uint32Array(microrelief.readWindowLevel(cpu, level).buffer);
                texels += a.length;
                for (let k = 0; k < a.length; ++k) differing += a[k] !== b[k];
                differing += Math.abs(a.length - b.length);
            }
            const sameScale = gpu.scaleExponent === cpu.scaleExponent && gpu.maxHeight === cpu.maxHeight;
            const sameLevels = gpu.levelSizes.length === cpu.levelSizes.length;
            lines.push(`${name} ${sameLevels ? levels : -1} ${texels} ${differing} ${sameScale ? 1 : 0} ${gpu.builtOn} ${cpu.builtOn}`);
            for (const map of [gpu, cpu]) if (map.dispose) map.dispose();
        }
        return lines.join('\n');
    }

    // Bad input, each refused with one error while the scene keeps drawing: a map wider than
    // the GPU's MAX_TEXTURE_SIZE, a file that is no image (the page's own HTML), and a GPU
    // pyramid where EXT_color_buffer_float is missing (reported missing by the renderer's
    // extension list for that call: SwiftShader has it). Then the scene is drawn again.
    // Returns one line a case: "what: ErrorName: message".
    async function refusals() {
        const {microrelief, renderer, render} = app();
        const lines = [];
        const attempt = async (what, f) => {
            try {
                await f();
                lines.push(`${what}: no error`);
            } catch (e) {
                lines.push(`${what}: ${e.name}: ${e.message}`);
            }
        };
        const wide = renderer.capabilities.maxTextureSize + 1;
        await attempt('too large', () => microrelief.createReliefMap(renderer, microrelief.heightsFromArray(new Float32Array(wide), wide, 1)));
        await attempt('not an image', () => microrelief.loadHeights('index.html'));
        const has = renderer.extensions.has;
        renderer.extensions.has = (name) => name !== 'EXT_color_buffer_float' && has.call(renderer.extensions, name);
        try {
            await attempt('no extension', () => microrelief.createReliefMap(renderer, microrelief.heightsFromArray(new Float32Array(4), 2, 2), {pyramid: 'gpu'}));
        } finally {
            renderer.extensions.has = has;
        }
        await render();
        return lines.join('\n');
    }

    return {pick, depth, depthLogarithmic, shadows, selfShadow, shadowAcne, withoutFloorInShadowMap, pyramids, refusals};
})();
'ready';
