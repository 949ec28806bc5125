#!/usr/bin/env python3
"""Writes glTF scenes of many copies of one mesh, each twice: placed as instances
(EXT_mesh_gpu_instancing) and baked into one mesh of the same world-space triangles, so that
`glint bench rays` measures instancing against flattening on the same geometry.

    python3 benches/scenes/instances.py OUT_DIR

writes OUT_DIR/{tetra-100k,sphere-8,sphere-64}{,-baked}.gltf (with .bin buffers):
tetra-100k is a 4-triangle tetrahedron on a 47^3 grid (100k copies), sphere-N a 4,900-triangle
UV sphere N times on a line along x, each copy turned about y so that the copies differ.
"""
import json
import math
import struct
import sys
from pathlib import Path


def tetra():
    pos = [(0, 0, 0), (0.5, 0, 0), (0, 0.5, 0), (0, 0, 0.5)]
    idx = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
    return pos, idx


def sphere(rings=35, segments=70):
    pos = []
    for r in range(rings + 1):
        th = math.pi * r / rings
        for s in range(segments):
            ph = 2 * math.pi * s / segments
            pos.append((math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph)))
    idx = []
    for r in range(rings):
        for s in range(segments):
            a, b = r * segments + s, r * segments + (s + 1) % segments
            c, d = a + segments, b + segments
            if r > 0:
                idx.append((a, b, c))
            if r < rings - 1:
                idx.append((b, d, c))
    return pos, idx


def write(path, pos, idx, translations, rotations_y):
    """One mesh; instanced when translations has several rows, else as given."""
    bin_ = bytearray()
    for p in pos:
        bin_ += struct.pack("<3f", *p)
    pos_len = len(bin_)
    for t in idx:
        bin_ += struct.pack("<3I", *t)
    idx_len = len(bin_) - pos_len
    lo = [min(p[a] for p in pos) for a in range(3)]
    hi = [max(p[a] for p in pos) for a in range(3)]
    views = [
        {"buffer": 0, "byteLength": pos_len},
        {"buffer": 0, "byteOffset": pos_len, "byteLength": idx_len},
    ]
    accessors = [
        {"bufferView": 0, "componentType": 5126, "count": len(pos), "type": "VEC3", "min": lo, "max": hi},
        {"bufferView": 1, "componentType": 5125, "count": 3 * len(idx), "type": "SCALAR"},
    ]
    node = {"mesh": 0}
    used = []
    if translations is not None:
        attrs = {}
        off = len(bin_)
        for t in translations:
            bin_ += struct.pack("<3f", *t)
        views.append({"buffer": 0, "byteOffset": off, "byteLength": len(bin_) - off})
        accessors.append({"bufferView": 2, "componentType": 5126, "count": len(translations), "type": "VEC3"})
        attrs["TRANSLATION"] = 2
        if rotations_y is not None:
            off = len(bin_)
            for a in rotations_y:
                bin_ += struct.pack("<4f", 0, math.sin(a / 2), 0, math.cos(a / 2))
            views.append({"buffer": 0, "byteOffset": off, "byteLength": len(bin_) - off})
            accessors.append({"bufferView": 3, "componentType": 5126, "count": len(rotations_y), "type": "VEC4"})
            attrs["ROTATION"] = 3
        node["extensions"] = {"EXT_mesh_gpu_instancing": {"attributes": attrs}}
        used = ["EXT_mesh_gpu_instancing"]
    doc = {
        "asset": {"version": "2.0", "generator": "benches/scenes/instances.py"},
        "buffers": [{"byteLength": len(bin_), "uri": path.stem + ".bin"}],
        "bufferViews": views,
        "accessors": accessors,
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "nodes": [node],
        "scenes": [{"nodes": [0]}],
        "scene": 0,
    }
    if used:
        doc["extensionsUsed"] = used
    path.with_suffix(".bin").write_bytes(bin_)
    path.write_text(json.dumps(doc))


def baked(pos, idx, translations, rotations_y):
    """The copies' world-space vertices and triangles as one mesh."""
    out_pos, out_idx = [], []
    for k, t in enumerate(translations):
        a = rotations_y[k] if rotations_y else 0.0
        c, s = math.cos(a), math.sin(a)
        base = len(out_pos)
        for x, y, z in pos:
            # glTF's rotation about +y: x' = c x + s z, z' = -s x + c z.
            out_pos.append((c * x + s * z + t[0], y + t[1], -s * x + c * z + t[2]))
        out_idx += [(i + base, j + base, l + base) for i, j, l in idx]
    return out_pos, out_idx


def main():
    out = Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    side = 47
    grid = [(float(i % side), float(i // side % side), float(i // side // side)) for i in range(100_000)]
    cases = [("tetra-100k", tetra(), grid, None)]
    for n in (8, 64):
        cases.append((f"sphere-{n}", sphere(), [(2.5 * k, 0.0, 0.0) for k in range(n)], [0.7 * k for k in range(n)]))
    for name, (pos, idx), ts, rs in cases:
        write(out / f"{name}.gltf", pos, idx, ts, rs)
        bp, bi = baked(pos, idx, ts, rs)
        write(out / f"{name}-baked.gltf", bp, bi, None, None)
        print(f"{name}: {len(ts)} copies of {len(idx)} triangles")


if __name__ == "__main__":
    main()
