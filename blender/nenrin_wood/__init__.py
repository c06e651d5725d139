"""nenrin wood for Blender: import nenrin texture sets (EXR maps with OBJ, or glTF) onto an
object with a complete material, and bake nenrin wood onto the selected object's UVs by
running `nenrin bake uv`. Install: scripts/install-blender-addon (docs/blender.md)."""

bl_info = {
    "name": "nenrin wood",
    "author": "nenrin",
    "version": (1, 0, 0),
    "blender": (3, 4, 0),
    "location": "File > Import > nenrin texture set; Object > nenrin: bake wood onto UVs",
    "description": "Grown wood from nenrin: texture sets with coat, normal map and fibre "
                   "anisotropy, and UV bakes of nenrin's solid wood",
    "category": "Import-Export",
}

import json
import os
import shutil
import subprocess
import tempfile

import bpy
from bpy.props import EnumProperty, FloatVectorProperty, IntProperty, StringProperty
from bpy_extras.io_utils import ImportHelper

from . import material as nenrin_material

DESCRIPTION = "texture-set.json"


def read_description(folder):
    path = os.path.join(folder, DESCRIPTION)
    try:
        with open(path, encoding="utf-8") as f:
            description = json.load(f)
    except FileNotFoundError:
        raise FileNotFoundError(f"{path}: not found; a nenrin texture set has one "
                                "(written by `nenrin bake uv`)") from None
    except json.JSONDecodeError as e:
        raise ValueError(f"{path}: line {e.lineno}: not JSON ({e.msg})") from None
    if description.get("format") != "nenrin texture set":
        raise ValueError(f"{path}: \"format\" is not \"nenrin texture set\"")
    return description


def apply_texture_set(obj, folder, use_png=False):
    """Gives `obj` (a mesh with UVs) the material of the set in `folder`."""
    description = read_description(folder)
    if obj.type != "MESH" or not obj.data.uv_layers:
        raise ValueError(f"{obj.name}: a nenrin texture set needs a mesh with a UV map")
    mat = nenrin_material.build_material("nenrin " + description["object"], folder,
                                         description, use_png)
    obj.data.materials.clear()
    obj.data.materials.append(mat)
    return mat


def _numpy_bool_alias():
    """Blender 3.4's glTF importer uses numpy.bool, an alias of bool that NumPy 1.24 removed
    (Debian 12 ships both): put the alias back, as it was, so the importer runs."""
    import numpy
    if "bool" not in numpy.__dict__:
        numpy.bool = bool


def import_texture_set(filepath):
    """Imports the mesh of a set (texture-set.json, NAME.obj, NAME.gltf or NAME.glb) with its
    material; returns the new object and whether it got the full nenrin material (a glTF
    without its texture-set.json keeps what Blender's glTF importer made)."""
    folder = os.path.dirname(os.path.abspath(filepath))
    ext = os.path.splitext(filepath)[1].lower()
    if ext in (".gltf", ".glb") and not os.path.exists(os.path.join(folder, DESCRIPTION)):
        # A glTF passed on without its set: Blender's glTF importer alone (coat and normal
        # map, but Blender 3 reads no anisotropy).
        _numpy_bool_alias()
        before = set(bpy.data.objects)
        bpy.ops.import_scene.gltf(filepath=filepath)
        created = [o for o in bpy.data.objects if o not in before and o.type == "MESH"]
        if not created:
            raise ValueError(f"{filepath}: no mesh was imported")
        return created[0], False
    description = read_description(folder)
    before = set(bpy.data.objects)
    if ext in (".gltf", ".glb"):
        _numpy_bool_alias()
        bpy.ops.import_scene.gltf(filepath=filepath)
    else:
        mesh = filepath if ext == ".obj" else os.path.join(folder, description["mesh"])
        # nenrin's space is Y-up like OBJ's: the importer's defaults turn it to Blender's Z-up.
        bpy.ops.wm.obj_import(filepath=mesh, forward_axis="NEGATIVE_Z", up_axis="Y")
    created = [o for o in bpy.data.objects if o not in before and o.type == "MESH"]
    if not created:
        raise ValueError(f"{filepath}: no mesh was imported")
    obj = created[0]
    apply_texture_set(obj, folder, use_png=ext in (".gltf", ".glb"))
    return obj, True


class NENRIN_OT_import_texture_set(bpy.types.Operator, ImportHelper):
    """Import a nenrin texture set: its mesh and a complete material (coat, roughness,
    normal map, fibre anisotropy)"""

    bl_idname = "import_scene.nenrin_texture_set"
    bl_label = "Import nenrin texture set"
    bl_options = {"REGISTER", "UNDO"}
    filter_glob: StringProperty(default="*.json;*.obj;*.gltf;*.glb", options={"HIDDEN"})

    def execute(self, context):
        try:
            obj, complete = import_texture_set(self.filepath)
        except (OSError, ValueError, KeyError) as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        context.view_layer.objects.active = obj
        if complete:
            self.report({"INFO"}, f"nenrin: {obj.name} imported with its wood material")
        else:
            self.report({"WARNING"}, f"nenrin: {obj.name} imported with the glTF importer's "
                        f"material: no {DESCRIPTION} next to the file, so no fibre anisotropy")
        return {"FINISHED"}


FINISHES = [(f, f, f"nenrin's {f} finish (docs/scene-format.md)")
            for f in ("oiled", "matte", "varnished", "brushed", "bare")]


class NenrinPreferences(bpy.types.AddonPreferences):
    bl_idname = __name__
    nenrin: StringProperty(name="nenrin executable", subtype="FILE_PATH", default="nenrin",
                           description="The nenrin command (a path, or a name on PATH)")

    def draw(self, context):
        self.layout.prop(self, "nenrin")


def nenrin_executable(context):
    prefs = context.preferences.addons.get(__name__)
    name = prefs.preferences.nenrin if prefs else "nenrin"
    found = shutil.which(bpy.path.abspath(name))
    if not found:
        raise FileNotFoundError(f"the nenrin executable \"{name}\" was not found: set it in "
                                "the add-on's preferences")
    return found


def bake_scene(name, obj_path, skeleton, grain, finish, log_position, log_rotate):
    material = {"name": "wood", "type": "wood", "skeleton": skeleton, "finish": finish}
    if grain:
        material["grain"] = grain
    return {
        "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
        "materials": [material],
        "objects": [{"name": name, "type": "mesh", "file": obj_path, "material": "wood",
                     "log": {"position": list(log_position), "rotate": list(log_rotate)}}],
    }


class NENRIN_OT_bake_wood(bpy.types.Operator):
    """Bake nenrin wood onto the selected object's UV map (runs `nenrin bake uv`) and give
    it the resulting material"""

    bl_idname = "object.nenrin_bake_wood"
    bl_label = "nenrin: bake wood onto UVs"
    bl_options = {"REGISTER", "UNDO"}

    skeleton: StringProperty(name="Skeleton", subtype="FILE_PATH",
                             description="nenrin skeleton JSON (docs/skeleton-format.md)")
    grain: StringProperty(name="Grain", subtype="FILE_PATH",
                          description="Grain JSON (optional, docs/grain-format.md)")
    finish: EnumProperty(name="Finish", items=FINISHES, default="oiled")
    resolution: IntProperty(name="Resolution", default=2048, min=16, max=16384)
    output: StringProperty(name="Output folder", subtype="DIR_PATH",
                           description="Where the maps go (default: next to the .blend)")
    log_position: FloatVectorProperty(name="Log position", size=3, default=(0, 0, 1.5),
                                      description="Where the piece sits in the tree (m, Y up)")
    log_rotate: FloatVectorProperty(name="Log rotation", size=3, default=(0, 0, 90),
                                    description="Degrees about x, y, z")

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return obj is not None and obj.type == "MESH" and obj.data.uv_layers

    def invoke(self, context, event):
        return context.window_manager.invoke_props_dialog(self)

    def execute(self, context):
        obj = context.active_object
        if not self.skeleton:
            self.report({"ERROR"}, "nenrin: choose a skeleton file")
            return {"CANCELLED"}
        out = bpy.path.abspath(self.output) if self.output else \
            os.path.join(bpy.path.abspath("//") or tempfile.gettempdir(), "nenrin-" + obj.name)
        os.makedirs(out, exist_ok=True)
        try:
            exe = nenrin_executable(context)
            with tempfile.TemporaryDirectory() as work:
                mesh = os.path.join(work, "piece.obj")
                for o in context.selected_objects:
                    o.select_set(o == obj)
                # The object as it stands in the scene, Y up (nenrin's and OBJ's convention).
                bpy.ops.wm.obj_export(filepath=mesh, export_selected_objects=True,
                                      export_uv=True, export_normals=True,
                                      export_materials=False, forward_axis="NEGATIVE_Z",
                                      up_axis="Y")
                scene = os.path.join(work, "bake.json")
                with open(scene, "w", encoding="utf-8") as f:
                    json.dump(bake_scene(obj.name, mesh, bpy.path.abspath(self.skeleton),
                                         bpy.path.abspath(self.grain) if self.grain else "",
                                         self.finish, self.log_position, self.log_rotate), f)
                run = subprocess.run([exe, "bake", "uv", "--scene", scene, "--object", obj.name,
                                      "--res", str(self.resolution), "-o", out, "-q"],
                                     capture_output=True, text=True)
            if run.returncode != 0:
                self.report({"ERROR"}, "nenrin bake uv failed: " + run.stderr.strip())
                return {"CANCELLED"}
            apply_texture_set(obj, out)
        except (OSError, ValueError, KeyError) as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self.report({"INFO"}, f"nenrin: baked {self.resolution}² maps into {out}")
        return {"FINISHED"}


def menu_import(self, context):
    self.layout.operator(NENRIN_OT_import_texture_set.bl_idname,
                         text="nenrin texture set (.json/.obj/.gltf/.glb)")


def menu_object(self, context):
    self.layout.operator(NENRIN_OT_bake_wood.bl_idname)


classes = (NenrinPreferences, NENRIN_OT_import_texture_set, NENRIN_OT_bake_wood)


def register():
    for c in classes:
        bpy.utils.register_class(c)
    bpy.types.TOPBAR_MT_file_import.append(menu_import)
    bpy.types.VIEW3D_MT_object.append(menu_object)


def unregister():
    bpy.types.VIEW3D_MT_object.remove(menu_object)
    bpy.types.TOPBAR_MT_file_import.remove(menu_import)
    for c in reversed(classes):
        bpy.utils.unregister_class(c)
