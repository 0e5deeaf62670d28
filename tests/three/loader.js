// loader.js: the page-side checks of LoaderTest.cpp (suite ThreeLoader), evaluated in
// examples/three's page once it is ready, as checks.js is: ReliefMapLoader as three's
// loaders behave (its LoadingManager, setPath, progress, THREE.Cache, errors), and three's
// ordinary `map` from a TextureLoader as the relief's albedo.
window.threeLoaderChecks = (() => {
    const app = () => window.microreliefThree;

    // The canvas's RGBA bytes (row 0 the bottom).
    function readPixels(renderer) {
        const {width, height} = renderer.domElement;
        const gl = renderer.getContext(), bytes = new Uint8Array(4 * width * height);
        gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, bytes);
        return bytes;
    }

    // A LoadingManager that writes down what it is told, in order.
    function recordingManager(THREE) {
        const events = [];
        const manager = new THREE.LoadingManager(
            () => events.push('load'),
            (url, loaded, total) => events.push(`progress ${loaded}/${total}`),
            (url) => events.push(`error ${url}`));
        manager.onStart = () => events.push('start');
        return {manager, events};
    }

    const settle = (promise) => promise.then((value) => ({value}), (error) => ({error}));
    const describe = (error) => `${error && error.name}: ${error && error.message}`;
    const bits = (floats) => new Uint32Array(floats.buffer, floats.byteOffset, floats.length);

    // Returns lines "key value" (ThreeLoader.ALoaderLoadsAsThreesLoadersDo reads them).
    async function loading() {
        const {THREE, renderer, microrelief} = app();
        const out = [];
        // The bundled map through the loader (setPath, the manager, progress) and through
        // loadReliefMap: the same samples to the bit, 16 bits kept.
        const {manager, events} = recordingManager(THREE);
        const loader = new microrelief.ReliefMapLoader(renderer, manager).setPath('../../assets/');
        let progress = 0, progressDone = false, onLoadAt = -1;
        const map = await new Promise((resolve, reject) => loader.load('cobbles.png', (m) => {
            onLoadAt = events.length;
            resolve(m);
        }, (event) => {
            ++progress;
            progressDone ||= event.lengthComputable && event.loaded === event.total && event.total > 0;
        }, reject));
        await new Promise((resolve) => setTimeout(resolve, 0));
        out.push(`isLoader ${Number(loader instanceof THREE.Loader)}`);
        out.push(`isReliefMap ${Number(map instanceof microrelief.ReliefMap)} ${map.width}x${map.height} ${map.name}`);
        const exact = await microrelief.loadHeights('../../assets/cobbles.png');
        const texels = bits(microrelief.readTextureFloats(renderer, map.heights, 0, map.width, map.height));
        const samples = bits(exact.samples);
        let differing = 0, sixteenBit = 0;
        for (let k = 0; k < samples.length; ++k) {
            differing += texels[k] !== samples[k];
            const v = Math.round(exact.samples[k] * 65535);
            sixteenBit += v % 257 !== 0;  // not a value an 8-bit decode could give
        }
        out.push(`differing ${differing} of ${samples.length}`);
        out.push(`sixteenBit ${sixteenBit}`);
        out.push(`progressEvents ${progress} ${Number(progressDone)}`);
        out.push(`managerEvents ${events.join(',')}`);
        out.push(`onLoadBeforeManagerLoad ${Number(onLoadAt >= 0 && onLoadAt < events.indexOf('load'))}`);
        map.dispose();

        // loadAsync, and wrapU passed on to createReliefMap; THREE.Cache serves the second load
        // without a request.
        const realFetch = window.fetch;
        let fetches = 0;
        window.fetch = (...args) => {
            ++fetches;
            return realFetch(...args);
        };
        THREE.Cache.enabled = true;
        try {
            const cached = new microrelief.ReliefMapLoader(renderer).setOptions({wrapU: true});
            const first = await cached.loadAsync('../../assets/cobbles.png');
            const second = await cached.loadAsync('../../assets/cobbles.png');
            out.push(`wrapU ${Number(first.wrapU)} ${Number(second.wrapU)}`);
            out.push(`fetchesForTwoLoads ${fetches}`);
            first.dispose();
            second.dispose();
        } finally {
            THREE.Cache.enabled = false;
            THREE.Cache.clear();
            window.fetch = realFetch;
        }

        // Bad input: onError (and loadAsync's rejection) with one line naming the URL and the
        // reason; the manager's onError with the URL, once.
        for (const [what, url] of [['missing', 'no-such-map.png'], ['notAnImage', 'index.html']]) {
            const {manager: m, events: e} = recordingManager(THREE);
            const bad = new microrelief.ReliefMapLoader(renderer, m);
            const error = await new Promise((resolve) => bad.load(url, () => resolve(null), undefined, resolve));
            await new Promise((resolve) => setTimeout(resolve, 0));
            out.push(`${what} ${describe(error)}`);
            out.push(`${what}Manager ${e.filter((x) => x.startsWith('error')).join(',')}; ${e.includes('load') ? 'load' : 'noload'}`);
            const rejected = await settle(new microrelief.ReliefMapLoader(renderer).loadAsync(url));
            out.push(`${what}Async ${rejected.error ? describe(rejected.error) : 'resolved'}`);
        }
        return out.join('\n');
    }

    // three's ordinary `map` (a TextureLoader's texture, sRGB, its default flipY) as the relief's
    // albedo against the package's albedoMap (loadAlbedo: flipY false, filtered over the
    // footprint): the example's floor drawn in a scene of its own with each, and with the map
    // flipped the other way (a control: the measure must see a wrong map). Returns lines
    // "name differentPixels meanLevels" over the pixels the relief covers (channels summed).
    async function albedo(keep = null) {
        const {THREE, renderer, camera, map, microrelief} = app();
        const url = '../../assets/cobbles-albedo.png';
        const [albedoMap, plain] = await Promise.all([microrelief.loadAlbedo(url), new THREE.TextureLoader().loadAsync(url)]);
        plain.colorSpace = THREE.SRGBColorSpace;
        plain.wrapS = plain.wrapT = THREE.RepeatWrapping;
        const flipped = plain.clone();
        flipped.flipY = false;
        flipped.needsUpdate = true;
        const scene = new THREE.Scene();
        const sun = new THREE.DirectionalLight(0xffffff, 2.5);
        sun.position.set(-0.45, 0.8, -0.35);
        scene.add(sun, new THREE.HemisphereLight(0xbfd4ff, 0x3b3025, 0.8));
        // The scene drawn with a relief in a material of `parameters` (null: no relief).
        const draw = (parameters) => {
            const relief = parameters && new microrelief.Relief(map, {material: new microrelief.ReliefStandardMaterial({roughness: 0.85, ...parameters})});
            if (relief) scene.add(relief);
            renderer.render(scene, camera);
            const pixels = readPixels(renderer);
            if (relief) {
                scene.remove(relief);
                relief.material.dispose();
            }
            return pixels;
        };
        const none = draw(null);
        const reference = draw({albedoMap});
        const lines = [];
        for (const [name, parameters] of [['map', {map: plain}], ['flipped', {map: flipped}]]) {
            const seen = draw(parameters);
            let covered = 0, different = 0, sum = 0;
            for (let at = 0; at < seen.length; at += 4) {
                if ([0, 1, 2].every((c) => reference[at + c] === none[at + c])) continue;  // no relief there
                ++covered;
                let d = 0;
                for (let c = 0; c < 3; ++c) d = Math.max(d, Math.abs(seen[at + c] - reference[at + c]));
                different += d > 8;
                sum += d;
            }
            lines.push(`${name} ${covered} ${different / Math.max(1, covered)} ${sum / Math.max(1, covered)}`);
        }
        if (keep) draw(keep === 'albedoMap' ? {albedoMap} : {map: keep === 'map' ? plain : flipped});  // for a picture
        return lines.join('\n');
    }

    return {loading, albedo};
})();
