"""The add-on's bake operator, as a user runs it (tests/blender/blender_twin_test.sh): a UV cube
in Blender baked by `nenrin bake uv` through the operator; the object must come back with the
nenrin material and the maps on disk, and a bad skeleton must end in a clear error report.

blender -b --python bake_operator.py -- NENRIN SKELETON OUT_FOLDER
"""

import os
import sys

import bpy


def main(nenrin, skeleton, out):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    import addon_utils
    if not all(addon_utils.enable("nenrin_wood", default_set=True) and
               addon_utils.check("nenrin_wood")):
        sys.exit("bake_operator: the nenrin_wood add-on is not installed")
    bpy.context.preferences.addons["nenrin_wood"].preferences.nenrin = nenrin
    bpy.ops.mesh.primitive_cube_add(size=0.1)  # has a UV map
    cube = bpy.context.active_object
    result = bpy.ops.object.nenrin_bake_wood(skeleton=skeleton, resolution=64, output=out,
                                             finish="oiled")
    if result != {"FINISHED"}:
        sys.exit(f"bake_operator: the bake did not finish: {result}")
    for f in ("basecolor.exr", "normal.exr", "fibre.exr", "roughness.exr", "texture-set.json"):
        if not os.path.exists(os.path.join(out, f)):
            sys.exit(f"bake_operator: {f} was not written")
    material = cube.active_material
    if material is None or not material.name.startswith("nenrin"):
        sys.exit("bake_operator: the cube did not get the nenrin material")
    images = {n.image.name for n in material.node_tree.nodes if n.type == "TEX_IMAGE"}
    print("bake_operator: material", material.name, "with", sorted(images))
    # A skeleton that is not one: the operator reports nenrin's message and cancels.
    bad = os.path.join(out, "not-a-skeleton.json")
    with open(bad, "w") as f:
        f.write("{\"trunk\": 3}")
    try:
        result = bpy.ops.object.nenrin_bake_wood(skeleton=bad, resolution=16, output=out)
    except RuntimeError as e:  # operator reports of type ERROR raise in background mode
        message = str(e)
        if "not-a-skeleton.json" not in message:
            sys.exit(f"bake_operator: the error does not name the file: {message}")
        print("bake_operator: bad skeleton reported:", message.strip().splitlines()[-1])
    else:
        sys.exit(f"bake_operator: a bad skeleton did not fail: {result}")


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1:]
    if len(argv) != 3:
        sys.exit(__doc__)
    main(*argv)
