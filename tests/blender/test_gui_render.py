# Where do the add-on's handlers run on F12 in the interface, and do they touch Blender data
# only where Blender allows it (a locked interface off the main thread)?
# SPDX-License-Identifier: GPL-3.0-or-later
import json
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402

ss = sstest.addon()


def test_f12_under_xvfb():
    if shutil.which("xvfb-run") is None:
        print("   (no xvfb-run: skipped)")
        return
    folder = sstest.tempdir("gui")
    scene = sstest.standard_scene(48, 36)
    scene.objects["Key"].data.softshadow.method = "shadow_map"
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.frame_current = 2
    scene.softshadow.output_path = os.path.join(folder, "passes", "softshadow_####.exr")
    scene.render.use_lock_interface = False  # the passes' switch must turn it on
    blend = os.path.join(folder, "gui.blend")
    bpy.ops.wm.save_as_mainfile(filepath=blend)
    addon_args, env = sstest.child_blender(folder)
    env["SOFTSHADOW_GUI_OUT"] = folder
    child = os.path.join(os.path.dirname(os.path.abspath(__file__)), "gui_render_child.py")
    run = subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 1280x800x24", bpy.app.binary_path, blend,
                          *addon_args, "--python", child],
                         capture_output=True, text=True, env=env, timeout=600)
    log = run.stdout + run.stderr
    info_path = os.path.join(folder, "gui.json")
    sstest.check(os.path.exists(info_path), "the windowed Blender finished:\n%s" % log[-3000:])
    with open(info_path) as f:
        info = json.load(f)
    print("   handlers:", info["threads"])
    sstest.check(info["error"] == "", info["error"])
    threads = info["threads"]
    sstest.check(set(threads) == {"render_init", "render_pre"}, "both handlers ran: %s" % threads)
    for name, where in threads.items():
        # An interface render runs its handlers on the render job's thread: what they may do
        # there is bounded by the lock.
        sstest.check(not where["main_thread"], "%s ran on the render thread: %s" % (name, where))
        sstest.check(where["lock_interface"], "%s ran with the interface locked: %s" % (name, where))
    sstest.check(threads["render_pre"]["frame"] == 2, "the frame rendered: %s" % threads)
    sstest.check(info["problems"] == [] and info["path"].endswith("softshadow_0002.exr"),
                 "frame 2's passes written: %s" % info)
    sstest.check(sorted(os.listdir(os.path.join(folder, "passes"))) == ["softshadow_0002.exr"],
                 "only the rendered frame's file")


def test_off_the_main_thread_without_the_lock_nothing_is_touched():
    scene = sstest.standard_scene(32, 24)
    scene.softshadow.enabled = True
    sstest.check(scene.render.use_lock_interface, "turning the passes on locks the interface")
    scene.render.use_lock_interface = False
    import threading
    out = {}
    worker = threading.Thread(target=lambda: out.update(ss.handlers._compute(scene)))
    worker.start()
    worker.join()
    problems = [p for _, (path, ps, _, _) in out.items() for p in ps]
    sstest.check(any("Lock Interface is off" in p for p in problems), "said why: %s" % problems)


if __name__ == "__main__":
    sstest.run(dict(globals()))
