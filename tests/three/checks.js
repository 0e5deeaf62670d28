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

    return {pick, depth};
})();
'ready';
