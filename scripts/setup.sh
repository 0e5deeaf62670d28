#!/usr/bin/env bash
# Installs what is missing (Debian 12 packages), configures and builds microrelief in
# build/. Idempotent: a second run installs nothing and rebuilds only what changed.
# Sourced by run.sh and test.sh; usable alone: bash scripts/setup.sh
# gnuplot-nox draws the benchmark's plots (and lets the cli tests check them); clang-tools-14
# (clang-doc) writes the API reference (cmake/ApiReference.cmake).
# MICRORELIEF_EXTRA_PACKAGES adds packages (sanitize.sh and fuzz.sh: clang and its
# runtime); MICRORELIEF_SETUP_NO_BUILD=1 installs only.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${MICRORELIEF_BUILD_DIR:-$root/build}"

packages=(
  cmake ninja-build g++ pkg-config
  libglfw3-dev libglm-dev libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri libosmesa6-dev
  libopenimageio-dev openimageio-tools zlib1g-dev libgdal-dev libassimp-dev assimp-testmodels
  libgtest-dev libcli11-dev python3-glad glslang-tools
  libimgui-dev xvfb xauth xdotool
  chromium python3 emscripten
  gnuplot-nox clang-tools-14
)
read -r -a extra <<< "${MICRORELIEF_EXTRA_PACKAGES:-}"
packages+=("${extra[@]}")

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# node and npm for microrelief-three: Debian's nodejs and npm where neither program is there
# (a node installed otherwise, with its own npm, is left alone).
command -v node >/dev/null && command -v npm >/dev/null || missing+=(nodejs npm)
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  if [ "$(id -u)" -ne 0 ]; then sudo=sudo; else sudo=; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# microrelief-three's three.js (packages/microrelief-three/package-lock.json), for its example
# and the three tests: npm ci where node_modules is missing or older than the lock file; then
# CMake stages it (a configure that ran before it is run again).
three="$root/packages/microrelief-three"
if [ ! -f "$three/node_modules/three/package.json" ] || [ "$three/package-lock.json" -nt "$three/node_modules/.package-lock.json" ]; then
  echo "setup: npm ci in packages/microrelief-three"
  (cd "$three" && npm ci --ignore-scripts --no-audit --no-fund >/dev/null)
  [ ! -f "$build/build.ninja" ] || cmake "$build" >/dev/null
fi

if [ "${MICRORELIEF_SETUP_NO_BUILD:-0}" = 1 ]; then
  return 0 2>/dev/null || exit 0
fi
if [ ! -f "$build/build.ninja" ]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$build"
