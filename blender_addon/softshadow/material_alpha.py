# What a material lets through on shadow rays, read from its node tree where that needs no shading.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Cycles' shadow rays see (1 - alpha) of a surface through it. This module reads a material's
alpha where it is a constant or one Image Texture's alpha by UV, possibly through Math, Map Range
and Mix nodes, into a Principled BSDF's Alpha or a Mix Shader's factor with a Transparent BSDF;
any other tree it calls unreadable (the mesh is then opaque there and the export names it).

The result per material is None (opaque), or a dict {"alpha": float, "texture": (h, w) float32 or
None, "wrap": 0 repeat / 1 extend / 2 clip, "closest": bool, "uv_map": name or None (the active
render map)}, the library's ss_alpha_material (native.Scene.set_mesh_materials). A mapping on the
texture's alpha (Math, Map Range, Mix with constants) is applied to its texels: exact for affine
mappings, an approximation at the edges of thresholds (Cycles thresholds the filtered value).

Never imports bpy: it reads the node objects it is given.
"""
import numpy as np

from . import compat

WRAPS = {"REPEAT": 0, "EXTEND": 1, "CLIP": 2}

# Shader nodes that never let a shadow ray through (Glass too: Cycles' shadow rays are blocked
# by it, caustics aside).
OPAQUE_SHADERS = {
    "BSDF_DIFFUSE", "BSDF_GLOSSY", "BSDF_ANISOTROPIC", "BSDF_GLASS", "BSDF_REFRACTION",
    "BSDF_TRANSLUCENT", "BSDF_VELVET", "BSDF_SHEEN", "BSDF_TOON", "BSDF_HAIR", "BSDF_HAIR_PRINCIPLED",
    "SUBSURFACE_SCATTERING", "EMISSION", "EEVEE_SPECULAR", "BSDF_METALLIC", "BSDF_RAY_PORTAL",
    "HOLDOUT", "BACKGROUND",
}

# Alpha of one image, cached per image (its name, size, file and alpha mode): the texels are
# read from image.pixels once.
_image_alpha = {}


class Unreadable(Exception):
    """The tree needs shading to know its alpha."""


class _Field:
    """A float over the surface: a constant, or an image's alpha mapped texel-wise."""

    def __init__(self, constant=None, image=None, values=None, node=None, uv_map=None):
        self.constant, self.image, self.values, self.node, self.uv_map = constant, image, values, node, uv_map

    def map(self, function):
        if self.image is None:
            return _Field(constant=float(function(np.float64(self.constant))))
        return _Field(image=self.image, values=function(self.values), node=self.node, uv_map=self.uv_map)


def _combine(a, b, function):
    if a.image is not None and b.image is not None:
        raise Unreadable("two textures combined")
    if a.image is None and b.image is None:
        return _Field(constant=float(function(np.float64(a.constant), np.float64(b.constant))))
    if a.image is not None:
        c = b.constant
        return a.map(lambda v: function(v, c))
    c = a.constant
    return b.map(lambda v: function(c, v))


def image_alpha(image):
    """(h, w) float32 alpha of a Blender image, row 0 at v = 0 (image.pixels order), cached."""
    width, height = int(image.size[0]), int(image.size[1])
    key = (image.name, width, height, getattr(image, "filepath", ""), getattr(image, "alpha_mode", ""))
    cached = _image_alpha.get(key)
    if cached is not None:
        return cached
    if width <= 0 or height <= 0:
        raise Unreadable("image '%s' has no pixels" % image.name)
    if getattr(image, "alpha_mode", "STRAIGHT") == "NONE":
        alpha = np.ones((height, width), np.float32)
    else:
        pixels = np.empty(width * height * 4, np.float32)
        image.pixels.foreach_get(pixels)
        alpha = np.clip(pixels[3::4].reshape(height, width), 0.0, 1.0).astype(np.float32)
    _image_alpha[key] = alpha
    return alpha


def clear_cache():
    _image_alpha.clear()


def _linked(socket):
    links = [l for l in socket.links if not getattr(l, "is_muted", False)] if socket.is_linked else []
    return links[0].from_socket if links else None


def _float_default(socket):
    value = socket.default_value
    try:
        return float(value)
    except TypeError:
        return float(sum(value[:3]) / 3.0)  # a colour socket: its grey


def _input(node, *names):
    for name in names:
        socket = node.inputs.get(name)
        if socket is not None:
            return socket
    raise Unreadable("node '%s' has no input %s" % (node.name, names[0]))


def _float_field(socket, depth=0):
    """The float a socket carries, as a _Field."""
    if depth > 16:
        raise Unreadable("node chain too deep")
    source = _linked(socket)
    if source is None:
        return _Field(constant=_float_default(socket))
    node = source.node
    kind = node.type
    if kind == "REROUTE":
        return _float_field(node.inputs[0], depth + 1)
    if kind == "VALUE":
        return _Field(constant=float(node.outputs[0].default_value))
    if kind == "TEX_IMAGE":
        return _image_field(node, source)
    if kind == "MATH":
        return _math(node, depth)
    if kind == "MAP_RANGE" and getattr(node, "data_type", "FLOAT") == "FLOAT" \
            and getattr(node, "interpolation_type", "LINEAR") == "LINEAR":
        value = _float_field(_input(node, "Value"), depth + 1)
        lo, hi = (_constant(_input(node, n), depth) for n in ("From Min", "From Max"))
        to_lo, to_hi = (_constant(_input(node, n), depth) for n in ("To Min", "To Max"))
        if hi == lo:
            raise Unreadable("Map Range with an empty source range")
        clamp = bool(getattr(node, "clamp", True))

        def remap(v):
            t = (v - lo) / (hi - lo)
            if clamp:
                t = np.clip(t, 0.0, 1.0)
            return to_lo + t * (to_hi - to_lo)
        return value.map(remap)
    if kind == "INVERT":
        fac = _constant(_input(node, "Fac"), depth)
        value = _float_field(_input(node, "Color"), depth + 1)
        return value.map(lambda v: (1.0 - fac) * v + fac * (1.0 - v))
    if kind in ("MIX", "MIX_RGB") and getattr(node, "blend_type", "MIX") == "MIX":
        if kind == "MIX":
            data = getattr(node, "data_type", "FLOAT")
            suffix = {"FLOAT": "_Float", "RGBA": "_Color"}.get(data)
            if suffix is None:
                raise Unreadable("Mix node of %s" % data)
            sockets = {s.identifier: s for s in node.inputs}
            fac_socket, a_socket, b_socket = sockets["Factor_Float"], sockets["A" + suffix], sockets["B" + suffix]
        else:
            fac_socket, a_socket, b_socket = node.inputs[0], node.inputs[1], node.inputs[2]
        fac = float(np.clip(_constant(fac_socket, depth), 0.0, 1.0))
        a, b = _float_field(a_socket, depth + 1), _float_field(b_socket, depth + 1)
        return _combine(a, b, lambda x, y: (1.0 - fac) * x + fac * y)
    raise Unreadable("node '%s' (%s)" % (node.name, kind))


def _constant(socket, depth):
    field = _float_field(socket, depth + 1)
    if field.image is not None:
        raise Unreadable("a texture where a constant is needed")
    return field.constant


_MATH = {
    "ADD": lambda a, b: a + b,
    "SUBTRACT": lambda a, b: a - b,
    "MULTIPLY": lambda a, b: a * b,
    "DIVIDE": lambda a, b: np.where(b != 0.0, a / np.where(b != 0.0, b, 1.0), 0.0),
    "MINIMUM": np.minimum,
    "MAXIMUM": np.maximum,
    "GREATER_THAN": lambda a, b: np.where(a > b, 1.0, 0.0),
    "LESS_THAN": lambda a, b: np.where(a < b, 1.0, 0.0),
    "POWER": lambda a, b: np.where(a > 0.0, np.power(np.maximum(a, 1e-30), b), 0.0),
}


def _math(node, depth):
    function = _MATH.get(node.operation)
    if function is None:
        raise Unreadable("Math node '%s' (%s)" % (node.name, node.operation))
    a, b = _float_field(node.inputs[0], depth + 1), _float_field(node.inputs[1], depth + 1)
    out = _combine(a, b, function)
    if getattr(node, "use_clamp", False):
        out = out.map(lambda v: np.clip(v, 0.0, 1.0))
    return out


def _image_field(node, socket):
    if socket.name != "Alpha":
        raise Unreadable("Image Texture '%s' %s output (its Alpha is read)" % (node.name, socket.name))
    image = node.image
    if image is None:
        return _Field(constant=0.0)  # Cycles' missing image: alpha 0 is not what it shows
    if node.extension not in WRAPS:
        raise Unreadable("Image Texture '%s' extension %s" % (node.name, node.extension))
    if getattr(node, "projection", "FLAT") != "FLAT":
        raise Unreadable("Image Texture '%s' projection %s" % (node.name, node.projection))
    vector = _linked(node.inputs["Vector"])
    uv_map = None
    if vector is not None:
        source = vector.node
        if source.type == "UVMAP" and vector.name == "UV":
            uv_map = source.uv_map or None
        elif source.type == "TEX_COORD" and vector.name == "UV":
            uv_map = None
        else:
            raise Unreadable("Image Texture '%s' vector from %s" % (node.name, source.type))
    return _Field(image=image, values=image_alpha(image).astype(np.float64), node=node, uv_map=uv_map)


def _shader_alpha(socket, depth=0):
    """The alpha (a _Field) of the shader a socket carries: 1 - its transmission."""
    if depth > 16:
        raise Unreadable("shader chain too deep")
    source = _linked(socket)
    if source is None:
        return _Field(constant=1.0)  # nothing plugged in: black, opaque
    node = source.node
    kind = node.type
    if kind == "REROUTE":
        return _shader_alpha(node.inputs[0], depth + 1)
    if kind == "BSDF_TRANSPARENT":
        color = node.inputs["Color"]
        if _linked(color) is not None:
            raise Unreadable("Transparent BSDF '%s' with a linked colour" % node.name)
        return _Field(constant=1.0 - float(np.clip(_float_default(color), 0.0, 1.0)))
    if kind == "BSDF_PRINCIPLED":
        return _float_field(_input(node, "Alpha"), depth + 1).map(lambda v: np.clip(v, 0.0, 1.0))
    if kind == "MIX_SHADER":
        fac = _float_field(node.inputs[0], depth + 1).map(lambda v: np.clip(v, 0.0, 1.0))
        a, b = _shader_alpha(node.inputs[1], depth + 1), _shader_alpha(node.inputs[2], depth + 1)
        # transmission = (1 - f) (1 - a) + f (1 - b)  ->  alpha = (1 - f) a + f b
        if fac.image is None:
            f = fac.constant
            return _combine(a, b, lambda x, y: (1.0 - f) * x + f * y)
        if a.image is not None or b.image is not None:
            raise Unreadable("Mix Shader '%s' with textures on both sides" % node.name)
        x, y = a.constant, b.constant
        return fac.map(lambda f: (1.0 - f) * x + f * y)
    if kind == "ADD_SHADER":
        a, b = _shader_alpha(node.inputs[0], depth + 1), _shader_alpha(node.inputs[1], depth + 1)
        # transmissions add (Cycles clamps the sum to 1)
        return _combine(a, b, lambda x, y: np.clip(x + y - 1.0, 0.0, 1.0))
    if kind in OPAQUE_SHADERS:
        return _Field(constant=1.0)
    raise Unreadable("shader node '%s' (%s)" % (node.name, kind))


def _output_surface(material):
    tree = material.node_tree
    outputs = [n for n in tree.nodes if n.type == "OUTPUT_MATERIAL"]
    if not outputs:
        return None
    # The active output for Cycles (target ALL or CYCLES), as Blender chooses it.
    for node in outputs:
        if getattr(node, "is_active_output", False) and getattr(node, "target", "ALL") in ("ALL", "CYCLES"):
            return node.inputs["Surface"]
    for node in outputs:
        if getattr(node, "target", "ALL") in ("ALL", "CYCLES"):
            return node.inputs["Surface"]
    return outputs[0].inputs["Surface"]


def material_alpha(material, engine="CYCLES"):
    """A material's alpha for shadow rays: None (opaque) or the dict the module docstring names.
    Raises Unreadable with the reason when the tree cannot be read without shading it.
    `engine`: scene.render.engine; EEVEE's own shadow settings are honoured there
    (compat.material_shadow_alpha)."""
    if material is None:
        return None
    mode = compat.material_shadow_alpha(material, engine)
    if mode == "opaque":
        return None
    if not getattr(material, "use_nodes", True) or material.node_tree is None:
        return None  # no nodes: Cycles shades it opaque diffuse
    else:
        surface = _output_surface(material)
        if surface is None:
            return None
        field = _shader_alpha(surface)
    if mode == "clip":
        threshold = float(getattr(material, "alpha_threshold", 0.5))
        field = field.map(lambda v: np.where(v >= threshold, 1.0, 0.0))
    if field.image is None:
        alpha = float(np.clip(field.constant, 0.0, 1.0))
        return None if alpha >= 1.0 else {"alpha": alpha, "texture": None, "wrap": 0, "closest": False,
                                          "uv_map": None}
    texels = np.clip(field.values, 0.0, 1.0).astype(np.float32)
    node = field.node
    if node.extension != "CLIP" and bool(np.all(texels >= 1.0)):
        return None
    return {"alpha": 1.0, "texture": np.ascontiguousarray(texels), "wrap": WRAPS[node.extension],
            "closest": node.interpolation == "Closest", "uv_map": field.uv_map}


def mesh_materials(obj, engine="CYCLES"):
    """(per-slot alpha dicts or None, names of unreadable materials) of an object's slots."""
    out, unreadable = [], []
    for slot in getattr(obj, "material_slots", []):
        material = slot.material
        try:
            out.append(material_alpha(material, engine))
        except Unreadable as exc:
            unreadable.append("%s (%s)" % (material.name, exc))
            out.append(None)
    return out, unreadable


def mesh_alpha(obj, slots):
    """The library's per-mesh arrays for an evaluated object whose slot alphas are `slots`
    (some not None): {"uvs": (M*3, 2) float32, "triangle_material": (M,) int32, "materials":
    [dict...]} with one material per slot (opaque slots alpha 1), triangles in loop-triangle
    order (scene_export's). None when the mesh has no triangles."""
    mesh = obj.to_mesh()
    try:
        if mesh is None:
            return None
        mesh.calc_loop_triangles()
        count = len(mesh.loop_triangles)
        if count == 0:
            return None
        loops = np.empty(count * 3, np.int32)
        mesh.loop_triangles.foreach_get("loops", loops)
        material = np.empty(count, np.int32)
        mesh.loop_triangles.foreach_get("material_index", material)
        material = np.clip(material, 0, max(len(slots) - 1, 0))
        uvs = np.zeros((count * 3, 2), np.float32)
        layers = {}
        for index, alpha in enumerate(slots):
            if alpha is None or alpha["texture"] is None:
                continue
            name = alpha["uv_map"]
            layer = mesh.uv_layers.get(name) if name else next(
                (l for l in mesh.uv_layers if getattr(l, "active_render", False)), None)
            if layer is None:
                continue  # no UV map: (0, 0) everywhere, as Cycles samples it
            if layer.name not in layers:
                data = np.empty(len(mesh.loops) * 2, np.float32)
                layer.data.foreach_get("uv", data)
                layers[layer.name] = data.reshape(-1, 2)
            corners = np.repeat(material == index, 3)
            uvs[corners] = layers[layer.name][loops[corners]]
        materials = [alpha if alpha is not None else {"alpha": 1.0, "texture": None, "wrap": 0, "closest": False}
                     for alpha in slots]
        return {"uvs": uvs, "triangle_material": material.astype(np.int32), "materials": materials}
    finally:
        obj.to_mesh_clear()
