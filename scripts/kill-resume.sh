#!/usr/bin/env bash
# Kills a turntable with SIGKILL at KILLS random moments (default 50), resuming it each time, and
# checks that the finished sequence is byte-identical to an unbroken run with no temporary file left.
# Usage: scripts/kill-resume.sh [GLINT_BINARY] [KILLS]    (default target/release/glint, 50)
# Prints: kills landed (runs still going when killed), kills that caught a frame being written (a
# temporary file present right after), runs needed, frames compared, and PASS or FAIL.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
glint=${1:-$root/target/release/glint}
kills=${2:-50}
frames=${FRAMES:-24}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
run() { "$glint" turntable "$root/assets/demo/demo.glb" -o "$1" --frames "$frames" --width 64 --height 48 \
            --spp 16 --backend bvh --threads 2 --quiet >/dev/null 2>&1; }

start=$(date +%s%N)
run "$work/whole"
unbroken_ms=$(( ($(date +%s%N) - start) / 1000000 ))
echo "unbroken run: $frames frames in $unbroken_ms ms"

landed=0 mid_write=0 runs=0 cycles=0
for ((k = 0; k < kills; k++)); do
    # A moment uniformly within one unbroken run's length (the resumed runs are shorter, so the
    # later kills often find them finished: those are counted apart).
    delay_ms=$(( RANDOM * RANDOM % (unbroken_ms + 1) ))
    run "$work/broken" & pid=$!
    runs=$((runs + 1))
    sleep "$(awk "BEGIN { print $delay_ms / 1000 }")"
    if kill -9 "$pid" 2>/dev/null; then
        landed=$((landed + 1))
        wait "$pid" 2>/dev/null || true
        if compgen -G "$work/broken/.*.tmp" >/dev/null; then mid_write=$((mid_write + 1)); fi
    else
        wait "$pid" || true
    fi
    # Once finished, start over so that every kill hits a sequence still being rendered.
    if [ "$(ls "$work/broken" 2>/dev/null | wc -l)" -ge "$frames" ] && ! compgen -G "$work/broken/.*.tmp" >/dev/null; then
        if ! cmp -s <(cd "$work/broken" && cat $(ls)) <(cd "$work/whole" && cat $(ls)); then
            echo "FAIL: a finished sequence differs after kill $k"; exit 1
        fi
        rm -rf "$work/broken"
        cycles=$((cycles + 1))
    fi
done
run "$work/broken"; runs=$((runs + 1))
echo "kills: $kills attempted, $landed landed on a running process, $mid_write while a frame was being written; $runs runs; $cycles sequences finished and checked mid-way, plus the last"
bad=0
for f in "$work"/whole/*; do cmp -s "$f" "$work/broken/$(basename "$f")" || { echo "differs: $(basename "$f")"; bad=1; }; done
left=$(ls -A "$work/broken" | grep -c '\.tmp$' || true)
count=$(ls "$work/broken" | wc -l)
echo "frames: $count of $frames present, temporary files left: $left"
if [ "$bad" = 0 ] && [ "$left" = 0 ] && [ "$count" = "$frames" ]; then echo PASS; else echo FAIL; exit 1; fi
