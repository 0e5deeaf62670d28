#!/usr/bin/env bash
# Set up (plus gnuplot for the plots), build, and run microrelief-bench; arguments go
# to it (e.g. --quick). Results: out/bench/bench.csv, bench.md, *.png.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/scripts/setup.sh"
if ! command -v gnuplot >/dev/null 2>&1; then
  echo "bench: installing gnuplot-nox for the plots"
  if [ "$(id -u)" -ne 0 ]; then sudo=sudo; else sudo=; fi
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends gnuplot-nox >/dev/null
fi
cd "$root"
"$build/bin/microrelief-bench" "$@"
