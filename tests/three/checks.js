// checks.js: the measurements tests/three makes inside examples/three's page, evaluated there
// once the page is ready (ThreeTest.cpp sends this text as a script). It uses only what the
// page exposes in window.microreliefThree: three, microrelief-three, its renderer, scene,
// camera and relief. Pixels are (column, row), row 0 the top, as in microrelief-render's AOV.
window.threeChecks = (() => {
    const app = () => window.microreliefThree;

    // The NDC of pixel (column, row)'s centre.
    function pixelNdc(column, row) {
        const {width, height} = app().renderer.domElement;
        return new (app().THREE.Vector2)(((column + 0.5) / width) * 2 - 1, 1 - ((row + 0.5) / height) * 2);
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
    function depth(pixels, reliefPoints, point, normal, near, far) {
        const {THREE, renderer, scene, camera, microrelief} = app();
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
        const windowDepth = (world) => 0.5 + 0.5 * world.clone().project(camera).z;
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
    // and map: a white ReliefStandardMaterial relief, an ambient light and a directional
    // light towards `light` with a 2048-texel shadow map over [-0.8, 0.8]^2, and either
    // (`what` 'receive') a sphere of radius 0.12 at `sphere`, casting but not drawn, onto the
    // relief, or ('cast') the relief casting onto a ground square at y = -0.0005. The scene is
    // drawn three times: the light off, the caster not casting, casting (what the canvas keeps). At each of
    // `pixels` the hit point (the relief's: Relief.traceRays; the ground's: its plane met
    // analytically where the relief is missed) and whether the drawing shows it shadowed
    // (darker with the caster casting by more than half of what the light adds), and what the
    // geometry says: the ray from the point towards the light meets the sphere (analytically)
    // or the relief (traceRays). `margin`: a point whose answer changes within that distance
    // (the sphere's outline, or the same ray from points moved by margin along x and z) is
    // left out, as is one the light barely reaches (it adds under 24 levels).
    // Returns [expected, seen] per pixel: 1 shadowed, 0 lit, -1 left out.
    function shadows(what, pixels, light, sphereCentre, margin) {
        const {THREE, renderer, camera, map, microrelief} = app();
        const {width, height} = renderer.domElement;
        const toLight = new THREE.Vector3(...light).normalize();
        const scene = new THREE.Scene();
        const relief = new microrelief.Relief(map, {material: new microrelief.ReliefStandardMaterial({color: 0xffffff, roughness: 1})});
        const sun = new THREE.DirectionalLight(0xffffff, 2.5);
        sun.position.copy(toLight).multiplyScalar(2);
        sun.castShadow = true;
        sun.shadow.mapSize.set(2048, 2048);
        Object.assign(sun.shadow.camera, {left: -0.8, right: 0.8, bottom: -0.8, top: 0.8, near: 0.5, far: 4});
        scene.add(sun, sun.target, new THREE.AmbientLight(0xffffff, 0.4), relief);
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
            const gl = renderer.getContext(), bytes = new Uint8Array(4 * width * height);
            gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, bytes);
            return bytes;
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
                const d = new THREE.Ray(p, toLight).distanceToPoint(sphere.position);
                return Math.abs(d - radius) < margin ? -1 : Number(d < radius);
            });
        } else {
            const offsets = [[0, 0], [margin, 0], [-margin, 0], [0, margin], [0, -margin]];
            const from = [], towards = [];
            for (const p of points)
                for (const [dx, dz] of offsets) {
                    from.push(...(p ? [p.x + dx, p.y + 0.0005, p.z + dz] : [0, -10, 0]));
                    towards.push(...toLight.toArray());
                }
            const blocked = relief.traceRays(from, towards, [0, 100]).kind;
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
        render();
        return lines.join('\n');
    }

    return {pick, depth, shadows, refusals};
})();
'ready';
