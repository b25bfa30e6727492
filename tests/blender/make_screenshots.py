# How the user guide's screenshots are made: `blender -b --python tests/blender/make_screenshots.py`.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Builds the standard test scene, then drives a windowed Blender under Xvfb that takes the
light panel, output panel, viewport preview and compositor screenshots into docs/images/."""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402

sstest.addon()
folder = sstest.tempdir("shots")
scene = sstest.standard_scene(320, 240)
scene.softshadow.output_path = os.path.join(os.path.join(folder, "passes"), "softshadow_####.exr")
scene.softshadow.enabled = True
blend = os.path.join(folder, "shots.blend")
bpy.ops.wm.save_as_mainfile(filepath=blend)
scripts = os.path.join(folder, "scripts", "addons")
os.makedirs(scripts)
os.symlink(os.path.join(sstest.ADDON_PATH, "softshadow"), os.path.join(scripts, "softshadow"))
out = os.path.join(sstest.ROOT, "docs", "images")
os.makedirs(out, exist_ok=True)
env = dict(os.environ, BLENDER_USER_SCRIPTS=os.path.join(folder, "scripts"), SOFTSHADOW_SHOTS=out)
child = os.path.join(os.path.dirname(os.path.abspath(__file__)), "screenshots_child.py")
subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 1280x800x24", bpy.app.binary_path, blend,
                "--addons", "softshadow", "--python", child], env=env, timeout=300, check=True)
print("screenshots in", out, sorted(os.listdir(out)))
