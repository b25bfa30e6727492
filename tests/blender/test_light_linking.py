# Do Blender 4.0+'s light and shadow links reach every method, and match Cycles' shadow ratio?
# SPDX-License-Identifier: GPL-3.0-or-later
"""Blender 3.x has no light linking: there the tests check that nothing is sent and say so."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402

ss = sstest.addon()
W, H = 64, 48
HAS_LINKING = hasattr(bpy.types, "ObjectLightLinking") or "light_linking" in bpy.types.Object.bl_rna.properties
UNDER = sstest.shadow_centre(-1.0)  # the plate's shadow: every light sample blocked
GL_METHODS = ["shadow_map", "pcss", "dbuffer", "sweep", "penumbra_map", "occlusion_textures"]
# Cycles at this many samples leaves the shadow ratio's own noise well under the bound.
CYCLES_SAMPLES = 256
CYCLES_BOUND = 0.015


def _no_linking_here(what):
    if HAS_LINKING:
        return False
    print("  note: Blender %s has no light linking (4.0+), so this is not tested here: %s"
          % (bpy.app.version_string, what))
    return True


# The post: a box beside the plate's shadow (its own shadow falls apart), or a tile (no side a
# pixel centre could graze) across the edge of the plate's shadow, in Key's umbra and penumbra.
BESIDE, SHADOWED = (sstest.add_box, 0.6, (1.0, -2.0, 0.8)), (sstest.add_plane, 1.0, (1.5, 0.0, 1.3))


def _scene(post=BESIDE):
    """The standard scene with a second light, Fill, where Key is (so each has the plate's
    shadow under it) and a post."""
    scene = sstest.standard_scene(W, H)
    sstest.add_light("Fill", location=(-4, 0, 6), size=0.5)
    make, size, location = post
    make("Post", size, location)
    for name in ("Key", "Fill"):
        scene.objects[name].data.softshadow.samples = 64
    bpy.context.view_layer.update()
    return scene


def _link_collection(name, members, children=()):
    """A linking collection: members [(object, 'INCLUDE'|'EXCLUDE')], children [(collection, state)]."""
    collection = bpy.data.collections.new(name)
    for obj, _ in members:
        collection.objects.link(obj)
    for child, _ in children:
        collection.children.link(child)
    for i, (_, state) in enumerate(members):
        collection.collection_objects[i].light_linking.link_state = state
    for i, (_, state) in enumerate(children):
        collection.collection_children[i].light_linking.link_state = state
    return collection


def _native_links(scene):
    """{light name: (blockers, receivers) as mesh names} of the scene the add-on sends."""
    graph = bpy.context.evaluated_depsgraph_get()
    exported = ss.scene_export.export(graph, scene, mode="RENDER")
    live = ss.passes.LiveScene()
    try:
        live.rebuild(exported)
        names = [m["name"] for m in live.meshes]
        out = {}
        for light, index in live.light_indices().items():
            blockers, receivers = live.scene.light_links(index)
            out[light] = tuple(None if s is None else sorted(names[i] for i in s) for s in (blockers, receivers))
        return out
    finally:
        live.close()


def test_without_collections_nothing_is_linked():
    scene = _scene()
    links = _native_links(scene)
    sstest.check(links == {"Key": (None, None), "Fill": (None, None)}, "links: %s" % links)
    if not HAS_LINKING:
        print("  note: Blender %s has no light linking (4.0+): every light lights and is shadowed by every mesh"
              % bpy.app.version_string)


def test_collections_resolve_as_blender_does():
    if _no_linking_here("resolving linking collections"):
        return
    scene = _scene()
    ground, plate, post = (scene.objects[n] for n in ("Ground", "Occluder", "Post"))
    # Only excluded members: every other object blocks.
    scene.objects["Key"].light_linking.blocker_collection = _link_collection("NoPlate", [(plate, "EXCLUDE")])
    # An included child collection holding the post and the plate, the plate excluded directly: only the post.
    child = bpy.data.collections.new("Props")
    child.objects.link(post)
    child.objects.link(plate)
    scene.objects["Fill"].light_linking.receiver_collection = _link_collection(
        "PostOnly", [(plate, "EXCLUDE")], [(child, "INCLUDE")])
    bpy.context.view_layer.update()
    links = _native_links(scene)
    sstest.check(links["Key"] == (["Ground", "Post"], None), "Key: %s" % (links["Key"],))
    sstest.check(links["Fill"] == (None, ["Post"]), "Fill: %s" % (links["Fill"],))
    # An empty collection links nothing away.
    scene.objects["Key"].light_linking.blocker_collection = bpy.data.collections.new("Empty")
    bpy.context.view_layer.update()
    sstest.check(_native_links(scene)["Key"] == (None, None), "an empty collection: every mesh")


def test_an_instance_answers_to_its_instancer():
    """As in Cycles: a collection instance takes the links of the object that instances it
    when a linking collection names that object."""
    if _no_linking_here("links of instances"):
        return
    scene = _scene()
    props = bpy.data.collections.new("Props")
    prop = bpy.data.objects.new("Prop", scene.objects["Occluder"].data.copy())
    props.objects.link(prop)
    spawner = bpy.data.objects.new("Spawner", None)
    spawner.instance_type = "COLLECTION"
    spawner.instance_collection = props
    spawner.location = (2.0, 2.0, 1.0)
    scene.collection.objects.link(spawner)
    scene.objects["Key"].light_linking.blocker_collection = _link_collection("NoSpawner", [(spawner, "EXCLUDE")])
    bpy.context.view_layer.update()
    exported = ss.scene_export.export(bpy.context.evaluated_depsgraph_get(), scene, mode="RENDER")
    names = [m["name"] for m in exported.meshes]
    sstest.check("Spawner/Prop" in names, "the instance is exported: %s" % names)
    links = _native_links(scene)
    sstest.check(links["Key"] == (["Ground", "Occluder", "Post"], None), "Key: %s" % (links["Key"],))
    sstest.check(links["Fill"] == (None, None), "Fill: %s" % (links["Fill"],))


def test_the_live_scene_follows_link_edits():
    """The preview's scene, kept across edits, gets a light's links as they change."""
    if _no_linking_here("link edits in the live scene"):
        return
    scene = _scene()
    live = ss.passes.LiveScene()

    def sync():
        graph = bpy.context.evaluated_depsgraph_get()
        live.sync(ss.scene_export.export(graph, scene, mode="RENDER"))
        names = [m["name"] for m in live.meshes]
        blockers, receivers = live.scene.light_links(live.light_indices()["Key"])
        return None if blockers is None else sorted(names[i] for i in blockers), receivers
    try:
        sstest.check(sync() == (None, None), "no links at first")
        key, plate = scene.objects["Key"], scene.objects["Occluder"]
        key.light_linking.blocker_collection = _link_collection("NoPlate", [(plate, "EXCLUDE")])
        bpy.context.view_layer.update()
        sstest.check(sync() == (["Ground", "Post"], None), "the blocker collection arrives")
        key.light_linking.blocker_collection = None
        bpy.context.view_layer.update()
        sstest.check(sync() == (None, None), "and goes")
    finally:
        live.close()


def test_a_shadow_linked_blocker_shadows_only_the_other_light():
    if _no_linking_here("shadow linking"):
        return
    scene = _scene()
    plate = scene.objects["Occluder"]
    scene.objects["Key"].light_linking.blocker_collection = _link_collection("NoPlate", [(plate, "EXCLUDE")])
    bpy.context.view_layer.update()
    result = ss.render_passes(scene, methods=GL_METHODS + ["reference"])
    under = sstest.pixel_of(scene, UNDER)
    for method in GL_METHODS + ["reference"]:
        key, fill = result[("Key", method)], result[("Fill", method)]
        sstest.check(key[under] > 0.98, "%s: Key under the excluded plate V=%.3f, want lit" % (method, key[under]))
        sstest.check(fill[under] < 0.05, "%s: Fill under the plate V=%.3f, want its shadow" % (method, fill[under]))


def test_a_light_linked_receiver_gets_no_shadow_of_that_light():
    if _no_linking_here("light linking"):
        return
    scene = _scene()
    plate, post = scene.objects["Occluder"], scene.objects["Post"]
    linked = [(plate, "INCLUDE"), (post, "INCLUDE")]
    scene.objects["Key"].light_linking.receiver_collection = _link_collection("NoGround", linked)
    bpy.context.view_layer.update()
    result = ss.render_passes(scene, methods=GL_METHODS + ["reference"])
    under = sstest.pixel_of(scene, UNDER)
    for method in GL_METHODS + ["reference"]:
        if ("Key", method) not in result:  # sweep: Key lights no planar receiver here
            sstest.check(method == "sweep", "%s made no pass for Key: %s" % (method, ss.render_passes.last_problems))
            continue
        key, fill = result[("Key", method)], result[("Fill", method)]
        sstest.check(key[under] == 1.0, "%s: Key does not light the ground: V=%.3f, want 1" % (method, key[under]))
        sstest.check(fill[under] < 0.05, "%s: Fill still shadows the ground: V=%.3f" % (method, fill[under]))


# ---------------------------------------------------------------- against Cycles

def _diffuse_direct(scene, folder, name):
    """Cycles' Diffuse Direct luminance, (H, W) row 0 = top."""
    compat = ss.compat
    tree = compat.compositor_tree(scene, create=True, bpy_data=bpy.data)
    tree.nodes.clear()
    layers = tree.nodes.new("CompositorNodeRLayers")
    output, _ = compat.compositor_output(tree, bpy.types)
    socket = next(s for s in layers.outputs if s.name in ("DiffDir", "Diffuse Direct"))
    tree.links.new(socket, output.inputs["Image"])
    bpy.ops.render.render(write_still=False)
    path = os.path.join(folder, name + ".exr")
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_depth = "32"
    bpy.data.images["Render Result"].save_render(path, scene=scene)
    image = bpy.data.images.load(path)
    w, h = image.size
    pixels = np.empty(w * h * image.channels, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    return pixels.reshape(h, w, -1)[::-1, :, :3].mean(axis=2)


def _cycles_ratio(scene, light_name, folder):
    """The contract from Cycles: V = E(shadows) / E(no shadows) for one light alone, 1 where it
    sends nothing (a receiver it does not light)."""
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = CYCLES_SAMPLES
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.max_bounces = 0
    c.seed = 1
    c.filter_width = 0.01
    # A black world: only the light reaches Diffuse Direct (5.x worlds shade with nodes).
    world = bpy.data.worlds.new("Black")
    world.color = (0.0, 0.0, 0.0)
    for node in (world.node_tree.nodes if world.node_tree is not None else ()):
        if node.type == "BACKGROUND":
            node.inputs["Strength"].default_value = 0.0
    scene.world = world
    scene.view_layers[0].use_pass_diffuse_direct = True
    lights = [o for o in scene.objects if o.type == "LIGHT"]
    for obj in lights:
        obj.hide_render = obj.name != light_name
    light = scene.objects[light_name].data

    def shadows(on):
        light.use_shadow = on
        if hasattr(light, "cycles") and hasattr(light.cycles, "cast_shadow"):
            light.cycles.cast_shadow = on
    shadows(False)
    unshadowed = _diffuse_direct(scene, folder, "unshadowed")
    shadows(True)
    shadowed = _diffuse_direct(scene, folder, "shadowed")
    for obj in lights:
        obj.hide_render = False
    reach = unshadowed > 1e-6 * max(float(unshadowed.max()), 1e-30)
    v = np.ones_like(shadowed)
    v[reach] = np.clip(shadowed[reach] / unshadowed[reach], 0.0, 1.0)
    return v


def _final_key_pass(scene):
    """Key's final pass (what F12 composites: its method with Refine Final Renders)."""
    result = ss.render_passes(scene, lights="Key")
    (name, _method), = result.keys()
    return result[(name, _method)]


def _rmse(a, b):
    return float(np.sqrt(np.mean((a - b) ** 2)))


def _check_against_cycles(scene, what, unlink):
    """Key's final pass against Cycles' ratio within the bound; the pass made with the link
    taken away (`unlink()`) is far from it, so the link is what the bound measures."""
    folder = sstest.tempdir("linking")
    ours = _final_key_pass(scene)
    cycles = _cycles_ratio(scene, "Key", folder)
    rmse = _rmse(ours, cycles)
    unlink()
    bpy.context.view_layer.update()
    unlinked = _rmse(_final_key_pass(scene), cycles)
    print("  %s: final pass vs Cycles-%d shadow ratio: RMSE %.4f (bound %.3f; %.4f without the link)"
          % (what, CYCLES_SAMPLES, rmse, CYCLES_BOUND, unlinked))
    sstest.check(rmse <= CYCLES_BOUND, "%s: RMSE %.4f against Cycles > %.3f" % (what, rmse, CYCLES_BOUND))
    sstest.check(unlinked > 4 * CYCLES_BOUND,
                 "%s: without the link RMSE %.4f: the case tests nothing" % (what, unlinked))
    return ours, cycles


def test_shadow_linked_blocker_matches_cycles():
    if _no_linking_here("the comparison with Cycles' shadow linking"):
        return
    scene = _scene()
    plate = scene.objects["Occluder"]
    scene.objects["Key"].light_linking.blocker_collection = _link_collection("NoPlate", [(plate, "EXCLUDE")])
    bpy.context.view_layer.update()
    key = scene.objects["Key"]
    ours, cycles = _check_against_cycles(scene, "shadow-linked plate",
                                         lambda: setattr(key.light_linking, "blocker_collection", None))
    under = sstest.pixel_of(scene, UNDER)
    sstest.check(cycles[under] > 0.98 and ours[under] > 0.98, "no plate shadow: ours %.3f, Cycles %.3f"
                 % (ours[under], cycles[under]))
    sstest.check((cycles < 0.5).sum() > 20, "the post's shadow is there to compare")


def test_light_linked_receiver_matches_cycles():
    if _no_linking_here("the comparison with Cycles' light linking"):
        return
    scene = _scene(SHADOWED)
    plate, post = scene.objects["Occluder"], scene.objects["Post"]
    # Key lights the plate and the post (in the plate's shadow), not the ground.
    key = scene.objects["Key"]
    key.light_linking.receiver_collection = _link_collection("NoGround", [(plate, "INCLUDE"), (post, "INCLUDE")])
    bpy.context.view_layer.update()
    ours, cycles = _check_against_cycles(scene, "light-linked receivers",
                                         lambda: setattr(key.light_linking, "receiver_collection", None))
    penumbra = int(((cycles > 0.05) & (cycles < 0.95)).sum())
    sstest.check((cycles < 0.5).sum() > 20 and penumbra >= 3, "the tile's umbra and penumbra are there to compare:"
                 " %d dark pixels, %d in the penumbra" % ((cycles < 0.5).sum(), penumbra))


sstest.run(dict(globals()))
