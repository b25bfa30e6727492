# How the user guide's screenshots are made: in Blender 5.x with the add-on installed from the zip
# (tests/matrix/screenshots.sh), or `blender -b --python tests/blender/make_screenshots.py` here.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Builds the standard test scene, then drives a windowed Blender under Xvfb that takes the
light panel, output panel, viewport preview and compositor screenshots into docs/images/."""
import json
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import xvfb_screen  # noqa: E402
import bpy  # noqa: E402

sstest.addon()
folder = sstest.tempdir("shots")
scene = sstest.standard_scene(320, 240)
scene.softshadow.output_dir = os.path.join(folder, "passes")
blend = os.path.join(folder, "shots.blend")
bpy.ops.wm.save_as_mainfile(filepath=blend)
out = os.environ.get("SOFTSHADOW_SHOTS") or os.path.join(sstest.ROOT, "docs", "images")
os.makedirs(out, exist_ok=True)
shots = os.path.join(folder, "shots")
fbdir = os.path.join(folder, "screen")
os.makedirs(shots)
os.makedirs(fbdir)
addon_args, env = sstest.child_blender(folder)
env.update(SOFTSHADOW_SHOTS=shots, SOFTSHADOW_XVFB_FBDIR=fbdir)
child = os.path.join(os.path.dirname(os.path.abspath(__file__)), "screenshots_child.py")
subprocess.run([*xvfb_screen.command(fbdir), bpy.app.binary_path, blend,
                *addon_args, "--python", child], env=env, timeout=300, check=True)
for name in sorted(os.listdir(shots)):
    if not name.endswith(".xwd"):
        continue
    base = os.path.join(shots, name[:-4])
    with open(base + ".json") as f:
        rect = json.load(f)
    rgb = xvfb_screen.crop(xvfb_screen.read(base + ".xwd"), *rect)
    h, w = rgb.shape[:2]
    rgba = np.concatenate([rgb, np.ones((h, w, 1), np.float32)], axis=2)
    picture = bpy.data.images.new(name[:-4], w, h)
    picture.pixels.foreach_set(np.ascontiguousarray(np.flipud(rgba)).ravel())  # Blender: row 0 = bottom
    picture.filepath_raw = os.path.join(out, name[:-4] + ".png")
    picture.file_format = "PNG"
    picture.save()
print("screenshots in", out, sorted(os.listdir(out)))
