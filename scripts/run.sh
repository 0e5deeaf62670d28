#!/usr/bin/env bash
# Quick start, part one: set up, build, and render the bundled default map headless
# to out/microrelief.png. Extra arguments go to microrelief-render.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/scripts/setup.sh"
cd "$root"
"$build/bin/microrelief-render" "$@"
