# Does a moved object reach the library as its matrix alone, move the shadow, and leave the other
# meshes' GPU buffers in place?
# SPDX-License-Identifier: GPL-3.0-or-later
import collections
import contextlib
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402

ss = sstest.addon()
preview = sys.modules[ss.__name__ + ".preview"]
passes = sys.modules[ss.__name__ + ".passes"]
native = sys.modules[ss.__name__ + ".native"]
scene_export = sys.modules[ss.__name__ + ".scene_export"]
W, H = 64, 48

# How often each object's mesh is read from Blender (what an export reads): counted around the
# add-on's one mesh reader.
mesh_reads = collections.Counter()
_read_mesh = scene_export._local_mesh_arrays


def _counted_read(obj):
    mesh_reads[obj.original.name] += 1
    return _read_mesh(obj)


scene_export._local_mesh_arrays = _counted_read


def _scene():
    scene = sstest.standard_scene(W, H)
    sstest.add_box("Other", 0.6, (3.0, 3.0, 0.5))
    scene.objects["Key"].data.softshadow.method = "shadow_map"
    bpy.context.view_layer.update()
    return scene


@contextlib.contextmanager
def _preview_after_a_first_render(scene):
    """A kept preview scene that has rendered `scene` once: (live scene, depsgraph, camera)."""
    preview._state.full = True
    live = passes.LiveScene()
    try:
        depsgraph = bpy.context.evaluated_depsgraph_get()
        camera = scene_export.scene_camera(scene, depsgraph)
        preview._render_job(live, [preview.export_edit(depsgraph, scene)], camera, lambda: False)
        yield live, depsgraph, camera
    finally:
        live.close()


def _shadow_alpha(rgba, scene, point):
    """The overlay's opacity (shadow) at a world point; the overlay's rows start at the bottom."""
    row, col = sstest.pixel_of(scene, point)
    return float(rgba[H - 1 - row, col, 3])


def test_moving_one_object_sends_its_matrix_and_moves_the_shadow():
    scene = _scene()
    preview._state.full = True
    live = passes.LiveScene()
    try:
        depsgraph = bpy.context.evaluated_depsgraph_get()
        camera = scene_export.scene_camera(scene, depsgraph)
        first = preview.export_edit(depsgraph, scene)
        sstest.check(first is not None and first[0] == "full", "the first edit is a full export: %r" % (first,))
        before = preview._render_job(live, [first], camera, lambda: False)
        stats_before = native.cache_stats()

        scene.objects["Occluder"].location.x += 1.0  # its shadow moves from x = 2 to x = 4
        bpy.context.view_layer.update()  # runs depsgraph_update_post: the preview notes the move
        sstest.check(preview._state.changed == {"Occluder"},
                     "the update names the moved object alone: %s" % preview._state.changed)
        sstest.check(not preview._state.geometry, "a move is no geometry change: %s" % preview._state.geometry)
        edit = preview.export_edit(depsgraph, scene)
        sstest.check(edit[0] == "objects" and edit[2] == {"Occluder"}, "a partial edit: %r" % (edit[:1] + edit[2:],))
        sent = edit[1].meshes
        sstest.check(len(sent) == 1 and sent[0]["local"] is None and sent[0]["triangles"] is None,
                     "the moved object is exported as its matrix alone: %s" % [m["name"] for m in sent])
        after = preview._render_job(live, [edit], camera, lambda: False)
        stats_after = native.cache_stats()

        uploads = stats_after["mesh_uploads"] - stats_before["mesh_uploads"]
        sstest.check(uploads == 0, "no mesh uploaded after the move (its matrix is sent), got %d" % uploads)
        old, new = sstest.shadow_centre(-1.0), sstest.shadow_centre(0.0)
        sstest.check(_shadow_alpha(before, scene, old) > 0.5, "shadow at the old place before the move")
        sstest.check(_shadow_alpha(after, scene, old) < 0.05, "no shadow at the old place after the move: %.3f"
                     % _shadow_alpha(after, scene, old))
        sstest.check(_shadow_alpha(after, scene, new) > 0.5, "shadow at the new place after the move: %.3f"
                     % _shadow_alpha(after, scene, new))

        # The same as a scene built afresh with the object in its new place (the library moves
        # vertices in float32, the exporter in float64: a texel may flip at an edge).
        fresh = passes.LiveScene()
        preview._state.full = True
        rebuilt = preview._render_job(fresh, [preview.export_edit(depsgraph, scene)], camera, lambda: False)
        fresh.close()
        differ = np.mean(np.abs(rebuilt[..., 3] - after[..., 3]) > 1e-4)
        sstest.check(differ < 0.01, "incremental and fresh previews differ on %.4f of the pixels" % differ)
    finally:
        live.close()


def test_a_renamed_object_is_not_drawn_twice():
    scene = _scene()
    with _preview_after_a_first_render(scene) as (live, depsgraph, camera):
        scene.objects["Occluder"].name = "Plate"
        bpy.context.view_layer.update()
        edit = preview.export_edit(depsgraph, scene)
        sstest.check(edit[0] == "full", "a rename exports the scene whole: %s" % edit[0])
        preview._render_job(live, [edit], camera, lambda: False)
        names = sorted(m["name"] for m in live.meshes)
        sstest.check(names == ["Ground", "Other", "Plate"], "meshes after the rename: %s" % names)
        sstest.check(live.scene.mesh_count() == 3, "the library has 3 meshes: %d" % live.scene.mesh_count())


def test_render_passes_sends_only_the_moved_matrix():
    scene = _scene()
    first = ss.render_passes(scene, methods=["shadow_map"])[("Key", "shadow_map")]
    stats = native.cache_stats()
    again = ss.render_passes(scene, methods=["shadow_map"])[("Key", "shadow_map")]
    unchanged = native.cache_stats()
    sstest.check(unchanged["mesh_uploads"] == stats["mesh_uploads"], "an unchanged scene uploads nothing")
    sstest.check(unchanged["shadow_maps"] == stats["shadow_maps"], "an unchanged scene draws no shadow map")
    sstest.check(np.array_equal(first, again), "an unchanged scene renders the same")

    scene.objects["Occluder"].location.x += 1.0
    bpy.context.view_layer.update()
    reads = mesh_reads.copy()
    moved = ss.render_passes(scene, methods=["shadow_map"])[("Key", "shadow_map")]
    after = native.cache_stats()
    read = mesh_reads - reads
    sstest.check(not read, "a move reads no mesh from Blender, read %s" % dict(read))
    uploads = after["mesh_uploads"] - unchanged["mesh_uploads"]
    sstest.check(uploads == 0, "a move uploads no mesh (the matrix is sent), got %d" % uploads)
    sstest.check(after["shadow_maps"] == unchanged["shadow_maps"] + 1, "the light's map is redrawn once")
    row, col = sstest.pixel_of(scene, sstest.shadow_centre(0.0))
    sstest.check(moved[row, col] < 0.05, "the shadow moved with the object: V=%.3f" % moved[row, col])

    # Exactly what a freshly built scene gives.
    depsgraph = bpy.context.evaluated_depsgraph_get()
    exported = scene_export.export(depsgraph, scene)
    fresh = passes.LiveScene()
    try:
        result = passes.compute(exported, methods=["shadow_map"], live=fresh)
    finally:
        fresh.close()
    sstest.check(np.array_equal(result.arrays[("Key", "shadow_map")], moved),
                 "the updated scene renders exactly as a fresh one")


def _matches_a_fresh_export(scene, arrays, what):
    """render_passes' arrays are exactly those of a scene exported whole and built afresh."""
    exported = scene_export.export(bpy.context.evaluated_depsgraph_get(), scene)
    fresh = passes.LiveScene()
    try:
        result = passes.compute(exported, methods=["shadow_map"], live=fresh)
    finally:
        fresh.close()
    sstest.check(np.array_equal(result.arrays[("Key", "shadow_map")], arrays[("Key", "shadow_map")]),
                 "%s: render_passes renders exactly as a fresh export" % what)


def _animated_scene():
    """The plate slides +1 along x from frame 1 to 2 by a shape key; "Other" grows by an animated
    Displace modifier, "Driven" by a Displace whose strength a driver takes from the frame;
    "Still" has none of these."""
    scene = _scene()
    plate = scene.objects["Occluder"]
    plate.shape_key_add(name="Basis")
    slid = plate.shape_key_add(name="Slid")
    for point in slid.data:
        point.co.x += 1.0
    slid.value = 0.0
    slid.keyframe_insert("value", frame=1)
    slid.value = 1.0
    slid.keyframe_insert("value", frame=2)
    grow = scene.objects["Other"].modifiers.new("Grow", "DISPLACE")
    grow.strength = 0.0
    grow.keyframe_insert("strength", frame=1)
    grow.strength = 0.3
    grow.keyframe_insert("strength", frame=2)
    driven = sstest.add_box("Driven", 0.5, (-3.0, 2.5, 0.5))
    curve = driven.modifiers.new("Swell", "DISPLACE").driver_add("strength")
    curve.driver.expression = "frame * 0.1"
    sstest.add_box("Still", 0.5, (-3.0, -2.5, 0.5))
    scene.frame_set(1)
    return scene


def test_render_passes_reads_again_only_the_meshes_a_frame_change_animates():
    scene = _animated_scene()
    ss.render_passes(scene, methods=["shadow_map"])
    reads = mesh_reads.copy()
    again = ss.render_passes(scene, methods=["shadow_map"])
    read = mesh_reads - reads
    sstest.check(not read, "nothing changed: no mesh read, read %s" % dict(read))
    _matches_a_fresh_export(scene, again, "frame 1")

    scene.frame_set(2)
    reads = mesh_reads.copy()
    arrays = ss.render_passes(scene, methods=["shadow_map"])
    read = mesh_reads - reads
    sstest.check(set(read) == {"Occluder", "Other", "Driven"},
                 "the shape key's, the animated modifier's and the driven modifier's meshes are read again, "
                 "the ground's and the still box's are not: %s" % dict(read))
    row, col = sstest.pixel_of(scene, sstest.shadow_centre(0.0))
    sstest.check(arrays[("Key", "shadow_map")][row, col] < 0.05, "the shadow followed the shape key")
    _matches_a_fresh_export(scene, arrays, "frame 2")


def test_the_preview_follows_a_frame_change_and_reads_only_the_animated_meshes():
    scene = _animated_scene()
    with _preview_after_a_first_render(scene) as (live, depsgraph, camera):
        scene.frame_set(2)
        sstest.check({"Occluder", "Other", "Driven"} <= preview._state.geometry,
                     "the frame change's geometry updates are noted: %s" % preview._state.geometry)
        sstest.check("Still" not in preview._state.changed and "Ground" not in preview._state.changed,
                     "the still meshes are not: %s" % preview._state.changed)
        reads = mesh_reads.copy()
        edit = preview.export_edit(depsgraph, scene)
        read = mesh_reads - reads
        sstest.check(edit[0] == "objects" and set(read) == {"Occluder", "Other", "Driven"},
                     "a partial edit reading the animated meshes: %s %s" % (edit[0], dict(read)))
        rgba = preview._render_job(live, [edit], camera, lambda: False)
        sstest.check(_shadow_alpha(rgba, scene, sstest.shadow_centre(0.0)) > 0.5, "the shadow followed the frame")
        sstest.check(_shadow_alpha(rgba, scene, sstest.shadow_centre(-1.0)) < 0.05, "and left its old place")


def test_a_frame_change_handler_that_edits_a_mesh_makes_render_passes_read_every_mesh():
    scene = _animated_scene()
    ss.render_passes(scene, methods=["shadow_map"])
    still = scene.objects["Still"].data

    # Blender evaluates what frame_change_post handlers change without reporting it.
    def edit(scene, *_args):
        for vertex in still.vertices:
            vertex.co.z += 2.0
        still.update()
    bpy.app.handlers.frame_change_post.append(edit)
    try:
        scene.frame_set(2)
    finally:
        bpy.app.handlers.frame_change_post.remove(edit)
    reads = mesh_reads.copy()
    arrays = ss.render_passes(scene, methods=["shadow_map"])
    read = mesh_reads - reads
    sstest.check(set(read) == {"Ground", "Occluder", "Other", "Driven", "Still"},
                 "every mesh is read again: %s" % dict(read))
    _matches_a_fresh_export(scene, arrays, "after the handler's edit")


def test_an_object_hidden_in_the_viewport_is_read_at_every_call():
    scene = _scene()
    scene.objects["Other"].hide_set(True)  # the viewport's depsgraph leaves it out: no update vouches for it
    bpy.context.view_layer.update()
    ss.render_passes(scene, methods=["shadow_map"])
    reads = mesh_reads.copy()
    arrays = ss.render_passes(scene, methods=["shadow_map"])
    read = mesh_reads - reads
    sstest.check(set(read) == {"Other"}, "the hidden object alone is read again: %s" % dict(read))
    _matches_a_fresh_export(scene, arrays, "with a hidden object")


def test_a_scene_rebuilt_with_the_same_names_is_read_again():
    scene = _scene()
    ss.render_passes(scene, methods=["shadow_map"])
    scene = _scene()  # every object and mesh removed and made again under its old name
    for vertex in scene.objects["Occluder"].data.vertices:
        vertex.co.x += 1.0
    scene.objects["Occluder"].data.update()
    bpy.context.view_layer.update()
    reads = mesh_reads.copy()
    arrays = ss.render_passes(scene, methods=["shadow_map"])
    read = mesh_reads - reads
    sstest.check(set(read) == {"Ground", "Occluder", "Other"}, "every mesh read: %s" % dict(read))
    _matches_a_fresh_export(scene, arrays, "the rebuilt scene")


def test_an_object_the_library_refuses_does_not_rebuild_the_scene_at_each_sync():
    scene = _scene()
    sstest.add_light("evil\u202etxt", location=(1, 1, 6)).data.softshadow.method = "shadow_map"
    sstest.add_box("bad\u202ebox", 0.3, (-2.0, -2.0, 0.3))
    bpy.context.view_layer.update()
    live = passes.LiveScene()
    try:
        depsgraph = bpy.context.evaluated_depsgraph_get()
        live.sync(scene_export.export(depsgraph, scene))
        refused = sorted(live.refused)
        sstest.check(refused == ["bad\u202ebox", "evil\u202etxt"], "both refused: %s" % refused)
        sstest.check(len(live.problems) == 2, "one problem each: %s" % live.problems)
        kept = live.scene
        live.sync(scene_export.export(depsgraph, scene))
        sstest.check(live.scene is kept, "an unchanged refusal leaves the scene as it was (no rebuild)")
        sstest.check(len(live.problems) == 2, "the problems stay, once each: %s" % live.problems)

        scene.objects["Occluder"].location.x += 0.5
        bpy.context.view_layer.update()
        live.sync(scene_export.export(bpy.context.evaluated_depsgraph_get(), scene))
        sstest.check(live.scene is kept, "an edit of another object is sent, not rebuilt")

        scene.objects["bad\u202ebox"].name = "good box"  # the library takes it now
        bpy.context.view_layer.update()
        live.sync(scene_export.export(bpy.context.evaluated_depsgraph_get(), scene))
        sstest.check("good box" in [m["name"] for m in live.meshes] and sorted(live.refused) == ["evil\u202etxt"],
                     "the renamed object is sent: %s / %s" % ([m["name"] for m in live.meshes], sorted(live.refused)))
        sstest.check(len(live.problems) == 1 and "evil" in live.problems[0], "its problem is gone: %s" % live.problems)
    finally:
        live.close()


sstest.run(globals())
