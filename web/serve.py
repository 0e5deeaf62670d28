#!/usr/bin/env python3
"""serve.py: the web page's local HTTP server (the Python standard library only).

Serves web/, shaders/ and assets/ of ROOT (the repository, or an installed
share/microrelief: the same layout) and nothing else, on 127.0.0.1, without caching, so
the page always reads the shaders as they are. Prints the page's URL on its first line.
scripts/web.sh runs it; the web tests import it (serve()).

What it serves (docs/reliability-inputs.md): regular files whose real path, after
percent-decoding and with every symbolic link resolved, lies inside one of the three
folders; a folder's index.html for the folder's own URL; no folder listings. A path
that is not valid percent-encoded UTF-8, or holds a control character (NUL) or a ".."
segment, is a bad request (400); anything else outside is "not served" (404). A client
gets HEADER_SECONDS to send its request and IDLE_SECONDS for any one read or write; at
most MAX_CONNECTIONS connections are served at once, more are answered 503 and closed.
"""
import argparse
import functools
import http.server
import os
import pathlib
import re
import signal
import socket
import stat
import sys
import threading
import urllib.parse

SERVED = ("web", "shaders", "assets")
# A browser sends its request at once; these bound what a stalled or hostile client holds.
HEADER_SECONDS = 10.0  # the request line and headers, all of them
IDLE_SECONDS = 10.0  # any one read or write of the connection
MAX_CONNECTIONS = 32  # a browser opens about 6 per host


class Refused(Exception):
    """A request the server does not answer with a file: an HTTP status and why."""

    def __init__(self, status, reason, location=None):
        super().__init__(reason)
        self.status = status
        self.reason = reason
        self.location = location


_BAD_ESCAPE = re.compile(rb"%(?![0-9A-Fa-f]{2})")


def url_segments(target):
    """The decoded, normalised segments of a request target's path; raises Refused(400)."""
    raw = target.encode("latin-1")  # http.server decodes the request line as Latin-1
    raw = raw.split(b"?", 1)[0].split(b"#", 1)[0]
    if not raw.startswith(b"/"):
        raise Refused(400, "the path must start with /")
    if any(b <= 0x20 or b == 0x7F for b in raw) or _BAD_ESCAPE.search(raw):
        raise Refused(400, "not a percent-encoded path")
    try:
        text = urllib.parse.unquote_to_bytes(raw).decode("utf-8")
    except UnicodeDecodeError:
        raise Refused(400, "the path is not UTF-8") from None
    if any(ord(c) < 0x20 or ord(c) == 0x7F for c in text):
        raise Refused(400, "a control character (NUL, CR, ...) in the path")
    # After decoding: "%2e%2e" and "..%2f" are ".." too. A browser removes dot segments
    # before it sends a URL, so one that is still there is no browser's.
    segments = [s for s in text.split("/") if s not in ("", ".")]
    if ".." in segments:
        raise Refused(400, "'..' in the path")
    return segments, text.endswith("/")


def locate(root, target):
    """The real path of the regular file that `target` (a request's path) names under
    `root` (a resolved pathlib.Path); raises Refused. Opening it is still the caller's:
    open_regular() checks the type again on the open file."""
    segments, folder_url = url_segments(target)
    if not segments or segments[0] not in SERVED:
        raise Refused(404, "not served")
    folder = os.path.realpath(root / segments[0])
    path = os.path.realpath(os.path.join(folder, *segments[1:]))
    if os.path.commonpath([folder, path]) != folder:
        raise Refused(404, "not served")  # a symbolic link out of the folder
    if os.path.isdir(path):
        if not folder_url:  # relative URLs in the page resolve against the folder's URL
            raise Refused(301, "a folder", location="/" + "/".join(segments) + "/")
        path = os.path.realpath(os.path.join(path, "index.html"))
        if os.path.commonpath([folder, path]) != folder:
            raise Refused(404, "not served")
    return path


def open_regular(path):
    """`path` opened for reading and its size, or Refused(404) when it is not a regular file. Opened
    without blocking and checked on the descriptor: a FIFO cannot hang the server, and a
    link swapped in after locate() is not followed."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_NOFOLLOW | os.O_CLOEXEC)
    except OSError:
        raise Refused(404, "not found") from None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise Refused(404, "not a regular file")
        os.set_blocking(fd, True)
        return os.fdopen(fd, "rb"), info.st_size
    except BaseException:
        os.close(fd)
        raise


class Handler(http.server.SimpleHTTPRequestHandler):
    extensions_map = {
        **http.server.SimpleHTTPRequestHandler.extensions_map,
        ".js": "text/javascript",
        ".glsl": "text/plain",
        ".frag": "text/plain",
        ".vert": "text/plain",
    }

    @property
    def timeout(self):  # StreamRequestHandler.setup() puts it on the socket
        return self.server.idle_seconds

    def setup(self):
        super().setup()
        # The whole request within HEADER_SECONDS: the socket's timeout bounds each read,
        # not a client that sends one byte a second.
        self._hung_up = False
        self._watchdog = threading.Timer(self.server.header_seconds, self._hang_up)
        self._watchdog.daemon = True
        self._watchdog.start()

    def _hang_up(self):
        self._hung_up = True
        try:
            self.connection.shutdown(socket.SHUT_RDWR)
        except OSError:
            pass

    def parse_request(self):
        ok = super().parse_request()  # reads the headers
        self._watchdog.cancel()
        if self._hung_up:  # the headers were cut off, not ended: no request to answer
            self.close_connection = True
            return False
        return ok

    def finish(self):
        self._watchdog.cancel()
        super().finish()

    def send_head(self):
        if self.path in ("/", "/index.html"):
            self.send_response(302)
            self.send_header("Location", "/web/")
            self.send_header("Content-Length", "0")
            self.end_headers()
            return None
        try:
            path = locate(self.server.root, self.path)
            file, size = open_regular(path)
        except Refused as refused:
            if refused.location:
                self.send_response(refused.status)
                self.send_header("Location", refused.location)
                self.send_header("Content-Length", "0")
                self.end_headers()
            else:
                self.send_error(refused.status, refused.reason)
            return None
        try:
            self.send_response(200)
            self.send_header("Content-Type", self.guess_type(path))
            self.send_header("Content-Length", str(size))
            self.end_headers()
        except BaseException:  # the client went away
            file.close()
            raise
        return file

    def list_directory(self, path):  # never: folders give their index.html or nothing
        self.send_error(404, "not served")
        return None

    def end_headers(self):
        self.send_header("Cache-Control", "no-store")
        super().end_headers()

    def log_message(self, format, *args):
        if self.server.verbose:
            super().log_message(format, *args)


class Server(http.server.ThreadingHTTPServer):
    daemon_threads = True
    # Connections the kernel queues until they are accepted: beyond MAX_CONNECTIONS they
    # are accepted to be answered 503 at once, not left waiting in the queue.
    request_queue_size = 128

    def __init__(self, address, handler, root, verbose, header_seconds, idle_seconds,
                 max_connections):
        self.root = root
        self.verbose = verbose
        self.header_seconds = header_seconds
        self.idle_seconds = idle_seconds
        self._slots = threading.BoundedSemaphore(max_connections)
        super().__init__(address, handler)

    def process_request(self, request, client_address):
        if not self._slots.acquire(blocking=False):
            try:
                request.setblocking(False)  # a few bytes into an empty buffer; never wait
                request.sendall(b"HTTP/1.0 503 Service Unavailable\r\nContent-Length: 0\r\n"
                                b"Connection: close\r\n\r\n")
                request.recv(65536)  # what the client sent: closed unread, it resets the answer
            except OSError:
                pass
            self.shutdown_request(request)
            return
        try:
            super().process_request(request, client_address)
        except BaseException:
            self._slots.release()
            raise

    def process_request_thread(self, request, client_address):
        try:
            super().process_request_thread(request, client_address)
        finally:
            self._slots.release()

    def handle_error(self, request, client_address):
        # A client that went away or timed out is no server error.
        if self.verbose or not isinstance(sys.exc_info()[1], OSError):
            super().handle_error(request, client_address)


def serve(root, port=0, verbose=False, header_seconds=HEADER_SECONDS, idle_seconds=IDLE_SECONDS,
          max_connections=MAX_CONNECTIONS):
    """Starts the server on a thread; returns (server, url of the page)."""
    root = pathlib.Path(root).resolve()
    if not (root / "web" / "index.html").is_file():
        raise SystemExit(f"serve.py: error: {root}: no web/index.html there")
    handler = functools.partial(Handler, directory=str(root))
    server = Server(("127.0.0.1", port), handler, root, verbose, header_seconds, idle_seconds,
                    max_connections)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server, f"http://127.0.0.1:{server.server_address[1]}/web/"


def port_number(text):
    """`text` as a port: ASCII decimal digits without a leading zero (int() would take
    " 80", "+80", "8_0" and other scripts' digits), 0 to 65535; None otherwise."""
    if not re.fullmatch(r"0|[1-9][0-9]{0,4}", text, flags=re.ASCII):
        return None
    port = int(text)
    return port if port <= 65535 else None


def main():
    parser = argparse.ArgumentParser(description="Serve the microrelief web page locally.")
    parser.add_argument("--root", default=str(pathlib.Path(__file__).resolve().parent.parent),
                        help="folder holding web/, shaders/ and assets/ (default: this file's repository)")
    parser.add_argument("--port", default="0", help="port, 1 to 65535 (default, or 0: a free one)")
    parser.add_argument("--verbose", action="store_true", help="log every request")
    args = parser.parse_args()
    port = port_number(args.port)
    if port is None:
        print(f"serve.py: error: --port {args.port!r}: expected a whole number from 1 to 65535 "
              "(0: a free one)", file=sys.stderr)
        return 2
    args.port = port
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
