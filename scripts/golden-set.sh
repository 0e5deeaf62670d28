#!/usr/bin/env bash
# The golden set: pictures and position AOVs of microrelief-render over the scenes a
# behaviour-preserving change must leave alone (every base, both last levels, each method and
# debug view, shadows, tiles, a model, the level of detail, an animation, views from grazing,
# below and inside, a camera path), drawn by two builds and compared: PNGs byte for byte,
# OpenEXR AOVs pixel for pixel (oiiotool --diff with no tolerance: their headers carry the
# time they were written).
#
#   scripts/golden-set.sh OLD_RENDER NEW_RENDER [OUT]
#
# OLD_RENDER and NEW_RENDER are microrelief-render programs (a build of the commit before the
# change, e.g. `git worktree add /tmp/old REV` and `cmake --build` its microrelief-render;
# each reads the shaders beside it). Writes OUT/old and OUT/new (default out/golden), prints
# each file that differs, and exits 1 if any does. About a minute on 2 cores (llvmpipe).
set -euo pipefail

if [ $# -lt 2 ]; then
  echo "usage: scripts/golden-set.sh OLD_RENDER NEW_RENDER [OUT]" >&2
  exit 2
fi
out="${3:-out/golden}"
command -v oiiotool >/dev/null || { echo "golden-set: oiiotool not found (openimageio-tools)" >&2; exit 2; }

draw() {  # draw PROGRAM FOLDER
  local bin="$1" dir="$2"
  mkdir -p "$dir"
  r() {
    local name="$1"; shift
    "$bin" -q --size 200x150 "$@" --out "$dir/$name.png" --aov "$dir/$name.exr" 2>/dev/null ||
      echo "golden-set: $name: $bin failed (exit $?)"
  }
  r plane
  r plane-biq --interpolation biquadratic
  r plane-hard --shadows hard
  r plane-soft --shadows soft --light-size 3
  r plane-lod --pixel-error 2
  r plane-tile --tile 3,2
  r plane-model --model 0.8,0,0.2,0.1,0,1,0,0,-0.2,0,0.8,0
  r plane-point --light-position 0.3,0.6,0.2 --shadows hard
  r plane-graze --eye 1.2,0.08,0.3 --target 0,0.02,0
  r plane-below --eye 0.2,-0.5,0.3 --target 0,0,0
  r plane-inside --eye 0.05,0.03,0.02 --target 0.4,0.0,0.3 --fovy 70
  for m in normal offset steep pom relief maxmip cone rcsm; do r "m-$m" --method "$m"; done
  r m-maxmip-hard --method maxmip --shadows hard
  r m-cone-soft --method cone --shadows soft
  for v in iterations level normal depth position; do r "v-$v" --view "$v"; done
  r cyl --base cylinder
  r cyl-biq --base cylinder --interpolation biquadratic --shadows hard --radius 0.35 --length 0.8
  r cyl-tile --base cylinder --tile 4,1 --eye 0.3,1.2,0.9
  r cyl-maxmip --base cylinder --method maxmip
  r sph --base sphere
  r sph-soft --base sphere --shadows soft --interpolation biquadratic
  r ell --base ellipsoid --radii 0.6,0.3,0.4 --eye 1,0.6,1.1
  r ell-lod --base ellipsoid --radii 0.6,0.3,0.4 --pixel-error 1.5
  r anim --animate waves --time 0.7
  r albedo-none --albedo none
  r bg --background 0.5,0.2,0.1 --height-scale 0.2
  "$bin" -q --size 120x90 --turntable 3 --out "$dir/turn-{frame}.png" --manifest "$dir/path.csv" ||
    echo "golden-set: the camera path: $bin failed (exit $?)"
}

draw "$1" "$out/old"
draw "$2" "$out/new"

differ=0 count=0
for file in "$out"/old/*.png "$out"/old/*.exr; do
  name="$(basename "$file")"
  count=$((count + 1))
  if [ ! -f "$out/new/$name" ]; then
    echo "golden-set: $name: not drawn by $2"; differ=$((differ + 1))
  elif [[ "$name" == *.png ]]; then
    cmp -s "$file" "$out/new/$name" || { echo "golden-set: $name differs"; differ=$((differ + 1)); }
  elif ! oiiotool --fail 0 --warn 0 --diff "$file" "$out/new/$name" >/dev/null 2>&1; then
    echo "golden-set: $name differs"; differ=$((differ + 1))
  fi
done
echo "golden-set: $((count - differ)) of $count files equal ($out/old against $out/new)"
[ "$differ" -eq 0 ]
