// objects.js: what tests/three/ObjectsTest.cpp checks inside examples/three's compare page
// (shading=microrelief) about Relief and its materials behaving as three's objects do: a
// reversed-depth renderer, materials assigned after construction and shared, clone and copy,
// options changed after construction, toJSON and ObjectLoader. Each check returns lines of
// key=value: what it saw (an `error` where something threw), and for pictures the differences
// between two pictures the page's renderer drew on the same GPU (max, over: the fraction of
// channels more than 8 levels apart, mean, differing: the channels that differ at all).
window.objectChecks = (() => {
    const app = () => window.microreliefThree;

    // The scene's picture through the page's camera (or `camera`), read back at once (the
    // page's canvas keeps its drawing buffer; row 0 the bottom).
    function picture(scene, camera = app().camera, renderer = app().renderer) {
        renderer.render(scene, camera);
        const gl = renderer.getContext(), {width, height} = renderer.domElement;
        const bytes = new Uint8Array(4 * width * height);
        gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, bytes);
        return bytes;
    }

    function difference(a, b) {
        let max = 0, over = 0, sum = 0, differing = 0, background = 0;
        for (let k = 0; k < a.length; ++k) {
            const d = Math.abs(a[k] - b[k]);
            max = Math.max(max, d);
            over += d > 8;
            sum += d;
            differing += d > 0;
        }
        for (let k = 0; k < a.length; k += 4) background += a[k] === a[0] && a[k + 1] === a[1] && a[k + 2] === a[2];
        return {max, over: over / a.length, mean: sum / a.length, differing, covered: 1 - (4 * background) / a.length};
    }

    // A scene like the page's (its background, a sun for three's lights) holding `objects`.
    function sceneOf(...objects) {
        const {THREE, scene: page} = app();
        const scene = new THREE.Scene();
        scene.background = page.background;
        const sun = new THREE.DirectionalLight(0xffffff, 3);
        sun.position.set(-0.9, 1.6, -0.7);
        scene.add(sun, new THREE.HemisphereLight(0xbfd4ff, 0x3b3025, 0.8), ...objects);
        scene.updateMatrixWorld();
        return scene;
    }

    const shading = () => new (app().microrelief.ReliefShadingMaterial)({lightDirection: app().relief.material.uniforms.mrLightDirection.value,
                                                                        albedoMap: app().relief.material.uniforms.albedoMap.value});

    // `body`'s result as lines of `key=value`, nested keys joined by dots (the test reads
    // them without a JSON parser), or `error=` what it threw.
    function flatten(value, prefix = '', lines = []) {
        if (value !== null && typeof value === 'object') {
            for (const [key, inner] of Object.entries(value)) flatten(inner, prefix ? `${prefix}.${key}` : key, lines);
        } else {
            lines.push(`${prefix}=${String(value).replace(/\n/g, ' ')}`);
        }
        return lines;
    }

    async function run(body) {
        try {
            return flatten(await body()).join('\n');
        } catch (e) {
            return `error=${e.name}: ${String(e.message).replace(/\n/g, ' ')}`;
        }
    }

    const message = (call) => {
        try {
            call();
            return '';
        } catch (e) {
            return e.message;
        }
    };

    // A renderer with reversedDepthBuffer: a map built with it, the page's relief drawn and
    // picked with it, against the page's renderer (standard depth).
    function reversedDepth() {
        return run(async () => {
            const {THREE, microrelief, renderer: pageRenderer, camera, relief: pageRelief, scene: pageScene} = app();
            const canvas = document.createElement('canvas');
            Object.assign(canvas, {width: pageRenderer.domElement.width, height: pageRenderer.domElement.height});
            const renderer = new THREE.WebGLRenderer({canvas, antialias: false, preserveDrawingBuffer: true, reversedDepthBuffer: true});
            const reversed = renderer.capabilities.reversedDepthBuffer === true;
            try {
                const map = await microrelief.createReliefMap(renderer, await microrelief.loadHeights('../../assets/cobbles.png'));
                const relief = new microrelief.Relief(map, {material: shading(), heightScale: pageRelief.heightScale});
                const scene = sceneOf(relief);
                const drawn = picture(scene, camera.clone(), renderer);
                const expected = picture(pageScene);
                // Picks through a grid of pixels, each against the page's relief's.
                const raycaster = new THREE.Raycaster(), ndc = new THREE.Vector2();
                let hits = 0, disagreements = 0, largest = 0;
                for (let y = -0.9; y < 1; y += 0.15) {
                    for (let x = -0.9; x < 1; x += 0.15) {
                        raycaster.setFromCamera(ndc.set(x, y), camera);
                        const a = raycaster.intersectObject(relief)[0], b = raycaster.intersectObject(pageRelief)[0];
                        if (!a !== !b) ++disagreements;
                        if (!a || !b) continue;
                        ++hits;
                        largest = Math.max(largest, a.point.distanceTo(b.point));
                    }
                }
                return {reversed, picture: difference(drawn, expected), hits, disagreements, largest};
            } finally {
                renderer.dispose();
            }
        });
    }

    // relief.material = ... after construction: a library-shaded one and a three-lit one draw
    // what reliefs constructed with them draw; three's own materials are refused in one line.
    function assignedMaterial() {
        return run(() => {
            const {THREE, microrelief, map, relief: pageRelief, scene: pageScene} = app();
            const {Relief, ReliefStandardMaterial} = microrelief;
            const heightScale = pageRelief.heightScale;
            const relief = new Relief(map, {material: shading(), heightScale});
            relief.material = shading();
            const shaded = difference(picture(sceneOf(relief)), picture(pageScene));
            const parameters = {color: 0xd8c8a8, roughness: 0.7};
            const lit = new Relief(map, {material: shading(), heightScale});
            lit.material = new ReliefStandardMaterial(parameters);
            const constructed = new Relief(map, {material: new ReliefStandardMaterial(parameters), heightScale});
            const standard = difference(picture(sceneOf(lit)), picture(sceneOf(constructed)));
            return {shaded, standard,
                    plainAssigned: message(() => (relief.material = new THREE.MeshStandardMaterial())),
                    plainConstructed: message(() => new Relief(map, {material: new THREE.MeshPhysicalMaterial()})),
                    basic: message(() => (relief.material = new THREE.MeshBasicMaterial())),
                    kept: relief.material.isReliefMaterial === true};
        });
    }

    // gl.uniform* calls in the third of three frames of `scene` whose camera moves a little
    // each frame (as it does under OrbitControls): what a frame uploads once the programs
    // are compiled and the first frame's values are in three's caches.
    function uniformCalls(scene) {
        const gl = app().renderer.getContext(), camera = app().camera.clone();
        const names = Object.getOwnPropertyNames(WebGL2RenderingContext.prototype).filter((n) => /^uniform(Matrix)?\d/.test(n));
        let calls = 0;
        const saved = names.map((n) => [n, gl[n]]);
        for (const [n, f] of saved) gl[n] = (...args) => (++calls, f.apply(gl, args));
        try {
            for (let frame = 0; frame < 3; ++frame) {
                calls = 0;
                camera.position.x += 0.01;
                camera.updateMatrixWorld();
                picture(scene, camera);
            }
        } finally {
            for (const [n] of saved) delete gl[n];
        }
        return calls;
    }

    // Two reliefs of different height scales and places sharing one material, against the
    // same two each with its own: the same picture. Also with a three-lit material, and with
    // the two reliefs' last levels differing (two program variants of one material).
    function sharedMaterial() {
        return run(() => {
            const {microrelief, map, relief: pageRelief} = app();
            const make = (material, heightScale, x, interpolation = 'bilinear') => {
                const relief = new microrelief.Relief(map, {material, heightScale, interpolation});
                relief.position.set(x, 0, -0.1 * x);
                relief.scale.setScalar(0.6);
                return relief;
            };
            const s = pageRelief.heightScale;
            const pair = (first, second, interpolation) => sceneOf(make(first, s, -0.3), make(second, 2 * s, 0.3, interpolation));
            const one = shading();
            const shared = pair(one, one), own = pair(shading(), shading());
            const drawnShared = picture(shared), drawnOwn = picture(own);
            // Either relief alone: the pair's picture is not one relief drawn twice.
            const alone = difference(drawnOwn, picture(sceneOf(make(shading(), s, -0.3))));
            const lit = () => new microrelief.ReliefStandardMaterial({color: 0xd8c8a8, roughness: 0.7});
            const litOne = lit();
            const standard = difference(picture(pair(litOne, litOne)), picture(pair(lit(), lit())));
            const both = shading();
            const variants = difference(picture(pair(both, both, 'biquadratic')), picture(pair(shading(), shading(), 'biquadratic')));
            return {picture: difference(drawnShared, drawnOwn), alone, standard, variants,
                    uniformCalls: {shared: uniformCalls(shared), own: uniformCalls(own)}};
        });
    }

    // relief.clone() and copy(): the same map and material, their own box and uniforms, the
    // same picture; a change to the clone leaves the original as it was.
    function cloneAndCopy() {
        return run(() => {
            const {microrelief, scene: pageScene, relief} = app();
            const before = picture(pageScene);
            const clone = relief.clone();
            const cloned = difference(picture(sceneOf(clone)), before);
            const shares = {map: clone.reliefMap === relief.reliefMap, material: clone.material === relief.material,
                            uniforms: clone.uniforms !== relief.uniforms, geometry: clone.geometry !== relief.geometry,
                            depth: clone.customDepthMaterial !== relief.customDepthMaterial && clone.customDepthMaterial.relief === clone};
            clone.heightScale = 2 * relief.heightScale;
            const afterChange = difference(picture(pageScene), before);
            const changed = difference(picture(sceneOf(clone)), before);
            const other = new microrelief.Relief(relief.reliefMap, {material: shading(), heightScale: 3 * relief.heightScale});
            other.copy(relief);
            const copied = difference(picture(sceneOf(other)), before);
            return {cloned, shares, originalAfterChange: afterChange, cloneChanged: changed, copied,
                    heightScales: [relief.heightScale, clone.heightScale, other.heightScale]};
        });
    }

    // heightScale, interpolation and base set after construction against reliefs constructed
    // with them; each change must show (the pictures before and after differ).
    function liveOptions() {
        return run(async () => {
            const {microrelief, renderer, map, relief: pageRelief} = app();
            const {Relief} = microrelief;
            const s = pageRelief.heightScale;
            const result = {};
            const live = new Relief(map, {material: shading(), heightScale: s});
            const scene = sceneOf(live);
            const first = picture(scene);
            live.heightScale = 1.5 * s;
            const raised = picture(scene);
            result.heightScale = {live: difference(raised, picture(sceneOf(new Relief(map, {material: shading(), heightScale: 1.5 * s})))),
                                  change: difference(raised, first)};
            live.interpolation = 'biquadratic';
            const smooth = picture(scene);
            result.interpolation = {live: difference(smooth, picture(sceneOf(new Relief(map, {material: shading(), heightScale: 1.5 * s, interpolation: 'biquadratic'})))),
                                    change: difference(smooth, raised)};
            const wrapped = await microrelief.createReliefMap(renderer, await microrelief.loadHeights('../../assets/cobbles.png'), {wrapU: true});
            const curved = new Relief(wrapped, {material: shading(), base: 'cylinder'});
            const curvedScene = sceneOf(curved);
            const cylinder = picture(curvedScene);
            curved.base = {kind: 'sphere', radius: 0.4};
            const sphere = picture(curvedScene);
            result.base = {live: difference(sphere, picture(sceneOf(new Relief(wrapped, {material: shading(), base: {kind: 'sphere', radius: 0.4}})))),
                           change: difference(sphere, cylinder),
                           refused: message(() => (curved.base = 'plane')),
                           constructorRefused: message(() => new Relief(wrapped, {base: 'plane'})),
                           kept: curved.base.kind, ellipsoid: message(() => new Relief(map, {base: 'ellipsoid'}))};
            result.badHeightScale = message(() => (live.heightScale = -1));
            result.badInterpolation = message(() => (live.interpolation = 'trilinear'));
            picture(curvedScene);  // left on the canvas for the screenshot
            return result;
        });
    }

    // toJSON through ObjectLoader: a plain Mesh carrying the options, which Relief.fromMesh
    // makes the same relief again with the map.
    function json() {
        return run(() => {
            const {THREE, microrelief, relief, scene: pageScene, map} = app();
            const {Relief, ReliefStandardMaterial} = microrelief;
            relief.name = 'floor';
            const loader = new THREE.ObjectLoader();
            const loaded = loader.parse(JSON.parse(JSON.stringify(relief.toJSON())));
            const record = loaded.userData.microrelief;
            const restored = Relief.fromMesh(loaded, map, {albedoMap: relief.material.uniforms.albedoMap.value});
            const same = difference(picture(sceneOf(restored)), picture(pageScene));
            const lit = new Relief(map, {material: new ReliefStandardMaterial({roughness: 0.3, selfShadow: true}), heightScale: 0.2});
            const litLoaded = loader.parse(JSON.parse(JSON.stringify(sceneOf(lit).toJSON()))).children.find((o) => o.isMesh);
            const litRestored = Relief.fromMesh(litLoaded, map);
            return {isMesh: loaded.isMesh === true, type: loaded.type, name: loaded.name, heightScale: record && record.heightScale,
                    same, restoredType: restored.type, restoredName: restored.name,
                    lit: {type: litLoaded.material.type, roughness: litLoaded.material.roughness, selfShadow: litRestored.material.selfShadow,
                          material: litRestored.material.isReliefMaterial === true, heightScale: litRestored.heightScale},
                    wrongMap: message(() => Relief.fromMesh(loaded, {...map, width: 7})),
                    notRelief: message(() => Relief.fromMesh(new THREE.Mesh(), map))};
        });
    }

    return {reversedDepth, assignedMaterial, sharedMaterial, cloneAndCopy, liveOptions, json};
})();
