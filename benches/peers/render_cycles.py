#!/usr/bin/env python3
"""Blender Cycles as a peer renderer: one glTF model, imported by Blender's own glTF importer, rendered
unbiased to a linear EXR under a camera and world given on the command line (glTF coordinates, +Y up).

Run with a Python that has `bpy` (pip install bpy==5.0.1, in a venv outside the repository). Shared by
the accuracy bench (accuracy.py) and meant for the speed bench too. (Not named cycles.py: Blender
imports its Cycles add-on as the module `cycles`, and this script's folder is first on sys.path.)

    render_cycles.py MODEL OUT.exr --width W --height H --spp N --eye X,Y,Z --look-at X,Y,Z --fov DEG
              --bounces B [--threads 2] [--seed 1] [--world 1.0] [--distribution importer|GGX]
              [--tint importer|squared] [--absorption importer|spec] [--anisotropy importer|spec]
              [--iridescence importer|thin-film|spec] [--thin-walled importer|spec]
              [--lights SPEC|COMPAT] [--punctual importer|spec] [--srgb-filter importer|spec]
              [--env MAP.exr] [--report T.json]

Why each setting:
- Unbiased: no sample clamping, no glossy filter, caustics on, light threshold 0, no adaptive
  sampling, no denoiser, no path guiding; box pixel filter of width 1 (glint's `--filter box`).
- Depth: Cycles counts bounces after the first hit, glint's --max-depth counts bounces after the
  camera ray including the first hit's light sample, so glint D matches Cycles B = D - 1.
  Transparent bounces 64: alpha pass-through is not a bounce in glint either.
- glTF (x, y, z) is Blender (x, -z, y): the importer turns the model so, and the camera is placed so.
- `--distribution GGX`: the importer's Principled BSDF uses multiple-scattering GGX; glTF's BRDF is
  single-scatter GGX. `--tint squared`: Cycles tints transmission once per object (sqrt(base) per
  interface), glint by the base colour at every interface; squaring the base colour of fully
  transmissive materials makes Cycles do what glint does. `--absorption spec`: the importer's volume
  absorption is (1 - c) / d; the KHR_materials_volume spec's is -ln(c) / d.
- `--anisotropy spec`: the importer hands KHR_materials_anisotropy's strength to Blender's
  Anisotropic input, whose model (Burley: alpha_x = a / s, alpha_y = a s, s = sqrt(1 - 0.9 A)) is not
  the spec's (alpha_t = mix(a, 1, strength^2) along the tangent, alpha_b = a), and leaves the
  tangent unlinked (Cycles' default tangent, not the mesh's) unless there is an anisotropy texture.
  This sets Roughness and Anisotropic so that Blender's alpha_x, alpha_y are the spec's (where the
  ratio fits Blender's largest, 10), per shading point with math nodes (so a strength from the
  anisotropy texture is mapped too), and links the UV map's tangent where none is linked.
- `--iridescence thin-film`: Blender 5.0's importer reads no KHR_materials_iridescence (and refuses
  files that require it: give it a copy without extensionsRequired); this puts the extension's IOR
  and thickness (mix(min, max, texture G), max without a texture) into the Principled BSDF's thin
  film, the same Belcour-Barla model. Materials are found by name: make glTF names unique first.
  `spec` also turns a metal of grey base colour c under a film into a black dielectric of IOR
  (1 + sqrt c) / (1 - sqrt c): the extension takes a metal's base IOR so ("the extinction ... is
  thus assumed to be 0.0"), Cycles' film over a metal a complex IOR.
- `--thin-walled spec`: KHR_materials_transmission without KHR_materials_volume is a thin wall
  ("really two surfaces back-to-back ... there is no average refraction"); Blender's Principled
  BSDF has no thin-walled mode, so the importer refracts at each surface. This replaces the
  transmission of such materials by the spec's thin-walled BTDF (see `thin_walled`).
- `--lights COMPAT` reads 1 cd as 1 W/sr (glint's reading); SPEC divides by 683 lm/W.
- `--punctual spec`: KHR_lights_punctual's lights are points and directions of no size; the importer
  leaves Blender's sun at its default disc of 0.526 degrees, which BSDF rays can hit, so sunlight can
  reach through clear glass as caustics that a delta light cannot give. This sets each sun's angle
  (and each point and spot light's radius) to 0.
- `--srgb-filter spec`: Cycles interpolates an 8-bit sRGB image's encoded values and decodes the
  result (`svm_image_texture`: the lookup, then `color_srgb_to_linear_v4` under
  `NODE_IMAGE_COMPRESS_AS_SRGB`); the glTF spec says of the base colour texture "To achieve correct
  filtering, the transfer function SHOULD be decoded before performing linear interpolation", as
  glint does. Decoding first lowers bright texels' weight less than decoding after does, so on a
  contrasty texture Cycles is darker (SheenCloth's dark blue fabric: 3%). This replaces each 8-bit
  sRGB image by a float copy of its decoded values in linear colour space, which Cycles then
  interpolates as glint does.
- `--env`: a lat-long map as the world instead of the constant, importance-sampled (Cycles' default
  map resolution, the map's own size). Its centre column faces +X in glint and in Cycles; glint's
  longitude runs one way about +Y, Cycles' may run the other, so a map symmetric about its centre
  column is the same world in both.
"""
import argparse
import json
import math
import os
import struct
import sys
import time


def parse_args():
    ap = argparse.ArgumentParser()
    ap.add_argument("model")
    ap.add_argument("out")
    for name in ("--width", "--height", "--spp", "--bounces"):
        ap.add_argument(name, type=int, required=True)
    ap.add_argument("--eye", required=True)
    ap.add_argument("--look-at", required=True)
    ap.add_argument("--fov", type=float, required=True, help="vertical, degrees")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--world", type=float, default=1.0, help="constant world radiance")
    ap.add_argument("--distribution", default="importer", choices=["importer", "GGX", "MULTI_GGX"])
    ap.add_argument("--tint", default="importer", choices=["importer", "squared"])
    ap.add_argument("--absorption", default="importer", choices=["importer", "spec"])
    ap.add_argument("--anisotropy", default="importer", choices=["importer", "spec"])
    ap.add_argument("--iridescence", default="importer", choices=["importer", "thin-film", "spec"])
    ap.add_argument("--thin-walled", default="importer", choices=["importer", "spec"])
    ap.add_argument("--lights", default="SPEC", choices=["SPEC", "COMPAT"])
    ap.add_argument("--punctual", default="importer", choices=["importer", "spec"])
    ap.add_argument("--srgb-filter", default="importer", choices=["importer", "spec"])
    ap.add_argument("--env", default="", help="lat-long EXR world (replaces --world)")
    ap.add_argument("--report", default="")
    return ap.parse_args()


def point(s):
    x, y, z = (float(v) for v in s.split(","))
    return (x, -z, y)


def principled(materials):
    for m in materials:
        if m.node_tree:
            for n in m.node_tree.nodes:
                if n.bl_idname == "ShaderNodeBsdfPrincipled":
                    yield m, n


def square_transmissive_tint(materials):
    changed = []
    for m, n in principled(materials):
        weight = n.inputs["Transmission Weight"]
        if weight.is_linked or weight.default_value < 1.0:
            continue
        base = n.inputs["Base Color"]
        if base.is_linked:
            tree = m.node_tree
            src = base.links[0].from_socket
            mul = tree.nodes.new("ShaderNodeMix")
            mul.data_type, mul.blend_type = "RGBA", "MULTIPLY"
            mul.inputs["Factor"].default_value = 1.0
            tree.links.new(src, mul.inputs[6])
            tree.links.new(src, mul.inputs[7])
            tree.links.new(mul.outputs[2], base)
        else:
            r, g, b, a = base.default_value
            base.default_value = (r * r, g * g, b * b, a)
        changed.append(m.name)
    return changed


def spec_absorption(materials):
    # sigma_a per channel = -ln(c) / d; Blender's node gives density * (1 - colour), so pick the
    # largest sigma as density and the colour that leaves each channel's sigma.
    changed = []
    for m in materials:
        if not m.node_tree:
            continue
        for n in m.node_tree.nodes:
            if n.bl_idname != "ShaderNodeVolumeAbsorption":
                continue
            colour, density = n.inputs["Color"], n.inputs["Density"]
            if colour.is_linked or density.is_linked:
                continue
            sigma = [-math.log(min(max(c, 1e-6), 1.0)) * density.default_value
                     for c in colour.default_value[:3]]
            top = max(sigma)
            if top > 0:
                density.default_value = top
                colour.default_value = (*[1.0 - s / top for s in sigma], 1.0)
                changed.append(m.name)
    return changed


def math_node(tree, op, *inputs, clamp=False):
    """A Math node of `op` over sockets or constants; its output socket."""
    node = tree.nodes.new("ShaderNodeMath")
    node.operation, node.use_clamp = op, clamp
    for slot, x in zip(node.inputs, inputs):
        if isinstance(x, (int, float)):
            slot.default_value = x
        else:
            tree.links.new(x, slot)
    return node.outputs[0]


def spec_anisotropy(materials):
    # The spec's alphas in Blender's Burley mapping, per shading point (math nodes, so that a
    # strength from the anisotropy texture is mapped too): a = r^2 (glint's MIN_ALPHA 1e-3 below:
    # a smooth anisotropic surface becomes a rough line-shaped lobe), alpha_t = a + (1 - a) s^2;
    # Roughness = (alpha_t a)^(1/4), Anisotropic = (1 - a / alpha_t) / 0.9, at most 1.
    changed = []
    for m, n in principled(materials):
        strength, rough = n.inputs["Anisotropic"], n.inputs["Roughness"]
        if not strength.is_linked and strength.default_value <= 0:
            continue
        tree = m.node_tree
        s = math_node(tree, "MINIMUM", source(tree, strength), 1.0)
        a = math_node(tree, "MAXIMUM", math_node(tree, "POWER", source(tree, rough), 2.0), 1e-3)
        alpha_t = math_node(tree, "MULTIPLY_ADD", math_node(tree, "SUBTRACT", 1.0, a),
                            math_node(tree, "MULTIPLY", s, s), a)
        tree.links.new(math_node(tree, "POWER", math_node(tree, "MULTIPLY", alpha_t, a), 0.25), rough)
        ratio = math_node(tree, "SUBTRACT", 1.0, math_node(tree, "DIVIDE", a, alpha_t))
        tree.links.new(math_node(tree, "DIVIDE", ratio, 0.9, clamp=True), strength)
        tangent = n.inputs["Tangent"]
        if not tangent.is_linked:
            node = tree.nodes.new("ShaderNodeTangent")
            node.direction_type, node.uv_map = "UV_MAP", "UVMap"
            tree.links.new(node.outputs["Tangent"], tangent)
        changed.append(m.name)
    return changed


def gltf_document(path):
    """The JSON of a .gltf or .glb file and a reader of its images' bytes by image index."""
    data = open(path, "rb").read()
    if data[:4] == b"glTF":
        n = struct.unpack_from("<I", data, 12)[0]
        doc, chunk = json.loads(data[20:20 + n]), 20 + n
        blob = data[chunk + 8:chunk + 8 + struct.unpack_from("<I", data, chunk)[0]] if chunk < len(data) else b""
    else:
        doc, blob = json.loads(data), b""

    def image_bytes(i):
        im = doc["images"][i]
        if "bufferView" in im:
            v = doc["bufferViews"][im["bufferView"]]
            return blob[v.get("byteOffset", 0):v.get("byteOffset", 0) + v["byteLength"]]
        return open(os.path.join(os.path.dirname(path), im["uri"]), "rb").read()
    return doc, image_bytes


def imported(materials, doc):
    """(glTF material, Blender material, its Principled BSDF) for each glTF material the importer
    made, found by name (the bench makes glTF names unique)."""
    by_name = {m.name: (m, n) for m, n in principled(materials)}
    for g in doc.get("materials", []):
        found = by_name.get(g.get("name", ""))
        if found is not None:
            yield (g, *found)


def thin_film(materials, model, scratch, spec_metals):
    # Blender's importer reads no KHR_materials_iridescence; Principled's thin film is the same
    # Belcour-Barla model. thickness = mix(min, max, texture.g), max without a texture; the factor
    # has no Blender input, so only factor 1 is mapped (others are reported, left as imported).
    doc, image_bytes = gltf_document(model)
    changed, skipped = [], []
    for g, m, n in imported(materials, doc):
        ext = g.get("extensions", {}).get("KHR_materials_iridescence")
        if ext is None:
            continue
        if ext.get("iridescenceFactor", 0.0) != 1.0 or "iridescenceTexture" in ext:
            skipped.append(m.name)
            continue
        lo, hi = ext.get("iridescenceThicknessMinimum", 100.0), ext.get("iridescenceThicknessMaximum", 400.0)
        n.inputs["Thin Film IOR"].default_value = ext.get("iridescenceIor", 1.3)
        n.inputs["Thin Film Thickness"].default_value = hi
        tex = ext.get("iridescenceThicknessTexture")
        if tex is not None:
            import bpy
            image = doc["textures"][tex["index"]]["source"]
            file = os.path.join(scratch, f"iridescence{image}.png")
            with open(file, "wb") as f:
                f.write(image_bytes(image))
            tree = m.node_tree
            node = tree.nodes.new("ShaderNodeTexImage")
            node.image = bpy.data.images.load(file)
            node.image.colorspace_settings.name = "Non-Color"
            uv = tree.nodes.new("ShaderNodeUVMap")
            uv.uv_map = "UVMap" if tex.get("texCoord", 0) == 0 else f"UVMap.{tex['texCoord']:03d}"
            tree.links.new(uv.outputs["UV"], node.inputs["Vector"])
            split = tree.nodes.new("ShaderNodeSeparateColor")
            tree.links.new(node.outputs["Color"], split.inputs["Color"])
            ramp = tree.nodes.new("ShaderNodeMapRange")
            ramp.inputs["To Min"].default_value, ramp.inputs["To Max"].default_value = lo, hi
            tree.links.new(split.outputs["Green"], ramp.inputs["Value"])
            tree.links.new(ramp.outputs["Result"], n.inputs["Thin Film Thickness"])
        metal = n.inputs["Metallic"]
        if spec_metals and not metal.is_linked and metal.default_value == 1.0 and not n.inputs["Base Color"].is_linked:
            r, gr, b, _ = n.inputs["Base Color"].default_value
            if r == gr == b:
                # The extension's film over a metal takes the base's IOR as a real one from F0
                # (Fresnel0ToIor, "the extinction ... is thus assumed to be 0.0"); Cycles' film
                # over a metal uses a complex IOR. A black dielectric of that IOR is the spec's.
                n.inputs["Metallic"].default_value = 0.0
                n.inputs["IOR"].default_value = (1 + math.sqrt(r)) / (1 - math.sqrt(min(r, 0.999)))
                n.inputs["Base Color"].default_value = (0.0, 0.0, 0.0, 1.0)
        changed.append(m.name)
    return changed, skipped


def source(tree, socket):
    """What feeds an input: its link's socket, or a Value node holding its constant."""
    if socket.is_linked:
        return socket.links[0].from_socket
    node = tree.nodes.new("ShaderNodeValue")
    node.outputs[0].default_value = socket.default_value
    return node.outputs[0]


def thin_walled(materials, model):
    # KHR_materials_transmission without KHR_materials_volume is thin-walled: "really two surfaces
    # back-to-back ... there is no average refraction"; the importer makes a refracting interface
    # of it. This builds the spec's BSDF: the Principled BSDF without transmission (its diffuse,
    # specular and metal) mixed by transmission x (1 - metallic) with fresnel_mix(specular_btdf x
    # base, specular_brdf): the Fresnel at N.V of the IOR (Cycles' Fresnel node) between a GGX
    # refraction of IOR 1 tinted by the base colour (straight on, blurred by the roughness) and a
    # white GGX reflection. Exact where metallic is 0 or 1.
    doc, _ = gltf_document(model)
    changed = []
    for g, m, n in imported(materials, doc):
        ext = g.get("extensions", {})
        if "KHR_materials_transmission" not in ext or "KHR_materials_volume" in ext:
            continue
        tree = m.node_tree
        out = next((o for o in tree.nodes if o.bl_idname == "ShaderNodeOutputMaterial"), None)
        if out is None or not out.inputs["Surface"].is_linked:
            continue
        weight = source(tree, n.inputs["Transmission Weight"])
        metal = source(tree, n.inputs["Metallic"])
        for link in list(n.inputs["Transmission Weight"].links):
            tree.links.remove(link)
        n.inputs["Transmission Weight"].default_value = 0.0
        share = math_node(tree, "MULTIPLY", weight, math_node(tree, "SUBTRACT", 1.0, metal))
        through = tree.nodes.new("ShaderNodeBsdfRefraction")
        through.distribution = "GGX"
        through.inputs["IOR"].default_value = 1.0
        mirror = tree.nodes.new("ShaderNodeBsdfGlossy")
        mirror.distribution = "GGX"
        mirror.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
        rough = source(tree, n.inputs["Roughness"])
        for bsdf in (through, mirror):
            tree.links.new(rough, bsdf.inputs["Roughness"])
        base = n.inputs["Base Color"]
        if base.is_linked:
            tree.links.new(base.links[0].from_socket, through.inputs["Color"])
        else:
            through.inputs["Color"].default_value = base.default_value
        # Cycles' Fresnel node takes 1 / IOR on back faces (a wall seen from inside a closed mesh
        # would reflect totally); a thin wall has air on both sides, so hand it IOR's inverse there.
        ior = n.inputs["IOR"].default_value
        side = tree.nodes.new("ShaderNodeNewGeometry").outputs["Backfacing"]
        fresnel = tree.nodes.new("ShaderNodeFresnel")
        tree.links.new(math_node(tree, "MULTIPLY_ADD", side, 1.0 / ior - ior, ior), fresnel.inputs["IOR"])
        if n.inputs["Normal"].is_linked:
            tree.links.new(n.inputs["Normal"].links[0].from_socket, fresnel.inputs["Normal"])
            for bsdf in (through, mirror):
                tree.links.new(n.inputs["Normal"].links[0].from_socket, bsdf.inputs["Normal"])
        sheet = tree.nodes.new("ShaderNodeMixShader")
        tree.links.new(fresnel.outputs[0], sheet.inputs[0])
        tree.links.new(through.outputs[0], sheet.inputs[1])
        tree.links.new(mirror.outputs[0], sheet.inputs[2])
        both = tree.nodes.new("ShaderNodeMixShader")
        tree.links.new(share, both.inputs[0])
        tree.links.new(n.outputs["BSDF"], both.inputs[1])
        tree.links.new(sheet.outputs[0], both.inputs[2])
        alpha = n.inputs["Alpha"]
        if alpha.is_linked or alpha.default_value < 1.0:
            # The Principled BSDF's alpha would cut out only its own share: cut out the mix.
            coverage = source(tree, alpha)
            for link in list(alpha.links):
                tree.links.remove(link)
            alpha.default_value = 1.0
            clear = tree.nodes.new("ShaderNodeBsdfTransparent")
            cut = tree.nodes.new("ShaderNodeMixShader")
            tree.links.new(coverage, cut.inputs[0])
            tree.links.new(clear.outputs[0], cut.inputs[1])
            tree.links.new(both.outputs[0], cut.inputs[2])
            both = cut
        tree.links.new(both.outputs[0], out.inputs["Surface"])
        changed.append(m.name)
    return changed


def setup_camera(scene, eye, look_at, fov):
    """A camera at `eye` looking at `look_at` (glTF/OBJ coordinates, +Y up), vertical fov degrees."""
    import bpy
    from mathutils import Vector
    eye, target = Vector(point(eye)), Vector(point(look_at))
    data = bpy.data.cameras.new("peer")
    cam = bpy.data.objects.new("peer", data)
    scene.collection.objects.link(cam)
    cam.location = eye
    cam.rotation_mode = "QUATERNION"
    cam.rotation_quaternion = (target - eye).to_track_quat("-Z", "Y")
    data.sensor_fit = "VERTICAL"
    data.angle_y = math.radians(fov)
    dist = (target - eye).length
    data.clip_start, data.clip_end = dist * 1e-4, dist * 1e4
    scene.camera = cam


def punctual_lights(lights):
    """Lights of no size, as KHR_lights_punctual defines them; returns the names of those changed."""
    changed = []
    for light in lights:
        if light.type == "SUN" and light.angle != 0.0:
            light.angle = 0.0
            changed.append(light.name)
        elif light.type in ("POINT", "SPOT") and light.shadow_soft_size != 0.0:
            light.shadow_soft_size = 0.0
            changed.append(light.name)
    return changed


def decoded_srgb_images(images):
    """Replace each 8-bit sRGB image by a float copy of its decoded (linear) values, so that Cycles
    interpolates decoded values; returns the names of those replaced."""
    import bpy
    import numpy as np

    replaced = []
    for img in list(images):
        if img.is_float or img.colorspace_settings.name != "sRGB" or img.size[0] * img.size[1] == 0:
            continue
        w, h = img.size
        px = np.empty(w * h * 4, dtype=np.float32)
        img.pixels.foreach_get(px)  # a byte image's encoded values / 255
        px = px.reshape(-1, 4)
        c = px[:, :3]
        px[:, :3] = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
        lin = bpy.data.images.new(img.name + ".linear", w, h, alpha=True, float_buffer=True)
        lin.colorspace_settings.name = "Linear Rec.709"
        lin.alpha_mode = img.alpha_mode
        lin.pixels.foreach_set(px.ravel())
        lin.pack()
        img.user_remap(lin)
        replaced.append(img.name)
    return replaced


def setup_render(scene, a):
    """Unbiased CPU Cycles; `a` has width, height, threads, spp, seed, bounces and out."""
    r = scene.render
    r.engine = "CYCLES"
    r.resolution_x, r.resolution_y, r.resolution_percentage = a.width, a.height, 100
    r.threads_mode, r.threads = "FIXED", a.threads
    r.film_transparent = False
    r.use_motion_blur = False
    c = scene.cycles
    c.device, c.samples, c.seed, c.use_animated_seed = "CPU", a.spp, a.seed, False
    c.use_adaptive_sampling = c.use_denoising = c.use_guiding = False
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = a.bounces
    c.transparent_max_bounces, c.volume_bounces = 64, 0
    c.caustics_reflective = c.caustics_refractive = True
    c.blur_glossy = c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.light_sampling_threshold = 0.0
    c.pixel_filter_type, c.filter_width = "BOX", 1.0
    scene.view_settings.view_transform = "Standard"
    im = r.image_settings
    im.file_format, im.color_depth, im.color_mode, im.exr_codec = "OPEN_EXR", "32", "RGBA", "ZIP"
    r.use_file_extension = False
    r.filepath = os.path.abspath(a.out)


def main():
    a = parse_args()
    t_start = time.time()
    import bpy  # slow: after argument errors are reported

    bpy.ops.wm.read_factory_settings(use_empty=True)
    result = bpy.ops.import_scene.gltf(filepath=os.path.abspath(a.model),
                                       export_import_convert_lighting_mode=a.lights)
    if "FINISHED" not in result:
        sys.exit(f"{a.model}: Blender's glTF importer failed: {result}")
    scene = bpy.context.scene
    if a.distribution != "importer":
        for _, n in principled(bpy.data.materials):
            n.distribution = a.distribution
    # Thin walls first: they tint once per crossing in either reading, and squaring skips them
    # once their transmission is rebuilt (weight 0 on the Principled BSDF).
    thin = thin_walled(bpy.data.materials, a.model) if a.thin_walled == "spec" else []
    tinted = square_transmissive_tint(bpy.data.materials) if a.tint == "squared" else []
    absorbing = spec_absorption(bpy.data.materials) if a.absorption == "spec" else []
    aniso = spec_anisotropy(bpy.data.materials) if a.anisotropy == "spec" else []
    sized = punctual_lights(bpy.data.lights) if a.punctual == "spec" else []
    decoded = decoded_srgb_images(bpy.data.images) if a.srgb_filter == "spec" else []
    film, film_skipped = ([], [])
    if a.iridescence != "importer":
        film, film_skipped = thin_film(bpy.data.materials, a.model, os.path.dirname(os.path.abspath(a.out)),
                                       a.iridescence == "spec")
    world = bpy.data.worlds.new("peer")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (a.world,) * 3 + (1.0,)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
    if a.env:
        tex = world.node_tree.nodes.new("ShaderNodeTexEnvironment")
        tex.image = bpy.data.images.load(os.path.abspath(a.env))
        tex.image.colorspace_settings.name = "Linear Rec.709"
        tex.interpolation = "Linear"
        world.node_tree.links.new(tex.outputs["Color"], world.node_tree.nodes["Background"].inputs["Color"])
    scene.world = world
    setup_camera(scene, a.eye, a.look_at, a.fov)
    setup_render(scene, a)
    t0 = time.time()
    bpy.ops.render.render(write_still=True)
    report = {
        "model": a.model, "blender": bpy.app.version_string, "render_s": time.time() - t0,
        "total_s": time.time() - t_start, "spp": a.spp, "bounces": a.bounces,
        "distribution": a.distribution, "tint_squared": tinted, "spec_absorption": absorbing,
        "spec_anisotropy": aniso, "thin_film": film, "thin_film_not_mapped": film_skipped,
        "thin_walled": thin, "punctual": sized, "srgb_decoded_first": decoded,
        "load_average": os.getloadavg()[0],
    }
    print(json.dumps(report))
    if a.report:
        with open(a.report, "w") as f:
            json.dump(report, f, indent=1)


if __name__ == "__main__":
    main()
