#!/usr/bin/env bash
# The GL tests and the benchmark on a machine with a GPU but without Debian 12's packages
# (a borrowed one), run from a bundle that scripts/gpu-bundle.py made here:
#
#   python3 scripts/gpu-bundle.py BUNDLE build/bin/microrelief-bench build/bin/microrelief-gl-tests
#   bash scripts/gpu-bench.sh BUNDLE OUT            # there
#
# Writes OUT/env.txt (the GPU, the libraries resolved), OUT/gl-tests.log (the GL tests
# through EGL), and for each benchmark run OUT/bench-NAME.tar (its log, bench.csv, bench.md,
# the gnuplot script and its data: the machine may have no gnuplot): five files, within what
# a borrowed machine sends back. The runs: `plane`, every method on the plane over the
# quick run's relief sizes and views, the bundled map and the fetched ones (BUNDLE/maps),
# at 1024 x 1024; `glsl330`, the exact methods there with --glsl330 (the GL 3.3 path);
# `curved`, multilevel and maxmip on the three bases and both last levels.
# MICRORELIEF_GPU_TEST_SECONDS and MICRORELIEF_GPU_BENCH_SECONDS bound each step (150 and
# 300); MICRORELIEF_GPU_STEPS picks the steps (default "tests plane glsl330 curved"; on the
# H200 the tests took 118 s, and the tests with the plane and curved runs five minutes
# before every measurement warmed up for 0.3 s: 332 and 144 measurements; split the steps
# over two calls of a machine that runs a command 10 minutes at most); MICRORELIEF_GPU_TEST_FILTER
# picks tests (gtest's filter), MICRORELIEF_GPU_BENCH_SIZE the pictures' size; further
# arguments go to every benchmark run. A step cut short keeps what it wrote (bench.csv is
# written row by row). The GL tests' data are
# found where the build was: link the checkout to it first. The GLSL 3.30 sweep case
# Glsl330/...sphere_oblong75x33_biquadratic failed on an H200 before the seam's wrap became
# integer arithmetic (docs/perf/2026-12-04-gpu-h200.md): whether that mended it is for the
# next run to say.
set -uo pipefail
bundle="$(cd "$1" && pwd)"
out="$2"
shift 2
steps=" ${MICRORELIEF_GPU_STEPS:-tests plane glsl330 curved} "
for name in $steps; do
  case "$name" in tests|plane|glsl330|curved) ;;
    *) echo "gpu-bench: MICRORELIEF_GPU_STEPS: no step '$name' (tests, plane, glsl330, curved)"; exit 2 ;;
  esac
done
wanted() { [[ "$steps" == *" $1 "* ]]; }
mkdir -p "$out"
# The bundle's C++ runtime only where the machine's own is older than the build's, and then
# before any system folder.
LD_LIBRARY_PATH="$bundle/lib"
if LD_LIBRARY_PATH="$LD_LIBRARY_PATH" ldd "$bundle/bin/microrelief-bench" | grep -q "not found"; then
  LD_LIBRARY_PATH="$LD_LIBRARY_PATH:$bundle/lib/fallback"
fi
# glvnd's libEGL (in the bundle) finds the driver through its vendor file; the driver's
# libraries may live outside the loader's search path.
for dir in /usr/local/nvidia/lib64 /usr/local/nvidia/lib /usr/lib/x86_64-linux-gnu; do
  if [ -e "$dir/libEGL_nvidia.so.0" ]; then LD_LIBRARY_PATH="$LD_LIBRARY_PATH:$dir"; break; fi
done
export LD_LIBRARY_PATH
export MICRORELIEF_BENCH_MAPS="$bundle/maps"
for vendor in /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json \
              /usr/share/glvnd/egl_vendor.d/10_nvidia.json; do
  if [ -e "$vendor" ]; then export __EGL_VENDOR_LIBRARY_FILENAMES="$vendor"; break; fi
done
maps=default
if [ -f "$bundle/maps/maps.txt" ]; then maps=default,fetched; else
  echo "gpu-bench: no fetched maps in $bundle/maps: the bundled map alone"; fi
{
  date -u
  nvidia-smi -L 2>&1 || echo "no nvidia-smi"
  echo "LD_LIBRARY_PATH=$LD_LIBRARY_PATH"
  echo "__EGL_VENDOR_LIBRARY_FILENAMES=${__EGL_VENDOR_LIBRARY_FILENAMES:-}"
  nproc
  ldd "$bundle/bin/microrelief-bench"
} > "$out/env.txt" 2>&1
echo "gpu-bench: $(head -2 "$out/env.txt" | tail -1)"

step() {  # step SECONDS NAME COMMAND...: runs it bounded, says how it ended
  local seconds=$1 name=$2 start=$SECONDS
  shift 2
  timeout "$seconds" "$@"
  local status=$?
  echo "gpu-bench: $name: exit status $status after $((SECONDS - start)) s"
}


if wanted tests; then
  step "${MICRORELIEF_GPU_TEST_SECONDS:-150}" "gl tests" \
    "$bundle/bin/microrelief-gl-tests" --backend=egl --gtest_filter="${MICRORELIEF_GPU_TEST_FILTER:-*}" > "$out/gl-tests.log" 2>&1
  tail -3 "$out/gl-tests.log"
fi

bench() {  # bench NAME ARGS...
  local name=$1
  shift
  step "${MICRORELIEF_GPU_BENCH_SECONDS:-300}" "bench $name" \
    "$bundle/bin/microrelief-bench" --backend egl --out-dir "$out/bench-$name" "$@" \
    > "$out/bench-$name.log" 2>&1
  tail -2 "$out/bench-$name.log"
  mkdir -p "$out/bench-$name" && mv "$out/bench-$name.log" "$out/bench-$name/" &&
    tar -C "$out" -cf "$out/bench-$name.tar" "bench-$name" && rm -rf "$out/bench-${name:?}"
}
size="${MICRORELIEF_GPU_BENCH_SIZE:-1024x1024}"
if wanted plane; then
  bench plane --quick --size "$size" --bases plane --interpolations bilinear \
    --maps "$maps" "${@}"
fi
if wanted glsl330; then
  bench glsl330 --quick --size "$size" --methods multilevel,maxmip,cone --bases plane \
    --interpolations bilinear,biquadratic --maps "$maps" --glsl330 "${@}"
fi
if wanted curved; then
  bench curved --quick --size "$size" --methods multilevel,maxmip --bases plane,cylinder,sphere \
    --interpolations bilinear,biquadratic --maps default "${@}"
fi
