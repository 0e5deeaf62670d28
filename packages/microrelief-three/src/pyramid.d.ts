// Declarations of pyramid.js (hand-written; tests/three's typecheck holds them to the module).
import type {DataTexture, Texture, WebGLRenderer} from 'three';

import type {HeightMap} from './heights.js';

/** A WebGL that cannot do what was asked (an extension missing, a texture too large). */
export class ReliefGpuError extends Error {
    constructor(message: string);
    name: 'ReliefGpuError';
}

/** GL's mip sizes of width x height down to 1 x 1. */
export function windowLevelSizes(width: number, height: number): Array<[number, number]>;

/** Where the windows pyramid is built: the GPU where it renders into R16F, else WebAssembly ('auto'). */
export type PyramidBuilder = 'auto' | 'gpu' | 'cpu';

export interface ReliefMapOptions {
    /** true for the curved bases (cylinder, sphere, ellipsoid): u wraps round. Default false. */
    wrapU?: boolean;
    /** Default 'auto'. */
    pyramid?: PyramidBuilder;
}

/** What a ReliefMap is made of (createReliefMap makes them). */
export interface ReliefMapParts {
    renderer: WebGLRenderer;
    heights: DataTexture;
    windows: DataTexture;
    width: number;
    height: number;
    levelSizes: Array<[number, number]>;
    maxHeight: number;
    maxSample: number;
    scaleExponent: number;
    wrapU: boolean;
    builtOn: 'gpu' | 'cpu';
    name: string;
}

/** A height map's textures for one renderer: the samples (R32F) and the windows pyramid (R16F, a full mip chain). */
export class ReliefMap implements ReliefMapParts {
    constructor(parts: ReliefMapParts);
    renderer: WebGLRenderer;
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
    builtOn: 'gpu' | 'cpu';
    name: string;
    /** GPU memory of the textures, bytes. */
    readonly gpuBytes: number;
    /** WebAssembly memory of the picks' CPU twins, bytes (0 before the first pick; freed by dispose). */
    readonly twinBytes: number;
    dispose(): void;
}

/** The textures of `map` for `renderer`. Rejects with ReliefGpuError or HeightMapError, one line each. */
export function createReliefMap(renderer: WebGLRenderer, map: Pick<HeightMap, 'width' | 'height' | 'samples'> & {name?: string}, options?: ReliefMapOptions): Promise<ReliefMap>;

/** The red channel of a float texture's level as floats, read back exactly (for tests and tools). */
export function readTextureFloats(renderer: WebGLRenderer, texture: Texture, level: number, width: number, height: number): Float32Array;

/** The texels of a ReliefMap's windows level `level` (bounds / 2^scaleExponent). */
export function readWindowLevel(reliefMap: ReliefMap, level: number): Float32Array;
