#!/usr/bin/env python3
"""three_webgpu_equal.py: does microrelief-three's WebGPU entry draw what its WebGL entry draws?

One map (64 x 48, waves and one-texel spikes) on the plane in six views (`oblique` with the
bilinear last level; `lowLive` with the biquadratic, after the WebGPU relief drew with another
map, height scale and last level: its options set live; `ortho` through an orthographic
camera; `corner` into a 96 x 64 viewport of the target; `logDepth` and `logOrtho`, `oblique`
and `ortho` drawn by renderers made with logarithmicDepthBuffer) and on the cylinder (`round`,
biquadratic; with --all also `low` directly and the ellipsoid, bilinear), the library's
shading with the hard self-shadow, a box of three's own half buried in the plane's relief,
drawn 128 x 96 by the WebGL entry (WebGLRenderer, ReliefShadingMaterial) and by the WebGPU entry (WebGPURenderer,
ReliefShadingNodeMaterial) in headless Chromium (SwiftShader for both APIs), each into an
RGBA8 render target, and compared pixel by pixel (three_page/compare.js).

Thresholds (colours in 8-bit steps of the linear output): mean channel difference <= 0.05,
largest <= 8 (a pixel whose ray grazes an edge may differ), pixels differing by more than 2
or in hit/miss <= 0.5 %, hit/miss disagreeing at <= 0.2 % of the pixels; and the scene is
worth comparing (the relief covers at least 20 % of the picture). The page must also write
document.documentElement.dataset.api = 'webgpu' once the WebGPU entry's first frame is drawn,
and the entry refuse in one line, before the pictures: a WebGLRenderer (a TypeError pointing at
'microrelief-three'), a WebGPURenderer without a WebGPU adapter (forceWebGL, three's fallback
to WebGL 2: a ReliefGpuError), the entry's Relief drawn by a WebGLRenderer (a TypeError out
of its render, rather than three's failing to compile a node material), its traceRays
asked for GPU picks (a TypeError: the CPU twin traces this entry's picks), and an albedoMap
with NearestFilter both ways (a TypeError: three's WebGPU gives it no sampler, and the WGSL
would not compile).

Lit (LIT_VIEWS): the relief under three's directional, point and ambient lights, in the WebGL
entry's ReliefStandardMaterial and the WebGPU entry's ReliefStandardNodeMaterial, against three's
own mesh of the same map (MeshStandardMaterial) drawn by both renderers in the same page: the
relief may differ by what the mesh differs by, plus a margin (thresholds and what was measured
at LIT_VIEWS below). With selfShadow (SELF_SHADOW_VIEWS): the library's hard self-shadow towards
three's directional and point lights in both entries' standard materials, held to LIMITS.

Cast (CAST_VIEWS): the relief in both entries' standard materials casting into a directional
light's shadow map (three's WebGPU shadow pass draws it with the material's depthNode) onto
three's own square through it, and casting into it and receiving it, against three's own mesh
of the map doing the same in the same scene.

Picks (comparePicks): in three scenes (the plane, perspective; the plane turned, scaled and
moved, orthographic, biquadratic; the cylinder) three's Raycaster through every pixel's
centre on the WebGPU entry's Relief against the WebGL entry's Relief of the same map and
options (both traced by the CPU twin: relief_host.js), and against the WebGPU picture, drawn
with the relief alone: its hit/miss (alpha) and its points (the pixel centre unprojected at
the depth the relief wrote); the same rays through both entries' traceRays to the bit; the
map's twin memory freed by its dispose. Thresholds at PICK_EQUAL below.

Usage: three_webgpu_equal.py --package DIR (a built microrelief-three: its src/ and
generated/) [--three DIR (three's package; default the package's node_modules/three)]
[--chromium EXE] [--out DIR (VIEW_BASE.png: WebGL | WebGPU | differing pixels; lit_ and mesh_
VIEW_BASE_ROUGHNESS.png, litShadow_, cast_ and castMesh_VIEW_BASE.png)] [--all] [--only refusals|views|albedo|lit|cast|picks (one part alone)]
Exit status 0: equal within the thresholds; 1: not, or a program missing; 77: skipped (chromium
missing and MICRORELIEF_ALLOW_MISSING_BROWSER=1). ctest three.webgpu (label three).
"""
import argparse
import base64
import json
import os
import pathlib
import shutil
import sys
import tempfile

HERE = pathlib.Path(__file__).resolve().parent
REPO = HERE.parent.parent
SKIPPED = 77
# A view, a last level, a base: the suite's cases (about 25 s on two loaded cores, the picks
# included),
# then with --all `low` (what `lowLive` ends with, drawn directly) and the ellipsoid, whose
# traversal SwiftShader runs slowly (about 25 s more).
VIEWS = (("oblique", "bilinear", "plane"), ("lowLive", "biquadratic", "plane"), ("ortho", "bilinear", "plane"),
         ("corner", "bilinear", "plane"), ("round", "biquadratic", "cylinder"), ("logDepth", "bilinear", "plane"),
         ("logOrtho", "bilinear", "plane"))
MORE_VIEWS = (("low", "biquadratic", "plane"), ("round", "bilinear", "ellipsoid"))
LIMITS = {"meanDiff": 0.05, "maxDiff": 8, "differingFraction": 0.005}
HIT_DISAGREE_FRACTION = 0.002
# The relief under three's lights (ReliefStandardMaterial in WebGL, ReliefStandardNodeMaterial
# in WebGPU: directional, point and ambient lights; a view, a last level, a base, the
# materials' roughness). three's WebGL and WebGPU lighting are two codes, so the lit relief is
# held to what three's own mesh of the same map (the heights displaced, MeshStandardMaterial)
# differs by between the two renderers in the same page, plus LIT_MARGINS. At roughness 1
# nothing of three's that depends on the normal's screen derivatives shows (three adds the
# largest derivative of the normal to the roughness, at most 1: getGeometryRoughness, WebGL's
# lights_physical_fragment), and the pictures are as equal as the mesh's (measured: the relief
# bit-identical in both views; the mesh too in `oblique`, in `round` 2 pixels apart at its
# silhouette, by up to 81). Below 1 that sum shows, and the two drivers take their (coarse) derivatives from
# different pixels of a 2 x 2 quad (SwiftShader's GL and Vulkan; measured on the relief: the
# quads whose normal turns within them, e.g. a geometric roughness of 0.25 in WebGL and 0.10 in
# WebGPU over one quad): the relief's normal turns from pixel to pixel far more than the mesh's
# (whose normal is linear across each triangle), so it is held there to LIT_ROUGH_LIMITS, what
# that costs with room (measured at 0.55: the relief mean 1.01, largest 94, 6.8 % of the pixels
# over 2; the mesh mean 0.12, largest 25, 1.1 %). A wrong normal, position or view direction
# shows at roughness 1 already.
LIT_VIEWS = (("oblique", "bilinear", "plane", 1), ("round", "biquadratic", "cylinder", 1), ("oblique", "bilinear", "plane", 0.55))
# The map's colours (albedoMap: a 64 x 48 sRGB texture of stripes and checks, mipmapped), filtered
# over each pixel's footprint by the library's mr_surfaceAlbedo in both entries: in the library's
# own shading (ReliefShadingMaterial against ReliefShadingNodeMaterial) on the plane and the
# cylinder, and under three's lights at roughness 1 (ReliefStandardMaterial against
# ReliefStandardNodeMaterial), held to LIMITS as the views above.
ALBEDO_VIEWS = (("oblique", "bilinear", "plane", "shadingAlbedo"), ("round", "biquadratic", "cylinder", "shadingAlbedo"),
                ("oblique", "bilinear", "plane", "litAlbedo"))
# The library's self-shadow under three's lights (selfShadow: ReliefStandardMaterial against
# ReliefStandardNodeMaterial at roughness 1, the lights of LIT_VIEWS and a raking directional
# light; on the cylinder heightScale 0.4: compare.js's addLights and heightScaleOf): a view, a
# last level, a base. On the plane the WebGPU relief is drawn first without it and then given
# selfShadow: true (the property live, its program made again). The shadow rays are the library's in both entries, traced from the same
# hit towards the same light, so held to LIMITS as the library's own shading (the directional
# light's direction is three's uniform in WebGL, made in the shader in WebGPU: rounded apart,
# it may move a grazing ray's verdict at a pixel or two). Measured: bit-identical, 6 301 and
# 5 655 pixels. The scene must test the shadow: it darkens (by more than 8 in a channel) at
# least SELF_SHADOWED of the relief's pixels in the WebGL picture against the same without it
# (measured: 1 477 of 6 192 and 653 of 5 655).
# three's Fog on the lit relief (ReliefStandardMaterial against ReliefStandardNodeMaterial at
# roughness 1, 'litFog' in compare.js: clear near the camera, a dark blue from 1.5 away), held
# to LIMITS as the lit views; the fog must darken at least FOGGED of the relief's pixels by more
# than 8 (against the same scene without it), or the scene tests little.
FOG_VIEWS = (("oblique", "bilinear", "plane"),)
FOGGED = 0.2
SELF_SHADOW_VIEWS = (("oblique", "bilinear", "plane"), ("round", "biquadratic", "cylinder"))
SELF_SHADOWED = 0.05
# The relief casting into three's shadow map: a directional light's (the raking light of the
# self-shadow's scenes, at 8 times its intensity), BasicShadowMap (the nearest texel: no filter
# of three's own between the two renderers), on three's own grey square through the relief at a
# height inside its range (compare.js: setUp), where the relief's traced bumps cast their
# shadows (its proxy box would shadow the whole square); the relief lit as in LIT_VIEWS at
# roughness 1 and not receiving. As the lit views, against three's own mesh of the map casting
# in the same scene (measured: bit-identical). The two entries write the shadow map's depth
# differently (WebGL's ReliefDepthMaterial packs it into RGBA8, WebGPU writes depth32float), so
# a ground pixel whose depth from the light is within that rounding of the relief's (where the
# square meets the surface) may flip between lit and shadowed, which is the whole light there
# (up to 51 levels): the largest difference is not held, the mean and the pixels over 2 are
# (CAST_MARGINS over the mesh's). Measured: 4 pixels apart (0.03 %), mean 0.016. The scene must
# test it: the relief's shadow darkens at least CAST_SHADOWED of the pixels of the WebGL picture
# against the same scene with the relief not casting. `receive`: the relief casting into that
# map, the point light's cube map and a spot light's (BasicShadowMap too) and receiving them
# (its own shadows, and a ball's of three's own), no bias of the user's, against three's own
# mesh of the map doing the same (its own acne included: measured 3 pixels apart, mean 0.010);
# each entry moves its lookups off the surface by the map's texel (docs/three.md, "Shadow
# acne"), and without that move the lit tops shadow themselves. Measured: 4 pixels apart (0.033
# %, isolated: shadowed in one, lit in the other), mean 0.024; the maps darken 1 727 pixels
# against the relief not receiving them.
CAST_VIEWS = (("oblique", "bilinear", "plane", "cast"), ("oblique", "bilinear", "plane", "receive"))
CAST_MARGINS = {"meanDiff": 0.05, "differingFraction": 0.001}
CAST_SHADOWED = 0.02
LIT_MARGINS = {"meanDiff": 0.05, "maxDiff": 2, "differingFraction": 0.002}
LIT_ROUGH_LIMITS = {"meanDiff": 2, "maxDiff": 128, "differingFraction": 0.12}
# What the WebGPU entry says where it cannot draw (one line each, then the page draws on):
# case: (the error's name, what its message names).
REFUSALS = {
    "webglRenderer": ("TypeError", ["WebGLRenderer", "import from 'microrelief-three'"]),
    "noAdapter": ("ReliefGpuError", ["no WebGPU adapter", "WebGLRenderer", "'microrelief-three'"]),
    "tooLarge": ("ReliefGpuError", ["wide: ", " x 1 is larger than this WebGPU device's maxTextureDimension2D ("]),
    "drawnByWebGL": ("TypeError", ["Relief:", "WebGLRenderer", "import from 'microrelief-three'"]),
    "gpuPicks": ("TypeError", ["Relief.traceRays", "on 'gpu'", "auto or cpu"]),
    "nearestAlbedo": ("TypeError", ["ReliefStandardNodeMaterial", "albedoMap", "NearestFilter", "loadAlbedo"]),
}
# The picks (three's Raycaster through every pixel's centre, the relief alone): a view, a last
# level, a base, and whether the relief is turned, scaled and moved (its matrixWorld).
PICK_VIEWS = (("oblique", "bilinear", "plane", False), ("ortho", "biquadratic", "plane", True),
              ("round", "biquadratic", "cylinder", False))
# The WebGPU entry's picks are the WebGL entry's (the same CPU twin through the same host
# code): given the same rays (traceRays), every value the same to the bit. Through the
# Raycaster each entry's camera makes its own ray, and the WebGPU camera's projection is
# WebGPU's (depth in [0, 1]), so a ray's last bits differ (measured: distances and points up
# to 6e-12 apart, normals 3e-11, on a scene about 1 unit wide): the same pixels hit, and where
# both hit, distance, point, normal and uv within PICK_EQUAL (world units; uv and unit
# normals: absolute), far above a double's rounding and far below a float's (the GPU's picks,
# 1e-7). Against the WebGPU picture (floats on the GPU, the twin's doubles): hit/miss may
# differ where a ray grazes a silhouette, and a grazing pixel's float trace may find another
# bump than the pick's, each at <= PICK_PICTURE_FRACTION of the pixels: the pick's point
# more than kPictureApart (compare.js: 1e-4 world units) from the picture's (the pixel centre
# unprojected at its depth), the mean distance <= PICK_PICTURE_MEAN. Measured: no pixel
# disagreeing, largest 7e-6 apart, mean <= 1.4e-6.
PICK_EQUAL = 1e-9
PICK_PICTURE_MEAN = 1e-5
PICK_PICTURE_FRACTION = 0.002
THREE_FILES = ("three.module.js", "three.core.js", "three.webgpu.js", "three.tsl.js")


def verdict(s):
    """Why stats `s` fail, or an empty list."""
    why = [f"{k} {s[k]:.4g} > {limit}" for k, limit in LIMITS.items() if s[k] > limit]
    if s["hitDisagree"] > HIT_DISAGREE_FRACTION * s["pixels"]:
        why.append(f"hit/miss disagree at {s['hitDisagree']} pixels (> {HIT_DISAGREE_FRACTION:.1%})")
    if s["reliefGl"] < 0.2 * s["pixels"]:
        why.append(f"the relief covers {s['reliefGl']} pixels (< 20 %: the scene tests little)")
    return why


def lit_verdict(relief, mesh, roughness):
    """Why the lit relief's stats fail against the mesh's (three's own difference), or an empty list."""
    if roughness == 1:
        why = [f"{k} {relief[k]:.4g} > {mesh[k]:.4g} + {margin}" for k, margin in LIT_MARGINS.items() if relief[k] > mesh[k] + margin]
    else:
        why = [f"{k} {relief[k]:.4g} > {limit}" for k, limit in LIT_ROUGH_LIMITS.items() if relief[k] > limit]
    if relief["hitDisagree"] > HIT_DISAGREE_FRACTION * relief["pixels"]:
        why.append(f"hit/miss disagree at {relief['hitDisagree']} pixels (> {HIT_DISAGREE_FRACTION:.1%})")
    if relief["hitsGl"] < 0.2 * relief["pixels"]:
        why.append(f"the relief covers {relief['hitsGl']} pixels (< 20 %: the scene tests little)")
    return why


def pick_verdict(s):
    """Why pick stats `s` fail, or an empty list."""
    why = [f"{k} {s[k]:.3g} > {PICK_EQUAL}" for k in ("maxDistance", "maxPoint", "maxNormal", "maxUv") if s[k] > PICK_EQUAL]
    if s["exactDiffer"]:
        why.append(f"the same rays' traceRays differ between the entries in {s['exactDiffer']} values")
    if s["pickDisagree"]:
        why.append(f"the entries' picks disagree on hit/miss at {s['pickDisagree']} pixels")
    if s["pictureDisagree"] > PICK_PICTURE_FRACTION * s["pixels"]:
        why.append(f"picks and picture disagree on hit/miss at {s['pictureDisagree']} pixels (> {PICK_PICTURE_FRACTION:.1%})")
    if s["pictureApart"] > PICK_PICTURE_FRACTION * s["pixels"]:
        why.append(f"picks and picture's points apart at {s['pictureApart']} pixels (> {PICK_PICTURE_FRACTION:.1%})")
    if s["meanPictureApart"] > PICK_PICTURE_MEAN:
        why.append(f"picks and picture's points {s['meanPictureApart']:.3g} apart on average (> {PICK_PICTURE_MEAN})")
    if s["picksGpu"] < 0.2 * s["pixels"]:
        why.append(f"the relief is picked at {s['picksGpu']} pixels (< 20 %: the scene tests little)")
    if not s["twinBytes"] > 0 or s["twinBytesDisposed"] != 0:
        why.append(f"the map's twin holds {s['twinBytes']} bytes after the picks, {s['twinBytesDisposed']} after its dispose")
    return why


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--package", required=True, help="a built microrelief-three (src/, generated/)")
    parser.add_argument("--three", default=str(REPO / "packages/microrelief-three/node_modules/three"))
    parser.add_argument("--chromium", default="chromium")
    parser.add_argument("--out", help="where to write VIEW_BASE.png")
    parser.add_argument("--all", action="store_true", help="the ellipsoid too (slow on SwiftShader)")
    parser.add_argument("--only", choices=("refusals", "views", "albedo", "lit", "cast", "picks"), help="one part of the check alone")
    args = parser.parse_args()
    package, three = pathlib.Path(args.package), pathlib.Path(args.three)
    lacking = [] if shutil.which(args.chromium) else [f"no chromium ('{args.chromium}' not found: Debian package chromium)"]
    lacking += [f"no {three / 'build' / f} (npm ci in packages/microrelief-three)" for f in THREE_FILES
                if not (three / "build" / f).is_file()]
    lacking += [f"no {package / d} (build microrelief-three)" for d in ("src/webgpu.js", "generated/wgsl.js")
                if not (package / d).is_file()]
    if lacking:
        if os.environ.get("MICRORELIEF_ALLOW_MISSING_BROWSER") == "1":
            print(f"SKIPPED: {'; '.join(lacking)}")
            return SKIPPED
        print(f"three_webgpu_equal.py: {'; '.join(lacking)}", file=sys.stderr)
        return 1

    sys.path.insert(0, str(REPO / "tests/web"))
    sys.path.insert(0, str(REPO / "web"))
    import drive_chromium
    import serve

    root = pathlib.Path(tempfile.mkdtemp(prefix="microrelief-three-webgpu-"))
    browser, server, status = None, None, 0
    try:
        page = root / "web"
        shutil.copytree(HERE / "three_page", page)
        # Copies, not links: the server serves no link out of its folder.
        for f in THREE_FILES:
            (page / "node_modules/three/build").mkdir(parents=True, exist_ok=True)
            shutil.copy(three / "build" / f, page / "node_modules/three/build" / f)
        for d in ("src", "generated"):
            shutil.copytree(package / d, page / "node_modules/microrelief-three" / d)
        drive_chromium.FLAGS = [*drive_chromium.FLAGS, "--enable-unsafe-webgpu", "--use-webgpu-adapter=swiftshader"]
        server, url = serve.serve(str(root))
        browser = drive_chromium.Browser(shutil.which(args.chromium), str(root / "profile"))
        target = browser.send("Target.createTarget", {"url": "about:blank"}, session=False)["targetId"]
        browser.session = browser.send("Target.attachToTarget", {"targetId": target, "flatten": True},
                                       session=False)["sessionId"]
        browser.send("Page.enable")
        browser.send("Runtime.enable")
        browser.send("Page.navigate", {"url": url})
        browser.wait_event("Page.loadEventFired")
        out = pathlib.Path(args.out) if args.out else None
        if out:
            out.mkdir(parents=True, exist_ok=True)
        evaluate = lambda expression: browser.send("Runtime.evaluate", {"expression": expression, "returnByValue": True,
                                                                          "awaitPromise": True}, timeout=300)
        ready = evaluate("new Promise((done) => { const t = setInterval(() => { if (window.compareEntries) "
                         "{ clearInterval(t); done(true); } }, 50); setTimeout(() => done(false), 30000); })")
        if not ready.get("result", {}).get("value"):
            print("three_webgpu_equal.py: the page did not load (compare.js: its imports?)")
            status = 1
        runs = lambda part: not status and args.only in (None, part)
        answer = evaluate("refusals()") if runs("refusals") else {}
        if runs("refusals"):
            said = json.loads(answer["result"]["value"]) if "exceptionDetails" not in answer else {}
            for case, (name, parts) in REFUSALS.items():
                got = said.get(case, {"name": "", "message": f"refusals() threw: {answer.get('exceptionDetails')}"})
                why = ([f"{got['name'] or 'nothing'} thrown, not a {name}"] if got["name"] != name else [])
                why += ["more than one line"] if "\n" in got["message"] else []
                why += [f"no '{p}'" for p in parts if p not in got["message"]]
                print(f"refusal {case}: {'FAILED: ' + '; '.join(why) if why else 'ok'}: {got['message']}")
                status = status or (1 if why else 0)
        def draw(label, call, png):
            """compare.js's `call` evaluated: its JSON, the strip written to `png` under --out;
            None where it threw (said, as a failure)."""
            nonlocal status
            answer = evaluate(call)
            if "exceptionDetails" in answer:
                details = answer["exceptionDetails"]
                print(f"{label}: FAILED to draw: {(details.get('exception') or {}).get('description', details.get('text'))}")
                status = 1
                return None
            result = json.loads(answer["result"]["value"])
            if out and png:
                (out / png).write_bytes(base64.b64decode(result["png"]))
            return result

        def report(label, why, shown):
            nonlocal status
            print(f"{label}: {'differs: ' + '; '.join(why) if why else 'equal'} {shown}")
            status = status or (1 if why else 0)

        def darkens(stats, least, what):
            """Why a scene whose effect (`what`) darkens fewer than `least` of the relief's pixels tests little."""
            return ([f"{what} darkens {stats['shadowed']} pixels (< {least:.0%} of the relief's: the scene tests little)"]
                    if stats["shadowed"] < least * stats["reliefGl"] else [])

        def compared(label, kind, view, interpolation, base, roughness, png):
            """compareEntries for a picture of `kind` (compare.js; roughness None: its default)."""
            rough = "" if roughness is None else f", {roughness}"
            return draw(label, f"compareEntries({view!r}, {interpolation!r}, {base!r}, {kind!r}{rough})", png)

        # One picture a case, held to LIMITS (and, for the shadows and the fog, to darkening enough).
        single = [(f"{view} {interpolation} {base}", "shading", view, interpolation, base, None, f"{view}_{base}.png", None)
                  for view, interpolation, base in (VIEWS + (MORE_VIEWS if args.all else ())) if runs("views")]
        single += [(f"{kind} {view} {interpolation} {base}", kind, view, interpolation, base, 1, f"{kind}_{view}_{base}.png", None)
                   for view, interpolation, base, kind in ALBEDO_VIEWS if runs("albedo")]
        single += [(f"fog {view} {interpolation} {base}", "litFog", view, interpolation, base, 1, f"litFog_{view}_{base}.png",
                    (FOGGED, "the fog")) for view, interpolation, base in FOG_VIEWS if runs("lit")]
        single += [(f"selfShadow {view} {interpolation} {base}", "litShadow", view, interpolation, base, 1,
                    f"litShadow_{view}_{base}.png", (SELF_SHADOWED, "the self-shadow"))
                   for view, interpolation, base in SELF_SHADOW_VIEWS if runs("lit")]
        for label, kind, view, interpolation, base, roughness, png, effect in single:
            result = compared(label, kind, view, interpolation, base, roughness, png)
            if result is None:
                continue
            why = verdict(result["stats"]) + (darkens(result["stats"], *effect) if effect else [])
            report(label, why, json.dumps(result["stats"]))

        # Two pictures a case: the relief's differences held to three's own mesh's (lit, cast).
        def paired(view, interpolation, base, kinds, roughness, png):
            measured = {}
            for kind in kinds:
                result = compared(f"{kind} {view} {interpolation} {base}", kind, view, interpolation, base, roughness, png(kind))
                if result is None:
                    return None
                measured[kind] = result["stats"]
            return measured

        for view, interpolation, base, roughness in LIT_VIEWS if runs("lit") else ():
            measured = paired(view, interpolation, base, ("mesh", "lit"), roughness, lambda kind: f"{kind}_{view}_{base}_{roughness}.png")
            if measured:
                report(f"lit {view} {interpolation} {base} roughness {roughness}", lit_verdict(measured["lit"], measured["mesh"], roughness),
                       f"relief {json.dumps(measured['lit'])} mesh {json.dumps(measured['mesh'])}")
        for view, interpolation, base, part in CAST_VIEWS if runs("cast") else ():
            measured = paired(view, interpolation, base, (f"{part}Mesh", part), 1, lambda kind: f"{kind}_{view}_{base}.png")
            if not measured:
                continue
            relief, mesh = measured[part], measured[f"{part}Mesh"]
            why = [f"{k} {relief[k]:.4g} > {mesh[k]:.4g} + {margin}" for k, margin in CAST_MARGINS.items() if relief[k] > mesh[k] + margin]
            if relief["hitDisagree"] > HIT_DISAGREE_FRACTION * relief["pixels"]:
                why.append(f"hit/miss disagree at {relief['hitDisagree']} pixels (> {HIT_DISAGREE_FRACTION:.1%})")
            if relief["shadowed"] < CAST_SHADOWED * relief["pixels"]:
                why.append(f"the shadow map darkens {relief['shadowed']} pixels (< {CAST_SHADOWED:.0%}: the scene tests little)")
            report(f"{part} {view} {interpolation} {base}", why, f"relief {json.dumps(relief)} mesh {json.dumps(mesh)}")
        for view, interpolation, base, model in PICK_VIEWS if runs("picks") else ():
            answer = evaluate(f"comparePicks({view!r}, {interpolation!r}, {base!r}, {'true' if model else 'false'})")
            what = f"picks {view} {interpolation} {base}{' turned' if model else ''}"
            if "exceptionDetails" in answer:
                details = answer["exceptionDetails"]
                print(f"{what}: FAILED: {(details.get('exception') or {}).get('description', details.get('text'))}")
                status = 1
                continue
            stats = json.loads(answer["result"]["value"])
            why = pick_verdict(stats)
            print(f"{what}: {'differ: ' + '; '.join(why) if why else 'equal'} {json.dumps(stats)}")
            status = status or (1 if why else 0)
        api = evaluate("document.documentElement.dataset.api || ''").get("result", {}).get("value")
        if api != "webgpu" and args.only in (None, "views", "lit"):
            print(f"document.documentElement.dataset.api is '{api}', not 'webgpu'")
            status = 1
        for line in drive_chromium.page_log(browser.events):
            print(f"page: {line}", file=sys.stderr)
    except (drive_chromium.StepFailed, OSError) as e:
        print(f"three_webgpu_equal.py: {e}", file=sys.stderr)
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
