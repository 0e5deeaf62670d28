// three_version.js: the three.js this package runs on. What makes a relief (createReliefMap,
// Relief, the materials) asks first, so that a three older than the oldest the package is
// tested on is one line naming the range (package.json's peerDependencies), not an error
// inside three's renderer later (three 0.170: "Invalid value used as weak map key") or a
// picture subtly wrong (0.171 to 0.181: a relief's point-light shadow falls in the wrong
// places, 285 of 1,895 points of ctest three.range's cast-point view, when point shadows
// were a packed 2D atlas; r182 made them cube textures; r171 to r179 also named the
// logarithmic depth buffer USE_LOGDEPTHBUF, and the relief's depth was then linear). Asked
// at first use, not at import: the package has no side effects on import (sideEffects: false).
import {REVISION} from 'three';

// three's revision r<N> is its version 0.<N>.x.
export const kOldestThreeRevision = 182;

// Throws where the 'three' this package imports is older than its range.
export function requireSupportedThree() {
    if (Number.parseInt(REVISION, 10) >= kOldestThreeRevision) return;
    const found = REVISION === undefined ? 'a module without REVISION' : `r${REVISION}`;
    throw new Error(`microrelief-three needs three >=0.${kOldestThreeRevision}.0 (r${kOldestThreeRevision} or newer), but the 'three' it imports is ${found}`);
}

// The renderer this entry draws with: THREE.WebGLRenderer. A WebGPURenderer is named as such
// (issue 51: tried as a new user would, it was refused as "not a WebGLRenderer", and a relief
// drew as its white box in it, silently), pointing at the WebGPU entry in one line.
export const kWebGPURendererUnsupported = "microrelief-three draws with THREE.WebGLRenderer; a WebGPURenderer takes the WebGPU entry: import from 'microrelief-three/webgpu' (ReliefShadingNodeMaterial, the library's own shading; ReliefStandardNodeMaterial, three's lights)";

// Throws a TypeError for anything but a WebGLRenderer; `what` names the caller.
export function requireWebGLRenderer(renderer, what) {
    if (renderer && renderer.isWebGPURenderer) throw new TypeError(`${what}: ${kWebGPURendererUnsupported}`);
    if (!renderer || !renderer.isWebGLRenderer) throw new TypeError(`${what}: the first argument must be a THREE.WebGLRenderer`);
}
