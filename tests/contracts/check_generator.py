#!/usr/bin/env python3
"""check_generator.py ROOT: cmake/generate_contracts.py reads the methods' rows of
shaders/microrelief/variants.glsl (MR_TRAIT_*, MR_TRAITS_*) as the build does, and refuses,
naming the file and the line, each slip a row can make: a method without a row, a row of no
method, a row twice, a trait it does not define, a bit shared or not a power of two. Each
case edits a copy of the shaders; the build's own files are not touched."""
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(sys.argv[1])
SCRIPT = ROOT / "cmake" / "generate_contracts.py"
SPEC = "variants.glsl:MR_METHOD:Method:MR_TRAIT:MR_TRAITS"
failures = []


def generate(shaders):
    return subprocess.run([sys.executable, str(SCRIPT), "--block", str(ROOT / "shaders" / "relief_parameters.glsl"),
                           "--shaders", str(shaders), "--enums", SPEC, "--js", "-"],
                          capture_output=True, text=True)


def case(name, edit, expected):
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
        run = generate(shaders)
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

for failure in failures:
    print(f"check_generator: {failure}")
if failures:
    sys.exit(1)
print("check_generator: the rows are read, and each slip is refused with its line")
