#!/usr/bin/env bash
# Quick start, part two: set up, build, and run the whole test suite (CTest: cpu,
# shaders, gl.egl, gl.osmesa, cli, package, viewer, web, ...). Extra arguments go to ctest
# (e.g. -L cpu).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/scripts/setup.sh"
cd "$build"
ctest --output-on-failure --timeout 900 "$@"
