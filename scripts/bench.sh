#!/usr/bin/env bash
# Set up (gnuplot for the plots among the set-up's packages), fetch the real height maps (scripts/bench-maps.sh,
# into out/bench-maps; MICRORELIEF_BENCH_NO_FETCH=1 skips it, and a fetch that fails only
# warns: the benchmark then runs without them), build, and run microrelief-bench; arguments
# go to it (e.g. --quick, or a subcommand and its options: terrain --quick). Results:
# out/bench/bench.csv, bench.md, *.png. On a machine with
# a GPU it runs unchanged: EGL picks a hardware device before Mesa's software one, and the
# tables take the GL timer query's times wherever the renderer is not a CPU rasteriser.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/scripts/setup.sh"
if [ "${MICRORELIEF_BENCH_NO_FETCH:-0}" != 1 ]; then
  bash "$root/scripts/bench-maps.sh" "$root/out/bench-maps" ||
    echo "bench: warning: no real maps fetched; running without them" >&2
fi
cd "$root"
"$build/bin/microrelief-bench" "$@"
