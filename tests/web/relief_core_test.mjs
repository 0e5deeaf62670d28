// The browser's host core (web/relief_core.js, which the page and microrelief-three share)
// against the C++ it mirrors (ctest web.core; node, no browser): core_facts (core_facts.cpp)
// writes what the C++ table of bases, the pyramids' level sizes and S and the traversal's
// budget give, and every row, default, size, refusal, frame, box, level and exponent of the
// module as staged in the build tree must be the same, exactly. The rows' data (names,
// kinds, summaries, sizes, defaults, which shapes a row names) comes to both from the one
// place it is written (variants.glsl's //@base lines: glsl::kBaseRows, relief_layout.js's
// kBaseRows); what this holds is how each language reads them (a size's member, one number
// for three) and each kind's geometry, which both write: a size read or written otherwise, a
// row's box or frame written otherwise in one language, or a generated row one side does not
// read as the other fails here, naming the row. One line a failure; exit status 1 when one
// failed.
//
// node tests/web/relief_core_test.mjs CORE_FACTS STAGED_SHARE   (STAGED_SHARE: share/microrelief)
import {spawnSync} from 'node:child_process';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import {pathToFileURL} from 'node:url';

const [factsProgram, share] = process.argv.slice(2);
if (!factsProgram || !share || !fs.existsSync(path.join(share, 'web', 'relief_core.js'))) {
    console.error('usage: node relief_core_test.mjs CORE_FACTS STAGED_SHARE (the build tree\'s share/microrelief)');
    process.exit(2);
}

// The page's modules in a scratch folder marked as ES modules (node before 22 reads a .js
// file as CommonJS unless a package.json says otherwise).
const scratch = fs.mkdtempSync(path.join(os.tmpdir(), 'relief-core-'));
process.on('exit', () => fs.rmSync(scratch, {recursive: true, force: true}));
for (const file of ['relief_core.js', 'relief_layout.js']) fs.copyFileSync(path.join(share, 'web', file), path.join(scratch, file));
fs.writeFileSync(path.join(scratch, 'package.json'), '{"type": "module"}\n');
const core = await import(pathToFileURL(path.join(scratch, 'relief_core.js')).href);
const {kBaseKindValues} = await import(pathToFileURL(path.join(scratch, 'relief_layout.js')).href);

const run = spawnSync(factsProgram, [], {encoding: 'utf8', maxBuffer: 64 << 20});
if (run.status !== 0) {
    console.error(`relief_core_test: ${factsProgram} failed (status ${run.status}): ${run.stderr}`);
    process.exit(1);
}
const facts = JSON.parse(run.stdout);

let failures = 0, checks = 0;
const text = (x) => JSON.stringify(x, (k, v) => (Object.is(v, -0) ? '-0' : v));
// Exactly equal, -0 apart from 0 (a host's box corner of -0 is what the C++ has or not).
function same(a, b) {
    if (Array.isArray(a) || Array.isArray(b)) return Array.isArray(a) && Array.isArray(b) && a.length === b.length && a.every((x, k) => same(x, b[k]));
    return Object.is(a, b);
}
function expect(what, got, want, source = 'the C++') {
    ++checks;
    if (same(got, want)) return;
    ++failures;
    console.log(`${what}: relief_core.js has ${text(got)}, ${source} ${text(want)}`);
}
// `check()`, a throw counted as a failure of `what` (a row the core lacks, say).
function attempt(what, check) {
    try {
        check();
    } catch (e) {
        ++checks;
        ++failures;
        console.log(`${what}: relief_core.js throws ${e.message}`);
    }
}
function refusalOf(call) {
    try {
        call();
        return '(none)';
    } catch (e) {
        return e.message;
    }
}
// A row's sizes by the pages' keys, from the C++'s {field: numbers}.
const byKey = (sizes) => Object.fromEntries(Object.entries(sizes).map(([field, n]) => [core.baseSizeKey(field), n.length === 1 ? n[0] : n]));
// The C++'s sizes of a shape the core made, by field.
const sizesOf = (type, shape) => Object.fromEntries(type.sizes.map((size) => [size.field, size.read(shape)]));

// ---- the table of bases ----
expect('the table\'s names, in its order', core.kBaseNames, facts.bases.map((row) => row.name));
for (const row of facts.bases) {
    const type = core.kBaseTypes.find((t) => t.name === row.name);
    if (!type) continue;  // said above
    expect(`${row.name}: its kind (MICRORELIEF_BASE)`, kBaseKindValues[type.kind], row.kind);
    expect(`${row.name}: its sizes' fields`, type.sizes.map((s) => s.field), row.sizes.map((s) => s.field));
    expect(`${row.name}: its sizes' counts`, type.sizes.map((s) => s.count), row.sizes.map((s) => s.count));
    expect(`${row.name}: its sizes' labels`, type.sizes.map((s) => s.label), row.sizes.map((s) => s.label));
    expect(`${row.name}: its summary`, type.summary, row.summary);
    const defaults = core.baseShape(row.name);
    expect(`${row.name}: its defaults`, Object.values(sizesOf(type, defaults)), Object.values(row.defaults));
    for (const shape of row.shapes) attempt(`${row.name}: the ${shape.name} of ${text(shape.sizes)}`, () => {
        const made = core.baseShape(shape.name, byKey(shape.sizes));
        const what = `${row.name}: the ${shape.name} of ${text(shape.sizes)}`;
        expect(`${what}: its name`, core.baseName(made), shape.name);
        expect(`${what}: wrapsU`, core.wrapsU(made), shape.wrapsU);
        expect(`${what}: frameScale`, core.frameScale(made), shape.frameScale);
        for (const e of shape.extents) {
            const got = core.reliefExtent(e.size[0], e.size[1], e.maxHeight, e.heightScale, made);
            const where = `${what}: reliefExtent of ${e.size[0]} x ${e.size[1]}, max ${e.maxHeight}, s ${e.heightScale}`;
            expect(`${where}: min`, got.min, e.min);
            expect(`${where}: max`, got.max, e.max);
            expect(`${where}: top`, got.top, e.top);
        }
    });
    for (const r of row.refusals)
        expect(`${row.name}: refuses ${text(r.sizes)}`, refusalOf(() => core.baseShape(row.name, byKey(r.sizes))), r.message);
}
// The sizes of every row, each field once (the pages' boxes and URL keys: kBaseSizes), with
// the rows that have each; and a row's sizes as one list of numbers in its order (twin.js
// hands them so to the C++ twin, which writes them back in the row's order).
expect('the sizes of every row, each once (baseSizeFields)', core.kBaseSizes.map((size) => size.field), facts.baseSizeFields);
for (const size of core.kBaseSizes)
    expect(`${size.field}: the rows that have it`, size.bases, facts.bases.filter((row) => row.sizes.some((s) => s.field === size.field)).map((row) => row.name));
for (const row of facts.bases)
    for (const shape of row.shapes)
        attempt(`${row.name}: the ${shape.name} of ${text(shape.sizes)} as one list`, () => expect(`${row.name}: the ${shape.name} of ${text(shape.sizes)}: baseSizeNumbers`,
            core.baseSizeNumbers(core.baseShape(shape.name, byKey(shape.sizes))), Object.values(shape.sizes).flat()));
expect(`refuses the base '${facts.unknownBase.name}'`, refusalOf(() => core.baseShape(facts.unknownBase.name)), facts.unknownBase.message);

// ---- the pyramids and the traversal ----
for (const l of facts.levels) {
    const [w, h] = l.size;
    expect(`windowLevelSizes(${w}, ${h})`, core.windowLevelSizes(w, h), l.windows);
    expect(`maxMipLevelSizes(${w}, ${h})`, core.maxMipLevelSizes(w, h), l.maxMip);
    expect(`traversalBudget(${w}, ${h})`, core.traversalBudget(w, h), l.budget);
}
const bitsOf = (x) => new Uint32Array(new Float32Array([x]).buffer)[0];
const floatOf = (bits) => new Float32Array(new Uint32Array([bits]).buffer)[0];
for (const [bits, s, topBits, fromTop, fromStored] of facts.scales) {
    const x = floatOf(bits);
    const what = `the float of bits 0x${bits.toString(16)} (${x})`;
    expect(`${what}: pyramidScaleExponent`, core.pyramidScaleExponent(x), s);
    expect(`${what}: pyramidTop's bits`, bitsOf(core.pyramidTop(x)), topBits);
    // MaxPyramid::build's S and ReliefTextures': one function (relief_core.js says why).
    expect(`${what}: initialScaleExponent as MaxPyramid::build takes it`, core.initialScaleExponent(x), fromTop);
    expect(`${what}: initialScaleExponent as ReliefTextures takes it`, core.initialScaleExponent(x), fromStored);
}

// ---- the hosts' wording of a refusal (relief_core.js's own; no C++ to hold it to) ----
const wording = (message, size) => new TypeError(`Relief: ${size ? 'base ' : ''}${message}`);
expect('a host words a size\'s refusal', refusalOf(() => core.baseShape('cylinder', {length: 0}, wording)), 'Relief: base length must be a positive finite number', 'expected');
// The names as the C++ lists them (plane, cylinder, ellipsoid or sphere), from its table.
const listed = facts.bases.map((row, k, all) => (k === 0 ? '' : k + 1 === all.length ? ' or ' : ', ') + row.name).join('');
expect('a host words an unknown base', refusalOf(() => core.baseShape('cone', {}, wording)), `Relief: unknown base 'cone' (expected ${listed})`, 'expected');
expect('a vector of the wrong length', refusalOf(() => core.baseShape('ellipsoid', {radii: [1, 2]})), 'radii must be 3 numbers, not 2', 'expected');
expect('a size not given keeps its default', text(core.baseShape('cylinder', {radius: 0.4, length: null})), text({kind: 'cylinder', radius: 0.4, length: 1}), 'expected');

if (failures) {
    console.log(`relief_core_test: ${failures} of ${checks} checks failed`);
    process.exit(1);
}
console.log(`relief_core_test: ${checks} checks: web/relief_core.js agrees with the C++ (${facts.bases.length} bases, ${facts.scales.length} floats)`);
