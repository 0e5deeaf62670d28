// Declarations of heights.js (hand-written; tests/three's typecheck holds them to the module).

/** A height map as microrelief-render reads it: row 0 first (v = 0), every sample finite and >= 0. */
export interface HeightMap {
    width: number;
    height: number;
    samples: Float32Array;
    /** Names the map in errors. */
    name: string;
}

/** The most samples a side of a height map may have (16384, the C++ loader's limit). */
export const kMaxMapSide: number;

/** A height map that cannot be used: one line saying which and why. */
export class HeightMapError extends Error {
    constructor(message: string);
    name: 'HeightMapError';
}

export interface HeightsOptions {
    /** Names the map in errors. */
    name?: string;
}

export interface PngHeightsOptions extends HeightsOptions {
    /** The PNG channel the heights are read from (0: red or grey). */
    channel?: number;
}

/** A map from `width` x `height` values, row 0 first: Float32Array as it is, Uint16Array / 65535, Uint8Array / 255. */
export function heightsFromArray(array: Float32Array | Uint16Array | Uint8Array, width: number, height: number, options?: HeightsOptions): HeightMap;

/** A map from a PNG file's bytes, 8 or 16 bits, decoded exactly. */
export function heightsFromPng(bytes: Uint8Array, options?: PngHeightsOptions): Promise<HeightMap>;

/** A map from an image the browser has decoded: 8 bits, its red channel. */
export function heightsFromImage(image: HTMLImageElement | HTMLCanvasElement | HTMLVideoElement | ImageBitmap | OffscreenCanvas | ImageData, options?: HeightsOptions): HeightMap;

/** A map from a file's bytes: a PNG exactly, other formats through createImageBitmap (8 bits, red). */
export function heightsFromBytes(bytes: Uint8Array, options?: PngHeightsOptions): Promise<HeightMap>;

/** A map from a URL: a PNG through the exact decoder (16 bits kept), anything else through the browser. */
export function loadHeights(url: string | URL, options?: {channel?: number}): Promise<HeightMap>;
