// scene_checks.js: the programs' checks of a scene for the browser front ends, the web page
// and examples/three (docs/browser.md, "One validation"): the C++ core's own checks
// (validateScene in src/core/scene/Scene.cpp, resolveCamera in Camera.cpp, checkFloatLimits
// in FloatLimits.cpp, the table of bases, the model's) compiled to WebAssembly
// (web/wasm/scene_checks.cpp), their messages with the fields named by the pages' URL keys,
// as microrelief-render names them by its flags. The page builds the module into
// generated/scene_checks_wasm.js beside this file; microrelief-three ships both in its
// generated/ (loadSceneChecks).
//
//   const checks = await SceneChecks.load(createSceneChecksModule);
//   checks.refusal(view)                              // '' or why the programs refuse it
//   checks.refusal(view, {width, height, maxHeight, name}, [W, H])   // and the float limits
import {baseSizeKey} from './relief_core.js';  // a base size's key: "base.minorRadius" -> "minor-radius"

// The pages' names for the scene's fields (core/scene/SceneFields.h): their URL keys, which
// are microrelief-render's flags without the dashes (tests/web/check_url_keys.py). A field
// no page has a key for is named by the flag that sets it in microrelief-render, dashes
// and all: what a message suggests there ("use --normalize") is the program's to do. A base's
// size ("base.radius") is its key in words ("radius"), as the program's flag is.
export const kFieldNames = {
    'map.file': '--height',
    'map.load.channel': '--channel',
    'map.load.normalize': '--normalize',
    albedo: 'albedo',
    base: 'base',
    interpolation: 'interpolation',
    tiles: '--tile',
    heightScale: 'height-scale',
    model: 'model',
    animation: '--animate',
    time: '--time',
    'camera.eye': 'eye',
    'camera.target': 'target',
    'camera.up': 'up',
    'camera.fovyDegrees': 'fovy',
    size: 'size',
    method: 'method',
    'method.steps': 'steps',
    'method.pixelError': 'pixel-error',
    'shading.lightDirection': 'light',
    'shading.lightPosition': '--light-position',
    'shading.shadows': 'shadows',
    'shading.lightSizeDegrees': 'light-size',
    'shading.view': 'view',
    background: 'background',
};

export class SceneChecks {
    // The checks from emscripten's module factory (createSceneChecksModule). Rejects with
    // the factory's error (a build without em++ has a stub that says so).
    static async load(createModule) {
        return new SceneChecks(await createModule());
    }

    constructor(module) {
        const call = (name, returns, ...args) => module.cwrap(name, returns, args);
        this.reset = call('mr_scene_reset', null);
        this.setBase = call('mr_scene_set_base', null, 'string');
        this.setBaseSize = call('mr_scene_set_base_size', null, 'string', 'number', 'number', 'number');
        this.setRelief = call('mr_scene_set_relief', null, 'number', 'string');
        this.setCamera = call('mr_scene_set_camera', null, ...new Array(10).fill('number'));
        this.setSize = call('mr_scene_set_size', null, 'number', 'number');
        this.setMethod = call('mr_scene_set_method', null, 'string', 'number', 'number');
        this.setLight = call('mr_scene_set_light', null, 'number', 'number', 'number');
        this.setShading = call('mr_scene_set_shading', null, 'string', 'number', 'string');
        this.setBackground = call('mr_scene_set_background', null, 'number', 'number', 'number');
        this.check = call('mr_scene_check', 'number', 'number', 'number', 'number', 'string');
        this.lastError = call('mr_last_error', 'string');
        this.module = module;
        // Every field a message may name, and the name it gets here.
        this.fields = call('mr_scene_fields', 'string')().split('\n').filter(Boolean);
        this.names = {};
        const setName = call('mr_set_field_name', null, 'string', 'string');
        for (const field of this.fields) {
            const name = field.startsWith('base.') ? baseSizeKey(field) : kFieldNames[field];
            if (name === undefined) continue;
            this.names[field] = name;
            setName(field, name);
        }
    }

    // The fields a message may name that have no name here (map.samples: no program sets it
    // from text; mesh.file: the mesh base is not on the pages yet); the tests hold this list
    // to those two.
    unnamedFields() {
        return this.fields.filter((field) => !(field in this.names));
    }

    // Why microrelief-render would refuse `view` (the pages' views: scene.js's
    // viewFromQuery, examples/three's viewFromUrl), in the words of the page's URL keys; ''
    // where it draws it. With `map` ({width, height, maxHeight, name}: its texels, its largest
    // sample, its name in messages) and `pixels` ([W, H], the picture), also the float
    // limits the renderer checks before it draws (core/scene/FloatLimits.h).
    refusal(view, map = null, pixels = null) {
        this.reset();
        this.setBase(view.base ?? 'plane');
        for (const field of this.fields.filter((f) => f.startsWith('base.'))) {
            const value = view[field.slice('base.'.length)];
            if (value === null || value === undefined) continue;
            const [x, y = 0, z = 0] = Array.isArray(value) ? value : [value];
            this.setBaseSize(field, x, y, z);
        }
        this.setRelief(view.heightScale ?? Math.fround(0.1), view.interpolation ?? 'bilinear');
        if (view.model) this.setModel(view.model);
        this.setCamera(...view.eye, ...view.target, ...(view.up ?? [0, 1, 0]), view.fovy ?? 45);
        const [width, height] = pixels ?? [1, 1];
        this.setSize(width, height);
        this.setMethod(view.method ?? 'multilevel', view.steps ?? 64, view.pixelError ?? 0);
        if (view.light) this.setLight(...view.light);
        this.setShading(view.shadows ?? 'off', view.lightSize ?? 1, view.view ?? 'shaded');
        if (view.background) this.setBackground(...view.background);
        const passed = map ? this.check(map.width, map.height, map.maxHeight, map.name) : this.check(0, 0, 0, '');
        return passed ? '' : this.lastError();
    }

    setModel(rows) {
        const bytes = 12 * 8, at = this.module._malloc(bytes);
        try {
            this.module.HEAPF64.set(rows, at / 8);
            this.module._mr_scene_set_model(at);
        } finally {
            this.module._free(at);
        }
    }
}

// The largest sample of a map's heights: what the float limits take as its top.
export function largestSample(samples) {
    let largest = 0;
    for (let k = 0; k < samples.length; ++k) if (samples[k] > largest) largest = samples[k];
    return largest;
}
