#!/usr/bin/env bash
# The whole test suite under AddressSanitizer and UndefinedBehaviorSanitizer: the
# `sanitize` preset (CMakePresets.json: clang, RelWithDebInfo, build-sanitize/), with the
# LeakSanitizer suppressions of tests/sanitizers/lsan.supp (known leaks inside OpenImageIO
# and OSMesa, nothing of ours). Installs clang and its runtime if missing. Extra
# arguments go to ctest (e.g. -L cpu).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
MICRORELIEF_EXTRA_PACKAGES="clang libclang-rt-14-dev" MICRORELIEF_SETUP_NO_BUILD=1 \
  bash "$root/scripts/setup.sh"
cd "$root"
[ -f build-sanitize/build.ninja ] || cmake --preset sanitize >/dev/null
cmake --build --preset sanitize
ctest --preset sanitize --timeout 1800 "$@"
