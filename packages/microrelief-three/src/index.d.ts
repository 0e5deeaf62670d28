// Declarations of microrelief-three (hand-written, one file beside each module; tests/three's
// typecheck holds them to what index.js exports, under tsc --strict). docs/three.md: the API.
import type {WebGLRenderer} from 'three';

import type {ReliefMap, ReliefMapOptions} from './pyramid.js';

export {HeightMapError, heightsFromArray, heightsFromBytes, heightsFromImage, heightsFromPng, kMaxMapSide, loadHeights} from './heights.js';
export type {HeightMap, HeightsOptions, PngHeightsOptions} from './heights.js';
export {createReliefMap, ReliefGpuError, ReliefMap, readTextureFloats, readWindowLevel, windowLevelSizes} from './pyramid.js';
export type {PyramidBuilder, ReliefMapOptions, ReliefMapParts} from './pyramid.js';
export {albedoFromBytes, loadAlbedo} from './albedo.js';
export {ReliefMapLoader} from './loader.js';
export type {ReliefMapLoaderOptions} from './loader.js';
export {patchFragment, patchVertex, ReliefDepthMaterial, ReliefDistanceMaterial, ReliefPhysicalMaterial, ReliefShadingMaterial, ReliefStandardMaterial} from './materials.js';
export type {ReliefMaterialParameters, ReliefShadingParameters} from './materials.js';
export {baseShape, cameraRays, Relief, reliefExtent} from './relief.js';
export type {BaseShape, BaseSpec, CameraRays, PickWith, ReliefHit, ReliefInterpolation, ReliefMaterial, ReliefOptions, TraceOptions, TracedRays} from './relief.js';
export {kFieldNames, loadSceneChecks, SceneChecks} from './checks.js';
export type {SceneMap, SceneView} from './checks.js';

/** loadHeights, then createReliefMap with `options`. */
export function loadReliefMap(renderer: WebGLRenderer, url: string | URL, options?: ReliefMapOptions): Promise<ReliefMap>;
