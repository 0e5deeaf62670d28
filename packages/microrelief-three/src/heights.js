// heights.js: height maps into the samples microrelief-render reads (docs/engine.md,
// "Building on the host": heightMapFromSamples and loadHeightMap), as
// {width, height, samples: Float32Array (row 0 first, v = 0), name}:
//  * from a PNG file's bytes, decoded by the project's own decoder (generated/png.js, the
//    web page's web/png.js): a browser decodes images to 8 bits a channel, so a 16-bit map
//    would lose its low byte; the samples are loadHeightMap's exactly (channel 0, v * float(1 /
//    65535) or v * float(1 / 255));
//  * from any image the browser decodes (JPEG, WebP, an <img>, a canvas, an ImageBitmap):
//    8 bits, channel 0 (red), v * float(1 / 255);
//  * from a typed array and its size: Float32Array as it is, Uint16Array by 65535 and
//    Uint8Array by 255, as heightMapFromSamples does.
// Every sample must be finite and >= 0 and each side at most 16384 (the C++ loader's
// limits); anything else is one HeightMapError naming the source.
import {decodePng, heightsFromPng as pngHeights, PngError} from '../generated/png.js';

export const kMaxMapSide = 16384;

// A height map that cannot be used: one line saying which and why.
export class HeightMapError extends Error {
    constructor(message) {
        super(message);
        this.name = 'HeightMapError';
    }
}

const kPngSignature = [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a];

function checkSize(width, height, name) {
    if (!Number.isInteger(width) || !Number.isInteger(height) || width < 1 || height < 1)
        throw new HeightMapError(`${name}: the height map has no samples (${width} x ${height})`);
    if (width > kMaxMapSide || height > kMaxMapSide)
        throw new HeightMapError(`${name}: ${width} x ${height} is larger than the ${kMaxMapSide} x ${kMaxMapSide} a height map may have`);
}

// The checks of prepareHeights (src/core/heightmap/HeightMap.cpp), in its words.
function checkSamples(samples, width, name) {
    for (let k = 0; k < samples.length; ++k) {
        const h = samples[k];
        if (Number.isFinite(h) && h >= 0) continue;
        const advice = Number.isFinite(h) ? 'rescale the map to [0, 1]' : 'repair the map first';
        throw new HeightMapError(`${name}: sample (${k % width}, ${Math.floor(k / width)}) is ${h}; heights must be finite and >= 0 (${advice})`);
    }
}

// A map from `array` (width x height values, row 0 first): Float32Array, Uint16Array (/ 65535)
// or Uint8Array (/ 255).
export function heightsFromArray(array, width, height, {name = 'samples'} = {}) {
    checkSize(width, height, name);
    const count = width * height;
    if (!array || typeof array.length !== 'number' || array.length !== count)
        throw new HeightMapError(`${name}: expected ${count} samples for ${width} x ${height}, got ${array ? array.length : 'none'}`);
    let samples;
    if (array instanceof Float32Array) {
        samples = Float32Array.from(array);
    } else if (array instanceof Uint16Array || array instanceof Uint8Array) {
        const scale = Math.fround(1 / (array instanceof Uint16Array ? 65535 : 255));
        samples = new Float32Array(count);
        for (let k = 0; k < count; ++k) samples[k] = array[k] * scale;
    } else {
        throw new HeightMapError(`${name}: samples must be a Float32Array, Uint16Array or Uint8Array`);
    }
    checkSamples(samples, width, name);
    return {width, height, samples, name};
}

export function isPng(bytes) {
    return bytes.length >= 8 && kPngSignature.every((b, k) => bytes[k] === b);
}

// A map from a PNG file's bytes (Uint8Array), 8 or 16 bits, exactly as loadHeightMap reads it.
export async function heightsFromPng(bytes, {name = 'height map', channel = 0} = {}) {
    try {
        const png = await decodePng(bytes);
        const samples = pngHeights(png, channel);
        checkSamples(samples, png.width, name);
        return {width: png.width, height: png.height, samples, name};
    } catch (e) {
        if (e instanceof PngError) throw new HeightMapError(`${name}: ${e.message}`);
        throw e;
    }
}

// A map from an image the browser has decoded (HTMLImageElement, HTMLCanvasElement,
// ImageBitmap, OffscreenCanvas, ImageData): 8 bits, its red channel.
export function heightsFromImage(image, {name = 'image'} = {}) {
    let data, width, height;
    if (typeof ImageData !== 'undefined' && image instanceof ImageData) {
        ({data, width, height} = image);
    } else {
        width = image.naturalWidth || image.videoWidth || image.width;
        height = image.naturalHeight || image.videoHeight || image.height;
        checkSize(width, height, name);
        const canvas = typeof OffscreenCanvas !== 'undefined' ? new OffscreenCanvas(width, height) : Object.assign(document.createElement('canvas'), {width, height});
        const context = canvas.getContext('2d', {willReadFrequently: true});
        context.drawImage(image, 0, 0);
        data = context.getImageData(0, 0, width, height).data;
    }
    checkSize(width, height, name);
    const scale = Math.fround(1 / 255);
    const samples = new Float32Array(width * height);
    for (let k = 0; k < samples.length; ++k) samples[k] = data[4 * k] * scale;
    return {width, height, samples, name};
}

// A map from a URL: a PNG through the exact decoder, anything else through the browser.
export async function loadHeights(url, {channel = 0} = {}) {
    const name = String(url);
    let response;
    try {
        response = await fetch(url);
    } catch (e) {
        throw new HeightMapError(`${name}: cannot be read (${e.message})`);
    }
    if (!response.ok) throw new HeightMapError(`${name}: cannot be read (HTTP ${response.status})`);
    const bytes = new Uint8Array(await response.arrayBuffer());
    return heightsFromBytes(bytes, {name, channel});
}

// A map from a file's bytes: PNG exactly, other formats through createImageBitmap.
export async function heightsFromBytes(bytes, {name = 'height map', channel = 0} = {}) {
    if (isPng(bytes)) return heightsFromPng(bytes, {name, channel});
    let bitmap;
    try {
        bitmap = await createImageBitmap(new Blob([bytes]), {colorSpaceConversion: 'none', premultiplyAlpha: 'none'});
    } catch {
        throw new HeightMapError(`${name}: not a PNG, nor an image this browser decodes`);
    }
    try {
        if (channel !== 0) throw new HeightMapError(`${name}: only PNG maps are read from a channel other than 0`);
        return heightsFromImage(bitmap, {name});
    } finally {
        bitmap.close();
    }
}
