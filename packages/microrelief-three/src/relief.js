// relief.js: the relief as a three.js object. A Relief is a THREE.Mesh whose geometry is its
// proxy box (the relief's object-space bounds, a small margin added) and whose material
// traces the relief in every pixel the box covers. Its object space is microrelief's
// (docs/scene-and-cli.md): on the plane the map spans x in [-a/2, a/2], z in [-b/2, b/2],
// the longer side 1, heights y = s h; the curved bases are centred, their axis along y. Its
// matrixWorld is the library's model transform (any affine one).
//
// Per draw (onBeforeRender, and onBeforeShadow for three's shadow maps) it hands its
// materials the camera's rays (glsl/relief_three.glsl), which faces of the box run, the
// camera's matrices and the viewport. Raycaster hits (raycast, trace, traceRays) are traced by
// the library's CPU twin of that GLSL, in double, compiled to WebAssembly (twin.js), or by
// the GLSL itself on the GPU (pickWith), so a pick returns the point, uv and normal the pixel
// shows.
import * as THREE from 'three';

import {glue, library} from '../generated/glsl.js';
import * as core from '../generated/relief_core.js';
import {ReliefDepthMaterial, ReliefDistanceMaterial, ReliefPhysicalMaterial, ReliefShadingMaterial, ReliefStandardMaterial, reliefDefines} from './materials.js';
import {baseShape, boxFaces, cameraRays, checkBaseForMap, checkHeightScale, checkInterpolation, checkPixelError, checkRays, defineReliefOptions, raycastRelief, reliefExtent,
        reliefFrame, reliefMapUniforms, reliefUniforms, traceOne, traceRaysOnTwin, updateReliefBox} from './relief_host.js';
import {disposeOverrides, drawUnderOverride, restoreDrawRange} from './override.js';
import {kWebGPURendererUnsupported, requireSupportedThree} from './three_version.js';
import {twinLoaded} from './twin.js';

let pickResources = null;

// What a Relief draws with: a relief material, never three's own (whose shader does not
// trace): one line saying which to use instead.
function checkMaterial(material) {
    if (material && material.isReliefMaterial) return;
    const what = Array.isArray(material) ? 'an array of materials' : material && material.isMaterial ? `a ${material.type}` : String(material);
    const instead = material && material.isMeshPhysicalMaterial ? 'new ReliefPhysicalMaterial().copy(material)'
                                                                 : 'new ReliefStandardMaterial().copy(material)';
    throw new TypeError(`Relief: the material must be a ReliefStandardMaterial, ReliefPhysicalMaterial or ReliefShadingMaterial, not ${what}` +
                        (material && (material.isMeshStandardMaterial) ? ` (${instead} traces the relief with its parameters)` : ''));
}

// The relief material a material's three record stands for (Relief.fromMesh).
function reliefMaterialFrom(material, albedoMap) {
    const record = (material && material.userData && material.userData.microrelief) || {};
    if (record.type === 'ReliefShadingMaterial') {
        return new ReliefShadingMaterial({shadows: record.shadows, lightDirection: new THREE.Vector3().fromArray(record.lightDirection),
                                          albedo: new THREE.Color().fromArray(record.albedo), albedoMap});
    }
    const result = material && material.isMeshPhysicalMaterial ? new ReliefPhysicalMaterial() : new ReliefStandardMaterial();
    if (material && material.isMeshStandardMaterial) result.copy(material);
    result.selfShadow = !!record.selfShadow;
    result.albedoMap = albedoMap;
    delete result.userData.microrelief;
    return result;
}

// The WebGPURenderers told that a Relief does not draw in them (once each).
const _toldWebGPU = new WeakSet();
function warnWebGPURenderer(renderer) {
    if (_toldWebGPU.has(renderer)) return;
    _toldWebGPU.add(renderer);
    console.error(`Relief: ${kWebGPURendererUnsupported}`);
}

export {baseShape, cameraRays, reliefExtent};

export class Relief extends THREE.Mesh {
    // `reliefMap`: createReliefMap's. Options: material (a ReliefStandardMaterial,
    // ReliefPhysicalMaterial or ReliefShadingMaterial, which reliefs may share; a
    // ReliefStandardMaterial by default), heightScale (s, 0.1), base ('plane', 'cylinder',
    // 'sphere', 'ellipsoid', or {kind, radius, length, radii}), interpolation ('bilinear' or
    // 'biquadratic'), pixelError (level of detail in pixels; 0 is exact). Each option is a
    // property too, settable at any time (relief_host.js's defineReliefOptions, below): the box
    // is rebuilt and the materials' program variant switched where a change needs it.
    constructor(reliefMap, {material = null, heightScale = 0.1, base = 'plane', interpolation = 'bilinear', pixelError = 0} = {}) {
        requireSupportedThree();
        if (!reliefMap || !reliefMap.windows) throw new TypeError('Relief: the first argument must be a ReliefMap (createReliefMap)');
        checkHeightScale(heightScale);
        checkInterpolation(interpolation);
        checkPixelError(pixelError);
        const shape = baseShape(base);
        checkBaseForMap(shape, base, reliefMap);
        if (material !== null) checkMaterial(material);
        super(new THREE.BufferGeometry(), material ?? new ReliefStandardMaterial());
        this.isRelief = true;
        this.type = 'Relief';
        this.uniforms = reliefUniforms(pixelError);
        this.setReliefMap(reliefMap, shape, Math.fround(heightScale), interpolation);
        this.customDepthMaterial = new ReliefDepthMaterial(this);
        this.customDistanceMaterial = new ReliefDistanceMaterial(this);
        this.onBeforeRender = (renderer, scene, camera, geometry, material, group) => {
            // A WebGPURenderer draws the box with none of this: said once, in one line.
            if (renderer.isWebGPURenderer) return warnWebGPURenderer(renderer);
            this.prepareDraw(renderer, camera, true);
            // scene.overrideMaterial (normal, depth, distance): the traced surface (override.js).
            drawUnderOverride(this, renderer, scene, camera, geometry, material, group);
        };
        this.onAfterRender = (renderer, scene, camera, geometry) => restoreDrawRange(geometry);
        this.onBeforeShadow = (renderer, object, camera, shadowCamera) => this.prepareDraw(renderer, shadowCamera, false);
    }

    // The material three draws the box with: a relief material (one many reliefs may share),
    // never three's own, refused here in one line naming what to use.
    get material() {
        return this._material;
    }

    set material(material) {
        checkMaterial(material);
        this._material = material;
        if (material.relief === null) material.relief = this;  // renderer.compile's variant before a draw
    }

    get reliefMap() {
        return this._reliefMap;
    }

    // Another map for this relief (its wrapU must suit the base).
    set reliefMap(reliefMap) {
        if (!reliefMap || !reliefMap.windows) throw new TypeError('Relief: reliefMap must be a ReliefMap (createReliefMap)');
        this.setReliefMap(reliefMap, this._base, this.heightScale, this._interpolation);
    }

    setReliefMap(reliefMap, shape, heightScale, interpolation) {
        checkBaseForMap(shape, shape.kind, reliefMap);
        this._reliefMap = reliefMap;
        const u = this.uniforms;
        u.mrHeights.value = reliefMap.heights;
        u.mrWindows.value = reliefMap.windows;
        reliefMapUniforms(reliefMap, u);
        u.mrHeightScale.value = heightScale;
        this._base = Object.freeze(shape);
        u.mrFrameScale.value.set(...core.frameScale(shape));
        this._interpolation = interpolation;
        this.updateBox();
        this.shadowMaterialsNeedUpdate();
    }

    // The box (ReliefRenderer::uploadBox): the bounds from the pyramid's top, grown; a new
    // geometry (a clone's box is its own). relief_host.js: updateReliefBox, both entries'.
    updateBox() {
        updateReliefBox(this);
    }

    shadowMaterialsNeedUpdate() {
        if (this.customDepthMaterial) this.customDepthMaterial.needsUpdate = true;
        if (this.customDistanceMaterial) this.customDistanceMaterial.needsUpdate = true;
    }

    // The options, as the constructor takes them (the material shared).
    get options() {
        return {material: this.material, heightScale: this.heightScale, base: this._base, interpolation: this._interpolation, pixelError: this.pixelError};
    }

    // three's clone: the same ReliefMap and material (as a Mesh's clone shares its geometry
    // and material), its own box, uniforms and shadow materials; the same picture.
    clone(recursive) {
        return new this.constructor(this._reliefMap, this.options).copy(this, recursive);
    }

    copy(source, recursive) {
        const box = this.geometry;
        super.copy(source, recursive);  // Mesh: the transform, flags, userData and material (and the geometry: not the source's here)
        this.geometry = box;
        this.pixelError = source.pixelError;
        this.setReliefMap(source.reliefMap, source.base, source.heightScale, source.interpolation);
        return this;
    }

    // three's JSON cannot hold a relief: its heights and pyramid are GPU textures a ReliefMap
    // holds for one renderer, megabytes that a scene file should not carry. So toJSON writes
    // what ObjectLoader reads, a plain Mesh (the proxy box with its material's three record:
    // a MeshStandardMaterial or MeshPhysicalMaterial of the same parameters), and the relief's
    // options in userData.microrelief; Relief.fromMesh(mesh, reliefMap) makes the relief
    // again from ObjectLoader's Mesh and the map, loaded as it was the first time.
    toJSON(meta) {
        const data = super.toJSON(meta);
        data.object.type = 'Mesh';
        const base = {...this._base};
        data.object.userData = {...data.object.userData, microrelief: {
            heightScale: this.heightScale, base, interpolation: this.interpolation, pixelError: this.pixelError,
            map: {width: this._reliefMap.width, height: this._reliefMap.height, wrapU: this._reliefMap.wrapU},
        }};
        return data;
    }

    // The Relief a Relief's toJSON describes: `mesh` as ObjectLoader made it (its transform,
    // name, flags and userData kept), drawn with `reliefMap` and a relief material of the
    // recorded one's parameters; its albedoMap (a texture the app loads, as it loads the
    // heights: not in the JSON) given again here.
    static fromMesh(mesh, reliefMap, {albedoMap = null} = {}) {
        const record = mesh && mesh.userData && mesh.userData.microrelief;
        if (!record) throw new TypeError('Relief.fromMesh: the mesh has no userData.microrelief (not written by a Relief\'s toJSON)');
        const {width, height, wrapU} = record.map;
        if (reliefMap && (reliefMap.width !== width || reliefMap.height !== height || reliefMap.wrapU !== wrapU))
            throw new TypeError(`Relief.fromMesh: the relief was drawn with a ${width} x ${height} map${wrapU ? ' (wrapU)' : ''}, not this ${reliefMap.width} x ${reliefMap.height} one${reliefMap.wrapU ? ' (wrapU)' : ''}`);
        const relief = new this(reliefMap, {heightScale: record.heightScale, base: record.base, interpolation: record.interpolation,
                                            pixelError: record.pixelError, material: reliefMaterialFrom(mesh.material, albedoMap)});
        THREE.Object3D.prototype.copy.call(relief, mesh, false);
        delete relief.userData.microrelief;
        return relief;
    }

    // This draw's uniforms: the model, the camera's rays, which faces run, the viewport
    // (the view's camera; a shadow pass takes its NDC from the clip position instead).
    // Traced relative to the camera, as the library's renderer traces relative to the eye
    // (ReliefRenderer::parameters): the shader's world is three's moved by minus the
    // camera's position, each matrix that meets a world position composed with that move
    // here in double (JavaScript's numbers), so that a relief far from three's origin (a
    // planet, a large level) is traced as exactly as one at it; mrWorldOrigin gives three's
    // own world-space uniforms (shadow matrices) their world back.
    prepareDraw(renderer, camera, withViewport) {
        const u = this.uniforms;
        const rays = reliefFrame(this, camera, u);
        // The viewport GL rasterises this draw into (three's own record of it starts empty
        // until setSize, setViewport or setRenderTarget is called).
        if (withViewport) u.mrViewport.value.fromArray(renderer.getContext().getParameter(renderer.getContext().VIEWPORT));
        else u.mrViewport.value.set(0, 0, 0, 0);
        u.mrFaces.value = boxFaces(this.box, this.matrixWorld, camera, rays.range);
    }

    // Which faces of the box run for `camera` (relief_host.js: boxFaces).
    facesFor(camera, range) {
        return boxFaces(this.box, this.matrixWorld, camera, range);
    }

    // What traces the picks (raycast, trace, traceRays): 'auto' (the default: the CPU twin
    // where the package has it, generated/twin_wasm.js, else the GPU), 'cpu' (the twin;
    // refused in a package packed without emscripten) or 'gpu' (glsl/pick.frag: a draw and a
    // readback, which waits for the GPU's queue).
    get pickWith() {
        return this._pickWith ?? 'auto';
    }

    set pickWith(value) {
        if (!['auto', 'cpu', 'gpu'].includes(value)) throw new TypeError(`Relief: pickWith '${value}' (expected auto, cpu or gpu)`);
        this._pickWith = value;
    }

    // three's Raycaster: the relief's own hit (pickWith says what traces it): {distance,
    // point, uv (three's convention), normal (object space, as three's Mesh gives it),
    // worldNormal, object}.
    raycast(raycaster, intersects) {
        raycastRelief(this, raycaster, intersects);
    }

    // The first hit of the world ray origin + t direction (direction unit), t in [near, far]:
    // {distance, point, uv, normal, worldNormal, kind, iterations}, or null for a miss.
    // options.on: what traces it (pickWith's values; this.pickWith by default).
    trace(origin, direction, near = 0, far = Infinity, options = {}) {
        return traceOne(this, origin, direction, near, far, options);
    }

    // Many world rays at once: `origins` and `directions` are 3 n numbers, `ranges` 2 n (tMin,
    // tMax; t in units of each direction's length) or one pair for all. options.on: what
    // traces them ('auto', 'cpu' or 'gpu'; this.pickWith by default). Returns t, kind (0 a
    // miss, 1 the surface, 2 to 5 the box's walls, bottom or caps), exhausted, point (3 n,
    // world), normal (3 n, world unit), uv (2 n, three's convention), iterations, and on
    // ('cpu' or 'gpu': what traced them). The twin's values are its doubles; the GPU's
    // floats (its points about the first ray's origin, in double).
    traceRays(origins, directions, ranges = [0, Infinity], {on = this.pickWith} = {}) {
        checkRays(origins, directions, ranges, on, ['auto', 'cpu', 'gpu']);
        if (on === 'cpu' || (on === 'auto' && twinLoaded())) return traceRaysOnTwin(this, origins, directions, ranges);
        return this.traceRaysOnGpu(origins, directions, ranges);
    }

    // traceRays on the GPU (glsl/pick.frag).
    traceRaysOnGpu(origins, directions, ranges) {
        const n = origins.length / 3;
        const renderer = this.reliefMap.renderer;
        if (!pickResources) pickResources = makePickResources();
        const {scene, camera, material} = pickResources;
        const width = Math.min(n, 1024), rows = Math.ceil(n / width);
        const rayData = [new Float32Array(4 * width * rows), new Float32Array(4 * width * rows)];
        // Relative to the first ray's origin, in double, as prepareDraw traces relative to
        // the camera: the origins and the hits are floats about it, put back here.
        const base = [origins[0] ?? 0, origins[1] ?? 0, origins[2] ?? 0];
        for (let k = 0; k < n; ++k) {
            const range = ranges.length === 2 ? ranges : ranges.slice(2 * k, 2 * k + 2);
            rayData[0].set([origins[3 * k] - base[0], origins[3 * k + 1] - base[1], origins[3 * k + 2] - base[2], range[0]], 4 * k);
            rayData[1].set([directions[3 * k], directions[3 * k + 1], directions[3 * k + 2], Math.min(range[1], 3.4e38)], 4 * k);
        }
        const textures = rayData.map((data) => {
            const texture = new THREE.DataTexture(data, width, rows, THREE.RGBAFormat, THREE.FloatType);
            texture.needsUpdate = true;
            return texture;
        });
        const target = new THREE.WebGLRenderTarget(width, 12 * rows, {depthBuffer: false, generateMipmaps: false});
        this.updateWorldMatrix(true, false);
        const u = material.uniforms;
        Object.assign(u, this.uniforms);
        u.mrObjectToWorld = {value: new THREE.Matrix4().makeTranslation(-base[0], -base[1], -base[2]).multiply(this.matrixWorld)};
        u.mrWorldToObject = {value: this.matrixWorld.clone().invert().multiply(new THREE.Matrix4().makeTranslation(...base))};
        u.mrRayOrigins = {value: textures[0]};
        u.mrRayDirections = {value: textures[1]};
        u.mrRayRows = {value: rows};
        const key = `${this.base.kind}:${this.interpolation}`;
        if (material.userData.key !== key) {
            material.defines = reliefDefines(this);
            material.userData.key = key;
            material.needsUpdate = true;
        }
        const previous = [renderer.getRenderTarget(), renderer.getActiveCubeFace(), renderer.getActiveMipmapLevel()];
        const bytes = new Uint8Array(4 * width * 12 * rows);
        try {
            renderer.setRenderTarget(target);
            renderer.render(scene, camera);
            renderer.readRenderTargetPixels(target, 0, 0, width, 12 * rows, bytes);
        } finally {
            renderer.setRenderTarget(...previous);
            target.dispose();
            for (const t of textures) t.dispose();
        }
        const all = new Float32Array(bytes.buffer);
        const field = (k) => all.subarray(k * width * rows, k * width * rows + n);
        const interleave = (fields) => {
            const out = new Float32Array(fields.length * n);
            fields.forEach((f, c) => field(f).forEach((v, k) => (out[fields.length * k + c] = v)));
            return out;
        };
        const point = interleave([3, 4, 5]);
        const world = new Float64Array(3 * n);
        for (let k = 0; k < 3 * n; ++k) world[k] = point[k] + base[k % 3];
        return {t: Float64Array.from(field(0)), kind: field(1).slice(), exhausted: field(2).slice(), point: world,
                normal: Float64Array.from(interleave([6, 7, 8])), uv: Float64Array.from(interleave([9, 10])), iterations: field(11).slice(), on: 'gpu'};
    }

    dispose() {
        this.geometry.dispose();
        this.customDepthMaterial.dispose();
        this.customDistanceMaterial.dispose();
        disposeOverrides(this);
    }

    // heightScale, pixelError, interpolation and base as properties: relief_host.js's, both
    // entries' (a new variant: the shadow materials' programs made again).
    static {
        defineReliefOptions(this.prototype, {shapeOf: baseShape, variantChanged: (relief) => relief.shadowMaterialsNeedUpdate()});
    }
}


// A full-viewport triangle tracing a batch of rays (glsl/pick.frag), shared by all reliefs.
function makePickResources() {
    const material = new THREE.ShaderMaterial({
        glslVersion: THREE.GLSL3,
        vertexShader: 'void main() { vec2 c = vec2(float((gl_VertexID & 1) << 2), float((gl_VertexID & 2) << 1)); gl_Position = vec4(c - 1.0, 0.0, 1.0); }',
        fragmentShader: library + glue.reliefThree.replace('varying vec4 mrClip;', 'vec4 mrClip;') + glue.pick,
        uniforms: {},
        depthTest: false,
        depthWrite: false,
    });
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(9), 3));
    const mesh = new THREE.Mesh(geometry, material);
    mesh.frustumCulled = false;
    // A camera three can turn to reversed depth (reversedDepthBuffer: THREE.Camera has no
    // updateProjectionMatrix); the vertex shader ignores it.
    return {scene: mesh, camera: new THREE.OrthographicCamera(), material};
}
