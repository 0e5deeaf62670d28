#!/usr/bin/env python3
"""page_webgpu_equal.py: does the page (web/) draw on WebGPU what it draws on WebGL 2?

The page as the build stages it (share/microrelief: web/, shaders/, assets/, the page's
naga-wasm in web/generated/naga/), served by web/serve.py, in headless Chromium with WebGPU on
SwiftShader (--enable-unsafe-webgpu --use-webgpu-adapter=swiftshader) and WebGL 2 on
SwiftShader (tests/web/drive_chromium.py). Each case is one view (clean=1, the canvas alone)
drawn with api=webgpu and with api=webgl2; the two screenshots are compared pixel by pixel.

Thresholds, 8-bit channels of the page's canvas: mean channel difference <= 0.05, largest <= 8,
pixels differing by more than 2 <= 0.5 % of the picture; and each picture is worth comparing
(at least 20 % of its pixels are not the background, its top left pixel's colour). Why these: both paths trace the same
GLSL (naga's WGSL of relief.frag in WebGPU) through the same pyramids (read back from the
WebGL builder) with every pixel's ray made bit for bit as in WebGL (relief_gpu.js), so on
SwiftShader the pictures are expected to be identical (measured: every case here, every
pixel); the margins are three.webgpu's, for a driver that rounds one ray's grazing edge
differently. A wrong flip, a wrong ray, a wrong texel or a shading change is far past them.

Also: document.documentElement.dataset.api is the API asked for once the picture is drawn;
without the api key the page picks WebGPU for a view it can draw (multilevel) and WebGL 2 for
one it cannot (maxmip); api=webgpu with a method the WebGPU path does not draw (cone) is an
error in one line starting 'api=webgpu: ', nothing drawn (data-api unset); a value the key
does not take is an error naming the key; maxmip chosen in the panel is refused there in one
line under api=webgpu (the view kept, on WebGPU), and drawn in WebGL 2 without the key.

Usage: page_webgpu_equal.py --root DIR (the build's share/microrelief) [--chromium EXE]
[--out DIR (CASE.png: WebGL 2 | WebGPU | differing pixels in white, for every case)]
[--only CASE ... (these views alone; the checks of the key run always)]
Exit status 0: equal within the thresholds; 1: not, or a program missing; 77: skipped (chromium
or the staged naga-wasm missing and MICRORELIEF_ALLOW_MISSING_BROWSER=1). ctest web.webgpu_page (label web).
"""
import argparse
import os
import pathlib
import shutil
import struct
import sys
import tempfile
import time
import zlib

HERE = pathlib.Path(__file__).resolve().parent
REPO = HERE.parent.parent
SKIPPED = 77
SIZE = (160, 120)
# name -> the page's query (without api, clean and size): bases, last levels, cameras,
# shadows, the albedo, a debug view.
# The WebGPU picture of the first case is drawn without the api key: the page's own choice.
# (The ellipsoid is left out: SwiftShader's Vulkan takes about 12 s to compile its variant.)
CASES = {
    "plane_bilinear_hard": "shadows=hard",
    "plane_biquadratic_low": "interpolation=biquadratic&eye=0.9,0.12,0.5&target=0,0.01,0&albedo=none",
    "plane_bilinear_above_soft": "eye=0.05,0.9,0.25&target=0,0,0&shadows=soft&light-size=4",
    "plane_bilinear_inside": "eye=0.42,0.098,0.4&target=0,0.02,0&fovy=70",
    "cylinder_biquadratic_normals": "base=cylinder&interpolation=biquadratic&eye=1.2,0.6,1.1&target=0,0,0&shadows=hard&view=normal",
}
LIMITS = {"mean": 0.05, "max": 8, "differing": 0.005}
WORTH = 0.2


def decode_png(data):
    """8-bit RGB or RGBA, not interlaced (Chromium's screenshots): (width, height, rows of RGB)."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in (2, 6) or interlace:
        raise ValueError(f"PNG of depth {depth}, colour type {colour}, interlace {interlace}")
    channels = 3 if colour == 2 else 4
    raw, stride, rows, previous = zlib.decompress(idat), width * channels, [], bytearray(width * channels)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - channels] if x >= channels else 0
            b, c = previous[x], previous[x - channels] if x >= channels else 0
            if kind == 1:
                line[x] = (line[x] + a) & 255
            elif kind == 2:
                line[x] = (line[x] + b) & 255
            elif kind == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line[k] for x in range(width) for k in range(x * channels, x * channels + 3)))
        previous = line
    return width, height, rows


def encode_png(width, height, rows):
    chunk = lambda kind, body: struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    raw = b"".join(b"\0" + row for row in rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def compare(gl, gpu, background):
    """Statistics of two pictures (decode_png's), and the rows of GL | GPU | differing pixels."""
    width, height = gl[0], gl[1]
    total, largest, differing, covered, shown = 0, 0, 0, 0, []
    for y in range(height):
        a, b = gl[2][y], gpu[2][y]
        marks = bytearray()
        for x in range(width):
            d = [abs(a[3 * x + k] - b[3 * x + k]) for k in range(3)]
            total += sum(d)
            largest = max(largest, *d)
            differing += max(d) > 2
            covered += tuple(a[3 * x:3 * x + 3]) != background
            marks += b"\xff\xff\xff" if max(d) > 0 else b"\0\0\0"
        shown.append(a + b + bytes(marks))
    n = width * height
    return {"mean": total / (3 * n), "max": largest, "differing": differing / n, "covered": covered / n}, shown


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--root", required=True, help="the build's share/microrelief")
    parser.add_argument("--chromium", default="chromium")
    parser.add_argument("--out", help="a folder for the pictures")
    parser.add_argument("--only", nargs="*", help="these cases alone")
    args = parser.parse_args()
    allow_missing = os.environ.get("MICRORELIEF_ALLOW_MISSING_BROWSER") == "1"
    chromium = shutil.which(args.chromium)
    root = pathlib.Path(args.root)
    lacking = [] if chromium else [f"no {args.chromium} (Debian package chromium)"]
    lacking += [f"no {root / f} (build the project)" for f in ("web/relief_gpu.js", "web/generated/naga/index.js")
                if not (root / f).is_file()]
    naga = (root / "web/generated/naga/wasm/naga_bg.wasm").is_file()
    if not naga:
        lacking.append("the build has no naga-wasm (npm ci in packages/microrelief-three, then configure again): "
                       "the page has no WebGPU path to compare")
    if lacking:
        if allow_missing and (not chromium or not naga):
            print(f"SKIPPED: {'; '.join(lacking)}")
            return SKIPPED
        print(f"page_webgpu_equal.py: {'; '.join(lacking)}", file=sys.stderr)
        return 1

    sys.path.insert(0, str(REPO / "tests/web"))
    sys.path.insert(0, str(root / "web"))
    import drive_chromium
    import serve
    # WebGPU on SwiftShader, its canvases shown through Vulkan on SwiftShader (drive_chromium.py
    # --webgpu's flags: without Vulkan for the compositor Chromium here loses the page's WebGPU
    # device at its first frame, no shared image for the canvas's swap chain).
    drive_chromium.FLAGS = [*drive_chromium.FLAGS, *drive_chromium.WEBGPU_FLAGS]
    scratch = pathlib.Path(tempfile.mkdtemp(prefix="microrelief-page-webgpu-"))
    out = pathlib.Path(args.out) if args.out else None
    if out:
        out.mkdir(parents=True, exist_ok=True)
    server, url = serve.serve(str(root))
    browser, failures = None, []
    state_js = ("JSON.stringify({api: document.documentElement.dataset.api || '', "
                "state: document.documentElement.dataset.state, error: document.getElementById('error').textContent})")
    try:
        browser = drive_chromium.Browser(chromium, str(scratch / "profile"))
        targets = browser.send("Target.getTargets", session=False)["targetInfos"]
        target = [t for t in targets if t["type"] == "page"][0]["targetId"]
        browser.session = browser.send("Target.attachToTarget", {"targetId": target, "flatten": True},
                                       session=False)["sessionId"]
        for domain in ("Page.enable", "Runtime.enable", "DOM.enable"):
            browser.send(domain)
        import json

        def visit(query, shot=None):
            steps = [{"open": f"{query}&clean=1&size={SIZE[0]}x{SIZE[1]}".lstrip("&"), "size": list(SIZE)},
                     {"wait": "ready"}, {"eval": state_js}]
            if shot:
                steps.append({"screenshot": str(shot)})
            started = time.monotonic()
            outcome = drive_chromium.run_steps(browser, url, steps, 120)
            if os.environ.get("PAGE_WEBGPU_TIMES"):
                print(f"  {query}: {time.monotonic() - started:.1f} s")
            return json.loads(outcome[2]["value"])

        # The key, the automatic choice and the refusal.
        checks = [("method=maxmip", "webgl2", "ready", ""),
                  ("api=webgpu&method=cone", "", "error", "api=webgpu: the page's WebGPU path draws the multilevel method only"),
                  ("api=webgl", "", "error", "the URL: api=webgl: expected webgpu, webgl2")]
        for query, api, state, error in checks:
            got = visit(query)
            print(f"{query}: data-api {got['api'] or '(none)'}, {got['state']}{', ' + got['error'] if got['error'] else ''}")
            if got["api"] != api or got["state"] != state or not got["error"].startswith(error) or \
                    (error and "\n" in got["error"]) or (not error and got["error"]):
                failures.append(f"{query}: expected data-api '{api}', state {state}"
                                f"{', the error ' + repr(error) if error else ''}; got {got}")

        # The panel: method=maxmip chosen there is refused in one line under api=webgpu (the
        # view stays multilevel, on WebGPU); without the key the page goes on in WebGL 2.
        choose = ("new Promise((resolve) => { const m = document.getElementById('method'); m.value = 'maxmip';"
                  " m.dispatchEvent(new Event('change')); const root = document.documentElement, started = Date.now();"
                  " const poll = () => { if (Date.now() - started > 30000 || (root.dataset.state !== 'loading'"
                  " && (root.dataset.api === 'webgl2' || document.getElementById('input-error').textContent)))"
                  " resolve(JSON.stringify({api: root.dataset.api, state: root.dataset.state,"
                  " refused: document.getElementById('input-error').textContent, method: m.value}));"
                  " else setTimeout(poll, 100); }; poll(); })")
        for query, expected in (("api=webgpu", {"api": "webgpu", "state": "ready", "method": "multilevel",
                                                "refused": "api=webgpu: the page's WebGPU path draws the multilevel method only, "
                                                           "not method=maxmip (drawn in WebGL 2: api=webgl2, or no api key)"}),
                                ("method=multilevel", {"api": "webgl2", "state": "ready", "method": "maxmip", "refused": ""})):
            outcome = drive_chromium.run_steps(browser, url, [
                {"open": f"{query}&size={SIZE[0]}x{SIZE[1]}", "size": list(SIZE)}, {"wait": "ready"}, {"eval": choose}], 120)
            got = json.loads(outcome[2]["value"])
            print(f"{query}, maxmip chosen in the panel: {got}")
            if got != expected:
                failures.append(f"{query}, maxmip chosen in the panel: expected {expected}, got {got}")

        for name, query in CASES.items():
            if args.only and name not in args.only:
                continue
            pictures = {}
            for api in ("webgl2", "webgpu"):
                shot = scratch / f"{name}_{api}.png"
                chosen = api == "webgpu" and name == next(iter(CASES))
                got = visit(query if chosen else f"{query}&api={api}", shot)
                if got["api"] != api or got["state"] != "ready":
                    failures.append(f"{name}: api={api} drew nothing ({got})")
                    break
                pictures[api] = decode_png(shot.read_bytes())
            if len(pictures) < 2:
                continue
            stats, shown = compare(pictures["webgl2"], pictures["webgpu"], tuple(pictures["webgl2"][2][0][0:3]))
            print(f"{name}: mean {stats['mean']:.4f}, largest {stats['max']}, differing {100 * stats['differing']:.2f} %, "
                  f"relief {100 * stats['covered']:.0f} % of the picture")
            if out:
                (out / f"{name}.png").write_bytes(encode_png(3 * SIZE[0], SIZE[1], shown))
            over = [k for k in LIMITS if stats[k] > LIMITS[k]]
            if over or stats["covered"] < WORTH:
                failures.append(f"{name}: " + (f"past the limits in {', '.join(over)} ({stats}; limits {LIMITS})" if over
                                               else f"the relief covers {100 * stats['covered']:.0f} % (< {100 * WORTH:.0f} %)"))
        for line in drive_chromium.page_log(browser.events):
            print(f"page: {line}")
    except (drive_chromium.StepFailed, OSError) as e:
        failures.append(str(e))
    finally:
        if browser:
            browser.close()
        server.shutdown()
        shutil.rmtree(scratch, ignore_errors=True)
    for f in failures:
        print(f"FAILED: {f}", file=sys.stderr)
    print("page_webgpu_equal.py: " + ("failed" if failures else "the WebGPU pictures are the WebGL 2 pictures within the limits"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
