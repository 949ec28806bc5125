#!/usr/bin/env python3
"""Writes specgloss.gltf: two spheres in KHR_materials_pbrSpecularGlossiness materials.

'gold' is the extension's own example (diffuse black, specular [1, 0.766, 0.336], glossiness 0.9)
with the metallic-roughness fallback the spec pairs with it (base colour gold, roughness 0.1,
metallic 1); 'textured' has a 2x2 diffuse texture and a 2x2 specular-glossiness texture whose
alphas (glossiness) are 255, 128, 0 and 64, scaled by glossinessFactor 0.5.
Pure Python, no dependencies: `python3 make_specgloss.py` rebuilds it.
"""
import base64
import json
import math
import os
import struct
import zlib


def png(rgba_rows):
    """A PNG (8-bit RGBA) of rows of (r, g, b, a) tuples."""
    h, w = len(rgba_rows), len(rgba_rows[0])
    raw = b"".join(b"\0" + bytes(c for px in row for c in px) for row in rgba_rows)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def sphere(rings=16, segments=32):
    pos, nrm, uv, idx = [], [], [], []
    for r in range(rings + 1):
        th = math.pi * r / rings
        for s in range(segments + 1):
            ph = 2 * math.pi * s / segments
            n = (math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph))
            pos.append(tuple(0.5 * c for c in n))
            nrm.append(n)
            uv.append((s / segments, r / rings))
    for r in range(rings):
        for s in range(segments):
            a, b = r * (segments + 1) + s, (r + 1) * (segments + 1) + s
            idx += [a, a + 1, b, a + 1, b + 1, b]
    return pos, nrm, uv, idx


def main():
    pos, nrm, uv, idx = sphere()
    blob, views, accessors = b"", [], []
    for data, kind, comp, fmt in [(pos, "VEC3", 5126, "<3f"), (nrm, "VEC3", 5126, "<3f"),
                                  (uv, "VEC2", 5126, "<2f"), (idx, "SCALAR", 5125, "<I")]:
        raw = b"".join(struct.pack(fmt, *(v if isinstance(v, tuple) else (v,))) for v in data)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(raw)})
        acc = {"bufferView": len(views) - 1, "componentType": comp, "count": len(data), "type": kind}
        if data is pos:
            acc["min"], acc["max"] = [-0.5] * 3, [0.5] * 3
        accessors.append(acc)
        blob += raw + b"\0" * (-len(raw) % 4)
    images = []
    for rows in [
        [[(200, 30, 30, 255), (30, 200, 30, 255)], [(30, 30, 200, 255), (200, 200, 200, 255)]],
        [[(255, 255, 255, 255), (128, 128, 128, 128)], [(10, 10, 10, 0), (60, 90, 120, 64)]],
    ]:
        images.append({"uri": "data:image/png;base64," + base64.b64encode(png(rows)).decode()})
    sampler = {"magFilter": 9728, "minFilter": 9728, "wrapS": 33071, "wrapT": 33071}
    doc = {
        "asset": {"version": "2.0", "generator": "glint assets/specgloss/make_specgloss.py"},
        "extensionsUsed": ["KHR_materials_pbrSpecularGlossiness"],
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0, "translation": [-0.6, 0, 0]}, {"mesh": 1, "translation": [0.6, 0, 0]}],
        "meshes": [
            {"name": "gold", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                                             "indices": 3, "material": 0}]},
            {"name": "textured", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                                                 "indices": 3, "material": 1}]},
        ],
        "materials": [
            {"name": "gold",
             "pbrMetallicRoughness": {"baseColorFactor": [1.0, 0.766, 0.336, 1.0], "roughnessFactor": 0.1},
             "extensions": {"KHR_materials_pbrSpecularGlossiness": {
                 "diffuseFactor": [0.0, 0.0, 0.0, 1.0], "specularFactor": [1.0, 0.766, 0.336],
                 "glossinessFactor": 0.9}}},
            {"name": "textured",
             "extensions": {"KHR_materials_pbrSpecularGlossiness": {
                 "diffuseTexture": {"index": 0}, "diffuseFactor": [1.0, 1.0, 1.0, 1.0],
                 "specularGlossinessTexture": {"index": 1}, "specularFactor": [0.05, 0.05, 0.05],
                 "glossinessFactor": 0.5}}},
        ],
        "samplers": [sampler],
        "textures": [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 0}],
        "images": images,
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
        "bufferViews": views,
        "accessors": accessors,
    }
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "specgloss.gltf")
    with open(out, "w") as f:
        json.dump(doc, f)
        f.write("\n")


if __name__ == "__main__":
    main()
