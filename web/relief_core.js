// relief_core.js: what the browser's two hosts of the library share, written once: the web
// page (web/scene.js, web/relief_gl.js) and microrelief-three (its scripts/build.mjs copies
// this file into the package's generated/, beside relief_layout.js). Pure functions and
// rows, no DOM, no WebGL, no three: the table of bases, the pyramids' level sizes and scale
// S, and the traversal's budget. Each mirrors the C++ named beside it, in doubles where the
// C++ has doubles and in floats (Math.fround, Float32Array bits) where it has floats, so
// that a host hands the shaders what the C++ renderer hands them. ctest web.core
// (tests/web/relief_core_test.mjs) holds every row, default, size and exponent here to the
// C++ itself.
import {kBaseKindValues, kBaseRows, kBudgetBase, kBudgetPerTexel} from './relief_layout.js';

// ---- the table of bases (core/base/BaseType.h; each row's data written once in
// shaders/microrelief/variants.glsl, its //@base line, generated into relief_layout.js's
// kBaseRows as into the C++'s glsl::kBaseRows; each kind's geometry written beside its surface
// in core/base/PlaneSurface.cpp, CylinderSurface.cpp and EllipsoidSurface.cpp) ----
//
// A shape is BaseShape's members that its row's sizes set, with its kind: {kind: 'plane'},
// {kind: 'cylinder', radius, length} or {kind: 'ellipsoid', radii: [A, B, C]}; a kind is its
// name in relief_layout.js's kBaseKindValues (MICRORELIEF_BASE's values, generated from
// variants.glsl too). A row: its name (the scene's base, --base, the page's base=), its kind,
// its summary, its sizes (the scene's base.* fields, each read from and written into a
// shape), its defaults (the shape a scene gets when it names the base and none of its sizes),
// whether a shape of its kind goes by its name (null: every one no other row takes), and its
// kind's frame scale and box.

// Each kind's geometry, the code the rows cannot be (BaseType.h's frameScale and boxMax, as
// each kind's C++ file writes them): a kind of kBaseKindValues without its entry here stops
// this module (ctest web.core says so first).
const cylinderFrame = (b) => [b.radius, 0.5 * b.length, b.radius];
const kKindGeometry = {
    plane: {
        frameScale: () => [1, 1, 1],
        // The map's rectangle, its longer side one unit, from y = 0 to the top.
        boxMax: (b, w, h, top) => {
            const longer = Math.max(w, h);
            return [(0.5 * w) / longer, top, (0.5 * h) / longer];
        },
        boxIsSymmetric: false,
    },
    cylinder: {
        frameScale: cylinderFrame,
        // The column of the shell's radius 1 + top between the caps.
        boxMax: (b, w, h, top) => {
            const f = cylinderFrame(b);
            return [f[0] * (1 + top), f[1], f[2] * (1 + top)];
        },
        boxIsSymmetric: true,
    },
    ellipsoid: {
        frameScale: (b) => b.radii.slice(),
        // The ball of the shell's radius 1 + top.
        boxMax: (b, w, h, top) => b.radii.map((r) => r * (1 + top)),
        boxIsSymmetric: true,
    },
};
for (const kind of Object.keys(kBaseKindValues))
    if (!Object.hasOwn(kKindGeometry, kind)) throw new Error(`relief_core.js: no frame and box for the base kind '${kind}' (kKindGeometry)`);

// A generated size as a row's: its numbers of a shape (`count` of its member's), and a shape
// with them (one number for a member of three sets all three: the sphere's radius).
function sizeOf(size) {
    const {field, label, member, memberWidth, count} = size;
    return {
        field, label, count, member,
        read: (b) => (memberWidth === 1 ? [b[member]] : b[member].slice(0, count)),
        write: (b, n) => (b[member] = memberWidth === 1 ? n[0] : count === 1 ? new Array(memberWidth).fill(n[0]) : n.slice(0, count)),
        // A member of more numbers than the size: the row takes the shapes whose are equal.
        narrow: count < memberWidth,
    };
}

// A generated row as the table's.
function typeOf(row) {
    const sizes = row.sizes.map(sizeOf);
    const shape = (numbers) => {
        const b = {kind: row.kind};
        sizes.forEach((size, k) => size.write(b, numbers(row.sizes[k])));
        return b;
    };
    const narrow = sizes.filter((size) => size.narrow);
    return {
        name: row.name, kind: row.kind, summary: row.summary, sizes,
        defaults: shape((size) => size.defaults),
        names: narrow.length ? (b) => narrow.every(({member}) => b[member].every((x) => x === b[member][0])) : null,
        ...kKindGeometry[row.kind],
    };
}

export const kBaseTypes = Object.freeze(kBaseRows.map(typeOf).map((row) => Object.freeze({...row, sizes: Object.freeze(row.sizes.map((size) => Object.freeze({...size, key: baseSizeKey(size.field)})))})));

// A size's key (the page's URL key, microrelief-three's option, the flag without its dashes):
// "base.minorRadius" -> "minor-radius", as a program derives a base size's flag
// (core/base/BaseTable.cpp: sceneFieldFlag).
export function baseSizeKey(field) {
    return field.slice(field.indexOf('.') + 1).replace(/[A-Z]/g, (c) => `-${c.toLowerCase()}`);
}

// The names, in the table's order (--help's, the viewer's list).
export const kBaseNames = Object.freeze(kBaseTypes.map((type) => type.name));

// The row named `name`, or undefined.
export const baseTypeNamed = (name) => kBaseTypes.find((type) => type.name === name);

// The sizes of every row, each field once, in the table's order (BaseTable.cpp:
// baseSizeFields): {field, key, viewName, count, label, bases}, `viewName` a page's view's
// name for it (the field after "base.": scene_checks.js reads a view's sizes so; not the
// shape's member, which a row's size names), `bases` the names of the rows that have it. A field is one scene field, of one count in every row that has it.
export const kBaseSizes = Object.freeze((() => {
    const sizes = new Map();
    for (const type of kBaseTypes)
        for (const size of type.sizes) {
            const seen = sizes.get(size.field);
            if (seen && seen.count !== size.count) throw new Error(`relief_core.js: the base size ${size.field} is ${seen.count} numbers in one row, ${size.count} in ${type.name}`);
            if (seen) seen.bases.push(type.name);
            else sizes.set(size.field, {field: size.field, key: size.key, viewName: size.field.slice(size.field.indexOf('.') + 1), count: size.count, label: size.label, bases: [type.name]});
        }
    return [...sizes.values()].map((size) => Object.freeze({...size, bases: Object.freeze(size.bases)}));
})());

// A shape's sizes as its row reads them, in the row's order, every number in one list (the
// sphere's radius one number): what a host hands a size-blind API (the twin's WebAssembly),
// which makes the shape back from the row's name and these (baseShape's reverse).
export const baseSizeNumbers = (shape) => baseType(shape).sizes.flatMap((size) => size.read(shape));

// The row a shape goes by: its kind's rows, the first whose `names` takes it, else the
// kind's own (BaseTable.cpp: baseType(shape)).
export function baseType(shape) {
    let general = null;
    for (const type of kBaseTypes) {
        if (type.kind !== shape.kind) continue;
        if (type.names === null) general ??= type;
        else if (type.names(shape)) return type;
    }
    if (general === null) throw new Error(`a base of kind '${shape.kind}', which the table of bases does not hold`);
    return general;
}

// The name a shape goes by: "sphere" for an ellipsoid of equal radii (BaseShape.cpp: baseName).
export const baseName = (shape) => baseType(shape).name;

// The errors baseShape throws: Error with the message as it stands (the page's, whose keys
// are the program's flags). A host words them its own way with its own `refusal`.
const kRefusal = (message) => new Error(message);

// The shape of base `name` with the sizes in `given` (a size's key -> its number, or its
// numbers for a vector: {radius: 0.4}), each size not given (undefined or null) its row's
// default (BaseShape.h, BaseTable.cpp: baseType(name), validateBaseShape). A name no row has,
// or a size that is not positive and finite, is refused: `refusal(message, key)` makes the
// error thrown (key: the size's, or undefined for the name), Error(message) by default.
export function baseShape(name, given = {}, refusal = kRefusal) {
    const type = kBaseTypes.find((t) => t.name === name);
    if (!type) {
        const names = kBaseNames.map((n, k) => (k === 0 ? '' : k + 1 === kBaseNames.length ? ' or ' : ', ') + n).join('');
        throw refusal(`unknown base '${name}' (expected ${names})`, undefined);
    }
    const shape = structuredClone(type.defaults);
    for (const size of type.sizes) {
        const value = given[size.key];
        if (value === undefined || value === null) continue;
        const numbers = Array.isArray(value) || ArrayBuffer.isView(value) ? Array.from(value) : [value];
        if (numbers.length !== size.count)
            throw refusal(`${size.key} must be ${size.count === 1 ? 'one number' : `${size.count} numbers`}, not ${numbers.length}`, size.key);
        size.write(shape, numbers);
    }
    for (const size of type.sizes)
        if (size.read(shape).some((n) => !(n > 0) || !Number.isFinite(n))) throw refusal(`${size.key} must be a positive finite number`, size.key);
    return shape;
}

// Whether u is periodic: the curved bases (BaseShape::wrapsU).
export const wrapsU = (shape) => shape.kind !== 'plane';

// World size of the canonical frame's unit along x, y, z (BaseShape::frameScale).
export const frameScale = (shape) => baseType(shape).frameScale(shape);

// The relief's object-space box for a map of width x height samples whose top is
// `maxHeight`: {min, max, top} with top = s max h (core/base/ReliefExtent.cpp, BaseShape::boxMin
// and boxMax).
export function reliefExtent(width, height, maxHeight, heightScale, shape) {
    const type = baseType(shape);
    const top = heightScale * maxHeight;
    const high = type.boxMax(shape, width, height, top);
    const low = type.boxIsSymmetric ? high.map((c) => -c) : [-high[0], 0, -high[2]];
    return {min: low, max: high, top};
}

// ---- the pyramids (core/heightmap/MaxPyramid.cpp; peers/MaxMipPyramid.cpp) ----

// A float's bits and back.
const floatBits = (() => {
    const f = new Float32Array(1), u = new Uint32Array(f.buffer);
    return {
        bits(value) {
            f[0] = value;
            return u[0];
        },
        value(bits) {
            u[0] = bits >>> 0;
            return f[0];
        },
    };
})();

// GL's mip sizes of W x H down to 1 x 1: the windows' levels (MaxPyramid.cpp: windowLevelSizes).
export function windowLevelSizes(width, height) {
    const sizes = [];
    for (let w = width, h = height; ; w = Math.max(w >> 1, 1), h = Math.max(h >> 1, 1)) {
        sizes.push([w, h]);
        if (w === 1 && h === 1) return sizes;
    }
}

// maxmip's quadtree: W and H rounded up to powers of two, halved down to 1 x 1
// (peers/MaxMipPyramid.cpp: maxMipLevelSizes).
export function maxMipLevelSizes(width, height) {
    const ceilPowerOfTwo = (n) => {
        let p = 1;
        while (p < n) p *= 2;
        return p;
    };
    return windowLevelSizes(ceilPowerOfTwo(width), ceilPowerOfTwo(height));
}

// S for a pyramid whose top is `top` (>= 0): e - 14 for its binary exponent e (from the
// float's exponent field), clamped to [-112, 113] (MaxPyramid.cpp: pyramidScaleExponent).
export function pyramidScaleExponent(top) {
    const e = (floatBits.bits(top) >>> 23) - 127;
    return Math.min(Math.max(e - 14, -112), 113);
}

// The top of a pyramid of half bounds whose largest sample is `largestSample` (>= 0): the
// sample rounded up to 11 significant bits, a half's, a carry running into the exponent
// (MaxPyramid.cpp: pyramidTop, roundUpToHalfBits).
export function pyramidTop(largestSample) {
    const bits = floatBits.bits(largestSample) & 0x7fffffff;
    return floatBits.value(((bits + 0x1fff) & ~0x1fff) >>> 0);
}

// S for samples whose largest is `largestSample`, before a pyramid is built: what MaxPyramid::
// build takes, and what ReliefTextures takes before a GPU build (there written
// pyramidScaleExponent(storedBound(largest, Half, pyramidScaleExponent(largest))); storedBound's
// floor, the least normal half times 2^S, lies below any normal float it is given with that
// S, and a subnormal's S is the least either way, so the two are one function: web.core holds
// this to both).
export const initialScaleExponent = (largestSample) => pyramidScaleExponent(pyramidTop(largestSample));

// float's ldexp(x, e): x 2^e rounded to a float.
const ldexpFloat = (x, e) => Math.fround(x * 2 ** e);

// The S that texels drawn with S = `s` ask for, their top read back as `stored` (the top's
// bound / 2^s, a half read as a float) (gl/PyramidBuilder.cpp: settleScale's step): a top
// past a half's range asks for 16 more, one at or below the least normal half (maybe raised
// to it) for 28 less, to look again; else the top's own, clamped.
export function fittingScaleExponent(stored, s) {
    const least = pyramidScaleExponent(0), most = pyramidScaleExponent(3e38);
    let fitting;
    if (stored === Infinity) fitting = s + 16;
    else if (stored === 0) fitting = least;
    else if (stored <= 2 ** -14) fitting = s - 28;
    else fitting = pyramidScaleExponent(ldexpFloat(stored, s));
    return Math.min(Math.max(fitting, least), most);
}

// A GPU build's S settled (PyramidBuilder::settleScale): `drawWith(s)` draws every texel
// with S = s and returns the top it reads back (bound / 2^s); where the top asks for another
// S, every texel again with it (two draws settle it in practice, a few more where the top
// went past a half's range; the 17th stands). Returns {scaleExponent, maxHeight}.
export function settleScale(scaleExponent, drawWith) {
    for (let attempt = 0; ; ++attempt) {
        const stored = drawWith(scaleExponent);
        const fitting = fittingScaleExponent(stored, scaleExponent);
        if (fitting === scaleExponent || attempt === 16) return {scaleExponent, maxHeight: ldexpFloat(stored, scaleExponent)};
        scaleExponent = fitting;
    }
}

// ---- the traversal (core/trace/MultilevelTracer.cpp: traversalBudget) ----

// The most iterations a ray may take on a W x H map (maxIterations), from the GLSL's
// constants (relief_query.glsl, through relief_layout.js).
export const traversalBudget = (width, height) => kBudgetPerTexel * (width + height) + kBudgetBase;
