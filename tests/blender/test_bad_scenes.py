# Do bad scenes give a report message, no pass for what failed, and every other pass?
# SPDX-License-Identifier: GPL-3.0-or-later
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402

ss = sstest.addon()


def _bad_scene(folder):
    scene = sstest.standard_scene(32, 24)
    scene.objects["Key"].data.softshadow.method = "shadow_map"
    scene.softshadow.output_path = os.path.join(folder, "softshadow_####.exr")
    nan = sstest.add_box("NaNBox", 0.5, (2, 2, 1))
    nan.data.vertices[0].co = (math.nan, 0.0, 0.0)
    sstest.add_plane("NoFaces", 1.0, (0, 2, 1), faces=False)
    zero = sstest.add_light("ZeroLight", location=(1, 1, 5), size=0.5)
    zero.data.size = 0.0
    zero.data.softshadow.method = "shadow_map"
    bpy.context.view_layer.update()
    return scene


def test_bad_objects_and_light_reported_rest_produced():
    folder = sstest.tempdir("bad")
    scene = _bad_scene(folder)
    path, problems, _ = ss.api.render_frame(scene)
    text = "\n".join(problems)
    sstest.check("NaNBox" in text and "not finite" in text, "NaN object reported: %s" % problems)
    sstest.check("NoFaces" in text and "no faces" in text, "faceless mesh reported: %s" % problems)
    sstest.check("ZeroLight" in text, "zero-size light reported: %s" % problems)
    sstest.check(path and os.path.exists(path), "the good light's pass is still written")
    channels = sstest.exr_channels(path)
    sstest.check("ViewLayer.Key_shadow_map.V" in channels and all(".Key_shadow_map" in c for c in channels),
                 "only the good light's passes: %s" % channels)
    arrays = ss.render_passes(scene)
    sstest.check(list(arrays) == [("Key", "shadow_map")], "API: only the good pass: %s" % list(arrays))
    sstest.check(any("ZeroLight" in p for p in ss.render_passes.last_problems), "API keeps the problems")


def test_the_library_refuses_bad_meshes_and_lights_naming_them():
    """LiveScene sends every exported object; the library's refusals name the object and say why."""
    verts = np.zeros((3, 3), np.float32)
    verts[1, 0] = verts[2, 1] = 1.0
    tris = np.array([[0, 1, 2]], np.uint32)
    bad = verts.copy()
    bad[1, 2] = np.nan
    eye = ss.scene_export.column_major(np.eye(4))
    nan_matrix = list(eye)
    nan_matrix[12] = float("nan")
    meshes = [{"name": "Good", "local": verts, "triangles": tris, "flags": 3, "matrix": eye},
              {"name": "NaNVertex", "local": bad, "triangles": tris, "flags": 3, "matrix": eye},
              {"name": "BadIndex", "local": verts, "triangles": np.array([[0, 1, 3]], np.uint32), "flags": 3,
               "matrix": eye},
              {"name": "NaNMatrix", "local": verts, "triangles": tris, "flags": 3, "matrix": nan_matrix}]
    lights = [ss.scene_export.light_values("Zero", "AREA", "SQUARE", np.eye(4), size=0.0),
              ss.scene_export.light_values("NaNSize", "POINT", "", np.eye(4), radius=float("nan")),
              ss.scene_export.light_values("Key", "AREA", "SQUARE", np.eye(4), size=1.0)]
    live = ss.passes.LiveScene()
    try:
        live.rebuild(ss.scene_export.ExportedScene(meshes=meshes, lights=lights))
        text = "\n".join(live.problems)
        sstest.check([m["name"] for m in live.meshes] == ["Good"] and list(live.light_indices()) == ["Key"],
                     "only the good ones sent: %s %s" % ([m["name"] for m in live.meshes], live.light_indices()))
        for name, why in (("NaNVertex", "not finite"), ("BadIndex", "vertex index 3"),
                          ("NaNMatrix", "transform is not finite"), ("Zero", "size greater than zero"),
                          ("NaNSize", "not finite")):
            line = next((p for p in live.problems if "'%s'" % name in p), "")
            sstest.check(why in line, "%s: %r in %s" % (name, why, text))
        sstest.check(len(live.problems) == 5, "one line each: %s" % text)
        # An edit the library refuses (the good light made zero-size, the good mesh moved to NaN)
        # removes that object with its message; the rest stays.
        edited = [dict(lights[2], size=0.0, size_y=0.0)]
        live.apply(ss.scene_export.ExportedScene(meshes=[dict(meshes[0], matrix=nan_matrix)], lights=edited),
                   ["Key", "Good"])
        sstest.check(live.meshes == [] and live.light_indices() == {}, "both edits refused")
        sstest.check(any("'Key'" in p and "size greater than zero" in p for p in live.problems)
                     and any("'Good'" in p and "transform is not finite" in p for p in live.problems),
                     "the edits' refusals named: %s" % live.problems)
        live.sync(ss.scene_export.ExportedScene(meshes=meshes, lights=lights))
        sstest.check([m["name"] for m in live.meshes] == ["Good"] and list(live.light_indices()) == ["Key"],
                     "sent again once they are good")
        # The same edit in a full sync: the scene is rebuilt around the refusal.
        live.sync(ss.scene_export.ExportedScene(meshes=meshes, lights=lights[:2] + edited))
        sstest.check(live.light_indices() == {} and "Key" in live.refused, "the sync's edit refused")
    finally:
        live.close()


def test_operator_reports_instead_of_raising():
    folder = sstest.tempdir("bad-op")
    _bad_scene(folder)
    # In background mode a WARNING report is printed; the operator still finishes.
    result = bpy.ops.softshadow.render_passes()
    sstest.check(result == {"FINISHED"}, "finishes with warnings: %s" % result)


def test_no_camera():
    folder = sstest.tempdir("nocam")
    scene = _bad_scene(folder)
    scene.camera = None
    path, problems, _ = ss.api.render_frame(scene)
    sstest.check(path == "" and any("no camera" in p for p in problems), "no camera reported: %s" % problems)
    sstest.check(os.listdir(folder) == [], "nothing written: %s" % os.listdir(folder))
    try:
        bpy.ops.softshadow.render_passes()
        sstest.check(False, "the operator must report an error")
    except RuntimeError as exc:
        sstest.check("no pass" in str(exc) or "camera" in str(exc), "error report: %s" % exc)
    scene.softshadow.enabled = True
    scene.softshadow.on_failure = "CONTINUE"  # (STOP would end this test's Blender)
    ss.handlers.on_render_pre(scene)  # the render handler must not raise either
    sstest.check(any("camera" in p for p in ss.handlers.last_report["problems"]), "handler stored the problem")


if __name__ == "__main__":
    sstest.run(dict(globals()))
