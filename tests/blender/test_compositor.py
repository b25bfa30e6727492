# Is the compositor wired to the passes once, and refreshed (not duplicated) on every render?
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402

ss = sstest.addon()


def _counts(tree):
    counts = {}
    for node in tree.nodes:
        counts[node.bl_idname] = counts.get(node.bl_idname, 0) + 1
    return counts


def test_setup_then_rerender_does_not_pile_up():
    folder = sstest.tempdir("comp")
    scene = sstest.standard_scene(32, 24)
    scene.objects["Key"].data.softshadow.method = "shadow_map"
    scene.softshadow.output_path = os.path.join(folder, "softshadow_####.exr")
    scene.softshadow.enabled = True
    scene.frame_current = 3
    result = bpy.ops.softshadow.setup_compositor()
    sstest.check(result == {"FINISHED"}, "set-up operator: %s" % result)
    result = bpy.ops.softshadow.render_passes()
    sstest.check(result == {"FINISHED"}, "render operator: %s" % result)
    tree = ss.compat.compositor_tree(scene)
    first = _counts(tree)
    for _ in range(2):
        bpy.ops.softshadow.render_passes()
        bpy.ops.softshadow.setup_compositor()
        ss.handlers.on_render_pre(scene)
    sstest.check(_counts(tree) == first, "same nodes after re-rendering: %s vs %s" % (_counts(tree), first))
    sstest.check(first.get("CompositorNodeImage") == 1, "one Image node: %s" % first)
    sstest.check(len([g for g in bpy.data.node_groups if g.name.startswith(ss.compositor.GROUP_NAME)]) == 1,
                 "one darken group datablock")
    sstest.check(len([i for i in bpy.data.images if i.name.startswith(ss.compositor.IMAGE_NAME)]) == 1,
                 "one passes image datablock")

    node = tree.nodes[ss.compositor.IMAGE_NODE]
    sstest.check(node.image is not None and node.image.source == "SEQUENCE", "image is a sequence")
    sstest.check(node.image.type == "MULTILAYER", "multilayer: %s" % node.image.type)
    sstest.check("Key_shadow_map" in ss.compositor.pass_sockets(node), "pass socket: %s" % list(node.outputs.keys()))
    group = tree.nodes[ss.compositor.GROUP_NODE]
    link = group.inputs["Visibility"].links[0]
    sstest.check(link.from_node == node and link.from_socket.name == "Key_shadow_map",
                 "darken group reads the pass: %s.%s" % (link.from_node.name, link.from_socket.name))
    output = ss.compositor.final_output(scene)
    sstest.check(output.inputs["Image"].links[0].from_node == group,
                 "group feeds the final output (%s)" % output.bl_idname)
    layers = group.inputs["Image"].links[0].from_node
    sstest.check(layers.bl_idname == "CompositorNodeRLayers", "group darkens the render layer")


def test_chosen_pass_and_sequence_frame():
    folder = sstest.tempdir("comp2")
    scene = sstest.standard_scene(32, 24)
    sstest.add_light("Fill", location=(2, 2, 5), size=0.3).data.softshadow.method = "shadow_map"
    scene.objects["Key"].data.softshadow.method = "shadow_map"
    scene.softshadow.output_path = os.path.join(folder, "softshadow_####.exr")
    bpy.ops.softshadow.setup_compositor()
    for frame in (1, 2):
        scene.frame_set(frame)
        sstest.check(bpy.ops.softshadow.render_passes() == {"FINISHED"}, "frame %d" % frame)
        if frame == 1:
            choices = [i[0] for i in ss.compositor.pass_enum_items(scene)]
            sstest.check(sorted(choices) == ["FIRST", "Fill_shadow_map", "Key_shadow_map"],
                         "passes to choose from: %s" % choices)
            scene.softshadow.compositor_pass = "Fill_shadow_map"
    tree = ss.compat.compositor_tree(scene)
    group = tree.nodes[ss.compositor.GROUP_NODE]
    sstest.check(group.inputs["Visibility"].links[0].from_socket.name == "Fill_shadow_map", "chosen pass linked")
    node = tree.nodes[ss.compositor.IMAGE_NODE]
    # The node maps scene frame f to file number f (start 1, offset 0).
    sstest.check(node.frame_start == 1 and node.frame_offset == 0 and node.frame_duration >= scene.frame_end,
                 "sequence follows the frame: start %d offset %d duration %d"
                 % (node.frame_start, node.frame_offset, node.frame_duration))
    sstest.check(sorted(os.listdir(folder)) == ["softshadow_0001.exr", "softshadow_0002.exr"],
                 "one EXR per frame: %s" % os.listdir(folder))


def test_setup_inserts_before_the_output_keeps_the_chain_and_strength_is_live():
    folder = sstest.tempdir("comp3")
    scene = sstest.standard_scene(32, 24)
    scene.objects["Key"].data.softshadow.method = "shadow_map"
    scene.softshadow.output_path = os.path.join(folder, "softshadow_####.exr")
    tree = ss.compat.compositor_tree(scene, create=True, bpy_data=bpy.data)
    for node in list(tree.nodes):
        tree.nodes.remove(node)
    layers = tree.nodes.new("CompositorNodeRLayers")
    glare = tree.nodes.new("CompositorNodeGlare")
    composite, _ = ss.compat.compositor_output(tree, bpy.types)  # (Composite, or 5.x Group Output)
    viewer = tree.nodes.new("CompositorNodeViewer")
    tree.links.new(layers.outputs["Image"], glare.inputs["Image"])
    tree.links.new(glare.outputs["Image"], composite.inputs["Image"])
    tree.links.new(glare.outputs["Image"], viewer.inputs["Image"])
    node, changes = ss.compositor.setup(scene, ss.api.frame_exr_path(scene))
    text = "; ".join(changes)
    sstest.check("inserted 'SoftShadow Darken' between Glare.Image and %s" % composite.name in text,
                 "says what changed: %s" % text)
    group = tree.nodes[ss.compositor.GROUP_NODE]
    sstest.check(group.inputs["Image"].links[0].from_node == glare, "the glare chain feeds the group")
    sstest.check(composite.inputs["Image"].links[0].from_node == group, "the group feeds the Composite")
    sstest.check(glare.inputs["Image"].links[0].from_node == layers, "Render Layers -> Glare kept")
    sstest.check(viewer.inputs["Image"].links[0].from_node == glare, "the Viewer link kept")
    sstest.check(len(tree.nodes) == 6, "four nodes of the artist's plus ours: %s" % [n.name for n in tree.nodes])
    again = ss.compositor.setup(scene, ss.api.frame_exr_path(scene))[1]
    sstest.check(not any(c.startswith("inserted") or c.startswith("added") for c in again),
                 "a second set-up changes nothing: %s" % again)
    scene.softshadow.strength = 0.25
    sstest.close(group.inputs["Strength"].default_value, 0.25, 1e-6, "Strength follows the slider")


def test_a_chosen_pass_that_is_gone_is_said_not_replaced():
    folder = sstest.tempdir("comp4")
    scene = sstest.standard_scene(32, 24)
    fill = sstest.add_light("Fill", location=(2, 2, 5), size=0.3)
    fill.data.softshadow.method = "shadow_map"
    scene.objects["Key"].data.softshadow.method = "shadow_map"
    scene.softshadow.output_path = os.path.join(folder, "softshadow_####.exr")
    bpy.ops.softshadow.setup_compositor()
    scene.softshadow.compositor_pass = "Fill_shadow_map"
    fill.data.softshadow.enabled = False
    path, problems, _ = ss.api.render_frame(scene)
    sstest.check(any("Fill_shadow_map" in p and "not in the pass file" in p for p in problems),
                 "the missing choice is reported: %s" % problems)
    group = ss.compat.compositor_tree(scene).nodes[ss.compositor.GROUP_NODE]
    linked = [l.from_socket.name for l in group.inputs["Visibility"].links]
    sstest.check("Key_shadow_map" not in linked, "no silent fall-back to another light: %s" % linked)


if __name__ == "__main__":
    sstest.run(dict(globals()))
