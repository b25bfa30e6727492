# Does compat.py pick the right API shape for Blender 3.x, 4.x and 5.x? (fake objects, no bpy needed)
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import sys
from types import SimpleNamespace as NS

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
compat = sstest.addon().compat


class FakeGroups:
    def __init__(self):
        self.made = []

    def new(self, name, kind):
        tree = NS(name=name, kind=kind)
        self.made.append(tree)
        return tree


def test_compositor_tree_3x_shape():
    tree = NS(name="Compositing")
    scene = NS(use_nodes=False, node_tree=tree)
    sstest.check(compat.compositor_tree(scene) is tree, "3.x: scene.node_tree is the tree")
    sstest.check(scene.use_nodes is False, "looking must not switch nodes on")
    sstest.check(compat.compositor_tree(scene, create=True) is tree, "3.x create returns node_tree")
    sstest.check(scene.use_nodes is True, "3.x create switches use_nodes on")


def test_compositor_tree_5x_shape():
    data = NS(node_groups=FakeGroups())
    scene = NS(compositing_node_group=None)
    sstest.check(compat.compositor_tree(scene) is None, "5.x: no group yet, no create -> None")
    tree = compat.compositor_tree(scene, create=True, bpy_data=data)
    sstest.check(tree is not None and tree.kind == "CompositorNodeTree", "5.x: a compositor group is made")
    sstest.check(scene.compositing_node_group is tree, "5.x: the group is assigned to the scene")
    sstest.check(compat.compositor_tree(scene, create=True, bpy_data=data) is tree, "made only once")
    sstest.check(len(data.node_groups.made) == 1, "no second group")


def test_bgl_only_before_4():
    sstest.check(compat.has_bgl(NS(version=(3, 4, 1))), "3.4 has bgl")
    sstest.check(not compat.has_bgl(NS(version=(4, 0, 0))), "4.0 has no bgl")
    sstest.check(not compat.has_bgl(NS(version=(5, 0, 0))), "5.0 has no bgl")


def test_light_radius_both_names():
    sstest.close(compat.light_radius(NS(shadow_soft_size=0.25)), 0.25, 0, "shadow_soft_size")
    sstest.close(compat.light_radius(NS(radius=0.5)), 0.5, 0, "radius")
    sstest.close(compat.light_radius(NS()), 0.0, 0, "neither")


def test_object_visibility_both_shapes():
    sstest.check(compat.object_casts_shadow(NS(visible_shadow=False)) is False, "3.0+ visible_shadow")
    legacy = NS(cycles_visibility=NS(shadow=False, camera=True))
    sstest.check(compat.object_casts_shadow(legacy) is False, "2.9x cycles_visibility.shadow")
    sstest.check(compat.object_camera_visible(legacy) is True, "2.9x cycles_visibility.camera")
    sstest.check(compat.object_camera_visible(NS(visible_camera=False)) is False, "3.0+ visible_camera")
    sstest.check(compat.object_casts_shadow(NS()) is True, "default casts")


def test_material_shadow_method():
    sstest.check(compat.materials_cast_shadow([]), "no material casts")
    sstest.check(not compat.materials_cast_shadow([NS(shadow_method="NONE")]), "all NONE -> no cast")
    sstest.check(compat.materials_cast_shadow([NS(shadow_method="NONE"), NS(shadow_method="HASHED")]),
                 "one casting material -> casts")
    sstest.check(compat.materials_cast_shadow([NS(), None]), "4.2+ materials without shadow_method cast")


def test_group_sockets_both_shapes():
    class Sockets(list):
        def new(self, kind, name):
            s = NS(name=name, kind=kind)
            self.append(s)
            return s

    old = NS(inputs=Sockets(), outputs=Sockets())
    compat.add_group_socket(old, "INPUT", "NodeSocketFloat", "Visibility")
    compat.add_group_socket(old, "OUTPUT", "NodeSocketColor", "Image")
    sstest.check(compat.group_sockets(old, "INPUT") == ["Visibility"], "3.x inputs")
    sstest.check(compat.group_sockets(old, "OUTPUT") == ["Image"], "3.x outputs")

    class Interface:
        def __init__(self):
            self.items_tree = []

        def new_socket(self, name, in_out, socket_type):
            item = NS(name=name, in_out=in_out, socket_type=socket_type, item_type="SOCKET")
            self.items_tree.append(item)
            return item

    new = NS(interface=Interface())
    compat.add_group_socket(new, "INPUT", "NodeSocketFloat", "Visibility")
    compat.add_group_socket(new, "OUTPUT", "NodeSocketColor", "Image")
    sstest.check(compat.group_sockets(new, "INPUT") == ["Visibility"], "4.x interface inputs")
    sstest.check(compat.group_sockets(new, "OUTPUT") == ["Image"], "4.x interface outputs")


def test_renderer_shadow_3x_cycles_and_4x_shared():
    light3 = NS(use_shadow=True, cycles=NS(cast_shadow=True))
    compat.set_renderer_shadow(light3, False)
    sstest.check(light3.cycles.cast_shadow is False and light3.use_shadow is True,
                 "3.x: Cycles' own cast_shadow off, EEVEE's use_shadow (our pass switch) kept")
    sstest.check(compat.renderer_shadow(light3) is False, "3.x read back")
    light4 = NS(use_shadow=True, cycles=NS())
    compat.set_renderer_shadow(light4, False)
    sstest.check(light4.use_shadow is False and compat.renderer_shadow(light4) is False, "4.0+: use_shadow")
    eevee3 = NS(use_shadow=True, cycles=NS(cast_shadow=True))
    compat.set_renderer_shadow(eevee3, False, engine="BLENDER_EEVEE")
    sstest.check(eevee3.use_shadow is False and eevee3.cycles.cast_shadow is True, "EEVEE: use_shadow always")


def test_this_blenders_shapes():
    # The real API of the Blender running the test (the version matrix runs it in each).
    import bpy
    scene = bpy.context.scene
    scene.render.engine = compat.eevee_engine_id(scene.render)
    sstest.check(scene.render.engine.startswith("BLENDER_EEVEE"), "EEVEE chosen: %s" % scene.render.engine)
    tree = compat.compositor_tree(scene, create=True, bpy_data=bpy.data)
    sstest.check(tree is not None and tree.bl_idname == "CompositorNodeTree", "a compositor tree")
    output, _ = compat.compositor_output(tree, bpy.types)
    again, created_again = compat.compositor_output(tree, bpy.types)
    sstest.check(again == output and not created_again, "one final output node")
    sstest.check("Image" in output.inputs, "the final output takes an Image")
    node, factor, a, b, result = compat.new_color_mix(tree.nodes, bpy.types, "MULTIPLY")
    sstest.check(node.blend_type == "MULTIPLY", "mix node blend type")
    sstest.check(a.type == "RGBA" and b.type == "RGBA" and result.type == "RGBA" and factor.type == "VALUE",
                 "colour sockets: %s %s %s %s" % (factor.type, a.type, b.type, result.type))
    light = bpy.data.lights.new("compat-light", "POINT")
    sstest.check(compat.light_radius(light) >= 0.0, "point light radius readable")
    bpy.data.lights.remove(light)


def _linking_collection(objects=(), children=()):
    """A 4.x linking collection: objects [(name, state)], children [(child collection, state)]."""
    return NS(objects=[NS(name=n) for n, _ in objects],
              collection_objects=[NS(light_linking=NS(link_state=s)) for _, s in objects],
              children=[c for c, _ in children],
              collection_children=[NS(light_linking=NS(link_state=s)) for _, s in children])


def test_light_links_3x_has_none():
    light = NS(name="Key", type="LIGHT")
    sstest.check(compat.light_links(light) == (None, None), "3.x: no light_linking, no links")


def test_light_links_4x_include_exclude_rules():
    props = NS(all_objects=[NS(name="Chair"), NS(name="Table")])
    only = _linking_collection([("Hero", "INCLUDE"), ("Table", "EXCLUDE")], [(props, "INCLUDE")])
    every_but = _linking_collection([("Wall", "EXCLUDE")])
    light = NS(light_linking=NS(receiver_collection=only, blocker_collection=every_but))
    receivers, blockers = compat.light_links(light)
    # The direct member's EXCLUDE wins over the child collection's INCLUDE.
    sstest.check(receivers[:2] == ("only", frozenset({"Hero", "Chair"})), "included minus excluded: %s" % (receivers,))
    sstest.check(receivers[2] == frozenset({"Hero", "Chair", "Table"}), "members: %s" % (receivers,))
    sstest.check(blockers[:2] == ("except", frozenset({"Wall"})), "only excluded: all but those: %s" % (blockers,))
    empty = NS(light_linking=NS(receiver_collection=_linking_collection(), blocker_collection=None))
    sstest.check(compat.light_links(empty) == (None, None), "an empty or unset collection: every object")
    objects = ["Ground", "Hero", "Wall", "Chair", "Hero"]
    sstest.check(compat.linked_meshes(receivers, objects) == [1, 3, 4], "meshes of included objects")
    sstest.check(compat.linked_meshes(blockers, objects) == [0, 1, 3, 4], "meshes but the excluded")
    sstest.check(compat.linked_meshes(None, objects) is None, "no set: every mesh")
    # An instance answers to its instancer when a collection of that kind names the instancer.
    meshes = [{"name": "Tree/Leaf", "object": "Leaf", "instancer": "Tree"},
              {"name": "Bush/Leaf", "object": "Leaf", "instancer": "Bush"}, {"name": "Rock", "object": "Rock"}]
    names = compat.link_objects(meshes, [("except", frozenset({"Tree"}), frozenset({"Tree"})), None])
    sstest.check(names == ["Tree", "Leaf", "Rock"], "instances' link objects: %s" % names)


if __name__ == "__main__":
    sstest.run(dict(globals()))
