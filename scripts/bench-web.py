#!/usr/bin/env python3
"""bench-web.py: the web page's frame time on WebGPU against WebGL 2, the same view in the
same headless Chromium (issue 51's measurement; docs/webgpu.md).

For each view and round, the page (the build tree's, as scripts/web.sh serves it) is opened
with api=webgl2 and then api=webgpu (the order alternating round by round), renders every
frame for --seconds, and the panel's frame times (wall time from the draw to the picture
done, web/app.js) are collected; the first --warmup frames of each opening are dropped. Per
round, the ratio WebGPU / WebGL 2 of the two openings' median frame times; per view, the
median of the rounds' ratios with their range, and the medians of the times. On SwiftShader
both APIs run on the CPU: read the ratio, not the times. Writes a Markdown table to stdout
(and --csv FILE).

Usage: python3 scripts/bench-web.py [--root build/share/microrelief] [--rounds 5]
       [--seconds 4] [--size 640x480] [--chromium chromium] [--csv FILE]
Needs a build with the page staged (cmake --build build) and naga-wasm staged with it
(microrelief-three's npm ci), and Chromium; WebGPU on SwiftShader as the tests use it
(tests/web/drive_chromium.py --webgpu).
"""
import argparse
import json
import pathlib
import statistics
import subprocess
import sys
import tempfile

REPO = pathlib.Path(__file__).resolve().parent.parent
DRIVER = REPO / "tests" / "web" / "drive_chromium.py"

# The views: the page's URL keys (docs/browser.md), each drawn by both APIs.
VIEWS = {
    "plane, hard shadows": "shadows=hard",
    "plane, biquadratic": "interpolation=biquadratic&eye=0.7,0.25,0.6",
    "cylinder": "base=cylinder",
}

COLLECT_JS = """(async () => {
  const times = [], label = document.getElementById('frame-time');
  const seen = new MutationObserver(() => {
    const m = /^([0-9.]+) ms/.exec(label.textContent);
    if (m) times.push(Number(m[1]));
  });
  seen.observe(label, {childList: true, characterData: true, subtree: true});
  const every = document.getElementById('continuous');
  every.checked = true;
  every.dispatchEvent(new Event('change'));
  await new Promise((done) => setTimeout(done, MS));
  every.checked = false;
  every.dispatchEvent(new Event('change'));
  seen.disconnect();
  return JSON.stringify({api: document.documentElement.dataset.api, times});
})()"""


def run_round(args, query, order):
    """Opens the view with each API of `order`; returns {api: [frame times, ms]}."""
    steps = []
    for api in order:
        steps += [{"open": f"{query}&api={api}&clean=1", "size": list(args.size)},
                  {"wait": "ready"},
                  {"eval": COLLECT_JS.replace("MS", str(int(args.seconds * 1000)))}]
    with tempfile.TemporaryDirectory(prefix="microrelief-bench-web-") as scratch:
        scratch = pathlib.Path(scratch)
        (scratch / "steps.json").write_text(json.dumps(steps))
        run = subprocess.run([sys.executable, str(DRIVER), "--chromium", args.chromium, "--root", str(args.root),
                              "--steps", str(scratch / "steps.json"), "--out", str(scratch / "out.json"),
                              "--webgpu", "--timeout", str(args.seconds * 4 + 120)],
                             capture_output=True, text=True)
        if run.returncode != 0:
            sys.exit(f"bench-web.py: the browser did not run the view '{query}': {run.stderr.strip()}")
        outcome = json.loads((scratch / "out.json").read_text())["steps"]
    times = {}
    for k, api in enumerate(order):
        state = outcome[3 * k + 1]
        if state.get("state") != "ready":
            sys.exit(f"bench-web.py: api={api} {query}: the page says '{state.get('error')}'")
        value = json.loads(outcome[3 * k + 2]["value"])
        if value["api"] != api:
            sys.exit(f"bench-web.py: api={api} {query}: the page drew with {value['api']}")
        kept = value["times"][args.warmup:]
        if len(kept) < 3:
            sys.exit(f"bench-web.py: api={api} {query}: {len(value['times'])} frames in {args.seconds} s (--seconds longer)")
        times[api] = kept
    return times


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--root", type=pathlib.Path, default=REPO / "build" / "share" / "microrelief",
                        help="the staged site (web/, shaders/, assets/)")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--seconds", type=float, default=4, help="rendering every frame, per opening")
    parser.add_argument("--warmup", type=int, default=2, help="frames dropped at the start of each opening")
    parser.add_argument("--size", default="640x480")
    parser.add_argument("--chromium", default="chromium")
    parser.add_argument("--csv", type=pathlib.Path, help="also every round's medians here")
    args = parser.parse_args()
    try:
        args.size = tuple(int(v) for v in args.size.split("x"))
        assert len(args.size) == 2 and min(args.size) > 0
    except (ValueError, AssertionError):
        sys.exit(f"bench-web.py: --size {args.size}: expected WxH")
    if not (args.root / "web" / "index.html").is_file():
        sys.exit(f"bench-web.py: {args.root}: no web/index.html (build first: cmake --build build)")

    rows, csv = [], ["view,round,webgl2_ms,webgpu_ms,ratio"]
    for name, query in VIEWS.items():
        ratios, gl, gpu = [], [], []
        for r in range(args.rounds):
            order = ("webgl2", "webgpu") if r % 2 == 0 else ("webgpu", "webgl2")
            times = run_round(args, query, order)
            a, b = statistics.median(times["webgl2"]), statistics.median(times["webgpu"])
            gl.append(a)
            gpu.append(b)
            ratios.append(b / a)
            csv.append(f"{name},{r},{a:.2f},{b:.2f},{b / a:.3f}")
            print(f"  {name}, round {r + 1}: WebGL 2 {a:.1f} ms, WebGPU {b:.1f} ms, ratio {b / a:.2f}", file=sys.stderr)
        rows.append((name, statistics.median(gl), statistics.median(gpu), statistics.median(ratios), min(ratios), max(ratios)))
    print(f"| view ({args.size[0]} x {args.size[1]}) | WebGL 2 median ms | WebGPU median ms | WebGPU / WebGL 2 (median of {args.rounds} rounds) | range |")
    print("| --- | --- | --- | --- | --- |")
    for name, a, b, ratio, low, high in rows:
        print(f"| {name} | {a:.1f} | {b:.1f} | {ratio:.2f} | {low:.2f} to {high:.2f} |")
    if args.csv:
        args.csv.write_text("\n".join(csv) + "\n")


if __name__ == "__main__":
    main()
