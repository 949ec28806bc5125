#!/usr/bin/env python3
"""Accuracy of glint's glTF materials against Blender Cycles, model by model: both render the model
under the same camera, a constant white world and matched path depth; the table says how far apart
they are beyond glint's own seed-to-seed noise. A bench, not a test (minutes per model).

    accuracy.py OUTDIR [MODEL ...] [--glint target/release/glint] [--bpy PYTHON_WITH_BPY]
                [--spp 256] [--width 320] [--height 240] [--depth 8] [--fov 35]
                [--distribution importer|GGX|MULTI_GGX] [--tint importer|squared]
                [--absorption importer|spec] [--anisotropy importer|spec] [--iridescence importer|thin-film|spec]
                [--thin-walled importer|spec] [--punctual spec|importer] [--srgb-filter spec|importer] [--strip KHR_materials_sheen ...]
                [--glint-args '--layering albedo --ggx multi'] [--cycles-from OTHER_OUTDIR]

--glint-args are added to both glint renders; --cycles-from reuses another run's cycles.exr per model
(made with the same size, spp, depth and Cycles settings) instead of rendering Cycles again.

MODEL is a name under ../shared/assets/gltf (the default list is issue 17's) or NAME=PATH. Needs numpy,
OpenEXR and Pillow in this Python; Blender's bpy in the --bpy one. Per model in OUTDIR/NAME: glint.exr
(seed 1), glint2.exr (seed 2), cycles.exr, logs; OUTDIR/results.json, OUTDIR/table.md and previews
(glint | Cycles | |difference| x 4) of the three models with the largest excess.

Measures, on the model's pixels (glint's coverage alpha > 0 in either seed):
- mean ratio: mean Rec.709 luminance of glint / Cycles;
- rmad: mean over pixels and RGB of |glint - Cycles| / mean of Cycles;
- noise: the same rmad between glint's two seeds;
- excess: rmad - noise (what is left once glint's own noise is taken away; Cycles' noise, about
  glint's at equal spp, stays in it).
"""
import argparse
import json
import math
import os
import shlex
import shutil
import struct
import subprocess
import sys
import urllib.parse
from pathlib import Path

import numpy as np
import OpenEXR
from PIL import Image

HERE = Path(__file__).resolve().parent
ASSETS = HERE.parent.parent.parent / "shared" / "assets" / "gltf"
MODELS = ["MetalRoughSpheresNoTextures", "DamagedHelmet", "ClearCoatTest", "ClearCoatCarPaint",
          "SheenCloth", "SpecularTest", "IridescenceSuzanne", "AnisotropyStrengthTest",
          "AnisotropyRotationTest", "TransmissionRoughnessTest", "AttenuationTest",
          "TransmissionTest", "ToyCar", "GlassVaseFlowers", "MaterialsVariantsShoe"]
# Files whose lights are in glint's convention (1 cd = 1 W/sr) rather than photometric units.
COMPAT_LIGHTS = {"IridescenceSuzanne"}


def model_path(name):
    for sub, ext in (("glTF-Binary", ".glb"), ("glTF", ".gltf")):
        p = ASSETS / name / sub / (name + ext)
        if p.is_file():
            return p
    return None


def prepared(src, folder, strip=()):
    """A copy of the model in `folder` that both renderers read. Primitives without a material get
    an explicit empty one (glint gives them glTF's default material, Blender's importer none: its
    own grey, not a shading difference worth measuring); material N is named "gltfN NAME" so that
    the Cycles driver can find it (glTF names repeat); extensionsRequired is dropped (Blender's
    importer refuses a file that requires an extension it lacks, KHR_materials_iridescence, which
    the driver maps itself); the material extensions in `strip` are taken out. A .gltf's external
    files are linked beside the copy."""
    data = src.read_bytes()
    glb = data[:4] == b"glTF"
    n = struct.unpack_from("<I", data, 12)[0] if glb else len(data)
    doc = json.loads(data[20:20 + n] if glb else data)
    missing = [p for m in doc.get("meshes", []) for p in m["primitives"] if "material" not in p]
    if missing:
        doc.setdefault("materials", []).append({"name": "gltf-default"})
        for p in missing:
            p["material"] = len(doc["materials"]) - 1
    for i, m in enumerate(doc.get("materials", [])):
        m["name"] = f"gltf{i} {m.get('name', '')}".strip()
        for ext in strip:
            m.get("extensions", {}).pop(ext, None)
    doc.pop("extensionsRequired", None)
    text = json.dumps(doc).encode()
    if not glb:
        for item in doc.get("buffers", []) + doc.get("images", []):
            uri = item.get("uri", "")
            link = folder / urllib.parse.unquote(uri)
            if uri and not uri.startswith("data:") and not link.exists():
                link.parent.mkdir(parents=True, exist_ok=True)
                link.symlink_to((src.parent / urllib.parse.unquote(uri)).resolve())
        dst = folder / "model.gltf"
        dst.write_bytes(text)
        return dst
    text += b" " * (-len(text) % 4)
    rest = data[20 + n:]
    out = struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(text) + len(rest))
    out += struct.pack("<II", len(text), 0x4E4F534A) + text + rest
    dst = folder / "model.glb"
    dst.write_bytes(out)
    return dst


def bounds(glint, path):
    out = subprocess.run([glint, "info", str(path)], capture_output=True, text=True).stdout
    for line in out.splitlines():
        if line.strip().startswith("bounds"):
            lo, hi = line.split("bounds", 1)[1].split("..")
            parse = lambda s: np.array([float(v) for v in s.strip(" []\n").split(",")])
            return parse(lo), parse(hi)
    return None


def camera(lo, hi, fov_deg, aspect, elevation_deg=15.0):
    """Eye and target: the bounding sphere fills the narrower field of view, seen from +Z, a little
    from above."""
    centre, radius = (lo + hi) / 2, np.linalg.norm(hi - lo) / 2
    half = math.radians(fov_deg) / 2
    half = min(half, math.atan(math.tan(half) * aspect))
    dist = radius / math.sin(half)
    el = math.radians(elevation_deg)
    eye = centre + dist * np.array([0.0, math.sin(el), math.cos(el)])
    fmt = lambda v: ",".join(f"{x:.6g}" for x in v)
    return fmt(eye), fmt(centre)


def read_exr(path):
    with OpenEXR.File(str(path)) as f:
        ch = f.channels()
        if "RGBA" in ch:
            px = ch["RGBA"].pixels.astype(np.float64)
            return px[..., :3], px[..., 3]
        if "RGB" in ch:
            px = ch["RGB"].pixels.astype(np.float64)
            return px, np.ones(px.shape[:2])
        rgb = np.stack([ch[c].pixels for c in "RGB"], -1).astype(np.float64)
        return rgb, (ch["A"].pixels.astype(np.float64) if "A" in ch else np.ones(rgb.shape[:2]))


def write_world(path):
    px = np.ones((8, 16, 3), np.float32)
    with OpenEXR.File({"compression": OpenEXR.ZIP_COMPRESSION}, {"RGB": px}) as f:
        f.write(str(path))


def lum(rgb):
    return rgb @ np.array([0.2126, 0.7152, 0.0722])


def rmad(a, b, mask):
    return float(np.abs(a - b)[mask].mean() / max(b[mask].mean(), 1e-12))


def preview(path, images):
    srgb = lambda x: np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(np.clip(x, 0, None), 1 / 2.4) - 0.055)
    tiles = [np.clip(srgb(np.clip(im, 0, 1)), 0, 1) for im in images]
    Image.fromarray((np.concatenate(tiles, 1) * 255 + 0.5).astype(np.uint8)).save(path)


def run(cmd, log):
    with open(log, "w") as f:
        return subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT).returncode == 0


def measure(a, name, path, out):
    d = out / name
    d.mkdir(parents=True, exist_ok=True)
    path = prepared(path, d, a.strip)
    b = bounds(a.glint, path)
    if b is None:
        return {"model": name, "error": "glint info gives no bounds"}
    eye, target = camera(*b, a.fov, a.width / a.height)
    size = ["--width", str(a.width), "--height", str(a.height), "--spp", str(a.spp)]
    view = ["--eye=" + eye, "--look-at=" + target, "--fov", str(a.fov)]
    for seed, exr in ((1, "glint.exr"), (2, "glint2.exr")):
        cmd = [a.glint, "render", str(path), "-o", str(d / exr), *size, *view, "--up", "0,1,0",
               "--default-lights", "off", "--env", str(out / "world.exr"), "--max-depth", str(a.depth),
               "--seed", str(seed), "--filter", "box", "--threads", "2", *shlex.split(a.glint_args)]
        if not run(cmd, d / f"glint{seed}.log"):
            return {"model": name, "error": "glint failed: " + (d / f"glint{seed}.log").read_text()[-300:]}
    cmd = [a.bpy, str(HERE / "render_cycles.py"), str(path), str(d / "cycles.exr"), *size,
           "--bounces", str(a.depth - 1), *view, "--threads", "2", "--distribution", a.distribution,
           "--tint", a.tint, "--absorption", a.absorption, "--anisotropy", a.anisotropy,
           "--iridescence", a.iridescence, "--thin-walled", a.thin_walled,
           "--punctual", a.punctual, "--srgb-filter", a.srgb_filter, "--report", str(d / "cycles.json"), "--lights", "COMPAT" if name in COMPAT_LIGHTS else "SPEC"]
    reuse = Path(a.cycles_from) / name / "cycles.exr" if a.cycles_from else None
    if reuse is not None and reuse.is_file():
        shutil.copyfile(reuse, d / "cycles.exr")
    elif not run(cmd, d / "cycles.log"):
        return {"model": name, "error": "Cycles failed: " + (d / "cycles.log").read_text()[-300:]}
    g, ga = read_exr(d / "glint.exr")
    g2, g2a = read_exr(d / "glint2.exr")
    c, _ = read_exr(d / "cycles.exr")
    mask = (ga > 0) | (g2a > 0)
    diff, noise = rmad(g, c, mask), rmad(g2, g, mask)
    return {"model": name, "pixels": int(mask.sum()),
            "mean_ratio": float(lum(g)[mask].mean() / max(lum(c)[mask].mean(), 1e-12)),
            "rmad": diff, "noise": noise, "excess": diff - noise,
            "images": [str(d / "glint.exr"), str(d / "cycles.exr")]}


def table(results, a):
    lines = [f"{a.width}x{a.height}, {a.spp} spp, glint --max-depth {a.depth} (Cycles {a.depth - 1} bounces), "
             f"distribution {a.distribution}, tint {a.tint}, absorption {a.absorption}, "
             f"anisotropy {a.anisotropy}, iridescence {a.iridescence}, thin-walled {a.thin_walled}, "
             f"punctual {a.punctual}, srgb filter {a.srgb_filter}, "
             f"glint args '{a.glint_args}'"
             + (f", without {', '.join(a.strip)}" if a.strip else ""), "",
             "| model | glint/Cycles mean | rmad | glint noise | excess | within targets |",
             "|---|---|---|---|---|---|"]
    for r in results:
        if "error" in r:
            lines.append(f"| {r['model']} | {r['error'].splitlines()[-1] if r['error'] else ''} | | | | no |")
            continue
        ok = r["excess"] <= 0.015 and abs(r["mean_ratio"] - 1) <= 0.03
        lines.append(f"| {r['model']} | {r['mean_ratio']:.3f} | {r['rmad']:.3f} | {r['noise']:.3f} | "
                     f"{r['excess']:.3f} | {'yes' if ok else 'no'} |")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("models", nargs="*")
    ap.add_argument("--glint", default=str(HERE.parent.parent / "target" / "release" / "glint"))
    ap.add_argument("--bpy", default=os.environ.get("PY_BPY", "python3"))
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=240)
    ap.add_argument("--depth", type=int, default=8)
    ap.add_argument("--fov", type=float, default=35.0)
    ap.add_argument("--distribution", default="GGX", choices=["importer", "GGX", "MULTI_GGX"])
    ap.add_argument("--anisotropy", default="importer", choices=["importer", "spec"])
    ap.add_argument("--glint-args", default="")
    ap.add_argument("--cycles-from", default="")
    ap.add_argument("--tint", default="importer", choices=["importer", "squared"])
    ap.add_argument("--iridescence", default="thin-film", choices=["importer", "thin-film", "spec"])
    ap.add_argument("--thin-walled", default="importer", choices=["importer", "spec"])
    ap.add_argument("--strip", action="append", default=[], metavar="EXTENSION",
                    help="take this material extension out of the model for both renderers")
    ap.add_argument("--absorption", default="spec", choices=["importer", "spec"])
    ap.add_argument("--srgb-filter", default="spec", choices=["importer", "spec"],
                    help="spec: Cycles interpolates sRGB textures' decoded values, as glint (see render_cycles.py)")
    ap.add_argument("--punctual", default="spec", choices=["importer", "spec"],
                    help="spec: Blender's lights of no size, as KHR_lights_punctual's (see render_cycles.py)")
    a = ap.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    write_world(out / "world.exr")
    results = []
    for spec in a.models or MODELS:
        name, _, given = spec.partition("=")
        path = Path(given) if given else model_path(name)
        if path is None or not path.is_file():
            print(f"{name}: not found under {ASSETS}; skipped", file=sys.stderr)
            continue
        r = measure(a, name, path, out)
        results.append(r)
        print(json.dumps({k: v for k, v in r.items() if k != "images"}), flush=True)
    (out / "results.json").write_text(json.dumps(results, indent=1))
    text = table(results, a)
    worst = sorted((r for r in results if "excess" in r), key=lambda r: -r["excess"])[:3]
    for r in worst:
        g, c = (read_exr(p)[0] for p in r["images"])
        preview(out / f"{r['model']}.png", [g, c, np.abs(g - c) * 4])
    (out / "table.md").write_text(text)
    print(text)


if __name__ == "__main__":
    main()
