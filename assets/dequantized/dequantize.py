#!/usr/bin/env python3
"""Writes a float copy of a KHR_mesh_quantization glTF: every integer attribute, morph target and
animation output becomes FLOAT by the glTF rules (normalized: c / max, at least -1; otherwise the
integer as it is), indices stay as they are, everything else is copied. An independent reading of the
spec, so that tests can render the quantized file against this one.

    python3 assets/dequantized/dequantize.py \
        ../shared/assets/gltf/AnimatedMorphCube/glTF-Quantized/AnimatedMorphCube.gltf \
        assets/dequantized/AnimatedMorphCube.gltf
"""
import base64, json, os, struct, sys

FMT = {5120: ("b", 127.0), 5121: ("B", 255.0), 5122: ("h", 32767.0), 5123: ("H", 65535.0),
       5125: ("I", None), 5126: ("f", None)}
DIMS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}

def main(src, dst):
    doc = json.load(open(src))
    base = os.path.dirname(src)
    bufs = [open(os.path.join(base, b["uri"]), "rb").read() for b in doc["buffers"]]
    index_accessors = {p["indices"] for m in doc["meshes"] for p in m["primitives"] if "indices" in p}
    index_accessors |= {s["input"] for a in doc.get("animations", []) for s in a["samplers"]}
    out = bytearray()
    views = []
    for i, a in enumerate(doc["accessors"]):
        v = doc["bufferViews"][a["bufferView"]]
        code, top = FMT[a["componentType"]]
        n = DIMS[a["type"]]
        size = struct.calcsize(code)
        stride = v.get("byteStride", size * n)
        start = v.get("byteOffset", 0) + a.get("byteOffset", 0)
        data = bufs[v["buffer"]]
        rows = [struct.unpack_from("<%d%s" % (n, code), data, start + k * stride) for k in range(a["count"])]
        keep = i in index_accessors or a["componentType"] == 5126
        if not keep:
            norm = a.pop("normalized", False)
            rows = [tuple(max(c / top, -1.0) if norm else float(c) for c in r) for r in rows]
            code, a["componentType"] = "f", 5126
            for key in ("min", "max"):
                if key in a:
                    a[key] = [f(r[c] for r in rows) for c, f in enumerate([min if key == "min" else max] * n)]
        while len(out) % 4:
            out.append(0)
        blob = b"".join(struct.pack("<%d%s" % (n, code), *r) for r in rows)
        views.append({"buffer": 0, "byteOffset": len(out), "byteLength": len(blob)})
        a["bufferView"], a["byteOffset"] = len(views) - 1, 0
        out += blob
    doc["bufferViews"] = views
    doc["buffers"] = [{"byteLength": len(out),
                       "uri": "data:application/octet-stream;base64," + base64.b64encode(out).decode()}]
    for key in ("extensionsUsed", "extensionsRequired"):
        if key in doc:
            doc[key] = [e for e in doc[key] if e != "KHR_mesh_quantization"]
            if not doc[key]:
                del doc[key]
    json.dump(doc, open(dst, "w"), indent=1)

if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
