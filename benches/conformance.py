#!/usr/bin/env python3
"""Conformance table over every glTF model and variant in ../shared/assets/gltf and glint's own
compressed test files in assets/: does it load, which extensions it uses, does it render without a
non-finite pixel, does a compressed variant render like its original (relative mean absolute
difference at the same seed), and how long it takes to load against the original (median of
`glint info` wall times, process start included). Not part of the test suite.

Usage: benches/conformance.py [--glint target/release/glint] [--out DIR] [--repeat 5]
Needs numpy and OpenEXR in this Python (e.g. a venv outside the repository).
"""
import argparse
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np
import OpenEXR

ROOT = Path(__file__).resolve().parent.parent
SHARED = ROOT.parent / "shared" / "assets" / "gltf"

# Compressed files glint carries itself, with the original each was made from (assets/*/README.md).
OWN = {
    "assets/meshopt/duck-ext.glb": "Duck/glTF-Binary",
    "assets/meshopt/boxanimated-khr.glb": "BoxAnimated/glTF-Binary",
    "assets/meshopt/meshprimitivemodes-khr.glb": "MeshPrimitiveModes/glTF",
    "assets/webp/boxtextured-webp.glb": "BoxTextured/glTF-Binary",
    "assets/draco/Box.gltf": "Box/glTF-Binary",
}
# Variants that hold the uncompressed data, in order of preference.
ORIGINALS = ["glTF-Binary", "glTF", "glTF-Embedded"]


def model_file(folder):
    files = sorted(folder.glob("*.glb")) + sorted(folder.glob("*.gltf"))
    return files[0] if files else None


def read_rgb(path):
    with OpenEXR.File(str(path)) as f:
        ch = f.channels()
        key = "RGBA" if "RGBA" in ch else "RGB"
        return ch[key].pixels[..., :3].astype(np.float64)


def info(glint, path, repeat):
    times, out = [], None
    for _ in range(repeat):
        t = time.perf_counter()
        r = subprocess.run([glint, "info", str(path)], capture_output=True, text=True)
        times.append(time.perf_counter() - t)
        out = r
    return out, statistics.median(times)


def extensions(text):
    for line in text.splitlines():
        if "extensions used" in line:
            used = line.split("extensions used", 1)[1].strip()
            return ", ".join(e.split(" ")[0] for e in used.split(", ") if e)
    return ""


def render(glint, path, out):
    r = subprocess.run(
        [glint, "render", str(path), "-o", str(out), "--width", "96", "--height", "72",
         "--spp", "8", "--seed", "1", "--threads", "2", "-q"],
        capture_output=True, text=True)
    return r, (read_rgb(out) if r.returncode == 0 and out.exists() else None)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--glint", default=str(ROOT / "target/release/glint"))
    ap.add_argument("--out", default=None)
    ap.add_argument("--repeat", type=int, default=5)
    a = ap.parse_args()
    out = Path(a.out or tempfile.mkdtemp(prefix="conformance-"))
    out.mkdir(parents=True, exist_ok=True)

    rows = []  # (label, file, original file or None)
    for model in sorted(p for p in SHARED.iterdir() if p.is_dir() and p.name != "LICENSES"):
        variants = sorted(v for v in model.iterdir() if v.is_dir() and v.name.startswith("glTF"))
        original = next((model_file(model / o) for o in ORIGINALS if (model / o).is_dir()), None)
        for v in variants:
            f = model_file(v)
            if f is None:
                continue
            orig = original if v.name not in ORIGINALS else None
            rows.append((f"{model.name}/{v.name}", f, orig))
    for own, orig in OWN.items():
        rows.append((own, ROOT / own, model_file(SHARED / orig)))
    dequant = ROOT / "assets/dequantized/AnimatedMorphCube.gltf"
    rows.append(("AnimatedMorphCube/glTF-Quantized vs assets/dequantized",
                 SHARED / "AnimatedMorphCube/glTF-Quantized/AnimatedMorphCube.gltf", dequant))

    print("| model / variant | loads | extensions used | renders finite | rmad vs original | load time vs original |")
    print("|---|---|---|---|---|---|")
    for k, (label, f, orig) in enumerate(rows):
        r, t = info(a.glint, f, a.repeat)
        loads = "yes" if r.returncode == 0 else "no: " + r.stderr.strip().splitlines()[-1][:80]
        exts = extensions(r.stdout) if r.returncode == 0 else ""
        finite, rmad, ratio = "", "", ""
        if r.returncode == 0:
            rr, img = render(a.glint, f, out / f"{k}.exr")
            finite = "yes" if img is not None and np.isfinite(img).all() else "NO"
            if orig is not None and img is not None:
                ro, ref = render(a.glint, orig, out / f"{k}-orig.exr")
                if ref is not None and ref.shape == img.shape:
                    rmad = f"{np.abs(img - ref).mean() / max(ref.mean(), 1e-9):.2e}"
                _, t0 = info(a.glint, orig, a.repeat)
                ratio = f"{t / t0:.2f}x ({t * 1e3:.0f} / {t0 * 1e3:.0f} ms)"
        print(f"| {label} | {loads} | {exts} | {finite} | {rmad} | {ratio} |", flush=True)


if __name__ == "__main__":
    main()
