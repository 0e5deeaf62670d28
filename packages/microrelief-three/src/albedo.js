// albedo.js: the map's colours as relief.frag samples them (AlbedoTexture): sRGB, 8 bits,
// mipmapped, repeating, row 0 of the image at the map's row 0 (v = 0; flipY false). A PNG is
// decoded by the project's own decoder (generated/png.js): its bytes as they are, no
// colour management; other formats through the browser (createImageBitmap, its colour
// conversion off).
import * as THREE from 'three';

import {decodePng, PngError} from '../generated/png.js';
import {HeightMapError, isPng} from './heights.js';

function albedoTexture(image) {
    const texture = image.data
        ? new THREE.DataTexture(image.data, image.width, image.height, THREE.RGBAFormat, THREE.UnsignedByteType)
        : new THREE.Texture(image);
    texture.colorSpace = THREE.SRGBColorSpace;
    texture.flipY = false;
    texture.wrapS = texture.wrapT = THREE.RepeatWrapping;
    texture.minFilter = THREE.LinearMipmapLinearFilter;
    texture.magFilter = THREE.LinearFilter;
    texture.generateMipmaps = true;
    texture.needsUpdate = true;
    return texture;
}

// An albedo texture from a file's bytes (Uint8Array); `name` names it in errors.
export async function albedoFromBytes(bytes, {name = 'albedo'} = {}) {
    if (isPng(bytes)) {
        let png;
        try {
            png = await decodePng(bytes);
        } catch (e) {
            if (e instanceof PngError) throw new HeightMapError(`${name}: ${e.message}`);
            throw e;
        }
        if (png.bitDepth !== 8) throw new HeightMapError(`${name}: albedos are 8-bit (this PNG has 16 bits a channel)`);
        const count = png.width * png.height, rgba = new Uint8Array(4 * count), used = Math.min(png.channels, 4);
        for (let p = 0; p < count; ++p) {
            for (let c = 0; c < 3; ++c) rgba[4 * p + c] = png.values[p * png.channels + (used < 3 ? 0 : c)];
            rgba[4 * p + 3] = 255;
        }
        return albedoTexture({data: rgba, width: png.width, height: png.height});
    }
    try {
        return albedoTexture(await createImageBitmap(new Blob([bytes]), {colorSpaceConversion: 'none', premultiplyAlpha: 'none'}));
    } catch {
        throw new HeightMapError(`${name}: not a PNG, nor an image this browser decodes`);
    }
}

// An albedo texture from a URL.
export async function loadAlbedo(url) {
    let response;
    try {
        response = await fetch(url);
    } catch (e) {
        throw new HeightMapError(`${url}: cannot be read (${e.message})`);
    }
    if (!response.ok) throw new HeightMapError(`${url}: cannot be read (HTTP ${response.status})`);
    return albedoFromBytes(new Uint8Array(await response.arrayBuffer()), {name: String(url)});
}
