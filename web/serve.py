#!/usr/bin/env python3
"""serve.py: the web page's local HTTP server (the Python standard library only).

Serves web/, shaders/ and assets/ of ROOT (the repository, or an installed
share/microrelief: the same layout) and nothing else, on 127.0.0.1, without caching, so
the page always reads the shaders as they are. Prints the page's URL on its first line.
scripts/web.sh runs it; the web tests import it (serve()).
"""
import argparse
import functools
import http.server
import pathlib
import signal
import sys
import threading

SERVED = ("web", "shaders", "assets")


class Handler(http.server.SimpleHTTPRequestHandler):
    extensions_map = {
        **http.server.SimpleHTTPRequestHandler.extensions_map,
        ".js": "text/javascript",
        ".glsl": "text/plain",
        ".frag": "text/plain",
        ".vert": "text/plain",
    }

    def send_head(self):
        top = self.path.lstrip("/").split("/", 1)[0].split("?", 1)[0]
        if self.path in ("/", "/index.html"):
            self.send_response(302)
            self.send_header("Location", "/web/")
            self.end_headers()
            return None
        if top not in SERVED:
            self.send_error(404, "not served")
            return None
        return super().send_head()

    def end_headers(self):
        self.send_header("Cache-Control", "no-store")
        super().end_headers()

    def log_message(self, format, *args):
        if self.server.verbose:
            super().log_message(format, *args)


def serve(root, port=0, verbose=False):
    """Starts the server on a thread; returns (server, url of the page)."""
    root = pathlib.Path(root).resolve()
    if not (root / "web" / "index.html").is_file():
        raise SystemExit(f"serve.py: error: {root}: no web/index.html there")
    handler = functools.partial(Handler, directory=str(root))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", port), handler)
    server.daemon_threads = True
    server.verbose = verbose
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server, f"http://127.0.0.1:{server.server_address[1]}/web/"


def main():
    parser = argparse.ArgumentParser(description="Serve the microrelief web page locally.")
    parser.add_argument("--root", default=str(pathlib.Path(__file__).resolve().parent.parent),
                        help="folder holding web/, shaders/ and assets/ (default: this file's repository)")
    parser.add_argument("--port", type=int, default=0, help="port (default: a free one)")
    parser.add_argument("--verbose", action="store_true", help="log every request")
    args = parser.parse_args()
    try:
        server, url = serve(args.root, args.port, args.verbose)
    except OSError as e:
        print(f"serve.py: error: port {args.port}: {e.strerror}", file=sys.stderr)
        return 1
    print(url, flush=True)
    stop = threading.Event()
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, lambda *_: stop.set())
    stop.wait()
    server.shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
