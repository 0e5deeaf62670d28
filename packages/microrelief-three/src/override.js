// override.js: the relief under scene.overrideMaterial. three draws every object of such a
// scene with the one override material (MeshNormalMaterial for GTAOPass, SSAOPass and
// SAOPass; MeshDepthMaterial for BokehPass and OutlinePass; MeshDistanceMaterial for a
// distance pass), so the relief would be its proxy box: two flat boxes, no crevice. three
// hands the override to the object's onBeforeRender and draws with it afterwards; the
// relief cannot swap it, so here it draws itself first, with a relief-patched equivalent
// of the override (the same three shader, patched as materials.js patches its own: the
// traced hit's view position, normal, uv and depth, gl_FragDepth the hit's), and three's
// own draw of the box for that call is emptied (the geometry's draw range count set to 0,
// put back in onAfterRender: three then binds the override's program and draws nothing).
//
// An equivalent is kept per relief and per override material, copied from the override at
// each draw (so its depthPacking, flatShading, blending, maps and the rest follow), its
// program rebuilt when the override's version or the relief's base or interpolation
// changes, disposed with the override or with the relief. Other overrides (a ShaderMaterial,
// other Mesh*Materials) draw the box as before.
import * as THREE from 'three';

import {patchFragment, patchVertex, reliefDefines} from './materials.js';

// The override materials the relief answers with its traced surface.
export function answersOverride(material) {
    return !!material && !material.isReliefMaterial && material.relief === undefined &&
           (material.type === 'MeshNormalMaterial' || material.type === 'MeshDepthMaterial' || material.type === 'MeshDistanceMaterial');
}

// relief -> Map(override material -> {patched, version, key, onDispose}).
const equivalents = new WeakMap();
// geometry -> the draw range count three's own draw of the box would have used.
const emptied = new WeakMap();

function reliefKey(relief) {
    return `${relief.base.kind}:${relief.interpolation}`;
}

function makeEquivalent(relief, override) {
    const patched = new THREE[override.type]();
    patched.onBeforeCompile = (shader) => {
        shader.defines = {
            ...shader.defines,
            ...reliefDefines(relief),
            MR_SHADOW_PASS: '',  // no lighting at the hit: an exhausted ray draws nothing
        };
        Object.assign(shader.uniforms, relief.uniforms);
        shader.vertexShader = patchVertex(shader.vertexShader);
        shader.fragmentShader = patchFragment(shader.fragmentShader);
    };
    patched.customProgramCacheKey = () => `microrelief-override:${reliefKey(relief)}`;
    const entry = {patched, version: -1, key: ''};
    entry.onDispose = () => forget(relief, override);
    override.addEventListener('dispose', entry.onDispose);
    return entry;
}

function forget(relief, override) {
    const map = equivalents.get(relief);
    const entry = map && map.get(override);
    if (!entry) return;
    override.removeEventListener('dispose', entry.onDispose);
    entry.patched.dispose();
    map.delete(override);
}

// The relief's equivalent of `override`, in step with it.
function equivalentOf(relief, override) {
    let map = equivalents.get(relief);
    if (!map) equivalents.set(relief, (map = new Map()));
    let entry = map.get(override);
    if (!entry) map.set(override, (entry = makeEquivalent(relief, override)));
    const {patched} = entry;
    patched.copy(override);
    patched.side = THREE.DoubleSide;  // the faces that run are chosen per draw (mrFaces)
    const key = reliefKey(relief);
    if (entry.version !== override.version || entry.key !== key) {
        entry.version = override.version;
        entry.key = key;
        patched.needsUpdate = true;
    }
    return patched;
}

// From the relief's onBeforeRender, after prepareDraw: where `material` is an override the
// relief answers, the relief drawn with its equivalent and three's coming draw of the box
// emptied. Returns whether it drew.
export function drawUnderOverride(relief, renderer, scene, camera, geometry, material, group) {
    restoreDrawRange(geometry);  // an earlier call that threw before its onAfterRender
    if (material === relief.material || !answersOverride(material)) return false;
    const patched = equivalentOf(relief, material);
    // A distance material takes its reference point from the light three's shadow map
    // records for it (renderer.properties); the equivalent reads the same one.
    const light = material.type === 'MeshDistanceMaterial' && renderer.properties ? renderer.properties.get(material).light : undefined;
    if (light) renderer.properties.get(patched).light = light;
    // What three's renderObject computes after onBeforeRender.
    relief.modelViewMatrix.multiplyMatrices(camera.matrixWorldInverse, relief.matrixWorld);
    relief.normalMatrix.getNormalMatrix(relief.modelViewMatrix);
    renderer.renderBufferDirect(camera, scene, geometry, patched, relief, group ?? null);
    emptied.set(geometry, geometry.drawRange.count);
    geometry.drawRange.count = 0;
    return true;
}

// From the relief's onAfterRender: the box's draw range as it was.
export function restoreDrawRange(geometry) {
    if (!emptied.has(geometry)) return;
    geometry.drawRange.count = emptied.get(geometry);
    emptied.delete(geometry);
}

// The relief's equivalents disposed (Relief.dispose).
export function disposeOverrides(relief) {
    const map = equivalents.get(relief);
    if (!map) return;
    for (const override of [...map.keys()]) forget(relief, override);
    equivalents.delete(relief);
}
