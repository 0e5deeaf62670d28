// microrelief-three: exact microrelief in three.js (docs/three.md).
//
//   const map = await loadReliefMap(renderer, 'cobbles.png');           // heights + pyramid
//   const relief = new Relief(map, {material: new ReliefStandardMaterial({albedoMap})});
//   scene.add(relief);                                                   // a THREE.Mesh
export {HeightMapError, heightsFromArray, heightsFromBytes, heightsFromImage, heightsFromPng, kMaxMapSide, loadHeights} from './heights.js';
export {createReliefMap, ReliefGpuError, ReliefMap, readTextureFloats, readWindowLevel, windowLevelSizes} from './pyramid.js';
export {albedoFromBytes, loadAlbedo} from './albedo.js';
export {ReliefMapLoader} from './loader.js';
export {patchFragment, patchVertex, ReliefDepthMaterial, ReliefDistanceMaterial, ReliefPhysicalMaterial, ReliefShadingMaterial, ReliefStandardMaterial} from './materials.js';
export {baseShape, cameraRays, Relief, reliefExtent} from './relief.js';
export {kFieldNames, loadSceneChecks, SceneChecks} from './checks.js';

import {loadHeights} from './heights.js';
import {createReliefMap} from './pyramid.js';

// A height map from a URL (a PNG decoded exactly, 16 bits kept) and its textures for
// `renderer`: loadHeights, then createReliefMap with `options` (wrapU, pyramid).
export async function loadReliefMap(renderer, url, options = {}) {
    return createReliefMap(renderer, await loadHeights(url), options);
}
