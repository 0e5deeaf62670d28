// bias.js: the page-side checks of ShadowBiasTest.cpp (suite ThreeShadowBias), evaluated in
// examples/three's three-lit page (cobbles.js) once it is ready: shadow acne on the
// example's floor under three's DEFAULT shadow camera (a DirectionalLight's: 10 x 10 units,
// near 0.5, far 500) with no bias of the user's, at several shadow map sizes and sun
// directions. Pixels are counted on the lit tops of the stones.
window.threeBiasChecks = (() => {
    const app = () => window.microreliefThree;
    const sunOf = () => app().scene.children.find((object) => object.isDirectionalLight);

    function readPixels(renderer) {
        const {width, height} = renderer.domElement;
        const gl = renderer.getContext(), bytes = new Uint8Array(4 * width * height);
        gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, bytes);
        return bytes;
    }

    // The sun as three makes it: its default shadow camera, `mapSize` texels a side, towards
    // `light` (at distance 2 from the floor's centre), bias and normalBias `userBias`.
    function setSun(mapSize, light, userBias) {
        const {THREE} = app();
        const sun = sunOf(), defaults = new THREE.DirectionalLight().shadow;
        sun.position.set(...light).normalize().multiplyScalar(2);
        const {left, right, top, bottom, near, far} = defaults.camera;
        Object.assign(sun.shadow.camera, {left, right, top, bottom, near, far});
        sun.shadow.camera.updateProjectionMatrix();
        sun.shadow.bias = 0;
        sun.shadow.normalBias = userBias;
        if (sun.shadow.mapSize.x !== mapSize) {
            sun.shadow.mapSize.set(mapSize, mapSize);
            if (sun.shadow.map) sun.shadow.map.dispose();
            sun.shadow.map = null;
        }
        return sun;
    }

    // The pixels of the camera's view where the floor's traced surface faces up (its normal
    // within 30 degrees of +y): the stones' tops, where acne shows and no true shadow edge of
    // the relief's own is near (the flanks and the gaps between the stones left out).
    function tops() {
        const {THREE, renderer, camera, floor} = app();
        const {width, height} = renderer.domElement;
        const raycaster = new THREE.Raycaster(), origins = [], directions = [];
        for (let row = 0; row < height; ++row)
            for (let column = 0; column < width; ++column) {
                raycaster.setFromCamera(new THREE.Vector2(((column + 0.5) / width) * 2 - 1, 1 - ((row + 0.5) / height) * 2), camera);
                origins.push(...raycaster.ray.origin.toArray());
                directions.push(...raycaster.ray.direction.toArray());
            }
        floor.updateMatrixWorld();
        const seen = floor.traceRays(origins, directions, [0, 100]);
        const top = new Uint8Array(width * height);  // GL's rows: row 0 the bottom
        for (let row = 0; row < height; ++row)
            for (let column = 0; column < width; ++column) {
                const k = row * width + column;
                top[(height - 1 - row) * width + column] = seen.kind[k] === 1 && seen.normal[3 * k + 1] > Math.cos(Math.PI / 6);
            }
        return top;
    }

    // shadowAcne of checks.js on the tops: the scene drawn with the floor in three's shadow
    // map (A) and out of it (B: the ball and the knot still cast, the floor's self-shadow is
    // still traced by its material), with the floor hidden and with the sun off; a top pixel
    // the sun lights (adds at least 24 levels a channel in B) is darker where A loses more
    // than a quarter of what the sun adds. Returns [lit top pixels, darker in A]; the canvas
    // keeps A.
    function acneOnTops(top, sun = sunOf()) {
        const {renderer, scene, camera, floor} = app();
        const intensity = sun.intensity;
        const draw = ({inMap = true, shown = true, sunOn = true}) => {
            floor.castShadow = inMap;
            floor.visible = shown;
            sun.intensity = sunOn ? intensity : 0;
            renderer.render(scene, camera);
            return readPixels(renderer);
        };
        const hidden = draw({inMap: false, shown: false}), dark = draw({inMap: false, sunOn: false});
        const b = draw({inMap: false}), a = draw({});
        const sum = (p, at) => p[at] + p[at + 1] + p[at + 2];
        let lit = 0, darker = 0;
        for (let at = 0; at < a.length; at += 4) {
            if (!top[at / 4] || [0, 1, 2].every((c) => hidden[at + c] === b[at + c])) continue;
            const added = sum(b, at) - sum(dark, at);
            if (added < 3 * 24) continue;
            ++lit;
            darker += sum(b, at) - sum(a, at) > added / 4;
        }
        return [lit, darker];
    }

    // For each case [mapSize, light direction, user bias]: "mapSize lx,ly,lz bias lit darker",
    // on the tops (or, with everywhere, on all the floor's lit pixels: flanks too).
    function acne(cases, everywhere = false) {
        const top = everywhere ? new Uint8Array(app().renderer.domElement.width * app().renderer.domElement.height).fill(1) : tops();
        return cases.map(([mapSize, light, userBias]) => {
            setSun(mapSize, light, userBias);
            return `${mapSize} ${light.join(',')} ${userBias} ${acneOnTops(top).join(' ')}`;
        }).join('\n');
    }

    // The same for a spot or point light as three makes it (its default shadow camera, near
    // 0.5, far 500; a spot's cone of 60 degrees about the floor's centre), at `position`,
    // `mapSize` texels a side (a point light's cube faces), no bias; the example's sun off.
    // Returns "kind mapSize px,py,pz lit darker".
    function acneOf(kind, mapSize, position, top = tops()) {
        const {THREE, scene} = app();
        const sun = sunOf(), made = {intensity: sun.intensity, castShadow: sun.castShadow};
        const light = kind === 'spot' ? new THREE.SpotLight(0xffffff, 6, 0, Math.PI / 3, 0, 0) : new THREE.PointLight(0xffffff, 6, 0, 0);
        light.position.set(...position);
        light.castShadow = true;
        light.shadow.mapSize.set(mapSize, mapSize);
        scene.add(light);
        if (light.target) scene.add(light.target);
        Object.assign(sun, {intensity: 0, castShadow: false});
        try {
            return `${kind} ${mapSize} ${position.join(',')} ${acneOnTops(top, light).join(' ')}`;
        } finally {
            scene.remove(light);
            if (light.target) scene.remove(light.target);
            light.dispose();
            Object.assign(sun, made);
        }
    }

    // Leaves the canvas with case [mapSize, light, userBias] drawn (for a picture).
    function draw(mapSize, light, userBias) {
        setSun(mapSize, light, userBias);
        const {renderer, scene, camera} = app();
        renderer.render(scene, camera);
        return 'drawn';
    }

    return {acne, acneOf, draw, tops};
})();
