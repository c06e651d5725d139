"""The Blender material of a nenrin texture set: every map wired into a Principled BSDF.

nenrin's surface is a Lambert base with a fibre highlight (Marschner et al. 2005) under a clear
GGX coat. In Blender:
  - base colour: basecolor.exr (scene-linear), or basecolor.png (sRGB) for a glTF set;
  - normal: normal.exr through a Normal Map node (tangent space of the UV map, strength 1);
  - fibre: fibre.exr through a second Normal Map node, which turns the tangent-space fibre into
    a world-space direction: the anisotropy tangent, rotated a quarter turn, because a fibre
    spreads its highlight across itself (a cone about its axis);
  - the coat: Blender 4's Principled has a real coat layer (Coat Weight, Roughness, IOR).
    Blender 3's Clearcoat is Disney's quarter-strength lobe (1 % where the film reflects 4 %),
    so there the film is the Principled specular lobe itself (Specular 0.5 = IOR 1.5) and the
    fibre highlight an anisotropic glossy lobe added to it.
The numbers come from texture-set.json (written by `nenrin bake uv`), see docs/uv-bake.md.
"""

import os

import bpy


def _input(node, *names):
    """The first input socket of `node` called one of `names` (names differ across versions)."""
    for name in names:
        socket = node.inputs.get(name)
        if socket is not None:
            return socket
    raise KeyError(f"{node.name} has none of the inputs {names}")


def _image(nodes, folder, file, colour, location):
    path = os.path.join(folder, file)
    if not os.path.exists(path):
        raise FileNotFoundError(f"nenrin texture set: {path} is missing")
    node = nodes.new("ShaderNodeTexImage")
    node.image = bpy.data.images.load(path, check_existing=True)
    node.image.reload()  # a bake into the same folder must show the new maps
    node.image.colorspace_settings.name = colour
    node.interpolation = "Linear"
    node.location = location
    node.label = file
    return node


def _linear_colour_space():
    names = {item.identifier for item in
             bpy.types.ColorManagedInputColorspaceSettings.bl_rna.properties["name"].enum_items}
    for name in ("Linear Rec.709", "Linear"):
        if name in names:
            return name
    return "Linear"


def _math(nodes, links, operation, a, b=None, location=(0, 0)):
    node = nodes.new("ShaderNodeMath")
    node.operation = operation
    node.location = location
    for socket, value in ((node.inputs[0], a), (node.inputs[1], b)):
        if value is None:
            continue
        if isinstance(value, (int, float)):
            socket.default_value = value
        else:
            links.new(value, socket)
    return node.outputs[0]


def _blender_anisotropy(nodes, links, roughness_image, strength):
    """Blender 3's anisotropic GGX from the set's glTF-style lobe: along the fibre alpha = r²
    (r from the roughness map), across it mix(alpha, 1, strength²). Blender takes the geometric
    mean of the two as roughness² and their ratio as sqrt(1 - 0.9 anisotropy)."""
    r = roughness_image.outputs["Color"]
    along = _math(nodes, links, "MULTIPLY", r, r, (-250, 300))
    s2 = strength * strength
    across = _math(nodes, links, "MULTIPLY_ADD", along, 1 - s2, (-100, 300))
    links.new(along, across.node.inputs[0])
    across.node.inputs[2].default_value = s2
    product = _math(nodes, links, "MULTIPLY", along, across, (50, 350))
    roughness = _math(nodes, links, "POWER", product, 0.25, (200, 350))
    ratio = _math(nodes, links, "DIVIDE", along, across, (50, 250))
    # 1 - ratio = 0.9 anisotropy (aspect² = ratio)
    anisotropy = _math(nodes, links, "MULTIPLY", _math(nodes, links, "SUBTRACT", 1.0, ratio,
                                                        (200, 250)), 1 / 0.9, (350, 250))
    anisotropy.node.use_clamp = True
    return roughness, anisotropy


def build_material(name, folder, description, use_png=False):
    """A new material for the set in `folder`; `description` is texture-set.json, parsed."""
    finish = description["finish"]
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    tree = material.node_tree
    nodes, links = tree.nodes, tree.links
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    output.location = (900, 0)
    bsdf = nodes.new("ShaderNodeBsdfPrincipled")
    bsdf.location = (300, 200)
    bsdf.distribution = "GGX"

    if use_png:
        base = _image(nodes, folder, "basecolor.png", "sRGB", (-600, 400))
        normal_image = _image(nodes, folder, "normal.png", "Non-Color", (-600, 0))
    else:
        base = _image(nodes, folder, "basecolor.exr", _linear_colour_space(), (-600, 400))
        normal_image = _image(nodes, folder, "normal.exr", "Non-Color", (-600, 0))
    fibre_image = _image(nodes, folder, "fibre.exr", "Non-Color", (-600, -400))
    roughness_image = _image(nodes, folder, "roughness.exr", "Non-Color", (-600, 200))

    normal_map = nodes.new("ShaderNodeNormalMap")
    normal_map.space = "TANGENT"
    normal_map.location = (-250, 0)
    links.new(normal_image.outputs["Color"], normal_map.inputs["Color"])
    # The fibre, decoded like a normal map: fx T + fy B + fz N in world space.
    fibre_map = nodes.new("ShaderNodeNormalMap")
    fibre_map.space = "TANGENT"
    fibre_map.location = (-250, -400)
    fibre_map.label = "fibre direction"
    links.new(fibre_image.outputs["Color"], fibre_map.inputs["Color"])

    links.new(base.outputs["Color"], bsdf.inputs["Base Color"])
    links.new(normal_map.outputs["Normal"], bsdf.inputs["Normal"])
    _input(bsdf, "IOR").default_value = finish["ior"]

    if bpy.app.version >= (4, 0, 0):
        # A real coat layer: the film on top, the fibre highlight as the anisotropic base lobe.
        _input(bsdf, "Coat Weight").default_value = finish["coat_weight"]
        _input(bsdf, "Coat Roughness").default_value = finish["coat_roughness"]
        _input(bsdf, "Coat IOR").default_value = finish["ior"]
        links.new(normal_map.outputs["Normal"], _input(bsdf, "Coat Normal"))
        links.new(roughness_image.outputs["Color"], bsdf.inputs["Roughness"])
        _input(bsdf, "Anisotropic").default_value = finish["anisotropy"]
        _input(bsdf, "Anisotropic Rotation").default_value = 0.25
        links.new(fibre_map.outputs["Normal"], bsdf.inputs["Tangent"])
        links.new(bsdf.outputs["BSDF"], output.inputs["Surface"])
        return material

    # Blender 3: the film is the specular lobe (F0 of IOR 1.5 = Specular 0.5), weighted. That
    # lobe is added on top of the diffuse, while nenrin's film takes its reflection from the
    # light going in and out of the wood: the base colour is scaled by (1 - F0)² to match at
    # normal incidence.
    f0 = ((finish["ior"] - 1) / (finish["ior"] + 1)) ** 2
    through = (1 - finish["coat_weight"] * f0) ** 2
    dimmed = nodes.new("ShaderNodeMixRGB")
    dimmed.blend_type = "MULTIPLY"
    dimmed.label = "under the film"
    dimmed.inputs["Fac"].default_value = 1.0
    dimmed.inputs["Color2"].default_value = (through, through, through, 1.0)
    dimmed.location = (0, 450)
    links.new(base.outputs["Color"], dimmed.inputs["Color1"])
    links.new(dimmed.outputs["Color"], bsdf.inputs["Base Color"])
    _input(bsdf, "Specular").default_value = 0.5 * finish["coat_weight"]
    _input(bsdf, "Roughness").default_value = finish["coat_roughness"]
    _input(bsdf, "Clearcoat").default_value = 0.0
    if finish["fibre_strength"] <= 0:
        links.new(bsdf.outputs["BSDF"], output.inputs["Surface"])
        return material
    # The fibre highlight: an anisotropic glossy lobe stretched across the fibres, tinted by
    # the wood; nenrin's lobe reflects about fibre_strength / 2 of the albedo.
    tint = nodes.new("ShaderNodeMixRGB")
    tint.blend_type = "MULTIPLY"
    tint.inputs["Fac"].default_value = 1.0
    tint.inputs["Color2"].default_value = (0.5 * finish["fibre_strength"],) * 3 + (1.0,)
    tint.location = (0, -200)
    links.new(dimmed.outputs["Color"], tint.inputs["Color1"])  # under the film too
    fibre = nodes.new("ShaderNodeBsdfAnisotropic")
    fibre.distribution = "GGX"
    fibre.location = (300, -300)
    fibre.label = "fibre highlight"
    links.new(tint.outputs["Color"], fibre.inputs["Color"])
    roughness, anisotropy = _blender_anisotropy(nodes, links, roughness_image,
                                                finish["anisotropy"])
    links.new(roughness, fibre.inputs["Roughness"])
    links.new(anisotropy, fibre.inputs["Anisotropy"])
    fibre.inputs["Rotation"].default_value = 0.25
    links.new(fibre_map.outputs["Normal"], fibre.inputs["Tangent"])
    links.new(normal_map.outputs["Normal"], fibre.inputs["Normal"])
    add = nodes.new("ShaderNodeAddShader")
    add.location = (650, 0)
    links.new(bsdf.outputs["BSDF"], add.inputs[0])
    links.new(fibre.outputs["BSDF"], add.inputs[1])
    links.new(add.outputs["Shader"], output.inputs["Surface"])
    return material
