// Declarations of relief.js (hand-written; tests/three's typecheck holds them to the module).
import type {Box3, BufferGeometry, Camera, IUniform, Intersection, JSONMeta, Mesh, MeshJSON, Raycaster, Texture, Vector2, Vector3, WebGLRenderer} from 'three';

import type {ReliefDepthMaterial, ReliefDistanceMaterial, ReliefPhysicalMaterial, ReliefShadingMaterial, ReliefStandardMaterial} from './materials.js';
import type {ReliefMap} from './pyramid.js';

type Triple = [number, number, number];

/** A base surface as asked for: a name takes microrelief-render's sizes (cylinder radius 0.3, length 1; sphere radius 0.5). */
export type BaseSpec =
    | 'plane' | 'cylinder' | 'sphere' | 'ellipsoid'
    | {kind: 'plane'}
    | {kind: 'cylinder'; radius?: number; length?: number}
    | {kind: 'sphere'; radius?: number}
    | {kind: 'ellipsoid'; radii?: Triple};

/** A base surface with its sizes (a sphere is an ellipsoid of equal radii). */
export type BaseShape = {kind: 'plane'} | {kind: 'cylinder'; radius: number; length: number} | {kind: 'ellipsoid'; radii: Triple};

export function baseShape(base?: BaseSpec): BaseShape;

/** The relief's object-space bounds for a top of `maxHeight`. */
export function reliefExtent(width: number, height: number, maxHeight: number, heightScale: number, base: BaseShape): {min: Triple; max: Triple};

/** A camera's rays as affine functions of the pixel's NDC, computed in double. */
export interface CameraRays {
    perspective: boolean;
    origin: Vector3;
    originDx: Vector3;
    originDy: Vector3;
    dir: Vector3;
    dirDx: Vector3;
    dirDy: Vector3;
    range: [number, number];
}

export function cameraRays(camera: Camera): CameraRays;

export type ReliefInterpolation = 'bilinear' | 'biquadratic';

export type ReliefMaterial = ReliefStandardMaterial | ReliefPhysicalMaterial | ReliefShadingMaterial;

export interface ReliefOptions<TMaterial extends ReliefMaterial = ReliefMaterial> {
    /** A relief material, which reliefs may share; a ReliefStandardMaterial by default. three's own materials are refused (copy them into a relief material). */
    material?: TMaterial | null;
    /** s: heights from 0 to s times the map's values. Default 0.1. */
    heightScale?: number;
    /** Default 'plane'. A curved base needs a map made with wrapU: true. */
    base?: BaseSpec;
    /** The finest level's surface. Default 'bilinear'. */
    interpolation?: ReliefInterpolation;
    /** The level of detail in pixels; 0 (the default) is exact. */
    pixelError?: number;
}

/** The hit a pixel shows. */
export interface ReliefHit {
    distance: number;
    point: Vector3;
    /** three's convention: row 0 of the image at uv.y = 1. */
    uv: Vector2;
    /** Object space, as three's Mesh gives it. */
    normal: Vector3;
    worldNormal: Vector3;
    /** 1 the surface, 2 to 5 the box's walls, bottom or caps. */
    kind: number;
    iterations: number;
}

/** What traces the picks: 'auto' (the CPU twin in WebAssembly where the package has it, else the GPU), 'cpu' or 'gpu'. */
export type PickWith = 'auto' | 'cpu' | 'gpu';

export interface TraceOptions {
    /** What traces the rays; the relief's pickWith by default. */
    on?: PickWith;
}

/** Many rays' hits: n values each (point and normal 3 n, uv 2 n); kind 0 is a miss. */
export interface TracedRays {
    t: Float64Array;
    kind: Float32Array;
    exhausted: Float32Array;
    point: Float64Array;
    normal: Float64Array;
    uv: Float64Array;
    iterations: Float32Array;
    /** What traced them: the CPU twin (its doubles) or the GPU (its floats). */
    on: 'cpu' | 'gpu';
}

/** The relief: a THREE.Mesh (its proxy box) whose material traces the height map in every pixel. */
export class Relief<TMaterial extends ReliefMaterial = ReliefMaterial> extends Mesh<BufferGeometry, TMaterial> {
    constructor(reliefMap: ReliefMap, options?: ReliefOptions<TMaterial>);
    readonly isRelief: true;
    /** Settable at any time (its wrapU must suit the base). */
    reliefMap: ReliefMap;
    /** The base's shape; set it as the constructor's option at any time (held to the map's wrapU). */
    get base(): BaseShape;
    set base(value: BaseSpec);
    /** Settable at any time, as every option: the box is rebuilt, the program variant switched at the next render. */
    interpolation: ReliefInterpolation;
    heightScale: number;
    pixelError: number;
    /** The options as the constructor takes them (the material the same object). */
    readonly options: Required<ReliefOptions<TMaterial>> & {base: BaseShape; material: TMaterial};
    /** The same map and material, its own box, uniforms and shadow materials. */
    clone(recursive?: boolean): this;
    copy(source: Relief<TMaterial>, recursive?: boolean): this;
    /** A plain Mesh record (ObjectLoader reads it) with the options in userData.microrelief: the heights are not in it. */
    toJSON(meta?: JSONMeta): MeshJSON;
    /** The Relief a Relief's toJSON describes, from ObjectLoader's Mesh and the map (and the albedoMap, also not in the JSON). */
    static fromMesh(mesh: Mesh, reliefMap: ReliefMap, options?: {albedoMap?: Texture | null}): Relief;
    /** The proxy box, object space. */
    box: Box3;
    uniforms: Record<string, IUniform>;
    customDepthMaterial: ReliefDepthMaterial;
    customDistanceMaterial: ReliefDistanceMaterial;
    /** This draw's uniforms (called before each draw). */
    prepareDraw(renderer: WebGLRenderer, camera: Camera, withViewport: boolean): void;
    /** Which faces of the box run for `camera` (1 front, 2 back, 3 both). */
    facesFor(camera: Camera, range: [number, number]): number;
    /** What traces raycast, trace and traceRays: 'auto' (the default), 'cpu' (refused in a package packed without emscripten) or 'gpu'. */
    pickWith: PickWith;
    raycast(raycaster: Raycaster, intersects: Intersection[]): void;
    /** The first hit of the world ray origin + t direction, t in [near, far], or null. */
    trace(origin: Vector3, direction: Vector3, near?: number, far?: number, options?: TraceOptions): ReliefHit | null;
    /** Many world rays at once: 3 n origins, 3 n directions, 2 or 2 n range values. */
    traceRays(origins: ArrayLike<number>, directions: ArrayLike<number>, ranges?: ArrayLike<number>, options?: TraceOptions): TracedRays;
    /** traceRays on the GPU (glsl/pick.frag). */
    traceRaysOnGpu(origins: ArrayLike<number>, directions: ArrayLike<number>, ranges: ArrayLike<number>): TracedRays;
    dispose(): void;
}
