# How the passes reach the compositor: one Image node on the EXR sequence and a darken group.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Nodes are found by name, so setting up or refreshing again never piles up nodes."""
import os
import zlib

import bpy

from . import compat, native, scene_export

IMAGE_NAME = "SoftShadow Passes"
IMAGE_NODE = "SoftShadow Passes"
GROUP_NAME = "SoftShadow Darken"
GROUP_NODE = "SoftShadow Darken"


def _tree(scene, create=True):
    return compat.compositor_tree(scene, create=create, bpy_data=bpy.data)


def passes_image(exr_path):
    """The image datablock reading the EXR sequence that `exr_path` is one frame of. It exists
    before its first file does: a render must not add datablocks (its dependency graph was built
    before, and would not see them until the next frame)."""
    image = bpy.data.images.get(IMAGE_NAME)
    if image is None:
        if os.path.exists(exr_path):
            image = bpy.data.images.load(exr_path, check_existing=False)
        else:
            image = bpy.data.images.new(IMAGE_NAME, 4, 4, float_buffer=True)
            image.source = "FILE"
            image.filepath = exr_path
        image.name = IMAGE_NAME
    elif bpy.path.abspath(image.filepath) != os.path.abspath(exr_path):
        image.filepath = exr_path
    if image.source != "SEQUENCE":
        image.source = "SEQUENCE"
    return image


def _set_sequence(owner, scene):
    # The file number equals the scene frame: start 1, offset 0, long enough for any frame.
    owner.frame_start = 1
    owner.frame_offset = 0
    owner.frame_duration = max(scene.frame_end, 1) + 1
    owner.use_auto_refresh = True


def image_node(scene, image=None):
    """The one Image node for the passes (created when missing)."""
    tree = _tree(scene)
    node = tree.nodes.get(IMAGE_NODE)
    if node is None or node.bl_idname != "CompositorNodeImage":
        if node is not None:
            tree.nodes.remove(node)
        node = tree.nodes.new("CompositorNodeImage")
        node.name = IMAGE_NODE
        node.label = "Soft Shadow Passes"
        node.location = (-300, -300)
    if image is not None and node.image != image:
        node.image = image
    _set_sequence(node, scene)
    return node


def existing_group(name):
    """The compositor node group of that name, when there is one of this version's making (an
    older one, without a Mask input, is removed: set-up makes it again)."""
    group = bpy.data.node_groups.get(name)
    if group is None or group.bl_idname != "CompositorNodeTree":
        return None
    if "Mask" not in compat.group_sockets(group, "INPUT"):
        bpy.data.node_groups.remove(group)
        return None
    return group


def new_group(name, colour_inputs, unit_inputs):
    """A compositor node group with colour inputs, float inputs in [0, 1] (default 1) and an
    Image output: (group, its Group Input node, its Group Output node)."""
    group = bpy.data.node_groups.new(name, "CompositorNodeTree")
    for socket_name in colour_inputs:
        compat.add_group_socket(group, "INPUT", "NodeSocketColor", socket_name)
    for socket_name in unit_inputs:
        socket = compat.add_group_socket(group, "INPUT", "NodeSocketFloat", socket_name)
        socket.default_value = 1.0
        socket.min_value, socket.max_value = 0.0, 1.0
    compat.add_group_socket(group, "OUTPUT", "NodeSocketColor", "Image")
    return group, group.nodes.new("NodeGroupInput"), group.nodes.new("NodeGroupOutput")


# A group's float inputs: the pass, its mask (where the light reaches a receiver) and Strength.
GROUP_INPUTS = ["Visibility", "Mask", "Strength"]


def guarded_visibility(nodes, links, inputs, x, y):
    """min(1, V + 1 - mask): V itself wherever the pass exists (outside its mask V is 1 by the
    library's contract), and 1 where the frame has no such pass (a failed light, or no pass file:
    the Image node then gives its pass and mask sockets the same stand-in value, whatever colour
    Blender's missing image has). So a failed pass leaves the render as it would be without it.
    Returns the output socket."""
    less, _fac, v_in, mask_in, less_out = compat.new_color_mix(nodes, bpy.types, "SUBTRACT")
    _fac.default_value = 1.0
    plus, _fac, a_in, one_in, plus_out = compat.new_color_mix(nodes, bpy.types, "ADD")
    _fac.default_value = 1.0
    one_in.default_value = (1.0, 1.0, 1.0, 1.0)
    low, _fac, b_in, cap_in, low_out = compat.new_color_mix(nodes, bpy.types, "DARKEN")
    _fac.default_value = 1.0
    cap_in.default_value = (1.0, 1.0, 1.0, 1.0)
    for node, dx in ((less, 0), (plus, 180), (low, 360)):
        node.location = (x + dx, y)
    less.name, plus.name, low.name = "Guard V - Mask", "Guard + 1", "Guard Min 1"
    links.new(inputs.outputs["Visibility"], v_in)
    links.new(inputs.outputs["Mask"], mask_in)
    links.new(less_out, a_in)
    links.new(plus_out, b_in)
    return low_out


def darken_group():
    """Image x mix(1, visibility, strength): the pass darkens a render layer."""
    group = existing_group(GROUP_NAME)
    if group is not None:
        return group
    group, inputs, outputs = new_group(GROUP_NAME, ["Image"], GROUP_INPUTS)
    nodes, links = group.nodes, group.links
    inputs.location, outputs.location = (-900, 0), (400, 0)
    visibility = guarded_visibility(nodes, links, inputs, -700, -300)
    factor, strength_in, lit_in, visibility_in, factor_out = compat.new_color_mix(nodes, bpy.types, "MIX")
    factor.name = "Shadow Factor"
    lit_in.default_value = (1.0, 1.0, 1.0, 1.0)
    factor.location = (-100, -150)
    multiply, one_in, image_in, shadow_in, image_out = compat.new_color_mix(nodes, bpy.types, "MULTIPLY")
    multiply.name = "Darken"
    one_in.default_value = 1.0
    multiply.location = (150, 0)
    links.new(inputs.outputs["Strength"], strength_in)
    links.new(visibility, visibility_in)
    links.new(inputs.outputs["Image"], image_in)
    links.new(factor_out, shadow_in)
    links.new(image_out, outputs.inputs["Image"])
    return group


def _find(tree, bl_idname):
    return next((n for n in tree.nodes if n.bl_idname == bl_idname), None)


def pass_sockets(node):
    """The Image node's pass outputs (multilayer passes), excluding the plain Image/Alpha."""
    return [s.name for s in node.outputs if s.enabled and s.name not in ("Image", "Alpha")]


# Blender keeps no reference to the strings of a dynamic enum: they must outlive the call.
_enum_items = []
FIRST_PASS = "FIRST"  # the choice before the artist made one (enum number 0)


def visibility_passes(node):
    """The main passes (`<light>_<method>`), not their mask, umbra or debug layers."""
    try:
        methods = native.method_names()
    except native.LibraryUnavailable:
        methods = ()  # no library, no new passes: only a light on auto's name is known
    endings = tuple("_" + m for m in methods + ("auto",))
    return [name for name in pass_sockets(node) if name.endswith(endings)]


def pass_enum_items(scene):
    """The passes the compositor can darken by: the outputs of the passes Image node. Each item's
    number is derived from its name, so a stored choice survives passes being added or removed."""
    tree = _tree(scene, create=False) if scene is not None else None
    node = tree.nodes.get(IMAGE_NODE) if tree is not None else None
    names = visibility_passes(node) if node is not None else []
    _enum_items[:] = [(FIRST_PASS, "First Pass", "The first pass of the file (render once: the passes "
                       "appear in this list)", 0)]
    _enum_items.extend((name, name, "Darken by the pass %s" % name, pass_enum_number(name)) for name in names)
    return _enum_items


def pass_enum_number(name):
    """The enum number of a pass name (0: the first pass), the same whatever the list holds."""
    return 0 if name in ("", FIRST_PASS) else 1 + zlib.crc32(name.encode()) % 0x7FFFFFF0


def pass_enum_name(number):
    return next((item[0] for item in _enum_items if item[3] == number and item[0] != FIRST_PASS), "")


def expected_passes(scene, view_layer):
    """The main pass names a render will write for the view layer's plainly placed lights (pass
    names are `<light>_<method asked for>`, so they are known before anything is computed)."""
    if not native.available():
        return []  # no library, no passes: the report says why
    names = []
    for obj in scene_export.rendering_objects(view_layer):
        light = obj.data if obj.type == "LIGHT" else None
        settings = getattr(light, "softshadow", None)
        if settings is None or not settings.enabled:
            continue
        if not (compat.light_use_shadow(light) or settings.replaces_shadow):
            continue
        names.append(native.pass_name(obj.name, settings.method or "auto"))
    return names


def missing_sockets(scene, view_layer):
    """The expected passes the compositor's Image node has no socket for. A render cannot add
    them for its first frame (its copy of the node tree is made before the frame's passes are),
    so they are caught before it starts. [] when the compositor is not set up."""
    tree = _tree(scene, create=False)
    node = tree.nodes.get(IMAGE_NODE) if tree is not None else None
    wired = tree is not None and any(n.name.startswith("SoftShadow ") and n.bl_idname == "CompositorNodeGroup"
                                     for n in tree.nodes)
    if node is None or not wired:
        return []
    have = set(pass_sockets(node))
    return [name for name in expected_passes(scene, view_layer) if name not in have]


def unguarded_groups(scene):
    """The soft-shadow group nodes made before groups read their pass's mask: a failed pass
    darkens through them by Blender's missing-image colour until Set Up Compositor runs again."""
    tree = _tree(scene, create=False)
    return [node.name for node in (tree.nodes if tree is not None else ())
            if node.bl_idname == "CompositorNodeGroup" and node.name.startswith("SoftShadow ")
            and "Visibility" in node.inputs and "Mask" not in node.inputs]


def apply_strength(scene):
    """The scene's Strength on the darken group node (called whenever the slider moves)."""
    tree = _tree(scene, create=False)
    for node in (tree.nodes if tree is not None else ()):
        if node.name.startswith("SoftShadow ") and "Strength" in node.inputs:
            node.inputs["Strength"].default_value = scene.softshadow.strength


def relink_chosen(scene):
    """Links the pass chosen in the UI right away (the set-up need not run again)."""
    tree = _tree(scene, create=False)
    node = tree.nodes.get(IMAGE_NODE) if tree is not None else None
    group_node = tree.nodes.get(GROUP_NODE) if tree is not None else None
    if node is not None and group_node is not None and "Visibility" in group_node.inputs:
        _relink(tree, group_node, node, _chosen_pass(scene))


def _chosen_pass(scene):
    return scene.softshadow.compositor_pass_name


def _relink(tree, group_node, node, pass_name):
    """Links the chosen pass to the group. A choice that is not among the passes is left
    unlinked and said (no silent fall-back to another light's shadow); no choice yet takes the
    first pass. Returns (linked pass or None, problem or '')."""
    names = visibility_passes(node)
    if not names:
        return None, ""
    if pass_name and pass_name not in names:
        return None, "the pass '%s' chosen to darken by is not in the pass file (it has %s)" % (
            pass_name, ", ".join(names))
    chosen = pass_name or names[0]
    link_pass(tree, node, chosen, group_node)
    return chosen, ""


def link_pass(tree, node, pass_name, group_node):
    """The pass to the group's Visibility and its mask to Mask (the guard against a missing pass)."""
    for socket_name, target in ((pass_name, group_node.inputs["Visibility"]),
                                (pass_name + "_mask", group_node.inputs.get("Mask"))):
        if target is None:
            continue
        source = node.outputs.get(socket_name)
        current = target.links[0].from_socket if target.is_linked else None
        if current is not None and current == source:
            continue
        for link in list(target.links):
            tree.links.remove(link)
        if source is not None:
            tree.links.new(source, target)


def place_between(before, node, output):
    """Lays `node` out right of `before`, moving the output further right when it is in the way."""
    node.location = (before.location.x + before.width + 80, before.location.y)
    if output.location.x < node.location.x + node.width + 80:
        output.location = (node.location.x + node.width + 80, output.location.y)


def final_output(scene):
    """The node that takes the compositor's final image (Composite, or Group Output in 5.0+)."""
    tree = _tree(scene)
    node, created = compat.compositor_output(tree, bpy.types)
    if created:
        node.location = (400, 100)
    return node


def setup(scene, exr_path=None):
    """Inserts the darken group just before the final output, keeping whatever fed it (Render
    Layers, or a chain such as Render Layers -> Glare), and adds the passes Image node.
    Returns (Image node, [what changed, in words])."""
    changes = []
    tree = _tree(scene)
    image = passes_image(exr_path) if exr_path else bpy.data.images.get(IMAGE_NAME)
    had_image_node = tree.nodes.get(IMAGE_NODE) is not None
    node = image_node(scene, image)
    if not had_image_node:
        changes.append("added the Image node '%s'" % IMAGE_NODE)
    output, created = compat.compositor_output(tree, bpy.types)
    if created:
        output.location = (600, 100)
        changes.append("added the output node '%s'" % output.name)
    output_input = output.inputs["Image"]
    group_node = tree.nodes.get(GROUP_NODE)
    if group_node is None:
        group_node = tree.nodes.new("CompositorNodeGroup")
        group_node.name = GROUP_NODE
        group_node.label = "Soft Shadow Darken"
        changes.append("added the group node '%s'" % GROUP_NODE)
    group = darken_group()
    if group_node.node_tree != group:
        group_node.node_tree = group
    group_node.inputs["Strength"].default_value = scene.softshadow.strength
    feeding = output_input.links[0].from_socket if output_input.is_linked else None
    if feeding is None or feeding.node != group_node:
        if feeding is None:
            layers = _find(tree, "CompositorNodeRLayers")
            if layers is None:
                layers = tree.nodes.new("CompositorNodeRLayers")
                layers.location = (output.location.x - 900, output.location.y)
                changes.append("added a Render Layers node")
            feeding = layers.outputs["Image"]
        for link in list(group_node.inputs["Image"].links):
            tree.links.remove(link)
        tree.links.new(feeding, group_node.inputs["Image"])
        for link in list(output_input.links):
            tree.links.remove(link)
        tree.links.new(group_node.outputs["Image"], output_input)
        place_between(feeding.node, group_node, output)
        node.location = (group_node.location.x - 120, group_node.location.y - 480)
        changes.append("inserted '%s' between %s.%s and %s" % (
            GROUP_NODE, feeding.node.name, feeding.name, output.name))
    chosen, problem = _relink(tree, group_node, node, _chosen_pass(scene))
    if problem:
        changes.append(problem)
    elif chosen:
        changes.append("darkening by %s" % chosen)
    return node, changes


def refresh(scene, exr_path):
    """After a frame's EXR was written: point the image at it, reload, update the sockets.
    Returns a problem ('' when none)."""
    tree = _tree(scene, create=False)
    image = passes_image(exr_path)
    image.reload()
    image.size[:]  # touching the buffer makes Blender read the passes (docs/contracts.md)
    if tree is None:
        return ""
    node = tree.nodes.get(IMAGE_NODE)
    if node is None:
        return ""
    if node.image != image:
        node.image = image
    _set_sequence(node, scene)
    group_node = tree.nodes.get(GROUP_NODE)
    if group_node is not None and "Visibility" in group_node.inputs:
        return _relink(tree, group_node, node, _chosen_pass(scene))[1]
    return ""
