#!/usr/bin/env python3
"""Writes variants.gltf: two quads and four materials with KHR_materials_variants.

The left quad is grey by default, red in 'warm' and blue in 'cool'; the right quad is grey by
default and gold in both 'warm' and 'cool' (one mapping naming two variants); 'plain' maps nothing,
so it keeps the defaults. Pure Python, no dependencies: `python3 make_variants.py` rebuilds it.
"""
import base64
import json
import os
import struct


def quad(x0):
    """Positions, normals and indices of a unit quad facing +Z with its left edge at x0."""
    pos = [(x0, 0, 0), (x0 + 1, 0, 0), (x0 + 1, 1, 0), (x0, 1, 0)]
    nrm = [(0, 0, 1)] * 4
    return pos, nrm, [0, 1, 2, 0, 2, 3]


def main():
    blob = b""
    views, accessors, meshes = [], [], []
    for k, x0 in enumerate([-1.05, 0.05]):
        pos, nrm, idx = quad(x0)
        for data, kind, comp, fmt in [
            (pos, "VEC3", 5126, "<3f"),
            (nrm, "VEC3", 5126, "<3f"),
            (idx, "SCALAR", 5123, "<H"),
        ]:
            raw = b"".join(struct.pack(fmt, *(v if isinstance(v, tuple) else (v,))) for v in data)
            views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(raw)})
            acc = {"bufferView": len(views) - 1, "componentType": comp, "count": len(data), "type": kind}
            if kind == "VEC3" and len(accessors) % 3 == 0:
                acc["min"] = [min(p[i] for p in data) for i in range(3)]
                acc["max"] = [max(p[i] for p in data) for i in range(3)]
            accessors.append(acc)
            blob += raw
            blob += b"\0" * (-len(blob) % 4)
        base = 3 * k
        mappings = (
            [{"material": 1, "variants": [0]}, {"material": 2, "variants": [1]}]
            if k == 0
            else [{"material": 3, "variants": [0, 1]}]
        )
        meshes.append({
            "name": ["left", "right"][k],
            "primitives": [{
                "attributes": {"POSITION": base, "NORMAL": base + 1},
                "indices": base + 2,
                "material": 0,
                "extensions": {"KHR_materials_variants": {"mappings": mappings}},
            }],
        })

    def mat(name, rgb, metallic=0.0, roughness=0.6):
        return {"name": name, "pbrMetallicRoughness": {
            "baseColorFactor": list(rgb) + [1.0], "metallicFactor": metallic, "roughnessFactor": roughness}}

    doc = {
        "asset": {"version": "2.0", "generator": "glint assets/variants/make_variants.py"},
        "extensionsUsed": ["KHR_materials_variants"],
        "extensions": {"KHR_materials_variants": {"variants": [
            {"name": "warm"}, {"name": "cool"}, {"name": "plain"}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0}, {"mesh": 1}],
        "meshes": meshes,
        "materials": [
            mat("grey", (0.5, 0.5, 0.5)),
            mat("red", (0.8, 0.05, 0.05)),
            mat("blue", (0.05, 0.1, 0.8)),
            mat("gold", (1.0, 0.78, 0.34), metallic=1.0, roughness=0.3),
        ],
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
        "bufferViews": views,
        "accessors": accessors,
    }
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "variants.gltf")
    with open(out, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
