#!/usr/bin/env python3
"""Time to a clean image: glint against Mitsuba 3 (llvm_ad_rgb) and Blender Cycles on the same scene,
camera, size, depth and thread count. A bench, not a test.

    speed.py OUTDIR [--glint target/release/glint] [--bpy PYTHON_WITH_BPY] [--spp 64]
             [--width 320] [--height 240] [--depth 5] [--threads 2] [--renderers glint,mitsuba,cycles]
             [--seeds 2]

This Python needs numpy, OpenEXR and mitsuba (`pip install mitsuba`; the llvm variant needs libLLVM:
`apt-get install libllvm19`, found through DRJIT_LIBLLVM_PATH, default /usr/lib/x86_64-linux-gnu/libLLVM-19.so).

    speed.py OUTDIR --scene many-emitters --renderers glint:power,glint:bvh,mitsuba,cycles

Scenes (`--scene`, ../shared/assets/obj):
- `bunny-cornell`: the Cornell box (Lambertian walls and boxes, its emissive ceiling quad as the
  only light) with the Stanford bunny as a rough metal (GGX, Schlick Fresnel from a base colour of
  0.9, roughness 0.3).
- `many-emitters`: the same room and bunny without the ceiling quad, lit by 1,200 small emissive
  triangles (4 colours and strengths, 300 each) strewn through its upper half: where a light
  sampler's choice among lights decides the noise.

- `helmet-env`: DamagedHelmet (../shared/assets/gltf) with its own textured materials, read by glint
  and by Blender's glTF importer (Mitsuba has no glTF reader, and exporting the five texture maps'
  glTF semantics to its principled BSDF would measure the export), under a generated lat-long sky
  (`sky.exr`: an elevation gradient, darker ground, and a sun of 3 degrees radius at 40 degrees,
  in the map's centre column, so the map is mirror-symmetric about that column and glint's and
  Cycles' longitude conventions give the same world); the camera of accuracy.py. glint and Cycles.

`glint:SAMPLER` runs glint with `--light-sampler SAMPLER` (power, bvh; plain `glint`: its default).
The script writes the geometry once as OBJ files
with explicit normals (the box flat, the bunny smooth), so every renderer reads the same triangles
and normals, and gives each renderer the same materials:
- glint: a scene file (Lambert: specular 0, roughness 1; metal: metallic 1); emitters two-sided.
- Mitsuba: twosided diffuse, principled (metallic 1, same roughness), area emitters; Mitsuba's are
  one-sided, so each emitter is a back-to-back pair (the reversed copy 1e-4 behind) as glint's are
  two-sided.
- Cycles: Diffuse BSDF; Principled metallic with single-scatter GGX; Emission added to the light's
  diffuse (Cycles emission is two-sided).
Depth: glint --max-depth D = Mitsuba max_depth D + 1 (path segments, 1 = emitters seen directly) =
Cycles D - 1 bounces.

Reported per renderer, in one run: sigma, the noise per sample (the root mean over pixels of each
pixel's variance across `--seeds` independent renders, default 2, times spp; with two seeds the RMSE
between them times sqrt(spp / 2)), and sigma* the same without the 0.1% of pixels of highest variance
(where a few glints or fireflies carry the whole RMSE, sigma* says how the rest of the image
converges; there two seeds give a noisy sigma, and more seeds at fewer spp a steadier one); ms per
sample (render time of the whole image / spp, load and build excluded; for Mitsuba after a 1-spp
warm-up that compiles its kernels); time to RMSE 0.01 = (ms per sample) x (sigma / 0.01)^2; and
the image mean relative to glint's (converged means should agree within 1%).
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
OBJ = HERE.parent.parent.parent / "shared" / "assets" / "obj"
EYE, LOOK_AT, FOV = (0.0, 1.0, 3.9), (0.0, 1.0, 0.0), 39.0


def read_obj(path):
    """Positions and triangles (fans of polygons) grouped by `usemtl` name."""
    v, groups, current = [], {}, "default"
    for line in open(path):
        w = line.split()
        if not w:
            continue
        if w[0] == "v":
            v.append([float(x) for x in w[1:4]])
        elif w[0] == "usemtl":
            current = w[1]
        elif w[0] == "f":
            idx = [int(t.split("/")[0]) for t in w[1:]]
            idx = [i - 1 if i > 0 else len(v) + i for i in idx]
            groups.setdefault(current, []).extend([idx[0], idx[k], idx[k + 1]] for k in range(1, len(idx) - 1))
    return np.array(v), {k: np.array(t) for k, t in groups.items()}


def read_mtl(path):
    mats, cur = {}, None
    for line in open(path):
        w = line.split("#")[0].split()
        if not w:
            continue
        if w[0] == "newmtl":
            cur = mats.setdefault(w[1], {})
        elif cur is not None and w[0] in ("Kd", "Ke"):
            cur[w[0]] = [float(x) for x in w[1:4]]
    return mats


def face_normals(p, tris):
    n = np.cross(p[tris[:, 1]] - p[tris[:, 0]], p[tris[:, 2]] - p[tris[:, 0]])
    return n / np.linalg.norm(n, axis=1, keepdims=True)


def write_obj(path, p, tris, normals):
    """`normals` per vertex (len(p)) or per triangle (flat: vertices written once per triangle)."""
    with open(path, "w") as f:
        if len(normals) == len(tris):
            p, normals = p[tris.reshape(-1)], np.repeat(normals, 3, axis=0)
            tris = np.arange(len(p)).reshape(-1, 3)
        f.writelines(f"v {a:.7g} {b:.7g} {c:.7g}\n" for a, b, c in p)
        f.writelines(f"vn {a:.7g} {b:.7g} {c:.7g}\n" for a, b, c in normals)
        f.writelines(f"f {a}//{a} {b}//{b} {c}//{c}\n" for a, b, c in tris + 1)


def emitter(out, name, p, tris, n, colour, radiance):
    """An emitter part, with the back-to-back twin (reversed, 1e-4 behind) one-sided renderers need."""
    write_obj(out / f"{name}.obj", p, tris, n)
    behind = p[tris.reshape(-1)] - 1e-4 * np.repeat(n, 3, axis=0)
    back = np.arange(len(behind)).reshape(-1, 3)
    write_obj(out / f"{name}_back.obj", behind, back[:, ::-1], -n)
    return (name, out / f"{name}.obj", {"kind": "emitter", "colour": colour, "radiance": radiance,
                                         "twin": str(out / f"{name}_back.obj")})


def many_emitters(out):
    """bunny_cornell without its ceiling light, lit by small triangles strewn through the room's upper half."""
    parts = [part for part in bunny_cornell(out) if part[2]["kind"] != "emitter"]
    rng = np.random.default_rng(7)
    groups = [("warm", [9.0, 6.0, 2.5]), ("cool", [1.5, 3.0, 7.0]), ("red", [14.0, 2.0, 1.5]), ("green", [2.0, 5.0, 2.0])]
    for name, radiance in groups:
        n = 300
        centre = rng.uniform([-0.95, 1.15, -0.95], [0.95, 1.9, 0.95], size=(n, 3))
        # Two random edges of about 4 cm from each centre.
        e1 = rng.normal(size=(n, 3))
        e1 *= 0.04 / np.linalg.norm(e1, axis=1, keepdims=True)
        e2 = np.cross(e1, rng.normal(size=(n, 3)))
        e2 *= 0.04 / np.linalg.norm(e2, axis=1, keepdims=True)
        p = np.stack([centre - (e1 + e2) / 3, centre + (2 * e1 - e2) / 3, centre + (2 * e2 - e1) / 3], axis=1)
        p = p.reshape(-1, 3)
        tris = np.arange(len(p)).reshape(-1, 3)
        parts.append(emitter(out, f"lights_{name}", p, tris, face_normals(p, tris), [0.0] * 3, radiance))
    return parts


def bunny_cornell(out):
    """The parts as (name, obj file, material) with material {kind, colour[, roughness, radiance]}."""
    box = OBJ / "CornellBox-Original" / "CornellBox-Original.obj"
    p, groups = read_obj(box)
    mtl = read_mtl(box.with_suffix(".mtl"))
    parts = []
    for name, tris in groups.items():
        n = face_normals(p, tris)
        m = mtl.get(name, {})
        if any(m.get("Ke", [0, 0, 0])):
            # Face down, into the room; the upward twin is for renderers with one-sided emitters.
            if n[:, 1].mean() > 0:
                tris, n = tris[:, ::-1], -n
            parts.append(emitter(out, "light", p, tris, n, m["Kd"], m["Ke"]))
        else:
            write_obj(out / f"{name}.obj", p, tris, n)
            parts.append((name, out / f"{name}.obj", {"kind": "diffuse", "colour": m.get("Kd", [0.8] * 3)}))
    bp, btris = read_obj(OBJ / "stanford-bunny" / "stanford-bunny.obj")
    btris = next(iter(btris.values()))
    a = math.radians(20.0)
    rot = np.array([[math.cos(a), 0, math.sin(a)], [0, 1, 0], [-math.sin(a), 0, math.cos(a)]])
    bp = (bp * 5.0) @ rot.T + np.array([-0.45, -0.16, 0.55])
    fn = np.cross(bp[btris[:, 1]] - bp[btris[:, 0]], bp[btris[:, 2]] - bp[btris[:, 0]])
    vn = np.zeros_like(bp)
    for k in range(3):
        np.add.at(vn, btris[:, k], fn)
    length = np.linalg.norm(vn, axis=1, keepdims=True)
    # Vertices no triangle uses (the scan has some) get any unit normal: Mitsuba refuses zero ones.
    vn = np.where(length > 0, vn / np.maximum(length, 1e-30), [0.0, 1.0, 0.0])
    write_obj(out / "bunny.obj", bp, btris, vn)
    parts.append(("bunny", out / "bunny.obj", {"kind": "metal", "colour": [0.9] * 3, "roughness": 0.3}))
    return parts


def helmet_env(out, width=512, height=256):
    """A glTF scene: {gltf, env} (main adds its camera as `view`); the sky written to `out`."""
    v = (np.arange(height) + 0.5) / height
    u = (np.arange(width) + 0.5) / width
    el = (0.5 - v)[:, None] * math.pi                      # +pi/2 at the top row
    az = (u - 0.5)[None, :] * 2 * math.pi                  # 0 at the centre column
    d = np.stack(np.broadcast_arrays(np.cos(el) * np.cos(az), np.sin(el), np.cos(el) * np.sin(az)), -1)
    sky = np.where(el[..., None] > 0, np.array([0.35, 0.5, 0.8]) * (0.4 + 0.6 * np.sin(el))[..., None]
                   + np.array([0.25, 0.22, 0.2]) * (1 - np.sin(el))[..., None],
                   np.array([0.12, 0.1, 0.08]) * np.ones_like(el)[..., None])
    sun_el = math.radians(40.0)
    sun = np.array([math.cos(sun_el), math.sin(sun_el), 0.0])
    sky = sky + np.where((d @ sun > math.cos(math.radians(3.0)))[..., None], np.array([1000.0, 950.0, 850.0]), 0.0)
    write_exr(out / "sky.exr", sky)
    return {"gltf": HERE.parent.parent.parent / "shared" / "assets" / "gltf" / "DamagedHelmet" / "glTF-Binary"
            / "DamagedHelmet.glb", "env": out / "sky.exr"}


SCENES = {"bunny-cornell": bunny_cornell, "many-emitters": many_emitters, "helmet-env": helmet_env}


def gltf_view(a, scene):
    from accuracy import bounds, camera
    b = bounds(a.glint, scene["gltf"])
    if b is None:
        sys.exit(f"{scene['gltf']}: glint info gives no bounds")
    eye, target = camera(*b, FOV, a.width / a.height)
    return ["--eye=" + eye, "--look-at=" + target, "--fov", str(FOV)]


def read_exr(path):
    import OpenEXR  # not in Blender's Python, which runs only cycles_job
    with OpenEXR.File(str(path)) as f:
        ch = f.channels()
        px = ch["RGBA"].pixels if "RGBA" in ch else ch["RGB"].pixels
        return px[..., :3].astype(np.float64)


def write_exr(path, rgb):
    import OpenEXR
    with OpenEXR.File({"compression": OpenEXR.ZIP_COMPRESSION}, {"RGB": rgb.astype(np.float32)}) as f:
        f.write(str(path))


def timed_glint(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    m = re.search(r"spp with \S+ in ([0-9.]+) s", r.stderr)
    if r.returncode != 0 or not m:
        sys.exit(f"glint failed: {r.stderr[-500:]}")
    return float(m.group(1))


def glint_command(a, parts, out, seed, light_sampler=None):
    """glint's command line for the scene `parts` (OBJ parts, or a glTF scene's dict) and the image it
    writes (profile.py runs the same command under perf)."""
    exr = out / f"glint{'_' + light_sampler if light_sampler else ''}_{seed}.exr"
    if isinstance(parts, dict):
        source, extra = str(parts["gltf"]), ["--env", str(parts["env"]), "--up", "0,1,0", *parts["view"]]
    else:
        toml = out / "scene.toml"
        lines = [f"[camera]\nposition = {list(EYE)}\nlook_at = {list(LOOK_AT)}\nfov = {FOV}\n"]
        for name, path, m in parts:
            lines.append(f'[[material]]\nname = "{name}"\nbase_color = {m["colour"]}')
            if m["kind"] == "metal":
                lines.append(f"metallic = 1.0\nroughness = {m['roughness']}")
            else:
                lines.append("metallic = 0.0\nroughness = 1.0\nspecular = 0.0")
            if m["kind"] == "emitter":
                lines.append(f"emissive = {m['radiance']}")
            lines.append(f'\n[[asset]]\npath = "{path.name}"\nmaterial = "{name}"\n')
        toml.write_text("\n".join(lines))
        source, extra = str(toml), []
    cmd = [a.glint, "render", source, "-o", str(exr), "--width", str(a.width), "--height", str(a.height),
           "--spp", str(a.spp), "--max-depth", str(a.depth), "--seed", str(seed), "--filter", "box",
           "--threads", str(a.threads), "--default-lights", "off", *extra, "--backend", "embree"]
    if light_sampler:
        cmd += ["--light-sampler", light_sampler]
    return cmd, exr


def glint(a, parts, out, seed, light_sampler=None):
    cmd, exr = glint_command(a, parts, out, seed, light_sampler)
    t = timed_glint(cmd)
    return read_exr(exr), t


def mitsuba(a, parts, out, seed, _cache={}):
    if isinstance(parts, dict):
        sys.exit("mitsuba: no glTF reader (see the helmet-env scene's note)")
    import drjit as dr
    import mitsuba as mi
    if not _cache:
        mi.set_variant("llvm_ad_rgb")
        dr.set_thread_count(a.threads)
        scene = {"type": "scene",
                 "integrator": {"type": "path", "max_depth": a.depth + 1},
                 "sensor": {"type": "perspective", "fov": FOV, "fov_axis": "y",
                            "to_world": mi.ScalarTransform4f().look_at(origin=EYE, target=LOOK_AT, up=(0, 1, 0)),
                            "film": {"type": "hdrfilm", "width": a.width, "height": a.height,
                                     "rfilter": {"type": "box"}, "pixel_format": "rgb"},
                            "sampler": {"type": "independent", "sample_count": a.spp}}}
        for name, path, m in parts:
            rgb = {"type": "rgb", "value": m["colour"]}
            if m["kind"] == "metal":
                bsdf = {"type": "principled", "base_color": rgb, "metallic": 1.0, "roughness": m["roughness"]}
            else:
                bsdf = {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": rgb}}
            scene[name] = {"type": "obj", "filename": str(path), "face_normals": False, "bsdf": bsdf}
            if m["kind"] == "emitter":
                emitter = {"type": "area", "radiance": {"type": "rgb", "value": m["radiance"]}}
                scene[name]["emitter"] = emitter
                scene[name + "_back"] = {"type": "obj", "filename": m["twin"], "face_normals": False,
                                         "bsdf": bsdf, "emitter": dict(emitter)}
        _cache["scene"] = mi.load_dict(scene)
        np.array(mi.render(_cache["scene"], spp=1, seed=999))  # compiles the kernels
    t0 = time.time()
    img = np.array(mi.render(_cache["scene"], spp=a.spp, seed=seed), dtype=np.float64)[..., :3]
    return img, time.time() - t0


def cycles_gltf(a, scene, out, seed):
    exr = out / f"cycles_{seed}.exr"
    cmd = [a.bpy, str(HERE / "render_cycles.py"), str(scene["gltf"]), str(exr), "--width", str(a.width),
           "--height", str(a.height), "--spp", str(a.spp), "--bounces", str(a.depth - 1), "--threads",
           str(a.threads), "--seed", str(seed), "--distribution", "GGX", "--env", str(scene["env"]),
           *scene["view"]]
    r = subprocess.run(cmd, capture_output=True, text=True)
    m = re.search(r'"render_s": ([0-9.]+)', r.stdout)
    if r.returncode != 0 or not m:
        sys.exit(f"Cycles failed: {(r.stdout + r.stderr)[-800:]}")
    return read_exr(exr), float(m.group(1))


def cycles(a, parts, out, seed):
    if isinstance(parts, dict):
        return cycles_gltf(a, parts, out, seed)
    job = out / "cycles_job.json"
    job.write_text(json.dumps({"parts": [[n, str(p), m] for n, p, m in parts], "width": a.width,
                               "height": a.height, "spp": a.spp, "bounces": a.depth - 1,
                               "threads": a.threads, "seed": seed, "out": str(out / f"cycles_{seed}.exr")}))
    r = subprocess.run([a.bpy, str(Path(__file__)), "--cycles-job", str(job)], capture_output=True, text=True)
    m = re.search(r'"render_s": ([0-9.]+)', r.stdout)
    if r.returncode != 0 or not m:
        sys.exit(f"Cycles failed: {(r.stdout + r.stderr)[-800:]}")
    return read_exr(out / f"cycles_{seed}.exr"), float(m.group(1))


def cycles_job(path):
    """Run under Blender's Python: the parts imported as OBJ, the materials built as node trees."""
    import bpy
    sys.path.insert(0, str(HERE))
    import render_cycles as rc
    j = json.loads(Path(path).read_text())
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    for name, obj, m in j["parts"]:
        bpy.ops.wm.obj_import(filepath=obj, forward_axis="NEGATIVE_Z", up_axis="Y")
        mat = bpy.data.materials.new(name)
        mat.use_nodes = True
        nt = mat.node_tree
        nt.nodes.clear()
        out = nt.nodes.new("ShaderNodeOutputMaterial")
        if m["kind"] == "metal":
            b = nt.nodes.new("ShaderNodeBsdfPrincipled")
            b.distribution = "GGX"
            b.inputs["Base Color"].default_value = (*m["colour"], 1.0)
            b.inputs["Metallic"].default_value = 1.0
            b.inputs["Roughness"].default_value = m["roughness"]
        else:
            b = nt.nodes.new("ShaderNodeBsdfDiffuse")
            b.inputs["Color"].default_value = (*m["colour"], 1.0)
        if m["kind"] == "emitter":
            e = nt.nodes.new("ShaderNodeEmission")
            top = max(m["radiance"])
            e.inputs["Color"].default_value = (*[c / top for c in m["radiance"]], 1.0)
            e.inputs["Strength"].default_value = top
            add = nt.nodes.new("ShaderNodeAddShader")
            nt.links.new(b.outputs[0], add.inputs[0])
            nt.links.new(e.outputs[0], add.inputs[1])
            b = add
        nt.links.new(b.outputs[0], out.inputs["Surface"])
        for ob in bpy.context.selected_objects:
            ob.data.materials.clear()
            ob.data.materials.append(mat)
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world
    rc.setup_camera(scene, ",".join(map(str, EYE)), ",".join(map(str, LOOK_AT)), FOV)
    rc.setup_render(scene, argparse.Namespace(**{k: j[k] for k in ("width", "height", "threads", "spp", "seed",
                                                                      "bounces", "out")}))
    t0 = time.time()
    bpy.ops.render.render(write_still=True)
    print(json.dumps({"render_s": time.time() - t0}))


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--cycles-job":
        return cycles_job(sys.argv[2])
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--glint", default=str(HERE.parent.parent / "target" / "release" / "glint"))
    ap.add_argument("--bpy", default=os.environ.get("PY_BPY", "python3"))
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=240)
    ap.add_argument("--depth", type=int, default=5)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--renderers", default="glint,mitsuba,cycles")
    ap.add_argument("--seeds", type=int, default=2, help="independent renders per renderer (at least 2)")
    ap.add_argument("--scene", choices=sorted(SCENES), default="bunny-cornell")
    a = ap.parse_args()
    if a.seeds < 2:
        ap.error("--seeds must be at least 2")
    os.environ.setdefault("DRJIT_LIBLLVM_PATH", "/usr/lib/x86_64-linux-gnu/libLLVM-19.so")
    out = Path(a.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    parts = SCENES[a.scene](out)
    if isinstance(parts, dict):
        parts["view"] = gltf_view(a, parts)  # `glint info` once, not per render
    renderers = {"glint": glint, "mitsuba": mitsuba, "cycles": cycles}
    rows = []
    for name in a.renderers.split(","):
        base, _, option = name.partition(":")
        run = (lambda a, parts, out, s: glint(a, parts, out, s, option)) if option else renderers[base]
        images, times = zip(*(run(a, parts, out, s) for s in range(1, a.seeds + 1)))
        stack = np.stack(images)
        mean = stack.mean(0)
        write_exr(out / f"{name}_mean.exr", mean)
        # Each pixel's variance of one sample: the unbiased variance across the seeds' images times spp
        # (with two seeds, the squared difference / 2: the RMSE between them times sqrt(spp / 2)).
        var = np.sort((stack.var(0, ddof=1) * a.spp).mean(-1).ravel())
        sigma = float(np.sqrt(var.mean()))
        trimmed = float(np.sqrt(var[:len(var) - len(var) // 1000].mean()))
        ms = 1e3 * sum(times) / (len(times) * a.spp)
        rows.append({"renderer": name, "sigma": sigma, "sigma_trimmed": trimmed, "ms_per_spp": ms,
                     "s_to_rmse_0.01": ms / 1e3 * (sigma / 0.01) ** 2, "mean": float(mean.mean())})
        print(json.dumps(rows[-1]), flush=True)
    ref = rows[0]
    lines = [f"{a.scene}, {a.width}x{a.height}, {a.spp} spp x {a.seeds} seeds, glint depth {a.depth}, {a.threads} threads, "
             f"load average {os.getloadavg()[0]:.1f}", "",
             f"| renderer | sigma | sigma* | ms/spp | s to RMSE 0.01 | mean / {ref['renderer']}'s | time ratio to {ref['renderer']} |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['renderer']} | {r['sigma']:.3f} | {r['sigma_trimmed']:.3f} | {r['ms_per_spp']:.1f} | "
                     f"{r['s_to_rmse_0.01']:.1f} | "
                     f"{r['mean'] / ref['mean']:.4f} | {r['s_to_rmse_0.01'] / ref['s_to_rmse_0.01']:.2f} |")
    text = "\n".join(lines) + "\n"
    (out / "table.md").write_text(text)
    (out / "results.json").write_text(json.dumps(rows, indent=1))
    print(text)


if __name__ == "__main__":
    main()
