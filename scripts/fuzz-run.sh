#!/usr/bin/env bash
# Runs the fuzz targets one after another, each for SECONDS of wall time (default 900), at priority $NICE
# (default 19, the lowest) and one process at a time, and appends per target its CPU time, executions, corpus
# size and crashes to fuzz/runs.tsv.  Findings land in fuzz/artifacts/<target>/.
# Usage: scripts/fuzz-run.sh [SECONDS] [TARGET...]   (needs cargo-fuzz and the nightly toolchain;
# NO_BUILD=1 skips the build)
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
secs=${1:-900}; shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(gltf_load glb_load obj_load scene_toml envmap_load texture_decode meshopt_decode ktx2_decode)
cd "$root/fuzz"
[ -d corpus ] || "$root/scripts/fuzz-seeds.sh"
# Built once up front (then each target's time is its fuzzing alone); the binaries run directly.  Debug
# assertions stay on so that integer overflow is a finding, not a wrap.
[ -n "${NO_BUILD:-}" ] || nice -n 19 cargo +nightly fuzz build --sanitizer none -O -a || exit 1
fz=$root/fuzz
bin=$fz/target/x86_64-unknown-linux-gnu/release
dict_of() { case $1 in gltf_load|glb_load) echo dict/gltf.dict;; obj_load) echo dict/obj.dict;; scene_toml) echo dict/toml.dict;; esac; }
for t in "${targets[@]}"; do
    mkdir -p "corpus/$t" "artifacts/$t"
    d=$(dict_of "$t"); dict=${d:+-dict=$fz/$d}
    log="artifacts/$t/run-$(date +%s).log"
    # Each target runs in its own artifacts folder, so that two runs of this script (on different
    # targets) never share libFuzzer's fuzz-0.log.
    (cd "artifacts/$t" && /usr/bin/time -f "%U %S" -o time nice -n "${NICE:-19}" \
        "$bin/$t" "$fz/corpus/$t" -artifact_prefix="$fz/artifacts/$t/" \
        -jobs=1 -workers=1 -rss_limit_mb=1024 -malloc_limit_mb=1024 -timeout=10 -max_len=65536 \
        -max_total_time="$secs" -print_final_stats=1 $dict >"$fz/$log" 2>&1)
    # With -jobs=1 libFuzzer runs the fuzzing in a child whose output goes to fuzz-0.log.
    f0="artifacts/$t/fuzz-0.log"
    [ -f "$f0" ] && cat "$f0" >>"$log" && rm -f "$f0"
    cpu=$(tail -1 "artifacts/$t/time" | awk '{ printf "%.1f", ($1 + $2) / 60 }')
    execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
    crashes=$(ls "artifacts/$t" | grep -c -E '^(crash|oom|timeout|leak|slow-unit)-' || true)
    printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$(date -u +%FT%TZ)" "$t" "$cpu" "${execs:-?}" "$(ls "corpus/$t" | wc -l)" "$crashes" | tee -a runs.tsv
done
