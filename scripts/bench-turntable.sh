#!/usr/bin/env bash
# What a camera path saves: a turntable rendered in one process against the same frames
# rendered by one process start each (their cameras taken from the first run's
# manifest), wall time and frames per second of both, and whether the pictures are the
# same bytes. Frames in out/bench-turntable/. README, "Camera paths and batch rendering".
#   bash scripts/bench-turntable.sh [VIEWS [SIZE]]     default: 360 512x512
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
render="${MICRORELIEF_RENDER:-$root/build/bin/microrelief-render}"
views="${1:-360}"
size="${2:-512x512}"
out="$root/out/bench-turntable"
rm -rf "$out"

now() { date +%s.%N; }

t0=$(now)
"$render" --turntable "$views" --size "$size" --out "$out/one/view-{frame:04d}.png" -q
t1=$(now)

# One start per frame, each with its frame's camera: the manifest's camera column.
tail -n +2 "$out/one/manifest.csv" | cut -d'"' -f2 > "$out/cameras.txt"
t2=$(now)
frame=0
while IFS= read -r camera; do
    # shellcheck disable=SC2086 # the camera column is a list of flags
    "$render" $camera --size "$size" --out "$(printf '%s/starts/view-%04d.png' "$out" "$frame")" -q
    frame=$((frame + 1))
done < "$out/cameras.txt"
t3=$(now)

same=0
for f in "$out"/one/view-*.png; do
    cmp -s "$f" "$out/starts/$(basename "$f")" && same=$((same + 1))
done
awk -v n="$views" -v size="$size" -v t0="$t0" -v t1="$t1" -v t2="$t2" -v t3="$t3" \
    -v same="$same" 'BEGIN {
    one = t1 - t0; many = t3 - t2
    printf "turntable of %d frames at %s\n", n, size
    printf "  one process:    %7.2f s  %6.2f fps\n", one, n / one
    printf "  %d starts:     %7.2f s  %6.2f fps\n", n, many, n / many
    printf "  one process is %.1fx faster; %d of %d pictures the same bytes\n", many / one, same, n
}'
