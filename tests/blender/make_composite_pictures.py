# How the user guide's Darken/Replace picture is made: `blender -b --python tests/blender/make_composite_pictures.py`.
# SPDX-License-Identifier: GPL-3.0-or-later
"""The Cycles scene of test_replace at 240x180: Cycles' own shadows, Darken, Replace, side by side
in docs/images/composite-darken-replace.png (through oiiotool)."""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import test_replace  # noqa: E402
import bpy  # noqa: E402

test_replace.W, test_replace.H = 240, 180
folder = sstest.tempdir("pictures")
scene = test_replace._cycles_scene(folder)
scene.render.resolution_x, scene.render.resolution_y = 240, 180
scene.use_nodes = True
scene.cycles.samples = 512
files = []
for name, mode in (("truth", None), ("darken", "DARKEN"), ("replace", "REPLACE")):
    if mode:
        scene.softshadow.composite = mode
        bpy.ops.softshadow.setup_compositor()
    scene.render.filepath = os.path.join(folder, name)
    bpy.ops.render.render(write_still=True)
    files.append(scene.render.filepath + ".exr")
out = os.path.join(sstest.ROOT, "docs", "images", "composite-darken-replace.png")
subprocess.run(["oiiotool"] + files + ["--mosaic:pad=8", "3x1", "--ch", "R,G,B", "--tocolorspace", "sRGB",
                                       "-d", "uint8", "-o", out], check=True)
print("picture in", out)
