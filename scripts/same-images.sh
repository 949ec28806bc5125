#!/usr/bin/env bash
# Renders every scene file of assets/ and benches/ and every shared asset with two glint binaries, in
# every backend, at a fixed seed, and compares the EXRs byte for byte (the check of a refactoring).
#   scripts/same-images.sh OLD_BINARY NEW_BINARY [OUT_DIR]
set -uo pipefail
old=$1 new=$2 out=${3:-/tmp/same-images}
cd "$(dirname "$0")/.."
rm -rf "$out" && mkdir -p "$out/old" "$out/new"
inputs=(assets/scenes/*.toml benches/scenes/*.toml assets/demo/demo.glb)
if [ -d ../shared/assets ]; then
    while IFS= read -r f; do inputs+=("$f"); done < <(find ../shared/assets \( -name '*.gltf' -o -name '*.glb' -o -name '*.obj' \) | sort)
fi
same=0 differ=0 failed=0
for f in "${inputs[@]}"; do
    for b in embree bvh grid; do
        key=$(echo "$f-$b" | tr '/.' '__')
        args=(render "$f" --backend "$b" --width 64 --height 48 --spp 4 --seed 7 --threads 2 --quiet)
        "$old" "${args[@]}" -o "$out/old/$key.exr" >"$out/old/$key.log" 2>&1; ro=$?
        "$new" "${args[@]}" -o "$out/new/$key.exr" >"$out/new/$key.log" 2>&1; rn=$?
        if [ $ro != $rn ]; then
            echo "EXIT $ro vs $rn: $f $b"; failed=$((failed + 1))
        elif [ $ro != 0 ]; then
            if cmp -s "$out/old/$key.log" "$out/new/$key.log"; then same=$((same + 1)); else
                echo "ERROR TEXT DIFFERS: $f $b"; differ=$((differ + 1)); fi
        elif cmp -s "$out/old/$key.exr" "$out/new/$key.exr"; then
            same=$((same + 1))
        else
            echo "DIFFER: $f $b"; differ=$((differ + 1))
        fi
    done
done
echo "same-images: ${#inputs[@]} inputs x 3 backends: $same identical, $differ differ, $failed exit codes differ"
[ $differ = 0 ] && [ $failed = 0 ]
