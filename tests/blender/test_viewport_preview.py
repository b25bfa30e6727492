# Is the live viewport preview drawn in a real Blender window, with its shadow where the scene puts it?
# SPDX-License-Identifier: GPL-3.0-or-later
import json
import os
import shutil
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import xvfb_screen  # noqa: E402
import bpy  # noqa: E402

ss = sstest.addon()
# The preview draws black with alpha 0.75 (1 - V): the umbra darkens the picture by about 75 %.
DARKENED = 0.4   # at least this fraction of the brightness is removed inside the umbra
UNCHANGED = 0.03  # a lit pixel changes by less than this (8-bit screenshots, same view)
LIT_GROUND = 0.2  # solid shading draws the lit ground at least this bright


def _screenshot(path):
    """Brightness of a snapshot, row 0 = bottom (as window coordinates)."""
    return np.flipud(xvfb_screen.read(path)).mean(axis=2)


def test_preview_under_xvfb():
    if shutil.which("xvfb-run") is None:
        print("   (no xvfb-run: skipped)")
        return
    folder = sstest.tempdir("preview")
    scene = sstest.standard_scene(64, 48)
    scene.objects["Key"].data.softshadow.method = "shadow_map"
    blend = os.path.join(folder, "preview.blend")
    bpy.ops.wm.save_as_mainfile(filepath=blend)
    points = {"shadow": list(sstest.shadow_centre(-1.0)), "far": [-3.5, -2.8, 0.0]}
    addon_args, env = sstest.child_blender(folder)
    fbdir = os.path.join(folder, "screen")
    os.makedirs(fbdir)
    env.update(SOFTSHADOW_PREVIEW_OUT=folder, SOFTSHADOW_PREVIEW_POINTS=json.dumps(points),
               SOFTSHADOW_XVFB_FBDIR=fbdir)
    child = os.path.join(os.path.dirname(os.path.abspath(__file__)), "viewport_child.py")
    run = subprocess.run([*xvfb_screen.command(fbdir), bpy.app.binary_path, blend,
                          *addon_args, "--python", child],
                         capture_output=True, text=True, env=env, timeout=600)
    log = run.stdout + run.stderr
    info_path = os.path.join(folder, "info.json")
    sstest.check(os.path.exists(info_path), "the windowed Blender finished:\n%s" % log[-3000:])
    with open(info_path) as f:
        info = json.load(f)
    sstest.check(info["error"] == "" and info["done"] >= 1, "the preview worker delivered: %s" % info)
    off = _screenshot(os.path.join(folder, "off.xwd"))
    on = _screenshot(os.path.join(folder, "on.xwd"))
    rx, ry = info["region"][:2]

    def at(image, name):
        x, y = info[name]
        col, row = int(rx + x), int(ry + y)
        return float(image[row - 1:row + 2, col - 1:col + 2].mean())

    # Without the preview the ground is drawn lit at both points: a black or empty window fails.
    sstest.check(at(off, "shadow") > LIT_GROUND and at(off, "far") > LIT_GROUND,
                 "the window shows the lit ground (%.3f, %.3f)" % (at(off, "shadow"), at(off, "far")))
    removed = 1.0 - at(on, "shadow") / at(off, "shadow")
    sstest.check(removed >= DARKENED, "the preview darkens the shadow centre by %.2f" % removed)
    change = abs(at(on, "far") - at(off, "far"))
    sstest.check(change <= UNCHANGED, "a lit pixel stays as it was (changed %.3f)" % change)
    print("   shadow darkened by %.2f, lit pixel changed %.3f" % (removed, change))


if __name__ == "__main__":
    sstest.run(dict(globals()))
