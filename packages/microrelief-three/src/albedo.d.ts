// Declarations of albedo.js (hand-written; tests/three's typecheck holds them to the module).
import type {Texture} from 'three';

/** The map's colours as the library samples them (sRGB, mipmapped, repeating, flipY false) from a file's bytes. */
export function albedoFromBytes(bytes: Uint8Array, options?: {name?: string}): Promise<Texture>;

/** The same from a URL. */
export function loadAlbedo(url: string | URL): Promise<Texture>;
