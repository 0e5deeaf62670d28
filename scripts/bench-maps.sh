#!/usr/bin/env bash
# Real height maps for microrelief-bench, taken from Debian 12 packages at benchmark time
# into a cache folder (nothing of them is committed): a rough stone wall with thin joints
# and a terrain. Writes FOLDER/maps.txt, one map a line, which the benchmark's default
# map list reads (microrelief-bench --help, docs/performance.md): FILE[:CHANNEL][:normalize]
# as --maps takes them, the file relative to FOLDER. Both maps here are one 8-bit channel
# spanning nearly the whole range (the wall 0 to 255, the terrain 2 to 249), so their lines
# carry no suffix. Idempotent: a second run downloads nothing.
#
#   bash scripts/bench-maps.sh [FOLDER]    # default: out/bench-maps, or $MICRORELIEF_BENCH_MAPS
#
# The maps (package, file in it, licence as the package's copyright file states it):
#   libirrlicht-doc (Irrlicht 1.8.5 engine's example media; zlib/libpng licence)
#     /usr/share/doc/libirrlicht-dev/media/rockwall_height.bmp.gz  256 x 256, 8 bit: the
#       height map of the engine's parallax-mapping example, a wall of rough stones with
#       joints one to three texels wide (rough stone, thin grooves)
#     /usr/share/doc/libirrlicht-dev/media/terrain-heightmap.bmp.gz  256 x 256, 8 bit: the
#       height map of its terrain-rendering example (terrain)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
folder="${1:-${MICRORELIEF_BENCH_MAPS:-$root/out/bench-maps}}"
mkdir -p "$folder"
folder="$(cd "$folder" && pwd)"

package=libirrlicht-doc
media=usr/share/doc/libirrlicht-dev/media
files=(rockwall_height.bmp terrain-heightmap.bmp)

have_all() {
  for f in "${files[@]}"; do [ -s "$folder/$f" ] || return 1; done
}

if ! have_all; then
  work="$(mktemp -d "$folder/.fetch.XXXXXX")"
  trap 'rm -rf "$work"' EXIT
  echo "bench-maps: downloading $package"
  if ! (cd "$work" && apt-get download -qq "$package" >/dev/null 2>"$work/apt.log"); then
    # A fresh machine's package lists may not know it yet.
    apt-get update -qq >/dev/null 2>&1 || true
    if ! (cd "$work" && apt-get download -qq "$package" >/dev/null 2>"$work/apt.log"); then
      echo "bench-maps: error: apt-get download $package failed: $(tail -n 1 "$work/apt.log")" >&2
      exit 1
    fi
  fi
  dpkg-deb -x "$work"/"$package"_*.deb "$work/x"
  for f in "${files[@]}"; do
    if [ ! -s "$work/x/$media/$f.gz" ]; then
      echo "bench-maps: error: $package has no /$media/$f.gz" >&2
      exit 1
    fi
    # Whole or not at all: unpacked beside the map, then renamed into place.
    gzip -dc "$work/x/$media/$f.gz" >"$folder/.$f.part"
    mv -f "$folder/.$f.part" "$folder/$f"
  done
  version="$(dpkg-deb -f "$work"/"$package"_*.deb Version)"
  {
    echo "Height maps for microrelief-bench, from Debian 12 packages (scripts/bench-maps.sh)."
    for f in "${files[@]}"; do
      echo "$f: $package $version, /$media/$f.gz (zlib/libpng licence: the package's copyright file)"
    done
  } >"$folder/.SOURCES.part"
  mv -f "$folder/.SOURCES.part" "$folder/SOURCES.txt"
fi

printf '%s\n' "${files[@]}" >"$folder/.maps.txt.part"
mv -f "$folder/.maps.txt.part" "$folder/maps.txt"
echo "bench-maps: ${files[*]} in $folder"
