# Do bad scenes give a report message, no pass for what failed, and every other pass?
# SPDX-License-Identifier: GPL-3.0-or-later
import math
import os
import sys

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
