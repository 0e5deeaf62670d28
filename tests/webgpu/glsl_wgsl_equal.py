#!/usr/bin/env python3
"""glsl_wgsl_equal.py: does naga's WGSL of the library trace, shadow and shade as the GLSL does?

For each base (plane, cylinder, ellipsoid) and last level (bilinear, biquadratic): the test
entry (entry.frag) assembled from the repository's shaders/ as ES 3.00 for WebGL 2, and from
--wgsl-shaders (default the same) as GLSL 4.50 and translated to WGSL by naga (translate.mjs);
both drawn in headless Chromium (tests/web/drive_chromium.py; WebGL 2 and WebGPU on
SwiftShader) over the same 160 x 120 rays through the same map (make_map.mjs), and every
output compared pixel by pixel (page/equal.js). docs/webgpu.md gives the results.

A case passes when the hit kinds, traversal iterations, stop levels and hard shadows are
equal at every pixel and t, the normals, the soft shadow and the colour agree to 1e-6
relative (t) and 1e-5 absolute (the rest: unit vectors and fractions in [0, 1]; on SwiftShader
all but one soft-shadow pixel of 115200 are bit-identical, that one 1.5e-6 apart), and the
scene is worth comparing (hits, shadowed pixels, penumbrae). For each case, tracers.frag (every
tracer of the library, the peers too) is translated and compiled, not drawn: each without a
message from Chromium's WebGPU. With --generated, the package's
built WGSL (generated/wgsl.js: one module a variant, scripts/build.mjs) is compiled too, each
module without a message from Chromium's WebGPU (Tint refuses what naga's validator lets by,
such as two pointer arguments into one variable). In ctest as web.wgsl
(tests/webgpu/CMakeLists.txt) on two cases, plane_bilinear and cylinder_biquadratic.

Needs chromium, node and naga-wasm (`npm ci` in packages/microrelief-three): where chromium or
naga-wasm is missing it fails saying so, or skips (exit status 77, a line saying what is
missing) under MICRORELIEF_ALLOW_MISSING_BROWSER=1, as the web and three suites do.

Usage: tests/webgpu/glsl_wgsl_equal.py [--wgsl-shaders DIR] [--generated DIR] [--chromium EXE]
           [--out DIR] [CASE ...]
Exit status 0: every case passed; 1: a case differed or failed to draw, or a program is missing;
2: a translation failed; 77: skipped (a program missing, and MICRORELIEF_ALLOW_MISSING_BROWSER=1).
"""
import argparse
import base64
import json
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

HERE = pathlib.Path(__file__).resolve().parent
REPO = HERE.parent.parent
CASES = {  # name: (base, MICRORELIEF_BASE, MICRORELIEF_INTERPOLATION), values of variants.glsl
    "plane_bilinear": ("plane", 0, 0), "plane_biquadratic": ("plane", 0, 1),
    "cylinder_bilinear": ("cylinder", 1, 0), "cylinder_biquadratic": ("cylinder", 1, 1),
    "ellipsoid_bilinear": ("ellipsoid", 2, 0), "ellipsoid_biquadratic": ("ellipsoid", 2, 1),
}
WGSL_MJS = REPO / "packages/microrelief-three/scripts/wgsl.mjs"  # the translator, as the package's build runs it
SKIPPED = 77  # ctest's SKIP_RETURN_CODE for web.wgsl
# node -e: writes each module of a built generated/wgsl.js (argv[1]) as package_NAME.wgsl into
# argv[2] and prints the names; refuses a package built without the WGSL.
PACKAGE_WGSL = """
import * as fs from 'node:fs';
import * as path from 'node:path';
import {pathToFileURL} from 'node:url';
const m = await import(pathToFileURL(process.argv[1]).href);
if (m.unavailable) throw new Error(m.unavailable);
for (const [name, text] of Object.entries(m.wgsl)) fs.writeFileSync(path.join(process.argv[2], `package_${name}.wgsl`), text);
console.log(Object.keys(m.wgsl).join(' '));
"""


def missing(chromium):
    """What this machine lacks to run the check (one line each), or an empty list."""
    why = [] if shutil.which(chromium) else [f"no chromium ('{chromium}' not found: Debian package chromium)"]
    if not shutil.which("node"):
        return why + ["no node (Debian package nodejs)"]
    naga = subprocess.run(["node", str(WGSL_MJS), "--version"], capture_output=True, text=True)
    if naga.returncode:
        why.append(naga.stderr.strip() or f"{WGSL_MJS.relative_to(REPO)} --version failed")
    return why


def verdict(s):
    """Why case stats `s` fail, or an empty list."""
    why = [f"{k} at {s[k]} pixels" for k in ("kindDiffer", "iterationsDiffer", "stopLevelDiffer", "hardDiffer")
           if s[k]]
    why += [f"{k} {s[k]:.3g} > {limit}" for k, limit in (("tMaxRel", 1e-6), ("normalMax", 1e-5), ("softMax", 1e-5),
                                                         ("colorMax", 1e-5), ("positionMax", 1e-4)) if s[k] > limit]
    why += [f"no {k} (the scene tests nothing there)" for k in ("hitsGl", "shadowedGl", "penumbraGl") if not s[k]]
    why += [f"{k} {s[k]} (a traversal ran out of its budget)" for k in ("exhaustedGl", "exhaustedGpu") if s[k]]
    return why


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("cases", nargs="*", metavar="CASE", help=", ".join(CASES) + " (default: all)")
    parser.add_argument("--wgsl-shaders", default=str(REPO / "shaders"), help="the shaders/ naga translates")
    parser.add_argument("--generated", help="a built microrelief-three's generated/ (make_map.mjs's default if unset)")
    parser.add_argument("--chromium", default="chromium", help="the browser (default: chromium on PATH)")
    parser.add_argument("--out", help="where to write CASE.png (WebGL 2 | WebGPU | differing pixels in white)")
    args = parser.parse_args()
    unknown = [c for c in args.cases if c not in CASES]
    if unknown:
        parser.error(f"no case {', '.join(unknown)} (the cases: {', '.join(CASES)})")
    cases = args.cases or list(CASES)
    lacking = missing(args.chromium)
    if lacking:
        if os.environ.get("MICRORELIEF_ALLOW_MISSING_BROWSER") == "1":
            print(f"SKIPPED: {'; '.join(lacking)}")
            return SKIPPED
        print(f"glsl_wgsl_equal.py: {'; '.join(lacking)}; MICRORELIEF_ALLOW_MISSING_BROWSER=1 skips this check instead",
              file=sys.stderr)
        return 1

    sys.path.insert(0, str(REPO / "tests/web"))
    sys.path.insert(0, str(REPO / "web"))
    import drive_chromium
    import serve

    root = pathlib.Path(tempfile.mkdtemp(prefix="microrelief-webgpu-"))
    browser, server, status = None, None, 0
    try:
        page = root / "web"
        shutil.copytree(HERE / "page", page)
        node = lambda *a: subprocess.run(["node", *map(str, a)], capture_output=True, text=True)
        made = node(HERE / "make_map.mjs", page / "map.json", *([args.generated] if args.generated else []))
        if made.returncode:
            print(made.stderr.strip(), file=sys.stderr)
            return 2
        for name in cases:
            _, base, interpolation = CASES[name]
            defines = ["--define", f"MICRORELIEF_BASE={base}", "--define", f"MICRORELIEF_INTERPOLATION={interpolation}"]
            es = node(HERE / "translate.mjs", "--entry", HERE / "entry.frag", "--out", page / f"{name}.es.frag", *defines)
            wgsl = node(HERE / "translate.mjs", "--entry", HERE / "entry.frag", "--out", page / f"{name}.wgsl", "--wgsl",
                        "--shaders", args.wgsl_shaders, *defines)
            tracers = node(HERE / "translate.mjs", "--entry", HERE / "tracers.frag", "--out", page / f"{name}.tracers.wgsl",
                           "--wgsl", "--shaders", args.wgsl_shaders, *defines)
            for done in (es, wgsl, tracers):
                if done.returncode:
                    print(f"{name}: {done.stderr.strip()}", file=sys.stderr)
                    status = 2
        if status:
            return status
        # The package's built WGSL (generated/wgsl.js, one module a variant), each compiled below.
        package_wgsl = []
        if args.generated:
            listed = node("--input-type=module", "-e", PACKAGE_WGSL, pathlib.Path(args.generated).resolve() / "wgsl.js", page)
            if listed.returncode:
                print(f"glsl_wgsl_equal.py: {args.generated}/wgsl.js: {listed.stderr.strip()}", file=sys.stderr)
                return 1
            package_wgsl = listed.stdout.split()

        drive_chromium.FLAGS = [*drive_chromium.FLAGS, "--enable-unsafe-webgpu", "--use-webgpu-adapter=swiftshader"]
        server, url = serve.serve(str(root))
        browser = drive_chromium.Browser(shutil.which(args.chromium), str(root / "profile"))
        target = browser.send("Target.createTarget", {"url": "about:blank"}, session=False)["targetId"]
        browser.session = browser.send("Target.attachToTarget", {"targetId": target, "flatten": True},
                                       session=False)["sessionId"]
        browser.send("Page.enable")
        browser.send("Runtime.enable")
        browser.send("Page.navigate", {"url": url})  # the server's root is web/: index.html
        browser.wait_event("Page.loadEventFired")
        out = pathlib.Path(args.out) if args.out else None
        if out:
            out.mkdir(parents=True, exist_ok=True)
        for name in cases:
            answer = browser.send("Runtime.evaluate", {"expression": f"runCase({name!r}, {CASES[name][0]!r})",
                                                       "returnByValue": True, "awaitPromise": True}, timeout=600)
            if "exceptionDetails" in answer:
                details = answer["exceptionDetails"]
                print(f"{name}: FAILED to draw: {(details.get('exception') or {}).get('description', details.get('text'))}")
                status = 1
                continue
            result = json.loads(answer["result"]["value"])
            if out:
                (out / f"{name}.png").write_bytes(base64.b64decode(result["png"]))
            why = verdict(result["stats"])
            print(f"{name}: {'differs: ' + '; '.join(why) if why else 'equal'} {json.dumps(result['stats'])}")
            status = status or (1 if why else 0)
        compiled = [(f"{name} tracers", f"{name}.tracers.wgsl") for name in cases]
        compiled += [(f"package {name}", f"package_{name}.wgsl") for name in package_wgsl]
        for what, file in compiled:
            answer = browser.send("Runtime.evaluate", {"expression": f"compileWgsl({file!r})",
                                                       "returnByValue": True, "awaitPromise": True}, timeout=120)
            messages = json.loads(answer["result"]["value"]) if "exceptionDetails" not in answer else [
                f"FAILED: {answer['exceptionDetails'].get('text')}"]
            print(f"{what}: {'compiles' if not messages else '; '.join(messages[:3])}")
            status = status or (1 if messages else 0)
        for line in drive_chromium.page_log(browser.events):
            print(f"page: {line}", file=sys.stderr)
    except (drive_chromium.StepFailed, OSError) as e:
        print(f"glsl_wgsl_equal.py: {e}", file=sys.stderr)
        status = 1
    finally:
        if browser:
            browser.close()
        if server:
            server.shutdown()
        shutil.rmtree(root, ignore_errors=True)
    return status


if __name__ == "__main__":
    sys.exit(main())
