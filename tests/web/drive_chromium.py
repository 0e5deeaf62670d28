#!/usr/bin/env python3
"""drive_chromium.py: headless Chromium driven through the DevTools protocol, for the web
tests (tests/web/WebPageTest.cpp). The Python standard library only.

Starts the page's own server (web/serve.py) on a free port, then Chromium with
--remote-debugging-pipe (the protocol over file descriptors 3 and 4: no port, no
WebSocket), WebGL 2 through SwiftShader, and runs a list of steps from a JSON file:

  {"open": "QUERY", "size": [W, H]}   the page at web/?QUERY, viewport W x H at DPR 1
                                      (web/PAGE?QUERY with "page": "PAGE", e.g. "three/")
  {"wait": "ready"}                   until <html data-state> is "ready" or "error"
  {"wait": "map-error"}               until <html data-map-error> is not empty
  {"wait": "frames", "above": N}      until data-frames > N and the state is settled
  {"wait": "opened", "above": N}      until data-opened > N (a file dropped or chosen
                                      was shown or refused) and the state is settled
  {"screenshot": "FILE.png"}          the viewport (Page.captureScreenshot), W x H
  {"drop": "FILE"}                    FILE dropped on the page's centre, as a user drops
                                      it (Input.dispatchDragEvent with the file's path)
  {"choose": "FILE"}                  FILE set on the page's file input, as a user
                                      chooses it (DOM.setFileInputFiles: a change event)
  {"drag": [X0, Y0, X1, Y1]}          a left-button drag in 4 moves (Shift held with
                                      "shift": true), as the mouse makes it
  {"wheel": [X, Y, DY]}               a wheel turn of DY pixels at (X, Y)
  {"eval": "EXPRESSION"}              its value (JSON) in the result

Writes {"steps": [...], "log": [...]} to --out: each step's outcome (a wait's state,
data-map, data-map-error, #error's text, data-frames, data-opened; an eval's value), and
the page's console errors and exceptions. With --flat, the same as lines
"STEP.KEY<TAB>VALUE" (STEP from 0, backslashes and newlines escaped as \\ and \n) and
"log<TAB>LINE", for a reader without JSON (the C++ test). Exits 0 when every step ran (whatever the page showed: the test judges), 1
when one could not (a wait timed out, Chromium died), saying why on stderr.
"""
import argparse
import base64
import fcntl
import json
import os
import pathlib
import queue
import shutil
import subprocess
import sys
import tempfile
import threading
import time

FLAGS = [
    "--headless=new",
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
    "--no-sandbox",
    "--no-first-run",
    "--no-default-browser-check",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-quic",
    "--disable-extensions",
    "--disable-dev-shm-usage",
    "--force-color-profile=srgb",
    "--hide-scrollbars",
    "--mute-audio",
    "--remote-debugging-pipe",
]

# With --webgpu: WebGPU on SwiftShader, and its canvases presented through Vulkan on
# SwiftShader too. Without the two Vulkan flags a page that draws WebGPU into a <canvas>
# loses its device at the first frame ("A valid external Instance reference no longer
# exists", Chromium 156 headless); WebGPU into textures alone runs either way.
WEBGPU_FLAGS = [
    "--enable-unsafe-webgpu",
    "--use-webgpu-adapter=swiftshader",
    "--enable-features=Vulkan",
    "--use-vulkan=swiftshader",
]

STATE_JS = """JSON.stringify({state: document.documentElement.dataset.state || '',
  map: document.documentElement.dataset.map || '',
  mapError: document.documentElement.dataset.mapError || '',
  frames: Number(document.documentElement.dataset.frames || 0),
  opened: Number(document.documentElement.dataset.opened || 0),
  error: (document.getElementById('error') || {}).textContent || '',
  shownMapError: (document.getElementById('map-error') || {}).hidden === false
      ? document.getElementById('map-error').textContent : ''})"""


class StepFailed(Exception):
    pass


class Browser:
    def __init__(self, chromium, profile):
        to_browser_r, self.to_browser = os.pipe()
        self.from_browser, from_browser_w = os.pipe()
        # The browser reads the protocol on descriptor 3 and writes it on 4. Its ends are
        # moved above those numbers first (close-on-exec, as Python's own descriptors
        # are), then copied into place in the child, where dup2's copies survive exec.
        child_r = fcntl.fcntl(to_browser_r, fcntl.F_DUPFD_CLOEXEC, 10)
        child_w = fcntl.fcntl(from_browser_w, fcntl.F_DUPFD_CLOEXEC, 10)
        os.close(to_browser_r)
        os.close(from_browser_w)

        def place():
            os.dup2(child_r, 3)
            os.dup2(child_w, 4)

        self.process = subprocess.Popen(
            [chromium, *FLAGS, f"--user-data-dir={profile}", "about:blank"],
            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
            close_fds=False, preexec_fn=place)
        os.close(child_r)
        os.close(child_w)
        self.stderr_lines = []
        threading.Thread(target=self._drain_stderr, daemon=True).start()
        self.messages = queue.Queue()
        self.events = []
        threading.Thread(target=self._read, daemon=True).start()
        self.next_id = 0
        self.session = None

    def _drain_stderr(self):
        for line in self.process.stderr:
            self.stderr_lines.append(line.decode(errors="replace").rstrip())

    def _read(self):
        buffer = b""
        while True:
            chunk = os.read(self.from_browser, 1 << 16)
            if not chunk:
                self.messages.put(None)
                return
            buffer += chunk
            while b"\0" in buffer:
                message, buffer = buffer.split(b"\0", 1)
                self.messages.put(json.loads(message))

    def send(self, method, params=None, session=True, timeout=60):
        self.next_id += 1
        command = {"id": self.next_id, "method": method, "params": params or {}}
        if session and self.session:
            command["sessionId"] = self.session
        os.write(self.to_browser, json.dumps(command).encode() + b"\0")
        deadline = time.monotonic() + timeout
        while True:
            left = deadline - time.monotonic()
            if left <= 0:
                raise StepFailed(f"{method}: no answer from Chromium in {timeout} s")
            try:
                message = self.messages.get(timeout=left)
            except queue.Empty:
                continue
            if message is None:
                raise StepFailed(f"{method}: Chromium closed the connection (exit status {self.process.poll()})\n"
                                 + "\n".join(self.stderr_lines[-20:]))
            if message.get("id") == self.next_id:
                if "error" in message:
                    raise StepFailed(f"{method}: {message['error'].get('message')}")
                return message.get("result", {})
            self.events.append(message)

    def wait_event(self, method, timeout=60):
        """Until the event `method` arrives (or has arrived since the last wait for it)."""
        deadline = time.monotonic() + timeout
        while True:
            for k, e in enumerate(self.events):
                if e.get("method") == method and not e.get("seen"):
                    e["seen"] = True
                    return e.get("params", {})
            left = deadline - time.monotonic()
            if left <= 0:
                raise StepFailed(f"no {method} from Chromium in {timeout} s")
            try:
                message = self.messages.get(timeout=left)
            except queue.Empty:
                continue
            if message is None:
                raise StepFailed(f"waiting for {method}: Chromium closed the connection")
            self.events.append(message)

    def evaluate(self, expression):
        result = self.send("Runtime.evaluate", {"expression": expression, "returnByValue": True,
                                                "awaitPromise": True})
        if "exceptionDetails" in result:
            raise StepFailed(f"evaluating {expression!r}: {result['exceptionDetails'].get('text')}")
        return result["result"].get("value")

    def close(self):
        try:
            self.send("Browser.close", session=False, timeout=5)
        except (StepFailed, OSError):  # gone already
            pass
        try:
            self.process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()


def page_log(events):
    log = []
    for e in events:
        method, params = e.get("method"), e.get("params", {})
        if method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "warning"):
            text = " ".join(str(a.get("value", a.get("description", ""))) for a in params.get("args", []))
            log.append(f"console.{params['type']}: {text}")
        elif method == "Runtime.exceptionThrown":
            details = params.get("exceptionDetails", {})
            log.append(f"exception: {details.get('exception', {}).get('description') or details.get('text')}")
    return log


def run_steps(browser, base_url, steps, timeout):
    outcomes = []
    size = None
    for step in steps:
        outcome = {"step": step}
        if "open" in step:
            size = step["size"]
            browser.send("Emulation.setDeviceMetricsOverride",
                         {"width": size[0], "height": size[1], "deviceScaleFactor": 1, "mobile": False})
            for e in browser.events:
                e["seen"] = True
            navigation = browser.send("Page.navigate", {"url": base_url + step.get("page", "") + "?" + step["open"]})
            if "errorText" in navigation:
                raise StepFailed(f"opening the page: {navigation['errorText']}")
            browser.wait_event("Page.loadEventFired", timeout)
        elif "wait" in step:
            deadline = time.monotonic() + timeout
            while True:
                state = json.loads(browser.evaluate(STATE_JS))
                settled = state["state"] in ("ready", "error")
                if step["wait"] == "ready" and settled:
                    break
                if step["wait"] == "map-error" and (state["mapError"] or state["state"] == "error"):
                    break
                if step["wait"] in ("frames", "opened") and settled and \
                        (state[step["wait"]] > step["above"] or state["state"] == "error"):
                    break
                if time.monotonic() > deadline:
                    raise StepFailed(f"waiting for {step['wait']}: still {state} after {timeout} s")
                time.sleep(0.1)
            outcome.update(state)
        elif "screenshot" in step:
            shot = browser.send("Page.captureScreenshot", {
                "format": "png", "captureBeyondViewport": False,
                "clip": {"x": 0, "y": 0, "width": size[0], "height": size[1], "scale": 1}})
            pathlib.Path(step["screenshot"]).write_bytes(base64.b64decode(shot["data"]))
        elif "drop" in step:
            x, y = size[0] / 2, size[1] / 2
            data = {"items": [], "files": [str(pathlib.Path(step["drop"]).resolve())], "dragOperationsMask": 1}
            for kind in ("dragEnter", "dragOver", "drop"):
                browser.send("Input.dispatchDragEvent", {"type": kind, "x": x, "y": y, "data": data})
        elif "choose" in step:
            document = browser.send("DOM.getDocument")
            node = browser.send("DOM.querySelector", {"nodeId": document["root"]["nodeId"], "selector": "#file"})
            browser.send("DOM.setFileInputFiles", {"nodeId": node["nodeId"],
                                                   "files": [str(pathlib.Path(step["choose"]).resolve())]})
        elif "drag" in step:
            x0, y0, x1, y1 = step["drag"]
            modifiers = 8 if step.get("shift") else 0
            mouse = lambda kind, x, y, buttons: browser.send("Input.dispatchMouseEvent", {
                "type": kind, "x": x, "y": y, "button": "left", "buttons": buttons,
                "clickCount": 1, "modifiers": modifiers})
            mouse("mousePressed", x0, y0, 1)
            for k in range(1, 5):
                mouse("mouseMoved", x0 + (x1 - x0) * k / 4, y0 + (y1 - y0) * k / 4, 1)
            mouse("mouseReleased", x1, y1, 0)
        elif "wheel" in step:
            x, y, dy = step["wheel"]
            browser.send("Input.dispatchMouseEvent", {"type": "mouseWheel", "x": x, "y": y,
                                                      "deltaX": 0, "deltaY": dy})
        elif "eval" in step:
            outcome["value"] = browser.evaluate(step["eval"])
        else:
            raise StepFailed(f"unknown step {step}")
        outcomes.append(outcome)
    return outcomes


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--chromium", default=shutil.which("chromium") or "chromium")
    parser.add_argument("--root", required=True, help="the folder holding web/, shaders/ and assets/")
    parser.add_argument("--steps", required=True, help="a JSON file: the list of steps")
    parser.add_argument("--out", required=True, help="the JSON result")
    parser.add_argument("--flat", help="the result as STEP.KEY<TAB>VALUE lines")
    parser.add_argument("--timeout", type=float, default=90, help="seconds a wait may take")
    parser.add_argument("--webgpu", action="store_true", help="give the pages WebGPU (SwiftShader)")
    args = parser.parse_args()
    if args.webgpu:
        FLAGS.extend(WEBGPU_FLAGS)

    sys.path.insert(0, str(pathlib.Path(args.root) / "web"))
    import serve  # web/serve.py: the server scripts/web.sh runs
    server, url = serve.serve(args.root)
    steps = json.loads(pathlib.Path(args.steps).read_text())
    profile = tempfile.mkdtemp(prefix="microrelief-chromium-")
    browser = None
    status, result = 0, {"steps": [], "log": []}
    try:
        browser = Browser(args.chromium, profile)
        targets = browser.send("Target.getTargets", session=False)["targetInfos"]
        pages = [t for t in targets if t["type"] == "page"]
        target = pages[0]["targetId"] if pages else \
            browser.send("Target.createTarget", {"url": "about:blank"}, session=False)["targetId"]
        browser.session = browser.send("Target.attachToTarget", {"targetId": target, "flatten": True},
                                       session=False)["sessionId"]
        for domain in ("Page.enable", "Runtime.enable", "DOM.enable"):
            browser.send(domain)
        result["steps"] = run_steps(browser, url, steps, args.timeout)
    except (StepFailed, OSError) as e:
        print(f"drive_chromium.py: {e}", file=sys.stderr)
        status = 1
    finally:
        if browser:
            result["log"] = page_log(browser.events)
            browser.close()
        server.shutdown()
        shutil.rmtree(profile, ignore_errors=True)
    pathlib.Path(args.out).write_text(json.dumps(result, indent=1))
    if args.flat:
        escape = lambda v: str(v).replace("\\", "\\\\").replace("\n", "\\n")
        lines = [f"{k}.{key}\t{escape(value)}" for k, outcome in enumerate(result["steps"])
                 for key, value in outcome.items() if key != "step"]
        lines += [f"log\t{escape(line)}" for line in result["log"]]
        pathlib.Path(args.flat).write_text("".join(line + "\n" for line in lines))
    for line in result["log"]:
        print(f"page: {line}", file=sys.stderr)
    return status


if __name__ == "__main__":
    sys.exit(main())
