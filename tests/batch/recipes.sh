#!/usr/bin/env bash
# The README's batch recipes ("Camera paths and batch rendering"), run as written but
# on a short path of small pictures: four shards as background processes, the Slurm
# array script with the variables Slurm would set given by hand, and gathering the
# results. Each set of frames must equal, byte for byte, the same path rendered in one
# process. GNU parallel is not installed by scripts/setup.sh: its line in the README is
# the background-process recipe's twin and is not run here.
#   bash recipes.sh path/to/microrelief-render path/to/source-tree
set -euo pipefail
render="$(realpath "$1")"
root="$(realpath "$2")"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"
# The recipes call the program by name.
mkdir bin && ln -s "$render" bin/microrelief-render
export PATH="$work/bin:$PATH"

fail() {
    echo "recipes: FAIL: $*" >&2
    exit 1
}
# Every frame of `folder` is there and equal to the one-process frame.
same_frames() {
    local folder="$1" count="$2" f name
    for ((f = 0; f < count; f++)); do
        printf -v name 'view-%04d.png' "$f"
        [ -f "$folder/$name" ] || fail "$folder/$name is missing"
        cmp -s "one/$name" "$folder/$name" || fail "$folder/$name differs from one/$name"
    done
    [ "$(ls -A "$folder" | grep -c '^\.')" -eq 0 ] || fail "temporary files in $folder"
}

# --- Four shards on one machine (README), 8 views of 48 x 32 instead of 360 of 512 x 512.
microrelief-render --turntable 8 --size 48x32 --out 'one/view-{frame:04d}.png' -q
for i in 0 1 2 3; do
  microrelief-render --turntable 8 --size 48x32 --out 'out/tt/view-{frame:04d}.png' --shard $i/4 -q &
done
wait
same_frames out/tt 8
for i in 0 1 2 3; do
    [ -f "out/tt/manifest-$i-of-4.csv" ] || fail "no manifest for shard $i"
done

# --- Gathering (README): a run over the whole path with --skip-existing draws what is
# missing and lists every frame; the shards' manifests as one, in frame order.
rm out/tt/view-0005.png  # as if shard 1 had been killed before it
check="$(microrelief-render --turntable 8 --size 48x32 --out 'out/tt/view-{frame:04d}.png' --skip-existing --manifest out/tt/check.csv)"
echo "$check"
case "$check" in *"8 frames of 8 (turntable): 1 rendered, 7 skipped"*) ;; *) fail "check run: $check" ;; esac
same_frames out/tt 8
{ head -n 1 out/tt/manifest-0-of-4.csv; tail -q -n +2 out/tt/manifest-*-of-4.csv | sort -t, -k1,1n; } > out/tt/manifest-all.csv
[ "$(cut -d, -f1 out/tt/manifest-all.csv | tr '\n' ' ')" = "frame 0 1 2 3 4 5 6 7 " ] ||
    fail "gathered manifest: $(cat out/tt/manifest-all.csv)"
[ "$(grep -c ',rendered$' out/tt/manifest-all.csv)" -eq 8 ] || fail "gathered manifest statuses"

# --- The Slurm array script, run as Slurm runs --array=0-3: four tasks at once, each
# with the variables Slurm sets (scripts/render-turntable.sbatch).
pids=()
for id in 0 1 2 3; do
    SLURM_ARRAY_JOB_ID=77 SLURM_ARRAY_TASK_ID=$id SLURM_ARRAY_TASK_COUNT=4 \
    SLURM_ARRAY_TASK_MIN=0 SLURM_ARRAY_TASK_MAX=3 SLURM_ARRAY_TASK_STEP=1 \
    MICRORELIEF_OUT=slurm MICRORELIEF_VIEWS=8 MICRORELIEF_SIZE=48x32 \
        bash "$root/scripts/render-turntable.sbatch" > "slurm-$id.log" &
    pids+=($!)
done
for p in "${pids[@]}"; do wait "$p" || fail "an array task failed: $(cat slurm-*.log)"; done
same_frames slurm 8
for i in 0 1 2 3; do
    grep -q "shard $i/4" "slurm-$i.log" || fail "task $i did not run shard $i/4: $(cat "slurm-$i.log")"
done
# Requeued after the frames were done, a task draws nothing.
again="$(SLURM_ARRAY_TASK_ID=2 SLURM_ARRAY_TASK_COUNT=4 SLURM_ARRAY_TASK_MIN=0 \
    MICRORELIEF_OUT=slurm MICRORELIEF_VIEWS=8 MICRORELIEF_SIZE=48x32 \
    bash "$root/scripts/render-turntable.sbatch")"
case "$again" in *"0 rendered, 2 skipped"*) ;; *) fail "requeued task: $again" ;; esac
# Outside an array the script says so, exit status 2.
status=0
env -u SLURM_ARRAY_TASK_ID MICRORELIEF_OUT=slurm bash "$root/scripts/render-turntable.sbatch" 2> err.log || status=$?
[ "$status" -eq 2 ] && grep -q "SLURM_ARRAY_TASK_ID is not set" err.log || fail "outside an array: $status $(cat err.log)"

echo "recipes: all passed"
