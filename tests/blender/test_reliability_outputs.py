# Do the add-on's failures of issue 29 read as what they are, before any render: lights whose
# pass names collide, a camera scaled to 0, a pass file that cannot be written, names that would
# steer the file name, a farm's SIGTERM during a write?
# SPDX-License-Identifier: GPL-3.0-or-later
import contextlib
import glob
import io
import os
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402

ss = sstest.addon()


def _scene(folder, template="softshadow_####.exr"):
    scene = sstest.standard_scene(32, 24)
    scene.objects["Key"].data.softshadow.method = "shadow_map"
    scene.softshadow.output_path = os.path.join(folder, template)
    return scene


def _temporary_files(folder):
    return sorted(glob.glob(os.path.join(glob.escape(folder), "**", ".ss*"), recursive=True))


def test_lights_with_the_same_pass_name_are_named_before_rendering():
    folder = sstest.tempdir("collide")
    scene = _scene(folder)
    for name, x in (("A.B", -3.0), ("A_B", 3.0), ("C D", 0.0), ("C_D", 1.0)):
        light = sstest.add_light(name, location=(x, 0, 6))
        light.data.softshadow.method = "shadow_map"
    bpy.context.view_layer.update()
    scene.softshadow.enabled = True
    scene.softshadow.on_failure = "CONTINUE"  # (STOP would end this test's Blender)
    ss.handlers.on_render_pre(scene)
    (path, problems, _chosen, failed), = ss.handlers.last_report["layers"].values()
    text = "\n".join(problems)
    sstest.check("'A.B'" in text and "'A_B'" in text and "same passes" in text, "both named: %s" % problems)
    sstest.check("'C D'" in text and "'C_D'" in text, "both named: %s" % problems)
    sstest.check(sorted(failed) == ["A_B", "C_D"], "the later light of each pair gets no pass: %s" % failed)
    channels = sstest.exr_channels(path)
    sstest.check(sorted(c for c in channels if c.endswith("_shadow_map.V")) ==
                 ["ViewLayer.A_B_shadow_map.V", "ViewLayer.C_D_shadow_map.V", "ViewLayer.Key_shadow_map.V"],
                 "the others' passes are written: %s" % channels)
    arrays = ss.render_passes(scene)
    sstest.check(sorted(arrays) == [("A.B", "shadow_map"), ("C D", "shadow_map"), ("Key", "shadow_map")],
                 "render_passes: %s" % sorted(arrays))
    sstest.check(any("'A_B'" in p for p in ss.render_passes.last_problems), ss.render_passes.last_problems)


def test_control_and_bidi_characters_in_a_light_name_get_the_librarys_rule():
    folder = sstest.tempdir("bidi")
    scene = _scene(folder)
    for name in ("evil\u202etxt", "csi\u009b2J"):
        light = sstest.add_light(name, location=(1, 1, 6))
        light.data.softshadow.method = "shadow_map"
    bpy.context.view_layer.update()
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        arrays = ss.render_passes(scene)
    sstest.check(list(arrays) == [("Key", "shadow_map")], "the other light keeps its pass: %s" % list(arrays))
    refused = [p for p in ss.render_passes.last_problems if "a bidirectional formatting character" in p]
    sstest.check(len(refused) == 2 and "\\u202E" in refused[0] + refused[1] and "\\u009B" in refused[0] + refused[1],
                 "both refused, shown escaped: %s" % ss.render_passes.last_problems)
    # The console line names the light as the user typed it, its hidden characters escaped.
    lines = [line for line in printed.getvalue().splitlines() if "gets no pass" in line]
    sstest.check(len(lines) == 2 and not any(c in "".join(lines) for c in "\u202e\u009b")
                 and "'evil\\u202Etxt'" in "".join(lines),
                 "printed without the raw characters: %r" % lines)


def test_camera_scaled_to_zero_is_refused_cleanly():
    folder = sstest.tempdir("cam0")
    scene = _scene(folder)
    for scale in ((0.0, 0.0, 0.0), (1.0, 0.0, 1.0)):
        scene.camera.scale = scale
        bpy.context.view_layer.update()
        arrays = ss.render_passes(scene)  # used to raise numpy's LinAlgError
        sstest.check(arrays == {}, "no passes: %s" % list(arrays))
        sstest.check(any("scaled to 0" in p and "'Camera'" in p for p in ss.render_passes.last_problems),
                     "the problem names the camera: %s" % ss.render_passes.last_problems)
        path, problems, _ = ss.api.render_frame(scene)
        sstest.check(path == "" and any("scaled to 0" in p for p in problems), "render_frame: %s" % problems)
        sstest.check(not any("internal error" in p or "LinAlgError" in p for p in problems), problems)
    scene.camera.scale = (2.0, 2.0, 2.0)  # a scale other than 0 keeps working (Blender normalises it)
    bpy.context.view_layer.update()
    sstest.check(list(ss.render_passes(scene)) == [("Key", "shadow_map")], "scaled camera renders")
    sstest.check(os.listdir(folder) == [], "render_passes writes no file: %s" % os.listdir(folder))


def test_a_folder_at_the_pass_files_path_is_an_output_error():
    folder = sstest.tempdir("outdir")
    scene = _scene(folder)
    scene.softshadow.enabled = True
    scene.softshadow.on_failure = "CONTINUE"  # (STOP would end this test's Blender)
    target = ss.api.frame_exr_path(scene)
    os.makedirs(target)
    ss.handlers.on_render_pre(scene)
    problems = ss.handlers.last_report["problems"]
    sstest.check(any(p.startswith("cannot write the pass file %s" % target) for p in problems),
                 "an output error: %s" % problems)
    sstest.check(not any("internal error" in p for p in problems), "no internal error: %s" % problems)
    sstest.check(os.path.isdir(target), "the folder stays")
    path, problems, _ = ss.api.render_frame(scene)
    sstest.check(path == "" and problems[0].startswith("cannot write the pass file"), problems)
    # A file where the pass folder should be.
    shutil.rmtree(target)
    blocker = os.path.join(folder, "blocker")
    open(blocker, "w").close()
    scene.softshadow.output_path = os.path.join(blocker, "softshadow_####.exr")
    path, problems, _ = ss.api.render_frame(scene)
    sstest.check(path == "" and problems[0].startswith("cannot write the pass file"), problems)
    sstest.check(_temporary_files(folder) == [], "no temporary file")


def test_a_read_only_mount_is_an_output_error():
    if shutil.which("unshare") is None or subprocess.run(
            ["unshare", "-rm", "true"], capture_output=True).returncode != 0:
        print("   (no user namespaces for a private read-only mount: skipped)")
        return
    folder = sstest.tempdir("rofs")
    scene = _scene(folder, os.path.join("ro", "softshadow_####.exr"))
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.softshadow.enabled = True
    os.makedirs(os.path.join(folder, "ro"))
    blend = os.path.join(folder, "ro.blend")
    bpy.ops.wm.save_as_mainfile(filepath=blend)
    addon_args, env = sstest.child_blender(folder)
    command = " ".join("'%s'" % a for a in [sstest.blender_binary(), "-b", blend] + addon_args + ["-f", "1"])
    run = subprocess.run(["unshare", "-rm", "sh", "-c", "mount -t tmpfs -o ro tmpfs '%s' && exec %s" % (
        os.path.join(folder, "ro"), command)], capture_output=True, text=True, env=env, timeout=600)
    log = run.stdout + run.stderr
    sstest.check(run.returncode == ss.handlers.EXIT_FAILED, "exit 3: %d\n%s" % (run.returncode, log[-2000:]))
    sstest.check("cannot write the pass file" in log and "Read-only file system" in log, log[-2000:])
    sstest.check("internal error" not in log, log[-2000:])


def test_names_are_text_in_the_template():
    folder = sstest.tempdir("names")
    scene = _scene(folder)
    scene.frame_current = 1
    cases = (("{scene}.exr", "Shot#7", "Shot#7_0001.exr"),  # '#' was the frame: Shot17.exr
             (os.path.join("{scene}", "{view_layer}_####.exr"), "..", os.path.join("_.", "ViewLayer_0001.exr")),
             (os.path.join("{scene}", "x_####.exr"), ".", os.path.join("_", "x_0001.exr")),
             ("{scene}_{view_layer}_##.exr", ".hidden", "_hidden_ViewLayer_01.exr"))
    for template, name, expected in cases:
        scene.softshadow.output_path = os.path.join(folder, template)
        scene.name = name
        path = ss.api.frame_exr_path(scene)
        sstest.check(path == os.path.join(folder, expected), "%r with %r -> %s" % (name, template, path))
        written, problems, _ = ss.api.render_frame(scene)
        sstest.check(written == path and os.path.exists(path), "%r: written %s: %s" % (name, written, problems))
        sstest.check(os.path.realpath(path).startswith(os.path.realpath(folder) + os.sep), "inside the folder")
    sstest.check(not os.path.exists(os.path.join(folder, "Shot17.exr")), "no frame in the name's '#'")
    # Blender's image loader takes the '#' in the file name as text: it opens the file and finds
    # the multilayer EXR (whose passes the Image node then lists).
    image = bpy.data.images.load(os.path.join(folder, "Shot#7_0001.exr"), check_existing=False)
    try:
        image.update()
    except RuntimeError:
        pass  # ("no image data": a multilayer image has its data per pass)
    sstest.check(image.type == "MULTILAYER", "Blender read the file: %s" % image.type)
    bpy.data.images.remove(image)


def test_sigterm_during_the_pass_file_write_leaves_no_temporary_file():
    folder = sstest.tempdir("sigterm")
    scene = _scene(folder, os.path.join("passes", "softshadow_####.exr"))
    scene.render.resolution_x, scene.render.resolution_y = 2048, 2048
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.softshadow.enabled = True
    scene.softshadow.extra_layers = True  # more to write: the write lasts long enough to be caught
    for i in range(5):
        light = sstest.add_light("Fill%d" % i, location=(i - 2.0, 1.0, 6))
        light.data.softshadow.method = "shadow_map"
    blend = os.path.join(folder, "big.blend")
    bpy.ops.wm.save_as_mainfile(filepath=blend)
    addon_args, env = sstest.child_blender(folder)
    passes = os.path.join(folder, "passes")
    for sig in (signal.SIGTERM, signal.SIGKILL):
        child = subprocess.Popen([sstest.blender_binary(), "-b", blend] + addon_args + ["-f", "1"], env=env,
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        seen = []
        deadline = time.time() + 600
        while time.time() < deadline and child.poll() is None and not seen:
            seen = _temporary_files(passes) if os.path.isdir(passes) else []
            time.sleep(0.0005)
        if seen:
            child.send_signal(sig)
        code = child.wait(timeout=600)
        sstest.check(seen, "the test saw the temporary file while it was written (%s)" % sig.name)
        sstest.check(code == -sig, "%s ended Blender: %d" % (sig.name, code))
        sstest.check(not os.path.exists(os.path.join(passes, "softshadow_0001.exr")), "no final file")
        left = _temporary_files(passes)
        if sig == signal.SIGTERM:
            sstest.check(left == [], "SIGTERM removes the temporary file: %s" % left)
        else:
            sstest.check(len(left) == 1, "SIGKILL leaves it (nothing runs then): %s" % left)
    # The next write into the folder removes the killed Blender's file.
    bpy.ops.wm.open_mainfile(filepath=blend)
    small = bpy.context.scene
    small.render.resolution_x, small.render.resolution_y = 32, 24
    path, problems, _ = ss.api.render_frame(small)
    sstest.check(path and os.path.exists(path), "written: %s" % problems)
    sstest.check(_temporary_files(passes) == [], "swept: %s" % _temporary_files(passes))


if __name__ == "__main__":
    sstest.run(dict(globals()))
