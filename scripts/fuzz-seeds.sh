#!/usr/bin/env bash
# Fills fuzz/corpus/<target>/ with seed inputs: the small files of assets/ and /work/shared/assets
# (or $SHARED), OBJs with their MTL appended as the obj_load target expects, tiny generated images.
# Usage: scripts/fuzz-seeds.sh   (idempotent; the corpora are not in git)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
shared=${SHARED:-/work/shared/assets}
c=$root/fuzz/corpus
max=65536   # seeds over 64 KiB only slow the fuzzer down (and libFuzzer's max_len follows the largest)
mkdir -p "$c"/{gltf_load,glb_load,obj_load,scene_toml,envmap_load,texture_decode,meshopt_decode,ktx2_decode,draco_decode}

small() { find "$@" -type f -size -${max}c 2>/dev/null || true; }
for f in $(small "$root/assets" "$shared" -name '*.gltf'); do cp "$f" "$c/gltf_load/$(basename "$f")"; done
for f in $(small "$root/assets" "$shared" -name '*.glb'); do cp "$f" "$c/glb_load/$(basename "$f")"; done
for f in $(small "$root/assets" "$shared" -name '*.obj'); do
    out="$c/obj_load/$(basename "$f")"
    mtl=$(sed -n 's/^mtllib[[:space:]]\+//p' "$f" | head -1 | tr -d '\r')
    sed 's/^mtllib .*/mtllib m.mtl/' "$f" > "$out"
    if [ -n "$mtl" ] && [ -f "$(dirname "$f")/$mtl" ]; then
        printf '\n#MTL\n' >> "$out"
        cat "$(dirname "$f")/$mtl" >> "$out"
    fi
done
# Hand-written OBJs: faces with texture and normal indices, negative indices, groups, materials.
printf 'mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\no quad\nusemtl red\nf 1/1/1 2/2/1 3/3/1 4/1/1\ng back\nusemtl glass\nf -1//1 -2//1 -3//1\n\n#MTL\nnewmtl red\nKd 1 0 0\nKs 0.5 0.5 0.5\nNs 50\nmap_Kd -bm 1 tex.png\nnewmtl glass\nillum 7\nNi 1.5\nTf 0.9 1 0.9\nd 0.5\nKe 1 1 1\n' > "$c/obj_load/quad-mtl.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\nl 1 2\np 3\n' > "$c/obj_load/tetra.obj"
cp "$root"/assets/scenes/*.toml "$c/scene_toml/"
for f in $(small "$root/assets" "$shared" -name '*.ktx2'); do cp "$f" "$c/ktx2_decode/$(basename "$f")"; done
for f in $(small "$root/assets" "$shared" \( -name '*.png' -o -name '*.jpg' -o -name '*.jpeg' -o -name '*.webp' \)); do
    cp "$f" "$c/texture_decode/$(basename "$f")"
done
for f in $(small "$root/assets" "$shared" \( -name '*.hdr' -o -name '*.exr' \)); do cp "$f" "$c/envmap_load/$(basename "$f")"; done
# Tiny generated images in every format the decoders read, and environment maps of both kinds.
python3 - "$c" <<'PY'
import io, struct, sys, zlib
c = sys.argv[1]
try:
    from PIL import Image
    im = Image.new("RGBA", (5, 3))
    im.putdata([(i * 40 % 256, i * 90 % 256, i * 17 % 256, 255 - i) for i in range(15)])
    for fmt, ext, mode in [("PNG", "png", "RGBA"), ("PNG", "grey16.png", "I;16"), ("JPEG", "jpg", "RGB"),
                           ("WEBP", "webp", "RGBA"), ("GIF", "gif", "P")]:
        im.convert(mode).save(f"{c}/texture_decode/gen.{ext}", fmt)
    im.convert("RGB").save(f"{c}/texture_decode/gen-progressive.jpg", "JPEG", progressive=True)
    im.save(f"{c}/texture_decode/gen-lossless.webp", "WEBP", lossless=True)
except ImportError:
    pass
# Radiance HDR, flat (uncompressed) RGBE scanlines.
w, h = 8, 4
rows = b"".join(bytes([(x * 30) % 256, (y * 60) % 256, 128, 128]) for y in range(h) for x in range(w))
open(f"{c}/envmap_load/gen.hdr", "wb").write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (h, w) + rows)
PY
# An EXR written by glint itself (the film writer), when a release build is there.
if [ -x "$root/target/release/glint" ]; then
    "$root/target/release/glint" render "$root/assets/dequantized/AnimatedMorphCube.gltf" -o "$c/envmap_load/gen.exr" \
        --width 8 --height 4 --spp 1 --backend bvh --quiet || true
fi
# meshopt: a few streams of each mode cut from the meshopt assets' BIN chunks (any bytes do).
for f in "$root"/assets/meshopt/*.glb; do
    for mode in 0 1 2; do
        { printf "\\x$(printf %02x $mode)\\x00\\x0b\\x40\\x00"; head -c 2048 "$f" | tail -c 1500; } > "$c/meshopt_decode/$(basename "$f" .glb)-$mode"
    done
done
# Draco: each primitive stream of the shared glTF-Draco files, behind the draco_decode header (vertex
# count u16, triangle count u16, attribute layout: the index into common::DRACO_LAYOUTS whose
# semantics-by-id match the file's).
python3 - "$shared/gltf" "$c/draco_decode" <<'PY'
import glob, json, os, struct, sys
layouts = [["NORMAL", "POSITION"], ["NORMAL", "POSITION", "TEXCOORD_0"],
           ["JOINTS_0", "NORMAL", "POSITION", "TEXCOORD_0", "WEIGHTS_0"],
           ["JOINTS_0", "NORMAL", "POSITION", "WEIGHTS_0"], ["POSITION", "NORMAL", "TEXCOORD_0"]]
for f in sorted(glob.glob(os.path.join(sys.argv[1], "*/glTF-Draco/*.gltf"))):
    d = json.load(open(f))
    for mi, m in enumerate(d["meshes"]):
        for pi, p in enumerate(m["primitives"]):
            e = p.get("extensions", {}).get("KHR_draco_mesh_compression")
            if not e:
                continue
            by_id = [k for k, _ in sorted(e["attributes"].items(), key=lambda kv: kv[1])]
            if by_id not in layouts:
                continue
            v = d["bufferViews"][e["bufferView"]]
            data = open(os.path.join(os.path.dirname(f), d["buffers"][v["buffer"]]["uri"]), "rb").read()
            o = v.get("byteOffset", 0)
            acc = d["accessors"]
            points = acc[p["attributes"]["POSITION"]]["count"]
            faces = acc[p["indices"]]["count"] // 3
            if points > 65535 or faces > 65535:
                continue
            head = struct.pack("<HHB", points, faces, layouts.index(by_id))
            name = "%s-%d-%d" % (os.path.basename(f)[:-5], mi, pi)
            open(os.path.join(sys.argv[2], name), "wb").write(head + data[o:o + v["byteLength"]])
PY
# KHR_animation_pointer: a triangle whose material, light, camera and node are animated by pointers
# (and one pointer at what glint does not animate).
python3 - "$c/gltf_load" <<'PY'
import base64, json, struct, sys
f = [0, 0, 0, 1, 0, 0, 0, 1, 0] + [0, 1] + [1, 0, 0, 1, 0, 0, 1, 1] + [0, 4] + [0.5, 1.5] + [0, 0, 0, 0, 2, 0]
data = struct.pack("<%df" % len(f), *f)
acc = [(0, 3, "VEC3"), (36, 2, "SCALAR"), (44, 2, "VEC4"), (76, 2, "SCALAR"), (84, 2, "SCALAR"), (92, 2, "VEC3")]
ptr = lambda s, p: {"sampler": s, "target": {"path": "pointer", "extensions": {"KHR_animation_pointer": {"pointer": p}}}}
doc = {
    "asset": {"version": "2.0"},
    "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_animation_pointer"],
    "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1, 0.5, 0.25], "intensity": 10}]}},
    "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
    "bufferViews": [{"buffer": 0, "byteLength": len(data)}],
    "accessors": [{"bufferView": 0, "byteOffset": o, "componentType": 5126, "count": n, "type": t} for o, n, t in acc],
    "materials": [{"emissiveFactor": [1, 1, 1], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 2}}}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
    "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
    "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 0, 5]}, {"extensions": {"KHR_lights_punctual": {"light": 0}}}],
    "scenes": [{"nodes": [0, 1, 2]}, {"name": "second", "nodes": [0]}],
    "animations": [{"channels": [
        ptr(0, "/materials/0/pbrMetallicRoughness/baseColorFactor"),
        ptr(1, "/materials/0/extensions/KHR_materials_emissive_strength/emissiveStrength"),
        ptr(1, "/extensions/KHR_lights_punctual/lights/0/intensity"),
        ptr(2, "/cameras/0/perspective/yfov"),
        ptr(3, "/nodes/2/translation"),
        ptr(1, "/nodes/0/weights"),
        ptr(1, "/materials/0/occlusionTexture/strength")],
        "samplers": [{"input": 1, "output": 2}, {"input": 1, "output": 3}, {"input": 1, "output": 4}, {"input": 1, "output": 5}]}],
}
open(sys.argv[1] + "/animation-pointer.gltf", "w").write(json.dumps(doc))
PY
# What was found before (and fixed) seeds its target too.
for d in "$root"/fuzz/regressions/*/; do cp "$d"* "$c/$(basename "$d")/" 2>/dev/null || true; done
for t in "$c"/*; do echo "$(basename "$t"): $(ls "$t" | wc -l) seeds, $(du -sk "$t" | cut -f1) KiB"; done
