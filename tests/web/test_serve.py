#!/usr/bin/env python3
"""test_serve.py: web/serve.py against a hostile client (CTest label server; no browser).

A scratch root with the page's layout, files outside the served folders that must never
be sent (each holds SECRET), symbolic links out of and within the folders and a FIFO;
then traversals, encodings, NUL, and clients that stall or send a byte at a time, over raw
sockets (http.client would refuse or rewrite the hostile paths). The standard library only.
Usage: test_serve.py PATH/TO/web/serve.py
"""
import importlib.util
import os
import pathlib
import socket
import sys
import tempfile
import threading
import time
import unittest

SECRET = b"SECRET-0b5f"
SERVE_PY = None  # set by main()


def load_serve():
    spec = importlib.util.spec_from_file_location("serve", SERVE_PY)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def make_root(top):
    root = pathlib.Path(top) / "root"
    for folder in ("web/sub", "shaders/microrelief", "assets", ".git", "build/bin"):
        (root / folder).mkdir(parents=True)
    (root / "web/index.html").write_text("<html>page</html>")
    (root / "web/app.js").write_text("export {};")
    (root / "shaders/microrelief/a.glsl").write_text("// a\n")
    (root / "assets/map.png").write_bytes(b"\x89PNG not really")
    for secret in ("README.md", ".git/config", "build/bin/microrelief-render"):
        (root / secret).write_bytes(SECRET)
    (pathlib.Path(top) / "outside.txt").write_bytes(SECRET)
    # Links out of the served folders, to a file and to a folder; one within.
    os.symlink("../README.md", root / "web/escape.md")
    os.symlink(str(pathlib.Path(top) / "outside.txt"), root / "assets/absolute.txt")
    os.symlink("../build", root / "web/build")
    os.symlink("../.git", root / "shaders/git")
    os.symlink("app.js", root / "web/inside.js")
    os.symlink("../web/app.js", root / "shaders/app.js")  # out, if into another served one
    os.mkfifo(root / "shaders/fifo.glsl")
    return root


def exchange(port, data, timeout=5.0):
    """Sends `data` as it is; returns the whole answer (the server closes: HTTP/1.0)."""
    with socket.create_connection(("127.0.0.1", port), timeout=timeout) as s:
        s.sendall(data)
        chunks = []
        while True:
            chunk = s.recv(65536)
            if not chunk:
                return b"".join(chunks)
            chunks.append(chunk)


def get(port, target):
    raw = target if isinstance(target, bytes) else target.encode("latin-1")
    answer = exchange(port, b"GET " + raw + b" HTTP/1.1\r\nHost: localhost\r\n\r\n")
    status = int(answer.split(b" ", 2)[1]) if answer.startswith(b"HTTP/") else None
    return status, answer


class ServeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.serve = load_serve()
        cls.scratch = tempfile.TemporaryDirectory()
        cls.root = make_root(cls.scratch.name)
        cls.server, _ = cls.serve.serve(cls.root, header_seconds=1.0, idle_seconds=1.0,
                                        max_connections=8)
        cls.port = cls.server.server_address[1]

    @classmethod
    def tearDownClass(cls):
        cls.server.shutdown()
        cls.server.server_close()
        cls.scratch.cleanup()

    def expect(self, target, status):
        with self.subTest(target=target):
            got, answer = get(self.port, target)
            self.assertEqual(got, status, answer[:200])
            self.assertNotIn(SECRET, answer)
            self.assertNotIn(b"Directory listing", answer)

    def test_serves_the_page(self):
        for target in ("/web/index.html", "/web/app.js", "/web/app.js?v=1", "/web/inside.js",
                       "/shaders/microrelief/a.glsl", "/shaders/./microrelief//a.glsl",
                       "/assets/map.png", "/web/", "/web/%61pp.js"):
            self.expect(target, 200)
        _, answer = get(self.port, "/web/")
        self.assertIn(b"<html>page</html>", answer)
        _, answer = get(self.port, "/web/app.js")
        self.assertIn(b"Content-Type: text/javascript", answer)
        self.expect("/web", 301)
        self.expect("/", 302)

    def test_traversal_is_refused(self):
        for target in ("/web/../README.md", "/web/%2e%2e/README.md", "/web/%2E%2E/.git/config",
                       "/web/%2e%2e/build/bin/microrelief-render", "/assets/../.git/config",
                       "/web/..%2fREADME.md", "/web/..%2F..%2Foutside.txt", "/web/../",
                       "/web/%2e%2e%2f", "/../README.md", "/shaders/microrelief/../../README.md",
                       "/web/.%2e/README.md"):
            self.expect(target, 400)
        for target in ("/README.md", "/.git/config", "/build/bin/microrelief-render", "//README.md",
                       "/web%2f..%2fREADME.md", "http://localhost/README.md", "/%77eb/../README.md"):
            with self.subTest(target=target):
                status, answer = get(self.port, target)
                self.assertIn(status, (400, 404), answer[:200])
                self.assertNotIn(SECRET, answer)

    def test_symlinks_out_of_a_folder_are_not_followed(self):
        for target in ("/web/escape.md", "/assets/absolute.txt", "/web/build/bin/microrelief-render",
                       "/shaders/git/config", "/web/build/", "/shaders/git/", "/shaders/app.js"):
            self.expect(target, 404)

    def test_no_folder_listings(self):
        for target in ("/web/sub/", "/shaders/", "/shaders/microrelief/", "/assets/"):
            self.expect(target, 404)

    def test_nul_control_and_bad_encodings_are_bad_requests(self):
        for target in (b"/web/%00", b"/web/app.js%00.png", b"/web/%0d%0aX: y", b"/web/%zz",
                       b"/web/%", b"/web/%c3%28", b"/web/%ff", b"/web/\xff", b"/web/\x01",
                       b"/web/%C0%AE%C0%AE/README.md"):
            with self.subTest(target=target):
                status, answer = get(self.port, target)
                self.assertEqual(status, 400, answer[:200])
                self.assertNotIn(SECRET, answer)
        self.expect("/web/app.js", 200)  # and the server is still there

    def test_a_fifo_does_not_hang_the_server(self):
        start = time.monotonic()
        self.expect("/shaders/fifo.glsl", 404)
        self.assertLess(time.monotonic() - start, 1.0)

    def test_stalled_clients_are_dropped(self):
        # Half-sent requests, a request dripped a byte at a time, and an idle connection:
        # all closed within the header deadline (1 s here), none holding a thread after.
        threads = threading.active_count()
        stalled = [socket.create_connection(("127.0.0.1", self.port)) for _ in range(6)]
        for s in stalled[:5]:
            s.sendall(b"GET /web/app.js HTTP/1.1\r\nHost: x\r\n")  # no blank line
        drip = stalled[5]
        start = time.monotonic()
        closed = False
        for byte in b"GET /web/app.js HTTP/1.1\r\nHost: localhost\r\nX-Slow: 1\r\n\r\n":
            try:
                drip.sendall(bytes([byte]))
            except OSError:
                closed = True
                break
            time.sleep(0.1)
            if time.monotonic() - start > 5.0:
                break
        if not closed:
            drip.settimeout(3.0)
            try:
                closed = drip.recv(1) == b""
            except OSError:
                closed = True
        self.assertTrue(closed, "a request dripped a byte at a time was not cut off")
        self.assertLess(time.monotonic() - start, 4.0)
        for s in stalled[:5]:
            s.settimeout(3.0)
            try:
                self.assertEqual(s.recv(1), b"")  # closed without an answer
            except ConnectionResetError:
                pass
            s.close()
        drip.close()
        deadline = time.monotonic() + 3.0
        while threading.active_count() > threads and time.monotonic() < deadline:
            time.sleep(0.05)
        self.assertLessEqual(threading.active_count(), threads)
        self.expect("/web/app.js", 200)

    def test_connections_are_bounded(self):
        # More stalled connections than the server takes: the rest are answered 503 at
        # once, the threads stay bounded, and the server serves again once they are gone.
        threads = threading.active_count()
        held = []
        try:
            for _ in range(40):
                s = socket.create_connection(("127.0.0.1", self.port))
                s.sendall(b"GET /web/app.js HTTP/1.1\r\n")
                held.append(s)
            time.sleep(0.2)
            # A handler thread and its watchdog per served connection, no more.
            self.assertLessEqual(threading.active_count(), threads + 2 * 8 + 2)
            busy = [s for s in held[8:] if s.settimeout(2.0) or s.recv(64).startswith(
                b"HTTP/1.0 503")]
            self.assertEqual(len(busy), len(held) - 8)
        finally:
            for s in held:
                s.close()
        deadline = time.monotonic() + 3.0
        while time.monotonic() < deadline:
            if get(self.port, "/web/app.js")[0] == 200:
                break
            time.sleep(0.1)
        self.expect("/web/app.js", 200)


class PortTest(unittest.TestCase):
    """--port, to serve.py and to scripts/web.sh: decimal digits, 1 to 65535 (0: a free
    one), anything else refused in one line with status 2, never a traceback (issue 47:
    '080' passed web.sh's range check as bash's octal, a port past 2^64 ended serve.py in
    an OverflowError)."""

    BAD = ["080", "65536", "99999999999999999999999", "-1", "+80", " 80", "8_0", "\u0668\u0660",
           "0x50", "8\n0", ""]

    def run_tool(self, argv):
        import subprocess
        return subprocess.run(argv, capture_output=True, text=True, timeout=30)

    def expect_refused(self, argv, tool):
        r = self.run_tool(argv)
        self.assertEqual(r.returncode, 2, f"{argv}: {r.stderr}")
        self.assertEqual(r.stderr.count("\n"), 1, f"{argv}: {r.stderr!r}")
        self.assertTrue(r.stderr.startswith(f"{tool}: error: --port "), r.stderr)
        self.assertIn("expected a whole number from 1 to 65535", r.stderr)
        self.assertNotIn("Traceback", r.stderr)

    def test_serve_py_refuses_what_is_no_port(self):
        for port in self.BAD:
            self.expect_refused([sys.executable, SERVE_PY, "--port", port], "serve.py")

    def test_web_sh_refuses_what_is_no_port(self):
        web_sh = pathlib.Path(SERVE_PY).resolve().parent.parent / "scripts" / "web.sh"
        for port in self.BAD:
            self.expect_refused(["bash", str(web_sh), "--port", port], "web.sh")
        # A port it takes goes on to the next check, the served folder's.
        with tempfile.TemporaryDirectory() as top:
            for port in ("1", "8000", "65535", "0"):
                r = self.run_tool(["bash", str(web_sh), "--port", port, "--root", top])
                self.assertEqual(r.returncode, 2, r.stderr)
                self.assertIn("no web/index.html there", r.stderr)

    def test_port_numbers(self):
        serve = load_serve()
        self.assertEqual(serve.port_number("8000"), 8000)
        self.assertEqual(serve.port_number("0"), 0)
        for port in self.BAD:
            self.assertIsNone(serve.port_number(port), port)


def main():
    global SERVE_PY
    if len(sys.argv) < 2:
        print("usage: test_serve.py PATH/TO/web/serve.py", file=sys.stderr)
        return 2
    SERVE_PY = sys.argv.pop(1)
    return 0 if unittest.main(exit=False, verbosity=2).result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
