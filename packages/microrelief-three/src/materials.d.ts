// Declarations of materials.js (hand-written; tests/three's typecheck holds them to the module).
import type {Color, MeshDepthMaterial, MeshDistanceMaterial, MeshPhysicalMaterial, MeshPhysicalMaterialParameters, MeshStandardMaterial,
             MeshStandardMaterialParameters, ShaderMaterial, Texture, Vector3} from 'three';

import type {Relief} from './relief.js';

/** A three.js fragment shader made to trace the relief before it shades. */
export function patchFragment(fragmentShader: string): string;

/** The box's vertex shader, with its clip position passed on. */
export function patchVertex(vertexShader: string): string;

/** The two parameters the relief's three-lit materials add to three's. */
export interface ReliefMaterialParameters {
    /** The map's colours (loadAlbedo), filtered over the pixel's footprint. */
    albedoMap?: Texture | null;
    /** The library's exact hard shadow of the relief on itself, towards each directional, point and spot light. */
    selfShadow?: boolean;
}

/** three's MeshStandardMaterial on a Relief: every parameter it takes, sampled at the traced hit. */
export class ReliefStandardMaterial extends MeshStandardMaterial {
    constructor(parameters?: MeshStandardMaterialParameters & ReliefMaterialParameters);
    readonly isReliefMaterial: true;
    /** The Relief it draws next: the last one drawn with it, or the first given it (reliefs may share it). */
    relief: Relief | null;
    albedoMap: Texture | null;
    selfShadow: boolean;
    /** Also from three's own MeshStandardMaterial: the way to give a Relief one. */
    copy(source: MeshStandardMaterial): this;
}

/** three's MeshPhysicalMaterial on a Relief. */
export class ReliefPhysicalMaterial extends MeshPhysicalMaterial {
    constructor(parameters?: MeshPhysicalMaterialParameters & ReliefMaterialParameters);
    readonly isReliefMaterial: true;
    relief: Relief | null;
    albedoMap: Texture | null;
    selfShadow: boolean;
    /** Also from three's own MeshPhysicalMaterial. */
    copy(source: MeshPhysicalMaterial): this;
}

/** The relief's depth from a light's camera for directional and spot lights' shadow maps (Relief sets it). */
export class ReliefDepthMaterial extends MeshDepthMaterial {
    constructor(relief: Relief);
    relief: Relief;
}

/** The same for point lights' shadow maps. */
export class ReliefDistanceMaterial extends MeshDistanceMaterial {
    constructor(relief: Relief);
    relief: Relief;
}

export interface ReliefShadingParameters {
    /** World, towards the light. */
    lightDirection?: Vector3;
    albedoMap?: Texture | null;
    /** The colour where there is no albedoMap, linear. */
    albedo?: Color;
    /** 'hard': the library's exact shadow. Default 'off'. */
    shadows?: 'off' | 'hard';
}

/** The library's own shading (microrelief-render's picture): one directional light, not three's lights. */
export class ReliefShadingMaterial extends ShaderMaterial {
    constructor(parameters?: ReliefShadingParameters);
    readonly isReliefMaterial: true;
    relief: Relief | null;
    shadows: 'off' | 'hard';
}
