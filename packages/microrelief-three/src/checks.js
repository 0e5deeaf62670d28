// The programs' checks of a scene (docs/three.md, "Checking a view"): microrelief-render's own
// C++ (validateScene, resolveCamera, checkFloatLimits) compiled to WebAssembly, with the web
// page's names for the fields (its URL keys), as the package's build copies them from the
// repository (web/scene_checks.js, web/wasm/scene_checks.cpp) into generated/.
//
//   const checks = await loadSceneChecks();
//   checks.refusal({eye, target, up, fovy, heightScale, base, model, ...})   // '' or why not
//   checks.refusal(view, {width, height, maxHeight, name}, [W, H])          // and the float limits
import {SceneChecks} from '../generated/scene_checks.js';
import createSceneChecksModule from '../generated/scene_checks_wasm.js';

export {kFieldNames, SceneChecks} from '../generated/scene_checks.js';

// The checks, once their WebAssembly is instantiated. Rejects where the package was built
// without it (--no-wasm), saying so.
export function loadSceneChecks() {
    return SceneChecks.load(createSceneChecksModule);
}
