# How the passes reach the compositor: one Image node on the EXR sequence and a darken group.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Nodes are found by name, so setting up or refreshing again never piles up nodes."""
import os

import bpy

from . import compat

IMAGE_NAME = "SoftShadow Passes"
IMAGE_NODE = "SoftShadow Passes"
GROUP_NAME = "SoftShadow Darken"
GROUP_NODE = "SoftShadow Darken"


def _tree(scene, create=True):
    return compat.compositor_tree(scene, create=create, bpy_data=bpy.data)


def passes_image(exr_path):
    """The image datablock reading the EXR sequence that `exr_path` is one frame of."""
    image = bpy.data.images.get(IMAGE_NAME)
    if image is None:
        image = bpy.data.images.load(exr_path, check_existing=False)
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


def darken_group():
    """Image x mix(1, visibility, strength): the pass darkens a render layer."""
    group = bpy.data.node_groups.get(GROUP_NAME)
    if group is not None and group.bl_idname == "CompositorNodeTree":
        return group
    group = bpy.data.node_groups.new(GROUP_NAME, "CompositorNodeTree")
    compat.add_group_socket(group, "INPUT", "NodeSocketColor", "Image")
    visibility = compat.add_group_socket(group, "INPUT", "NodeSocketFloat", "Visibility")
    strength = compat.add_group_socket(group, "INPUT", "NodeSocketFloat", "Strength")
    compat.add_group_socket(group, "OUTPUT", "NodeSocketColor", "Image")
    for socket, value in ((visibility, 1.0), (strength, 1.0)):
        socket.default_value = value
        socket.min_value, socket.max_value = 0.0, 1.0
    nodes, links = group.nodes, group.links
    inputs = nodes.new("NodeGroupInput")
    inputs.location = (-400, 0)
    outputs = nodes.new("NodeGroupOutput")
    outputs.location = (400, 0)
    factor, strength_in, lit_in, visibility_in, factor_out = compat.new_color_mix(nodes, bpy.types, "MIX")
    factor.name = "Shadow Factor"
    lit_in.default_value = (1.0, 1.0, 1.0, 1.0)
    factor.location = (-100, -150)
    multiply, one_in, image_in, shadow_in, image_out = compat.new_color_mix(nodes, bpy.types, "MULTIPLY")
    multiply.name = "Darken"
    one_in.default_value = 1.0
    multiply.location = (150, 0)
    links.new(inputs.outputs["Strength"], strength_in)
    links.new(inputs.outputs["Visibility"], visibility_in)
    links.new(inputs.outputs["Image"], image_in)
    links.new(factor_out, shadow_in)
    links.new(image_out, outputs.inputs["Image"])
    return group


def _find(tree, bl_idname):
    return next((n for n in tree.nodes if n.bl_idname == bl_idname), None)


def pass_sockets(node):
    """The Image node's pass outputs (multilayer passes), excluding the plain Image/Alpha."""
    return [s.name for s in node.outputs if s.enabled and s.name not in ("Image", "Alpha")]


def _relink(tree, group_node, node, pass_name):
    names = pass_sockets(node)
    if not names:
        return None
    chosen = pass_name if pass_name in names else names[0]
    target = group_node.inputs["Visibility"]
    current = target.links[0].from_socket if target.is_linked else None
    if current is None or current.node != node or current.name != chosen:
        for link in list(target.links):
            tree.links.remove(link)
        tree.links.new(node.outputs[chosen], target)
    return chosen


def final_output(scene):
    """The node that takes the compositor's final image (Composite, or Group Output in 5.0+)."""
    tree = _tree(scene)
    node, created = compat.compositor_output(tree, bpy.types)
    if created:
        node.location = (400, 100)
    return node


def setup(scene, exr_path=None):
    """Render Layers -> darken group (by the chosen pass) -> final output, plus the Image node."""
    tree = _tree(scene)
    image = passes_image(exr_path) if exr_path and os.path.exists(exr_path) else bpy.data.images.get(IMAGE_NAME)
    node = image_node(scene, image)
    layers = _find(tree, "CompositorNodeRLayers")
    if layers is None:
        layers = tree.nodes.new("CompositorNodeRLayers")
        layers.location = (-300, 100)
    composite = final_output(scene)
    group_node = tree.nodes.get(GROUP_NODE)
    if group_node is None:
        group_node = tree.nodes.new("CompositorNodeGroup")
        group_node.name = GROUP_NODE
        group_node.label = "Soft Shadow Darken"
        group_node.location = (layers.location.x + layers.width + 250, layers.location.y)
        node.location = (layers.location.x, layers.location.y - 450)
        if composite.location.x < group_node.location.x + 250:
            composite.location = (group_node.location.x + 250, group_node.location.y)
    if group_node.node_tree is None:
        group_node.node_tree = darken_group()
    group_node.inputs["Strength"].default_value = scene.softshadow.strength
    if not group_node.inputs["Image"].is_linked:
        tree.links.new(layers.outputs["Image"], group_node.inputs["Image"])
    for link in list(composite.inputs["Image"].links):
        if link.from_node != group_node:
            tree.links.remove(link)
    if not composite.inputs["Image"].is_linked:
        tree.links.new(group_node.outputs["Image"], composite.inputs["Image"])
    _relink(tree, group_node, node, scene.softshadow.compositor_pass)
    return node


def refresh(scene, exr_path):
    """After a frame's EXR was written: point the image at it, reload, update the sockets."""
    tree = _tree(scene, create=False)
    image = passes_image(exr_path)
    image.reload()
    image.size[:]  # touching the buffer makes Blender read the passes (DESIGN.md)
    if tree is None:
        return None
    node = tree.nodes.get(IMAGE_NODE)
    if node is None:
        return None
    if node.image != image:
        node.image = image
    _set_sequence(node, scene)
    group_node = tree.nodes.get(GROUP_NODE)
    if group_node is not None and "Visibility" in group_node.inputs:
        _relink(tree, group_node, node, scene.softshadow.compositor_pass)
    return node
