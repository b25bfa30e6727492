# How the Replace composite is set up: each light's own contribution isolated in a Cycles light
# group, rendered without the renderer's shadow, multiplied by its pass, and summed back.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Image + Σ_L Light_L × (mix(1, V_L, strength) − 1): the beauty holds every light unshadowed
(their shadows are off), so taking a light's contribution out and putting it back times V gives
each light the pass's shadow, and everything else (other lights, world, emission) as rendered.

How Light_L is isolated:
- Cycles: a light group `ss_<light>` (Render Layers output `Combined_ss_<light>`).
- EEVEE has no light groups: the light moves into a collection of its own, excluded from a view
  layer `SoftShadow without <light>`, and Light_L = Image − that layer's Image (one more EEVEE
  render of the view layer per light).

Set-up changes the file (lights' renderer shadows off, each marked `replaces_shadow` so their
passes are still computed; light groups or collections and view layers) and reports each change;
setting up Darken again undoes them."""
import re

import bpy

from . import compat, compositor, native, scene_export

GROUP_NAME = "SoftShadow Replace"
NODE_PREFIX = "SoftShadow Replace "


def _mix(nodes, blend_type, factor=1.0):
    """(node, factor, a, b, result) of a colour mix whose factor is set (ShaderNodeMix starts at 0.5)."""
    mix = compat.new_color_mix(nodes, bpy.types, blend_type)
    mix[1].default_value = factor
    return mix


def replace_group():
    """Image + Light × (mix(1, Visibility, Strength) − 1)."""
    group = compositor.existing_group(GROUP_NAME)
    if group is not None:
        return group
    group, inputs, outputs = compositor.new_group(GROUP_NAME, ["Image", "Light"], compositor.GROUP_INPUTS)
    nodes, links = group.nodes, group.links
    inputs.location, outputs.location = (-1100, 0), (500, 0)
    visibility = compositor.guarded_visibility(nodes, links, inputs, -900, -400)
    factor, f_fac, f_a, f_b, f_out = _mix(nodes, "MIX")
    f_a.default_value = (1.0, 1.0, 1.0, 1.0)
    shadowed, s_fac, s_a, s_b, s_out = _mix(nodes, "MULTIPLY")
    without, w_fac, w_a, w_b, w_out = _mix(nodes, "SUBTRACT")
    total, t_fac, t_a, t_b, t_out = _mix(nodes, "ADD")
    for node, x, y in ((factor, -250, -200), (shadowed, 0, -150), (without, 0, 100), (total, 250, 0)):
        node.location = (x, y)
    links.new(inputs.outputs["Strength"], f_fac)
    links.new(visibility, f_b)
    links.new(inputs.outputs["Light"], s_a)
    links.new(f_out, s_b)
    links.new(inputs.outputs["Image"], w_a)
    links.new(inputs.outputs["Light"], w_b)
    links.new(w_out, t_a)
    links.new(s_out, t_b)
    links.new(t_out, outputs.inputs["Image"])
    return group


def lightgroup_name(light_name):
    """Light group names hold letters, digits and '_' only."""
    return "ss_" + re.sub(r"[^A-Za-z0-9_]", "_", light_name)


def _lights(view_layer):
    """The light objects that get a pass (shadow on, or already replaced by ours)."""
    out = []
    for obj in scene_export.rendering_objects(view_layer):
        if obj.type != "LIGHT":
            continue
        settings = getattr(obj.data, "softshadow", None)
        if settings is None or not settings.enabled:
            continue
        if compat.light_use_shadow(obj.data) or compat.renderer_shadow(obj.data) or settings.replaces_shadow:
            out.append(obj)
    return out


def _render_layers(tree, view_layer, changes):
    for node in tree.nodes:
        if node.bl_idname == "CompositorNodeRLayers" and node.layer == view_layer.name:
            return node
    node = tree.nodes.new("CompositorNodeRLayers")
    node.layer = view_layer.name
    changes.append("added a Render Layers node for '%s'" % view_layer.name)
    return node


def _artist_feed(output_input):
    """What fed the output before our nodes: walk back through them along their Image input."""
    socket = output_input.links[0].from_socket if output_input.is_linked else None
    while socket is not None and socket.node.name.startswith(("SoftShadow ",)) and "Image" in socket.node.inputs:
        image_in = socket.node.inputs["Image"]
        socket = image_in.links[0].from_socket if image_in.is_linked else None
    return socket


WITHOUT_PREFIX = "SoftShadow without "
LIGHT_PREFIX = "SoftShadow Light "
LAYERS_PREFIX = "SoftShadow Render Layers "
COLLECTION_PREFIX = "SoftShadow "


def problem(scene, view_layer):
    """Why Replace cannot be set up here, or ''."""
    engine = scene.render.engine
    if engine == "CYCLES":
        if not compat.supports_lightgroups(view_layer):
            return "Replace needs Cycles light groups (Blender 3.2 or newer): use Darken"
        return ""
    if engine == compat.eevee_engine_id(scene.render):
        return ""
    return "Replace works with Cycles and EEVEE (the render engine is %s): use Darken there" % engine


def is_helper_layer(view_layer):
    """A view layer EEVEE Replace made (it needs no passes of its own)."""
    return view_layer.name.startswith(WITHOUT_PREFIX)


def _copy_layer_flags(source, target):
    """The main view layer's collection exclusions, holdouts and indirect-only flags."""
    for child in source.children:
        other = target.children.get(child.name)
        if other is None:
            continue
        other.exclude = child.exclude
        other.holdout = child.holdout
        other.indirect_only = child.indirect_only
        _copy_layer_flags(child, other)


def _eevee_light(scene, view_layer, obj, tree, layers, changes):
    """Light_L for EEVEE: Image − the Image of a view layer without the light."""
    name = COLLECTION_PREFIX + obj.name
    collection = bpy.data.collections.get(name)
    if collection is None:
        collection = bpy.data.collections.new(name)
        scene.collection.children.link(collection)
    if list(obj.users_collection) != [collection]:
        settings = obj.data.softshadow
        settings.home_collections = ";".join(c.name for c in obj.users_collection if c != collection)
        for other in list(obj.users_collection):
            if other != collection:
                other.objects.unlink(obj)
        if obj.name not in collection.objects:
            collection.objects.link(obj)
        changes.append("light '%s' moved into collection '%s'" % (obj.name, name))
    layer_name = WITHOUT_PREFIX + obj.name
    without = scene.view_layers.get(layer_name)
    if without is None:
        without = scene.view_layers.new(layer_name)
        changes.append("added view layer '%s'" % layer_name)
    _copy_layer_flags(view_layer.layer_collection, without.layer_collection)
    without.layer_collection.children[name].exclude = True
    for other in scene.view_layers:  # the light stays in every other layer
        if other != without and name in other.layer_collection.children and not is_helper_layer(other):
            other.layer_collection.children[name].exclude = False
    rl_name = LAYERS_PREFIX + layer_name
    rl = tree.nodes.get(rl_name)
    if rl is None:
        rl = tree.nodes.new("CompositorNodeRLayers")
        rl.name = rl_name
    rl.layer = layer_name
    stacked = len([n for n in tree.nodes if n.name.startswith(LAYERS_PREFIX)])
    rl.location = (layers.location.x, layers.location.y - 350 - 300 * stacked)
    sub_name = LIGHT_PREFIX + obj.name
    if tree.nodes.get(sub_name) is not None:  # (made again: its sockets differ by version)
        tree.nodes.remove(tree.nodes[sub_name])
    sub, fac, a, b, out = _mix(tree.nodes, "SUBTRACT")
    sub.name = sub_name
    sub.label = "Light: " + obj.name
    sub.location = (rl.location.x + rl.width + 60, rl.location.y)
    _link(tree, layers.outputs["Image"], a)
    _link(tree, rl.outputs["Image"], b)
    return out


def setup(scene, view_layer, node):
    """Light groups and shadows for every light with a pass, and one Replace group per light
    between what fed the output and the output. Returns [what changed, in words]."""
    changes = []
    tree = compat.compositor_tree(scene, create=True, bpy_data=bpy.data)
    output, created = compat.compositor_output(tree, bpy.types)
    if created:
        changes.append("added the output node '%s'" % output.name)
    output_input = output.inputs["Image"]
    layers = _render_layers(tree, view_layer, changes)
    feed = _artist_feed(output_input) or layers.outputs["Image"]
    darken = tree.nodes.get(compositor.GROUP_NODE)
    if darken is not None:
        tree.nodes.remove(darken)
        changes.append("removed the Darken group (Replace takes its place)")
    have = set(compositor.pass_sockets(node))
    previous, used = feed, set()
    for index, obj in enumerate(_lights(view_layer)):
        settings = obj.data.softshadow
        engine = scene.render.engine
        if engine == "CYCLES":
            group_name = lightgroup_name(obj.name)
            if obj.lightgroup != group_name:
                changes.append("light '%s' in light group %s" % (obj.name, group_name))
            light_output = compat.lightgroup_pass(view_layer, obj, group_name)  # (an output name)
        else:
            light_output = _eevee_light(scene, view_layer, obj, tree, layers, changes)
        if compat.renderer_shadow(obj.data, engine):
            compat.set_renderer_shadow(obj.data, False, engine)
            changes.append("light '%s': the renderer's shadow off (the pass replaces it)" % obj.name)
        settings.replaces_shadow = True
        pass_name = native.pass_name(obj.name, settings.method or "auto")
        if pass_name not in have:
            changes.append("light '%s': no pass %s in the pass file yet, left out" % (obj.name, pass_name))
            continue
        name = NODE_PREFIX + obj.name
        group_node = tree.nodes.get(name)
        if group_node is None:
            group_node = tree.nodes.new("CompositorNodeGroup")
            group_node.name = name
            group_node.label = "Replace: " + obj.name
            changes.append("added '%s'" % name)
        group_node.node_tree = replace_group()
        compositor.place_between(previous.node, group_node, output)
        group_node.inputs["Strength"].default_value = scene.softshadow.strength
        _link(tree, previous, group_node.inputs["Image"])
        if isinstance(light_output, str):
            # (Render Layers lists a new light group's output once the tree has updated)
            light_output = layers.outputs.get(light_output)
        if light_output is None:
            changes.append("light '%s': Render Layers has no output for its light group" % obj.name)
        else:
            _link(tree, light_output, group_node.inputs["Light"])
        compositor.link_pass(tree, node, pass_name, group_node)
        previous = group_node.outputs["Image"]
        used.add(name)
    for stale in [n for n in tree.nodes if n.name.startswith(NODE_PREFIX) and n.name not in used]:
        changes.append("removed '%s'" % stale.name)
        tree.nodes.remove(stale)
    if not (output_input.is_linked and output_input.links[0].from_socket == previous):
        _link(tree, previous, output_input)
        changes.append("inserted the Replace groups between %s.%s and %s" % (feed.node.name, feed.name, output.name))
    return changes


def _link(tree, from_socket, to_socket):
    if to_socket.is_linked and to_socket.links[0].from_socket == from_socket:
        return
    for link in list(to_socket.links):
        tree.links.remove(link)
    tree.links.new(from_socket, to_socket)


def teardown(scene, view_layer):
    """Back to the renderer's shadows and no Replace nodes, light groups stay (harmless), EEVEE's
    lights go back to their collections and its view layers go (when Darken is set up instead)."""
    changes = []
    tree = compat.compositor_tree(scene, create=False)
    if tree is not None:
        output, _ = compat.compositor_output(tree, bpy.types)
        output_input = output.inputs["Image"]
        feed = _artist_feed(output_input)
        ours = [n for n in tree.nodes if n.name.startswith((NODE_PREFIX, LIGHT_PREFIX, LAYERS_PREFIX))]
        for node in ours:
            changes.append("removed '%s'" % node.name)
            tree.nodes.remove(node)
        if ours and feed is not None:
            _link(tree, feed, output_input)
    for obj in view_layer.objects:
        settings = getattr(obj.data, "softshadow", None) if obj.type == "LIGHT" else None
        if settings is None:
            continue
        if settings.replaces_shadow:
            for engine in ("CYCLES", compat.eevee_engine_id(scene.render)):
                compat.set_renderer_shadow(obj.data, True, engine)
            settings.replaces_shadow = False
            changes.append("light '%s': the renderer's shadow back on" % obj.name)
        if settings.home_collections:
            homes = [bpy.data.collections.get(n) or (scene.collection if n == scene.collection.name else None)
                     for n in settings.home_collections.split(";")]
            for home in [h for h in homes if h is not None]:
                if obj.name not in home.objects:
                    home.objects.link(obj)
            for ours in [c for c in obj.users_collection if c.name == COLLECTION_PREFIX + obj.name]:
                ours.objects.unlink(obj)
                if not ours.objects:
                    bpy.data.collections.remove(ours)
            settings.home_collections = ""
            changes.append("light '%s' back in its collections" % obj.name)
    for layer in [l for l in scene.view_layers if is_helper_layer(l)]:
        changes.append("removed view layer '%s'" % layer.name)
        scene.view_layers.remove(layer)
    return changes
