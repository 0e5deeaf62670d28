#!/usr/bin/env bash
# Fuzzes the height-map loading path (tests/fuzz/HeightMapFuzzTarget.cpp) with libFuzzer,
# ASan and UBSan for a given time, one job:
#   bash scripts/fuzz.sh [SECONDS] [more libFuzzer flags]     (default 60 s)
# Builds the `fuzz` preset (clang) in build-fuzz/ first. The corpus it grows is kept in
# build-fuzz/fuzz/corpus (seeded from tests/fuzz/corpus), crash, leak and timeout inputs
# go to build-fuzz/fuzz/artifacts/; add one to tests/fuzz/corpus once fixed, and the
# fuzz.corpus test replays it from then on.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-60}"
shift || true
MICRORELIEF_EXTRA_PACKAGES="clang libclang-rt-14-dev" MICRORELIEF_SETUP_NO_BUILD=1 \
  bash "$root/scripts/setup.sh"
cd "$root"
[ -f build-fuzz/build.ninja ] || cmake --preset fuzz >/dev/null
cmake --build --preset fuzz
work="$root/build-fuzz/fuzz"
mkdir -p "$work/corpus" "$work/artifacts"
# intercept_tls_get_addr=0: see scripts/sanitize.sh (clang 14's tracer crash).
export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1:intercept_tls_get_addr=0"
export LSAN_OPTIONS="suppressions=$root/tests/sanitizers/lsan.supp"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# -timeout: an input that takes 10 s is a hang. The target loads maps of at most 2048 x
# 2048 (16 MiB of samples), so one allocation of more than 512 MiB or 2 GiB in all is a
# bug somewhere in the loading path. For a long unattended run add
# -fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1 to go on past findings.
exec build-fuzz/bin/microrelief-fuzz-heightmap "$work/corpus" tests/fuzz/corpus \
  -dict=tests/fuzz/heightmap.dict -max_total_time="$seconds" -timeout=10 \
  -rss_limit_mb=2048 -malloc_limit_mb=512 \
  -artifact_prefix="$work/artifacts/" -print_final_stats=1 "$@"
