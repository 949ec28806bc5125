#!/usr/bin/env python3
"""Writes the small test scenes of KHR_materials_diffuse_transmission and KHR_materials_dispersion.

dt-none.gltf, dt-0.gltf, dt-1.gltf: a white 2x2 quad at z = 0 facing a camera on +Z, specularFactor
0 (a pure Lambert base), lit only from behind by a directional light of irradiance pi travelling +Z;
without the extension, with diffuseTransmissionFactor 0, and with 1 (then its front shows radiance
E / pi = 1). dt-volume.gltf: the same light behind a unit cube with diffuse transmission 1 inside
KHR_materials_volume (thickness 1). disp-none.gltf, disp-0.gltf, disp-3.gltf: an orthographic camera
on +Z looking through a glass slab (transmission 1, IOR 1.5, volume, 2 thick, turned 60 degrees about
Y) at a thin white emissive vertical stripe; without KHR_materials_dispersion, with dispersion 0 and
with 3 (Abbe number 20/3). Pure Python, no dependencies: `python3 make_khr.py` rebuilds them.
"""
import base64
import json
import math
import os
import struct


def quad(cx, cy, cz, hx, hy):
    """A quad in the plane z = cz facing +Z, half-sizes hx, hy."""
    pos = [(cx - hx, cy - hy, cz), (cx + hx, cy - hy, cz), (cx + hx, cy + hy, cz), (cx - hx, cy + hy, cz)]
    return pos, [(0.0, 0.0, 1.0)] * 4, [0, 1, 2, 0, 2, 3]


def box(hx, hy, hz):
    """A closed box centred at the origin, flat-shaded, faces outwards (counter-clockwise)."""
    pos, nrm, idx = [], [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            n = [0.0, 0.0, 0.0]
            n[axis] = sign
            u, v = (axis + 1) % 3, (axis + 2) % 3
            h = [hx, hy, hz]
            corners = []
            for a, b in [(-1, -1), (1, -1), (1, 1), (-1, 1)]:
                p = [0.0, 0.0, 0.0]
                p[axis] = sign * h[axis]
                p[u] = a * h[u]
                p[v] = b * h[v]
                corners.append(tuple(p))
            if sign < 0:
                corners.reverse()
            k = len(pos)
            pos += corners
            nrm += [tuple(n)] * 4
            idx += [k, k + 1, k + 2, k, k + 2, k + 3]
    return pos, nrm, idx


class Doc:
    def __init__(self):
        self.blob = b""
        self.views, self.accessors, self.meshes = [], [], []

    def add(self, data, kind, comp, fmt):
        raw = b"".join(struct.pack(fmt, *(v if isinstance(v, tuple) else (v,))) for v in data)
        self.views.append({"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(raw)})
        acc = {"bufferView": len(self.views) - 1, "componentType": comp, "count": len(data), "type": kind}
        if kind == "VEC3":
            acc["min"] = [min(p[i] for p in data) for i in range(3)]
            acc["max"] = [max(p[i] for p in data) for i in range(3)]
        self.accessors.append(acc)
        self.blob += raw + b"\0" * (-len(raw) % 4)
        return len(self.accessors) - 1

    def mesh(self, name, geometry, material):
        pos, nrm, idx = geometry
        p = self.add(pos, "VEC3", 5126, "<3f")
        n = self.add(nrm, "VEC3", 5126, "<3f")
        i = self.add(idx, "SCALAR", 5123, "<H")
        self.meshes.append({"name": name, "primitives": [
            {"attributes": {"POSITION": p, "NORMAL": n}, "indices": i, "material": material}]})
        return len(self.meshes) - 1

    def write(self, path, nodes, materials, cameras, lights, used):
        doc = {
            "asset": {"version": "2.0", "generator": "glint assets/khr/make_khr.py"},
            "extensionsUsed": sorted(used),
            "scene": 0,
            "scenes": [{"nodes": list(range(len(nodes)))}],
            "nodes": nodes,
            "meshes": self.meshes,
            "materials": materials,
            "cameras": cameras,
            "buffers": [{"byteLength": len(self.blob), "uri": "data:application/octet-stream;base64,"
                         + base64.b64encode(self.blob).decode()}],
            "bufferViews": self.views,
            "accessors": self.accessors,
        }
        if lights:
            doc["extensions"] = {"KHR_lights_punctual": {"lights": lights}}
        with open(path, "w") as f:
            json.dump(doc, f, indent=1)
            f.write("\n")


# The light travels +Z: a directional light points down its node's -Z, turned half a turn about Y.
BEHIND = {"rotation": [0.0, 1.0, 0.0, 0.0], "extensions": {"KHR_lights_punctual": {"light": 0}}}
SUN = [{"type": "directional", "intensity": math.pi, "color": [1.0, 1.0, 1.0]}]


def diffuse_transmission(out, factor, volume=False):
    d = Doc()
    ext = {"KHR_materials_specular": {"specularFactor": 0.0}}
    used = {"KHR_lights_punctual", "KHR_materials_specular"}
    if factor is not None:
        ext["KHR_materials_diffuse_transmission"] = {"diffuseTransmissionFactor": factor}
        used.add("KHR_materials_diffuse_transmission")
    if volume:
        ext["KHR_materials_volume"] = {"thicknessFactor": 1.0}
        used.add("KHR_materials_volume")
    mat = {"name": "translucent", "pbrMetallicRoughness": {
        "baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0},
        "extensions": ext}
    geometry = box(0.5, 0.5, 0.5) if volume else quad(0.0, 0.0, 0.0, 1.0, 1.0)
    m = d.mesh("slab", geometry, 0)
    nodes = [{"mesh": m}, {"camera": 0, "translation": [0.0, 0.0, 3.0]}, BEHIND]
    cams = [{"type": "perspective", "perspective": {"yfov": 0.3, "aspectRatio": 1.0, "znear": 0.01}}]
    d.write(out, nodes, [mat], cams, SUN, used)


def dispersion(out, value):
    d = Doc()
    ext = {"KHR_materials_transmission": {"transmissionFactor": 1.0}, "KHR_materials_ior": {"ior": 1.5},
           "KHR_materials_volume": {"thicknessFactor": 2.0}}
    used = set(ext)
    if value is not None:
        ext["KHR_materials_dispersion"] = {"dispersion": value}
        used.add("KHR_materials_dispersion")
    glass = {"name": "glass", "pbrMetallicRoughness": {
        "baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.0},
        "extensions": ext}
    stripe = {"name": "stripe", "emissiveFactor": [1.0, 1.0, 1.0], "pbrMetallicRoughness": {
        "baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0}}
    slab = d.mesh("slab", box(5.0, 3.0, 1.0), 0)
    line = d.mesh("stripe", quad(0.0, 0.0, -8.0, 0.05, 3.0), 1)
    turn = math.radians(60.0)
    nodes = [
        {"mesh": slab, "rotation": [0.0, math.sin(turn / 2), 0.0, math.cos(turn / 2)]},
        {"mesh": line},
        {"camera": 0, "translation": [0.0, 0.0, 10.0]},
    ]
    cams = [{"type": "orthographic", "orthographic": {"xmag": 1.5, "ymag": 0.5, "znear": 0.01, "zfar": 100.0}}]
    d.write(out, nodes, [glass, stripe], cams, [], used)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    for name, factor in [("dt-none", None), ("dt-0", 0.0), ("dt-1", 1.0)]:
        diffuse_transmission(os.path.join(here, name + ".gltf"), factor)
    diffuse_transmission(os.path.join(here, "dt-volume.gltf"), 1.0, volume=True)
    for name, value in [("disp-none", None), ("disp-0", 0.0), ("disp-3", 3.0)]:
        dispersion(os.path.join(here, name + ".gltf"), value)


if __name__ == "__main__":
    main()
