// Declarations of webgpu.js, the entry 'microrelief-three/webgpu' (hand-written; tests/three's
// typecheck uses them under tsc --strict). docs/three.md: the API.
import type {BufferGeometry, Box3, Color, DataTexture, Intersection, Mesh, MeshBasicNodeMaterial, MeshStandardNodeMaterial, MeshStandardNodeMaterialParameters, Raycaster, Texture,
             UniformNode, Vector3, WebGPURenderer} from 'three/webgpu';

import type {HeightMap} from './heights.js';
import type {BaseShape, BaseSpec, ReliefHit, ReliefInterpolation, TracedRays} from './relief.js';

export {albedoFromBytes, loadAlbedo} from './albedo.js';
export {HeightMapError, heightsFromArray, heightsFromBytes, heightsFromImage, heightsFromPng, kMaxMapSide, loadHeights} from './heights.js';
export type {HeightMap, HeightsOptions, PngHeightsOptions} from './heights.js';
export {baseShape, cameraRays, reliefExtent} from './relief.js';
export type {BaseShape, BaseSpec, CameraRays, ReliefHit, ReliefInterpolation, TracedRays} from './relief.js';

/** The bases this entry draws: plane, cylinder, ellipsoid. */
export const kWebGPUBases: readonly string[];

/** The one line a WebGLRenderer gets from this entry. */
export const kWebGLRendererHere: string;

/** A WebGPU that cannot do what was asked (no adapter, a map past the device's limits). */
export class ReliefGpuError extends Error {
    constructor(message: string);
    name: 'ReliefGpuError';
}

/** The top-level items of a naga WGSL module. */
export function wgslItems(module: string): Array<{name: string; text: string}>;
/** The items of a WGSL module that `roots` reach, in the module's order. */
export function reachableWgsl(module: string, roots: readonly string[]): string;

export interface WebGPUReliefMapOptions {
    /** true for the curved bases (cylinder, sphere, ellipsoid): u wraps round. Default false. */
    wrapU?: boolean;
}

/** A height map's textures for a WebGPURenderer, the pyramid built in WebAssembly. */
export class ReliefMap {
    renderer: WebGPURenderer;
    heights: DataTexture;
    windows: DataTexture;
    width: number;
    height: number;
    levelSizes: Array<[number, number]>;
    levelCount: number;
    maxHeight: number;
    maxSample: number;
    scaleExponent: number;
    wrapU: boolean;
    builtOn: 'cpu';
    name: string;
    readonly gpuBytes: number;
    /** WebAssembly memory of the picks' CPU twins, bytes (0 before the first pick; freed by dispose). */
    readonly twinBytes: number;
    dispose(): void;
}

/** The textures of `map` for `renderer` (awaits its init); refuses a WebGLRenderer and a WebGPURenderer without a WebGPU adapter. */
export function createReliefMap(renderer: WebGPURenderer, map: HeightMap, options?: WebGPUReliefMapOptions): Promise<ReliefMap>;

export interface ReliefShadingNodeParameters {
    /** Towards the light, world. */
    lightDirection?: Vector3;
    /** The map's colours (loadAlbedo's texture: flipY false, sRGB, mipmapped); null: `albedo`. */
    albedoMap?: Texture | null;
    /** Linear. */
    albedo?: Color;
    /** Default 'off'. */
    shadows?: 'off' | 'hard';
}

/** The library's own shading as a node material (one relief a material so far). */
export class ReliefShadingNodeMaterial extends MeshBasicNodeMaterial {
    constructor(parameters?: ReliefShadingNodeParameters);
    readonly isReliefMaterial: true;
    relief: Relief | null;
    shadows: 'off' | 'hard';
    lightDirection: UniformNode<Vector3>;
    albedo: UniformNode<Color>;
    albedoMap: Texture | null;
}

export interface ReliefStandardNodeParameters extends MeshStandardNodeMaterialParameters {
    /** The map's colours, multiplying `color` (loadAlbedo's texture: flipY false, sRGB, mipmapped). */
    albedoMap?: Texture | null;
    /** The library's exact hard shadow of the relief on itself towards each directional, point and spot light (default false). */
    selfShadow?: boolean;
}

/** three's MeshStandardNodeMaterial at the traced hit: three's lights, as the WebGL entry's ReliefStandardMaterial (one relief a material so far; it casts into three's shadow maps and receives them, as the WebGL entry's). */
export class ReliefStandardNodeMaterial extends MeshStandardNodeMaterial {
    constructor(parameters?: ReliefStandardNodeParameters);
    readonly isReliefMaterial: true;
    relief: Relief | null;
    albedoMap: Texture | null;
    /** Settable at any time: the material's program is made again. */
    selfShadow: boolean;
}

export interface WebGPUReliefOptions {
    material?: ReliefShadingNodeMaterial | ReliefStandardNodeMaterial | null;
    /** Default 0.1. */
    heightScale?: number;
    /** Default 'plane'. A curved base needs a map made with wrapU: true. */
    base?: BaseSpec;
    /** Default 'bilinear'. */
    interpolation?: ReliefInterpolation;
    /** Level of detail in pixels; 0 (the default) is exact. */
    pixelError?: number;
}

/** The relief as a three.js Mesh for a WebGPURenderer: its proxy box, traced per pixel. */
export class Relief extends Mesh<BufferGeometry, ReliefShadingNodeMaterial | ReliefStandardNodeMaterial> {
    constructor(reliefMap: ReliefMap, options?: WebGPUReliefOptions);
    readonly isRelief: true;
    /** Each option is a property too, settable at any time. */
    reliefMap: ReliefMap;
    get base(): BaseShape;
    set base(value: BaseSpec);
    interpolation: ReliefInterpolation;
    heightScale: number;
    pixelError: number;
    box: Box3;
    /** three's Raycaster calls it: the relief's own hit (ReliefHit's fields and `object`), traced by the CPU twin as in the WebGL entry. */
    raycast(raycaster: Raycaster, intersects: Intersection[]): void;
    /** The first hit of the world ray origin + t direction, t in [near, far]; null for a miss. */
    trace(origin: Vector3, direction: Vector3, near?: number, far?: number, options?: WebGPUTraceOptions): ReliefHit | null;
    /** Many world rays at once (3 n origins and directions, 2 or 2 n range values), traced by the CPU twin. */
    traceRays(origins: ArrayLike<number>, directions: ArrayLike<number>, ranges?: ArrayLike<number>, options?: WebGPUTraceOptions): TracedRays;
    dispose(): void;
}

export interface WebGPUTraceOptions {
    /** The CPU twin traces this entry's picks (no GPU picks here). Default 'auto'. */
    on?: 'auto' | 'cpu';
}
