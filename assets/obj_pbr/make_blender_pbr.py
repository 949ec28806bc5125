"""Writes blender_pbr.obj/.mtl (+ rough.png): a cube whose Principled BSDF uses every value the OBJ
exporter's PBR extension writes, and a second material with a roughness texture, as Blender 5.0.1
exports them. Run: python -m venv v && v/bin/pip install bpy==5.0.1 && v/bin/python make_blender_pbr.py
"""
import os
import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.mesh.primitive_cube_add()
cube = bpy.context.active_object
bpy.ops.mesh.primitive_plane_add(location=(0, -2, 0))
plane = bpy.context.active_object

coated = bpy.data.materials.new("coated")
p = coated.node_tree.nodes["Principled BSDF"]
p.inputs["Base Color"].default_value = (0.8, 0.1, 0.1, 1)
p.inputs["Roughness"].default_value = 0.3
p.inputs["Metallic"].default_value = 1.0
p.inputs["Sheen Weight"].default_value = 0.2
p.inputs["Coat Weight"].default_value = 0.5
p.inputs["Coat Roughness"].default_value = 0.1
p.inputs["Anisotropic"].default_value = 0.4
p.inputs["Anisotropic Rotation"].default_value = 0.25
p.inputs["Specular IOR Level"].default_value = 0.25
cube.data.materials.append(coated)

textured = bpy.data.materials.new("textured")
p = textured.node_tree.nodes["Principled BSDF"]
img = bpy.data.images.new("rough", 2, 1)
img.pixels = [0.2, 0.2, 0.2, 1.0, 0.8, 0.8, 0.8, 1.0]
img.filepath_raw = os.path.join(HERE, "rough.png")
img.file_format = "PNG"
img.save()
t = textured.node_tree.nodes.new("ShaderNodeTexImage")
t.image = img
textured.node_tree.links.new(t.outputs["Color"], p.inputs["Roughness"])
plane.data.materials.append(textured)

bpy.ops.wm.obj_export(
    filepath=os.path.join(HERE, "blender_pbr.obj"),
    export_pbr_extensions=True,
    path_mode="RELATIVE",
)
