#!/usr/bin/env python3
"""check_generator.py ROOT: cmake/generate_contracts.py reads the methods' rows of
shaders/microrelief/variants.glsl (MR_TRAIT_*, MR_TRAITS_*) as the build does, and refuses,
naming the file and the line, each slip a row can make: a method without a row, a row of no
method, a row twice, a trait it does not define, a bit shared or not a power of two. So for
the bases' rows (//@base and //@size, read_named): a line of another form, a size above
every row, a kind that is no MR_BASE_*, a name twice, a default count that is neither 1 nor
the member's, a size not positive, a field of two counts, a member of two widths, an
example of another count, a kind without the row that takes its every shape, two such
rows, two rows that name the same shapes, an unknown tag. Each case edits a copy of the
shaders; the build's own files are not touched."""
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(sys.argv[1])
SCRIPT = ROOT / "cmake" / "generate_contracts.py"
SPEC = "variants.glsl:MR_METHOD:Method:MR_TRAIT:MR_TRAITS"
BASES = "variants.glsl:MR_BASE:BaseKind:@base"
failures = []


def generate(shaders, spec=SPEC):
    return subprocess.run([sys.executable, str(SCRIPT), "--block", str(ROOT / "shaders" / "relief_parameters.glsl"),
                           "--shaders", str(shaders), "--enums", spec, "--js", "-"],
                          capture_output=True, text=True)


def case(name, edit, expected, spec=SPEC):
    """The generator over variants.glsl edited by `edit` (text -> text) fails with a message
    matching `expected`."""
    with tempfile.TemporaryDirectory() as scratch:
        shaders = pathlib.Path(scratch) / "microrelief"
        shutil.copytree(ROOT / "shaders" / "microrelief", shaders)
        variants = shaders / "variants.glsl"
        text = variants.read_text()
        edited = edit(text)
        if edited == text:
            failures.append(f"{name}: the edit changed nothing (variants.glsl changed?)")
            return
        variants.write_text(edited)
        run = generate(shaders, spec)
        if run.returncode == 0 or not re.search(expected, run.stderr):
            failures.append(f"{name}: expected a refusal matching {expected!r}, got exit "
                            f"{run.returncode} and {run.stderr.strip()!r}")


# The real rows: accepted, each method with its traits.
run = generate(ROOT / "shaders" / "microrelief")
if run.returncode != 0:
    failures.append(f"the real variants.glsl: {run.stderr.strip()}")
elif "maxmip: Object.freeze(['solid', 'curved', 'max_pyramid'])" not in run.stdout:
    failures.append("the real variants.glsl: kMethodTraits does not give maxmip its row")

case("a method without a row", lambda t: re.sub(r"#define MR_TRAITS_CONE .*\n", "", t),
     r"variants\.glsl: no row for MR_TRAITS_CONE")
case("a row of no method", lambda t: t.replace("#define MR_TRAITS_CONE ", "#define MR_TRAITS_CONES "),
     r"variants\.glsl:\d+: MR_TRAITS_CONES is the row of no member of Method")
case("a row twice", lambda t: t.replace("#define MR_TRAITS_CONE ", "#define MR_TRAITS_RCSM (MR_TRAIT_STEPS)\n#define MR_TRAITS_CONE "),
     r"variants\.glsl:\d+: MR_TRAITS_RCSM is defined twice")
case("a trait not defined", lambda t: t.replace("#define MR_TRAITS_CONE (MR_TRAIT_SOLID", "#define MR_TRAITS_CONE (MR_TRAIT_SOLIDS"),
     r"variants\.glsl:\d+: MR_TRAITS_CONE: 'MR_TRAIT_SOLIDS' is not a MR_TRAIT_\* defined above it")
case("a bit shared", lambda t: re.sub(r"#define MR_TRAIT_TILES \d+", "#define MR_TRAIT_TILES 8", t),
     r"variants\.glsl:\d+: MR_TRAIT_TILES is 8: each trait is a power of two of its own")
case("a bit not a power of two", lambda t: re.sub(r"#define MR_TRAIT_TILES \d+", "#define MR_TRAIT_TILES 12", t),
     r"variants\.glsl:\d+: MR_TRAIT_TILES is 12: each trait is a power of two of its own")

# The bases' rows: the real ones accepted, the sphere one radius for the ellipsoid's three.
run = generate(ROOT / "shaders" / "microrelief", BASES)
if run.returncode != 0:
    failures.append(f"the real variants.glsl's bases: {run.stderr.strip()}")
elif ("{field: 'base.radius', label: 'Radius', member: 'radii', memberWidth: 3, count: 1, "
      "defaults: Object.freeze([0.5])" not in run.stdout):
    failures.append("the real variants.glsl: kBaseRows does not give the sphere its radius")

SPHERE = '//@size base.radius "Radius" radii[3] = 0.5\n'


def bases(name, edit, expected):
    case(name, edit, expected, BASES)


bases("a row without its summary", lambda t: t.replace('//@base plane PLANE "the plane', '//@base plane PLANE the plane'),
      r'variants\.glsl:\d+: not a row this generator reads \(//@base NAME KIND "summary"\)')
bases("a tag with a space", lambda t: t.replace("//@base cylinder ", "// @base cylinder "),
      r"variants\.glsl:\d+: not a row this generator reads")
bases("an unknown tag", lambda t: t.replace("//@size base.length", "//@sizes base.length"),
      r"variants\.glsl:\d+: '//@sizes' is not a tag of variants\.glsl")
bases("a size above every row", lambda t: t.replace("//@base plane ", SPHERE + "//@base plane "),
      r"variants\.glsl:\d+: a size above every row")
bases("a kind that is no member", lambda t: t.replace("//@base sphere ELLIPSOID", "//@base sphere BALL"),
      r"variants\.glsl:\d+: //@base sphere: 'BALL' is not a member of MR_BASE_\*")
bases("a name twice", lambda t: t.replace("//@base sphere ", "//@base ellipsoid "),
      r"variants\.glsl:\d+: //@base ellipsoid: the name is a row's above")
bases("two defaults for three", lambda t: t.replace("radii[3] = 0.5 0.5 0.5 example", "radii[3] = 0.5 0.5 example"),
      r"variants\.glsl:\d+: //@size base\.radii of ellipsoid: 2 defaults for radii\[3\]")
bases("a size of zero", lambda t: t.replace("length = 1\n", "length = 0\n"),
      r"variants\.glsl:\d+: //@size base\.length of cylinder: its defaults '0': a size is positive and finite")
bases("a size not a number", lambda t: t.replace("length = 1\n", "length = one\n"),
      r"variants\.glsl:\d+: //@size base\.length of cylinder: its defaults 'one' is not numbers")
bases("a field of two counts", lambda t: t.replace(SPHERE, SPHERE.replace("= 0.5", "= 0.5 0.5 0.5")),
      r"variants\.glsl:\d+: //@size base\.radius of sphere: 3 numbers, where cylinder's base\.radius is 1")
bases("a member of two widths", lambda t: t.replace(SPHERE, SPHERE.replace("radii[3]", "radii[2]")),
      r"variants\.glsl:\d+: //@size base\.radius of sphere: radii\[2\], where ellipsoid's is radii\[3\]")
bases("an example of another count", lambda t: t.replace("example 0.5 0.35 0.4", "example 0.5"),
      r"variants\.glsl:\d+: //@size base\.radii of ellipsoid: its example is 1 numbers, its defaults 3")
bases("a field twice in a row", lambda t: t.replace('//@size base.length "Length" length', '//@size base.radius "Length" length'),
      r"variants\.glsl:\d+: //@size base\.radius of cylinder: the row has the field above")
bases("two rows name the same shapes", lambda t: t.replace('//@size base.radii "Radius" radii[3] = 0.5 0.5 0.5 example 0.5 0.35 0.4',
                                                         '//@size base.radii "Radius" radii[3] = 0.5'),
      r"variants\.glsl: rows ellipsoid and sphere name the same shapes of ELLIPSOID")
bases("two rows take a kind whole", lambda t: t.replace(SPHERE, SPHERE + '//@base ball ELLIPSOID "a ball"\n'
                                                      '//@size base.radii "Radius" radii[3] = 1 1 1\n'),
      r"variants\.glsl: rows ellipsoid and ball both name every ELLIPSOID")
bases("no row takes a kind whole", lambda t: t.replace('//@base ellipsoid ELLIPSOID "the ellipsoid of radii A, B, C about the origin"\n'
                                                     '//@size base.radii "Radius" radii[3] = 0.5 0.5 0.5 example 0.5 0.35 0.4\n', ""),
      r"variants\.glsl: no //@base row takes every shape of ELLIPSOID")

for failure in failures:
    print(f"check_generator: {failure}")
if failures:
    sys.exit(1)
print("check_generator: the methods' and the bases' rows are read, and each slip is refused with its line")
