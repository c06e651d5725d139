"""Renders a nenrin scene's twin in Blender Cycles (run by tests/blender/blender_twin_test.sh):
the wood object imported through the installed nenrin add-on (scripts/install-blender-addon)
from its baked texture set (texture-set.json, or the set's .glb), or by Blender's own OBJ
importer from NAME.obj and its .mtl (no add-on), the rest of the scene
(camera, sun, uniform sky, diffuse boxes) rebuilt from the nenrin scene JSON.

blender -b --python render_twin.py -- SET_FILE SCENE.json OUT.exr
"""

import json
import math
import os
import sys

import bpy
from mathutils import Vector


def blender_space(v):
    """nenrin and OBJ are Y-up; Blender is Z-up (what its OBJ importer does: x, -z, y)."""
    return Vector((v[0], -v[2], v[1]))


def main(set_file, scene_path, out):
    with open(scene_path, encoding="utf-8") as f:
        scene = json.load(f)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    import addon_utils
    if not all(addon_utils.enable("nenrin_wood", default_set=True) and
               addon_utils.check("nenrin_wood")):
        sys.exit("render_twin: the nenrin_wood add-on is not installed")

    if set_file.endswith(".obj"):
        # Blender's own OBJ importer and the .mtl alone: what a user without the add-on gets.
        result = bpy.ops.wm.obj_import(filepath=set_file, forward_axis="NEGATIVE_Z", up_axis="Y")
    else:
        # The wood object, through the add-on: exactly what a user's import does.
        result = bpy.ops.import_scene.nenrin_texture_set(filepath=set_file)
    if result != {"FINISHED"}:
        sys.exit(f"render_twin: {set_file} could not be imported")

    s = bpy.context.scene
    materials = {m["name"]: m for m in scene["materials"]}
    for o in scene["objects"]:
        if o["type"] != "box":
            continue
        bpy.ops.mesh.primitive_cube_add(size=1, location=blender_space(o.get("position", [0, 0, 0])))
        box = bpy.context.active_object
        sx, sy, sz = o["size"]
        box.scale = (sx, sz, sy)
        m = materials[o["material"]]
        if m["type"] != "diffuse":
            sys.exit(f"render_twin: box material {m['type']} has no twin")
        colour = m.get("colour", 0.7)
        colour = colour if isinstance(colour, list) else [colour] * 3
        mat = bpy.data.materials.new(m["name"])
        mat.use_nodes = True
        nodes = mat.node_tree.nodes
        nodes.clear()
        diffuse = nodes.new("ShaderNodeBsdfDiffuse")
        diffuse.inputs["Color"].default_value = (*colour, 1)
        output = nodes.new("ShaderNodeOutputMaterial")
        mat.node_tree.links.new(diffuse.outputs["BSDF"], output.inputs["Surface"])
        box.data.materials.append(mat)

    cam = scene["camera"]
    bpy.ops.object.camera_add(location=blender_space(cam["position"]))
    camera = bpy.context.active_object
    forward = blender_space(cam["look_at"]) - camera.location
    camera.rotation_euler = forward.to_track_quat("-Z", "Y").to_euler()
    camera.data.sensor_fit = "VERTICAL"
    camera.data.angle_y = math.radians(cam.get("fov", 40))
    s.camera = camera

    world = bpy.data.worlds.new("sky")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    for light in scene["lights"]:
        colour = light.get("colour", [1, 1, 1])
        colour = colour if isinstance(colour, list) else [colour] * 3
        if light["type"] in ("sun", "distant"):
            bpy.ops.object.light_add(type="SUN")
            sun = bpy.context.active_object
            towards = blender_space(light["direction"]).normalized()
            sun.rotation_euler = (-towards).to_track_quat("-Z", "Y").to_euler()
            sun.data.energy = light.get("irradiance", 3.0)
            sun.data.color = colour
            sun.data.angle = 0.0
        elif light["type"] == "environment" and "colour" in light:
            background.inputs["Color"].default_value = (*colour, 1)
            background.inputs["Strength"].default_value = light.get("intensity", 1.0)
        else:
            sys.exit(f"render_twin: light {light['type']} has no twin")
    s.world = world

    r = scene["render"]
    s.render.engine = "CYCLES"
    s.cycles.device = "CPU"
    s.cycles.samples = r.get("spp", 16)
    s.cycles.use_adaptive_sampling = False
    s.cycles.use_denoising = False
    s.cycles.seed = r.get("seed", 1)
    s.cycles.max_bounces = r.get("max_depth", 4)
    s.cycles.pixel_filter_type = "BOX"
    s.cycles.filter_width = 1.0
    s.cycles.sample_clamp_direct = 0
    s.cycles.sample_clamp_indirect = 0
    s.cycles.caustics_reflective = True
    s.cycles.blur_glossy = 0.0
    s.render.resolution_x, s.render.resolution_y = r["resolution"]
    s.render.resolution_percentage = 100
    s.view_settings.view_transform = "Standard"
    s.render.image_settings.file_format = "OPEN_EXR"
    s.render.image_settings.color_depth = "32"
    s.render.image_settings.color_mode = "RGB"
    s.render.filepath = out
    bpy.ops.render.render(write_still=True)


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1:]
    if len(argv) != 3:
        sys.exit(__doc__)
    main(*argv)
