# Does `blender -b file.blend --addons softshadow -a` deliver per-frame passes that move with the
# occluder, and a composited output darkened where the pass is dark?
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402

ss = sstest.addon()
W, H = 64, 48
XS = (-3.0, -2.0, -1.0)  # the occluder's x on frames 1, 2, 3 (its shadow: -2, 0, 2)


def _make_blend(folder):
    scene = sstest.standard_scene(W, H)
    scene.objects["Key"].data.softshadow.method = "shadow_map"
    scene.softshadow.enabled = True
    box = scene.objects["Occluder"]
    for frame, x in enumerate(XS, start=1):
        box.location.x = x
        box.keyframe_insert("location", index=0, frame=frame)
    scene.frame_start, scene.frame_end = 1, len(XS)
    sstest.flat_white_workbench(scene)
    scene.render.filepath = os.path.join(folder, "render_####")
    scene.softshadow.output_path = os.path.join(os.path.join(folder, "passes"), "softshadow_####.exr")
    sstest.check(bpy.ops.softshadow.setup_compositor() == {"FINISHED"}, "compositor set up")
    path = os.path.join(folder, "anim.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    return scene, path


def test_three_frame_animation_render():
    folder = sstest.tempdir("anim")
    scene, blend = _make_blend(folder)
    run = sstest.blender_batch(folder, blend, ["-a"])
    log = run.log
    sstest.check(run.returncode == 0, "blender -a failed:\n%s" % log[-3000:])
    sstest.check(not sstest.our_tracebacks(log), "no traceback of ours:\n%s" % log[-3000:])
    centres, composite_ratio = [], []
    for frame, x in enumerate(XS, start=1):
        exr = os.path.join(folder, "passes", "softshadow_%04d.exr" % frame)
        png = os.path.join(folder, "render_%04d.png" % frame)
        sstest.check(os.path.exists(exr), "frame %d EXR written:\n%s" % (frame, log[-2000:]))
        sstest.check(os.path.exists(png), "frame %d render written" % frame)
        v = sstest.exr_channel(exr, "ViewLayer.Key_shadow_map.V")
        sstest.check(v.shape == (H, W), "frame %d pass shape %s" % (frame, v.shape))
        dark = v < 0.05
        sstest.check(dark.sum() > 4, "frame %d has a shadow (%d dark pixels)" % (frame, dark.sum()))
        cols = np.nonzero(dark)[1]
        centres.append(cols.mean())
        # Where the geometry puts the shadow's centre at this frame.
        expect = sstest.pixel_of(scene, sstest.shadow_centre(x))
        sstest.check(v[expect] < 0.05, "frame %d: dark where the geometry puts the shadow %s (V=%.3f)"
                     % (frame, expect, v[expect]))
        picture = sstest.png_gray(png)
        lit = (v > 0.95) & (picture > 0.5)
        sstest.check(lit.sum() > 50, "frame %d: lit ground visible" % frame)
        ratio = picture[dark].mean() / picture[lit].mean()
        composite_ratio.append(ratio)
        # The darken group multiplies by V (strength 1): under the umbra the output is ~black.
        sstest.check(ratio < 0.1, "frame %d: composited output darker under the pass (ratio %.3f)" % (frame, ratio))
    sstest.check(centres[0] < centres[1] < centres[2], "the shadow moves left to right: %s" % centres)
    print("   shadow centre columns", ["%.1f" % c for c in centres], "dark/lit", ["%.3f" % r for r in composite_ratio])


if __name__ == "__main__":
    sstest.run(dict(globals()))
