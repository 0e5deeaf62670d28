#!/usr/bin/env bash
# Serves the WebGL 2 page (web/) from a local HTTP server and prints its URL.
# Usage: bash scripts/web.sh [--port N] [--root DIR]
#   --port N    the port, 1 to 65535 (default, or 0: a free one)
#   --root DIR  the folder holding web/, shaders/ and assets/ (default: the build tree's
#               share/microrelief, built first by scripts/setup.sh where it is missing;
#               an installed <prefix>/share/microrelief works too)
# The page reads the GLSL as it is staged there, and the uniform block's layout module
# that the build generates (web/relief_layout.js): after editing a shader, run
# `cmake --build build` and reload. It needs Debian's python3 for the server (installed by
# scripts/setup.sh) and a browser with WebGL 2. Ctrl-C stops the server.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
serve_root=""
port=0

usage() { sed -n '2,11p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; }
while (($#)); do
  case "$1" in
    --port) [ $# -ge 2 ] || { echo "web.sh: error: --port needs a number" >&2; exit 2; }; port="$2"; shift 2 ;;
    --port=*) port="${1#--port=}"; shift ;;
    --root) [ $# -ge 2 ] || { echo "web.sh: error: --root needs a folder" >&2; exit 2; }; serve_root="$2"; shift 2 ;;
    --root=*) serve_root="${1#--root=}"; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "web.sh: error: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
# Decimal digits only, no leading zero (bash's arithmetic would read 080 as octal and fail,
# and wrap a number past 2^63), then compared as a decimal number: 1 to 65535, or 0 for a
# free one. %q keeps what was given on one line.
if ! [[ "$port" =~ ^(0|[1-9][0-9]{0,4})$ ]] || ((10#$port > 65535)); then
  printf 'web.sh: error: --port %q: expected a whole number from 1 to 65535 (0: a free one)\n' "$port" >&2
  exit 2
fi
if [ -z "$serve_root" ]; then
  serve_root="${MICRORELIEF_BUILD_DIR:-$root/build}/share/microrelief"
  if [ ! -f "$serve_root/web/relief_layout.js" ]; then
    echo "web.sh: building the page's generated files first (scripts/setup.sh)" >&2
    bash "$root/scripts/setup.sh" >&2
  fi
fi
if [ ! -f "$serve_root/web/index.html" ]; then
  echo "web.sh: error: $serve_root: no web/index.html there (--root names the folder holding web/)" >&2
  exit 2
fi

# Debian's python3 (a python3 earlier on PATH may be a shim of another installation).
python=/usr/bin/python3
[ -x "$python" ] || python="$(command -v python3 || true)"
if [ -z "$python" ]; then
  echo "web.sh: installing python3 (scripts/setup.sh)" >&2
  MICRORELIEF_SETUP_NO_BUILD=1 bash "$root/scripts/setup.sh"
  python=/usr/bin/python3
fi

echo "web.sh: serving $serve_root (web/, shaders/, assets/); open the URL below in a browser with WebGL 2; Ctrl-C stops" >&2
exec "$python" "$serve_root/web/serve.py" --root "$serve_root" --port "$port"
