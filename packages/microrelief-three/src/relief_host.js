// relief_host.js: the host code both entries share (the WebGL one, relief.js, and the WebGPU
// one, webgpu.js): the base's shape and the relief's bounds (the table of bases' rows in
// generated/relief_core.js), the proxy box, the option checks, and each draw's camera rays
// and matrices (the uniforms of glsl/relief_three.glsl, which the WebGPU entry's WGSL glue
// takes too), and the picks (three's Raycaster and the relief's own rays, traced by the CPU
// twin: twin.js). No renderer: each entry's Relief calls these from its own methods.
import * as THREE from 'three';

import * as core from '../generated/relief_core.js';
import {traceOnTwin, twinLoaded, twinUnavailable} from './twin.js';

const kBoxMargin = Math.fround(1e-3);  // ReliefRenderer's: the box grown by this, object units

// The base surface: {kind: 'plane'} or {kind: 'cylinder', radius, length} or
// {kind: 'ellipsoid', radii: [a, b, c]}; 'sphere' is an ellipsoid of equal radii. Strings
// take microrelief-render's defaults (the table of bases' rows: generated/relief_core.js).
export function baseShape(base = 'plane') {
    const {kind, ...sizes} = typeof base === 'string' ? {kind: base} : {...base};
    return core.baseShape(kind, sizes, (message, size) => new TypeError(`Relief: ${size ? 'base ' : ''}${message}`));
}

// The relief's object-space bounds for a top of `maxHeight` (ReliefExtent.cpp).
export function reliefExtent(width, height, maxHeight, heightScale, base) {
    const {min, max} = core.reliefExtent(width, height, maxHeight, heightScale, base);
    return {min, max};
}

// The six vectors of glsl/relief_three.glsl for `camera`: its rays as affine functions of
// the pixel's NDC, computed in double. Perspective: the eye, the direction through NDC
// (0, 0) scaled to a unit component along the view axis (t is then the view depth) and its
// steps per unit of NDC x and y. Otherwise (orthographic): origins on the near plane, one
// unit direction, t from the near plane. Also the t range, [near, far].
const _v = new THREE.Vector3(), _a = new THREE.Vector3(), _b = new THREE.Vector3(), _axis = new THREE.Vector3();
function unproject(camera, x, y, z, target) {
    return target.set(x, y, z).applyMatrix4(camera.projectionMatrixInverse).applyMatrix4(camera.matrixWorld);
}

export function cameraRays(camera) {
    const e = camera.projectionMatrix.elements;
    const perspective = e[11] === -1 && e[15] === 0;
    // NDC depths of two points in front of the camera, whatever its depth convention.
    const near = camera.near ?? 0.1, far = camera.far ?? 1000;
    const ndcZ = (viewDepth) => _v.set(0, 0, -viewDepth).applyMatrix4(camera.projectionMatrix).z;
    const zNear = ndcZ(near), zMid = ndcZ(0.5 * (near + far));
    const rays = {perspective};
    if (perspective) {
        const eye = new THREE.Vector3().setFromMatrixPosition(camera.matrixWorld);
        _axis.set(0, 0, -1).transformDirection(camera.matrixWorld);
        const d0 = unproject(camera, 0, 0, zMid, new THREE.Vector3()).sub(eye);
        const scale = 1 / d0.dot(_axis);
        const dx = unproject(camera, 1, 0, zMid, new THREE.Vector3()).sub(unproject(camera, 0, 0, zMid, _a)).multiplyScalar(scale);
        const dy = unproject(camera, 0, 1, zMid, new THREE.Vector3()).sub(unproject(camera, 0, 0, zMid, _a)).multiplyScalar(scale);
        Object.assign(rays, {origin: eye, originDx: new THREE.Vector3(), originDy: new THREE.Vector3(),
                             dir: d0.multiplyScalar(scale), dirDx: dx, dirDy: dy, range: [near, far]});
    } else {
        const o0 = unproject(camera, 0, 0, zNear, new THREE.Vector3());
        const ox = unproject(camera, 1, 0, zNear, new THREE.Vector3()).sub(o0);
        const oy = unproject(camera, 0, 1, zNear, new THREE.Vector3()).sub(o0);
        const dir = unproject(camera, 0, 0, zMid, _b).sub(o0).normalize().clone();
        Object.assign(rays, {origin: o0, originDx: ox, originDy: oy, dir, dirDx: new THREE.Vector3(), dirDy: new THREE.Vector3(),
                             range: [0, far - near]});
    }
    return rays;
}

// A base and a map that disagree on wrapU: a curved base needs it, the plane must not have it.
export function checkBaseForMap(shape, spec, reliefMap) {
    const wraps = core.wrapsU(shape);
    if (wraps === reliefMap.wrapU) return;
    const kind = typeof spec === 'string' ? spec : spec.kind;  // as asked: 'sphere' stays a sphere
    throw new TypeError(`Relief: ${/^[aeiou]/.test(kind) ? 'an' : 'a'} ${kind} base needs a map built with wrapU: ${wraps} (its u ${wraps ? 'wraps round' : 'does not wrap'})`);
}

export function checkHeightScale(value) {
    if (!(value > 0) || !Number.isFinite(value)) throw new TypeError('Relief: heightScale must be a positive finite number');
}

export function checkInterpolation(value) {
    if (!['bilinear', 'biquadratic'].includes(value)) throw new TypeError(`Relief: interpolation '${value}' (expected bilinear or biquadratic)`);
}

export function checkPixelError(value) {
    if (!(value >= 0)) throw new TypeError('Relief: pixelError must be a number >= 0');
}

// The options both entries' Relief carry as properties, settable at any time: heightScale
// (the box rebuilt), pixelError, interpolation and base (the box rebuilt, the base's frame
// scale set), defined once here on `prototype` (each entry's Relief.prototype) over its
// uniforms (reliefUniforms), its `_interpolation` and `_base` and its updateBox. What differs
// by entry comes in `hooks`: shapeOf(value), the base a value names (the entry's refusals:
// baseShape's, and the bases the entry draws), and variantChanged(relief), called where the
// program's variant changed (the last level, or the base's kind): the entry's programs made
// again.
export function defineReliefOptions(prototype, {shapeOf, variantChanged}) {
    Object.defineProperties(prototype, {
        heightScale: {
            get() {
                return this.uniforms.mrHeightScale.value;
            },
            set(value) {
                checkHeightScale(value);
                this.uniforms.mrHeightScale.value = Math.fround(value);
                this.updateBox();
            },
            configurable: true,
        },
        pixelError: {
            get() {
                return this.uniforms.mrPixelError.value;
            },
            set(value) {
                checkPixelError(value);
                this.uniforms.mrPixelError.value = value;
            },
            configurable: true,
        },
        interpolation: {
            get() {
                return this._interpolation;
            },
            set(value) {
                checkInterpolation(value);
                const changed = value !== this._interpolation;
                this._interpolation = value;
                if (changed) variantChanged(this);
            },
            configurable: true,
        },
        // The base's shape ({kind, radius, length} or {kind, radii}, frozen); set it as the
        // constructor's option (a name or a shape), held to the map's wrapU as there.
        base: {
            get() {
                return this._base;
            },
            set(value) {
                const shape = shapeOf(value);
                checkBaseForMap(shape, value, this.reliefMap);
                const changed = shape.kind !== this._base.kind;
                this._base = Object.freeze(shape);
                this.uniforms.mrFrameScale.value.set(...core.frameScale(shape));
                this.updateBox();
                if (changed) variantChanged(this);
            },
            configurable: true,
        },
    });
}

// The box (ReliefRenderer::uploadBox): the bounds from the pyramid's top, grown by
// kBoxMargin; a new geometry (a clone's box is its own). A BufferGeometry, not the
// BoxGeometry (whose parameters, all toJSON writes of it, do not hold the translation).
export function reliefBox(reliefMap, heightScale, base) {
    const extent = reliefExtent(reliefMap.width, reliefMap.height, reliefMap.maxHeight, heightScale, base);
    const lo = extent.min.map((c) => Math.fround(Math.fround(c) - kBoxMargin));
    const hi = extent.max.map((c) => Math.fround(Math.fround(c) + kBoxMargin));
    const box = new THREE.Box3(new THREE.Vector3(...lo), new THREE.Vector3(...hi));
    const size = box.getSize(new THREE.Vector3()), centre = box.getCenter(new THREE.Vector3());
    const geometry = new THREE.BufferGeometry().copy(new THREE.BoxGeometry(size.x, size.y, size.z).translate(centre.x, centre.y, centre.z));
    return {box, geometry};
}

// `relief`'s box for its map, height scale and base (reliefBox): relief.box and a new
// geometry, the previous one disposed. Each entry's Relief.updateBox, wherever one of the
// three changes.
export function updateReliefBox(relief) {
    const {box, geometry} = reliefBox(relief.reliefMap, relief.heightScale, relief.base);
    relief.box = box;
    const previous = relief.geometry;
    relief.geometry = geometry;
    previous.dispose();
}

// This draw's model and camera in `u` (uniform records {value} named as relief_three.glsl
// names them), and the camera's rays (returned). Traced relative to the camera, as the
// library's renderer traces relative to the eye (ReliefRenderer::parameters): the shader's
// world is three's moved by minus the camera's position, each matrix that meets a world
// position composed with that move here in double (JavaScript's numbers), so that a relief
// far from three's origin (a planet, a large level) is traced as exactly as one at it;
// mrWorldOrigin gives three's own world-space uniforms (shadow matrices) their world back.
export function reliefFrame(relief, camera, u) {
    const origin = _origin.setFromMatrixPosition(camera.matrixWorld);
    _fromOrigin.makeTranslation(origin.x, origin.y, origin.z);
    _toOrigin.makeTranslation(-origin.x, -origin.y, -origin.z);
    u.mrWorldOrigin.value.copy(origin);
    u.mrObjectToWorld.value.multiplyMatrices(_toOrigin, relief.matrixWorld);
    u.mrWorldToObject.value.copy(relief.matrixWorld).invert().multiply(_fromOrigin);
    const rays = cameraRays(camera);
    u.mrRayOrigin.value.copy(rays.origin).sub(origin);
    u.mrRayOriginDx.value.copy(rays.originDx);
    u.mrRayOriginDy.value.copy(rays.originDy);
    u.mrRayDir.value.copy(rays.dir);
    u.mrRayDirDx.value.copy(rays.dirDx);
    u.mrRayDirDy.value.copy(rays.dirDy);
    u.mrRange.value.set(...rays.range);
    u.mrPerspective.value = rays.perspective ? 1 : 0;
    u.mrViewProjection.value.multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse).multiply(_fromOrigin);
    u.mrCameraToWorld.value.multiplyMatrices(_toOrigin, camera.matrixWorld);
    u.mrWorldToCamera.value.multiplyMatrices(camera.matrixWorldInverse, _fromOrigin);
    return rays;
}

// The uniform records reliefFrame and a relief's map fill (relief_three.glsl's uniforms).
export function reliefUniforms(pixelError = 0) {
    return {
        mrHeights: {value: null}, mrWindows: {value: null},
        mrMapSize: {value: new THREE.Vector2()}, mrPyramidSize: {value: new THREE.Vector2()},
        mrLevelCount: {value: 0}, mrMaxHeight: {value: 0},
        mrObjectToWorld: {value: new THREE.Matrix4()}, mrWorldToObject: {value: new THREE.Matrix4()},
        mrHeightScale: {value: 0}, mrFrameScale: {value: new THREE.Vector3()},
        mrPixelError: {value: pixelError},
        mrRayOrigin: {value: new THREE.Vector3()}, mrRayOriginDx: {value: new THREE.Vector3()}, mrRayOriginDy: {value: new THREE.Vector3()},
        mrRayDir: {value: new THREE.Vector3()}, mrRayDirDx: {value: new THREE.Vector3()}, mrRayDirDy: {value: new THREE.Vector3()},
        mrViewport: {value: new THREE.Vector4()}, mrRange: {value: new THREE.Vector2()}, mrFaces: {value: 2},
        mrViewProjection: {value: new THREE.Matrix4()}, mrCameraToWorld: {value: new THREE.Matrix4()},
        mrWorldToCamera: {value: new THREE.Matrix4()}, mrPerspective: {value: 1},
        mrWorldOrigin: {value: new THREE.Vector3()},
    };
}

// A map's numbers in `u` (the textures are the entry's: each renderer its own kind).
export function reliefMapUniforms(reliefMap, u) {
    u.mrMapSize.value.set(reliefMap.width, reliefMap.height);
    u.mrPyramidSize.value.set(reliefMap.width, reliefMap.height);
    u.mrLevelCount.value = reliefMap.levelCount;
    u.mrMaxHeight.value = reliefMap.maxHeight;
}

// Which faces of the box run for `camera` (1 front, 2 back, 3 both): the box's back faces
// are never cut by the near plane: they run unless the far plane cuts the box; then its
// front faces, and both where near and far both cut it.
export function boxFaces(box, matrixWorld, camera, [near, far]) {
    let nearest = Infinity, farthest = -Infinity;
    const toView = _m.multiplyMatrices(camera.matrixWorldInverse, matrixWorld);
    for (let k = 0; k < 8; ++k) {
        _v.set(k & 1 ? box.max.x : box.min.x, k & 2 ? box.max.y : box.min.y, k & 4 ? box.max.z : box.min.z).applyMatrix4(toView);
        nearest = Math.min(nearest, -_v.z);
        farthest = Math.max(farthest, -_v.z);
    }
    if (camera.isOrthographicCamera || camera.projectionMatrix.elements[15] === 1) {
        nearest -= camera.near;
        farthest -= camera.near;
        [near, far] = [0, far];
    }
    if (farthest <= far) return 2;
    return nearest < near ? 3 : 1;
}

// ---- the picks, both entries' ----

// three's Raycaster on `relief` (each entry's Relief.raycast): the relief's own hit
// (relief.trace) where the ray meets its box, pushed as three's Mesh pushes one, with the
// fields of ReliefHit.
export function raycastRelief(relief, raycaster, intersects) {
    if (relief.material === undefined || relief.reliefMap.renderer === undefined) return;
    _inverse.copy(relief.matrixWorld).invert();
    _ray.copy(raycaster.ray).applyMatrix4(_inverse);
    if (!_ray.intersectsBox(relief.box)) return;
    const hit = relief.trace(raycaster.ray.origin, raycaster.ray.direction, raycaster.near, raycaster.far);
    if (!hit) return;
    intersects.push({...hit, object: relief, face: null, faceIndex: -1});
}

// The first hit of the world ray origin + t direction, t in [near, far], by
// relief.traceRays (each entry's Relief.trace): {distance, point, uv, normal (object space,
// as three's Mesh gives it), worldNormal, kind, iterations}, or null for a miss or an
// exhausted traversal.
export function traceOne(relief, origin, direction, near, far, options) {
    const rays = relief.traceRays([origin.x, origin.y, origin.z], [direction.x, direction.y, direction.z], [near, far], options);
    if (rays.kind[0] === 0 || rays.exhausted[0]) return null;
    const worldNormal = new THREE.Vector3().fromArray(rays.normal, 0);
    // three's Mesh gives the object-space normal: the world one through the model's transpose.
    const normal = worldNormal.clone().transformDirection(_m.copy(relief.matrixWorld).transpose());
    return {distance: rays.t[0], point: new THREE.Vector3().fromArray(rays.point, 0), uv: new THREE.Vector2().fromArray(rays.uv, 0),
            normal, worldNormal, kind: rays.kind[0], iterations: rays.iterations[0]};
}

// traceRays's arguments checked (3 n origins, 3 n directions, 2 or 2 n range values) and
// what traces them (`on`, one of `allowed`): a TypeError naming the wrong one.
export function checkRays(origins, directions, ranges, on, allowed) {
    const n = origins.length / 3;
    if (!Number.isInteger(n) || directions.length !== origins.length || (ranges.length !== 2 && ranges.length !== 2 * n))
        throw new TypeError('Relief.traceRays: 3 n origins, 3 n directions and 2 or 2 n range values');
    if (!allowed.includes(on)) throw new TypeError(`Relief.traceRays: on '${on}' (expected ${allowed.slice(0, -1).join(', ')} or ${allowed.at(-1)})`);
}

// World rays traced by the CPU twin (twin.js) through `relief`'s matrixWorld as it is now:
// traceRays's result, every value a double. Where the package has no twin (packed without
// emscripten) or it is not loaded yet, its one line (an Error).
export function traceRaysOnTwin(relief, origins, directions, ranges) {
    if (!twinLoaded()) throw new Error(twinUnavailable());
    relief.updateWorldMatrix(true, false);
    return traceOnTwin(relief, origins, directions, ranges);
}

const _m = new THREE.Matrix4(), _inverse = new THREE.Matrix4(), _ray = new THREE.Ray();
const _origin = new THREE.Vector3(), _fromOrigin = new THREE.Matrix4(), _toOrigin = new THREE.Matrix4();
