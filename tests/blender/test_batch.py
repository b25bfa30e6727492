# Can a farm trust `blender -b`: exactly the frames asked for, exit 3 when a frame's passes fail
# (no picture from missing or stale passes), nothing computed in a scene that did not opt in, and
# pass files named after the render output for every view layer?
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402

ss = sstest.addon()
W, H = 48, 36
XS = (-3.0, -2.0, -1.0, -1.5)  # the occluder's x on frames 1..4
PASS = "ViewLayer.Key_shadow_map.V"


def _blend(folder, name="batch.blend", enabled=True, current=1):
    scene = sstest.standard_scene(W, H)
    scene.objects["Key"].data.softshadow.method = "shadow_map"
    box = scene.objects["Occluder"]
    for frame, x in enumerate(XS, start=1):
        box.location.x = x
        box.keyframe_insert("location", index=0, frame=frame)
    scene.frame_start, scene.frame_end = 1, len(XS)
    sstest.flat_white_workbench(scene)
    scene.render.filepath = os.path.join(folder, "render_####")
    scene.softshadow.output_path = os.path.join(folder, "passes", "softshadow_####.exr")
    scene.frame_set(current)
    if enabled:
        scene.softshadow.enabled = True
        sstest.check(bpy.ops.softshadow.setup_compositor() == {"FINISHED"}, "compositor set up")
    path = os.path.join(folder, name)
    bpy.ops.wm.save_as_mainfile(filepath=path)
    return scene, path


def _files(folder, sub):
    path = os.path.join(folder, sub)
    return sorted(os.listdir(path)) if os.path.isdir(path) else []


def _check_composite(scene, folder, frame):
    """The frame's picture is dark where its pass says umbra, and the pass is where the geometry
    puts the shadow at that frame."""
    v = sstest.exr_channel(os.path.join(folder, "passes", "softshadow_%04d.exr" % frame), PASS)
    expect = sstest.pixel_of(scene, sstest.shadow_centre(XS[frame - 1]))
    sstest.check(v[expect] < 0.05, "frame %d: pass dark at the frame's shadow (V=%.3f)" % (frame, v[expect]))
    picture = sstest.png_gray(os.path.join(folder, "render_%04d.png" % frame))
    dark, lit = v < 0.05, (v > 0.95) & (picture > 0.5)
    ratio = picture[dark].mean() / picture[lit].mean()
    sstest.check(ratio < 0.1, "frame %d: composite darkened by its own pass (ratio %.3f)" % (frame, ratio))


def test_exactly_the_frames_asked_for():
    folder = sstest.tempdir("frames")
    scene, blend = _blend(folder, current=1)
    # Set-up made the current frame's (1) file; it must be left exactly as it is by renders of
    # other frames.
    sentinel = os.path.join(folder, "passes", "softshadow_0001.exr")
    sstest.check(os.path.exists(sentinel), "set-up wrote the current frame's passes")
    before = (os.stat(sentinel).st_mtime_ns, open(sentinel, "rb").read())
    forms = ((["-f", "2"], [2]), (["-s", "2", "-e", "3", "-a"], [2, 3]), (["-f", "3..4"], [3, 4]))
    for args, frames in forms:
        for name in _files(folder, "passes"):
            if name != "softshadow_0001.exr":
                os.remove(os.path.join(folder, "passes", name))
        for name in [n for n in os.listdir(folder) if n.endswith(".png")]:
            os.remove(os.path.join(folder, name))
        run = sstest.blender_batch(folder, blend, args)
        sstest.check(run.returncode == 0, "%s: exit %d\n%s" % (args, run.returncode, run.log[-3000:]))
        want = ["softshadow_0001.exr"] + ["softshadow_%04d.exr" % f for f in frames]
        sstest.check(_files(folder, "passes") == want,
                     "%s: pass files %s, want %s" % (args, _files(folder, "passes"), want))
        after = (os.stat(sentinel).st_mtime_ns, open(sentinel, "rb").read())
        sstest.check(after == before, "%s: frame 1's file untouched" % args)
        computed = [line for line in run.log.splitlines()
                    if ": wrote " in line and line.startswith("softshadow: frame")]
        sstest.check(len(computed) == len(frames), "%s: computed %d frames: %s" % (args, len(computed), computed))
        for frame in frames:
            _check_composite(scene, folder, frame)


def _library_can_be_hidden():
    """SOFTSHADOW_LIB hides the library only from the source tree: a zip install finds its own."""
    if os.environ.get("SOFTSHADOW_ZIP"):
        print("   (installed from the zip, whose library is always found: skipped)")
        return False
    return True


def test_library_missing_exits_3_before_the_frame_and_removes_the_stale_file():
    if not _library_can_be_hidden():
        return
    folder = sstest.tempdir("nolib")
    _blend(folder)
    stale = os.path.join(folder, "passes", "softshadow_0002.exr")
    shutil.copy(os.path.join(folder, "passes", "softshadow_0001.exr"), stale)  # an earlier run's
    missing = os.path.join(folder, "no-such-dir", "libsoftshadow.so")
    run = sstest.blender_batch(folder, os.path.join(folder, "batch.blend"), ["-f", "2"],
                               env={"SOFTSHADOW_LIB": missing})
    sstest.check(run.returncode == ss.handlers.EXIT_FAILED, "exit %d, want %d\n%s" % (
        run.returncode, ss.handlers.EXIT_FAILED, run.log[-3000:]))
    sstest.check("frame 2" in run.stderr and "libsoftshadow could not be loaded" in run.stderr,
                 "message names the frame and the cause:\n%s" % run.stderr[-2000:])
    sstest.check(not os.path.exists(stale), "the stale pass file of frame 2 is gone")
    sstest.check(not os.path.exists(os.path.join(folder, "render_0002.png")), "no picture for frame 2")


def test_unwritable_folder_exits_3():
    folder = sstest.tempdir("unwritable")
    scene, blend = _blend(folder)
    blocker = os.path.join(folder, "a_file")
    open(blocker, "w").close()
    scene.softshadow.output_path = os.path.join(blocker, "softshadow_####.exr")  # a file is no folder
    bpy.ops.wm.save_as_mainfile(filepath=blend)
    run = sstest.blender_batch(folder, blend, ["-f", "3"])
    sstest.check(run.returncode == ss.handlers.EXIT_FAILED, "exit %d\n%s" % (run.returncode, run.log[-3000:]))
    sstest.check("frame 3" in run.stderr and "cannot write the pass file" in run.stderr,
                 "message names the frame and the cause:\n%s" % run.stderr[-2000:])
    sstest.check(not os.path.exists(os.path.join(folder, "render_0003.png")), "no picture for frame 3")


def test_continue_setting_renders_on():
    if not _library_can_be_hidden():
        return
    folder = sstest.tempdir("continue")
    scene, blend = _blend(folder)
    scene.softshadow.on_failure = "CONTINUE"
    bpy.ops.wm.save_as_mainfile(filepath=blend)
    run = sstest.blender_batch(folder, blend, ["-f", "2"], env={"SOFTSHADOW_LIB": os.path.join(folder, "none.so")})
    sstest.check(run.returncode == 0, "CONTINUE: exit %d\n%s" % (run.returncode, run.log[-2000:]))
    sstest.check("frame 2" in run.log and "libsoftshadow could not be loaded" in run.log, "still reported")
    sstest.check(os.path.exists(os.path.join(folder, "render_0002.png")), "the frame rendered")


def test_missing_sockets_stop_before_any_frame():
    folder = sstest.tempdir("sockets")
    scene, blend = _blend(folder)
    sstest.add_light("Added Later", location=(2, -2, 5), size=0.3)
    bpy.ops.wm.save_as_mainfile(filepath=blend)
    run = sstest.blender_batch(folder, blend, ["-f", "2"])
    sstest.check(run.returncode == ss.handlers.EXIT_FAILED, "exit %d\n%s" % (run.returncode, run.log[-2000:]))
    sstest.check("Added_Later_auto" in run.stderr and "Set Up Compositor" in run.stderr,
                 "names the missing pass and the fix:\n%s" % run.stderr[-2000:])
    sstest.check(_files(folder, "passes") == ["softshadow_0001.exr"], "nothing computed: %s" % _files(folder, "passes"))


def test_a_light_that_does_not_render_needs_no_socket():
    folder = sstest.tempdir("sockets-hidden")
    scene, blend = _blend(folder)
    hidden = bpy.data.collections.new("Off For Render")
    scene.collection.children.link(hidden)
    light = sstest.add_light("Hidden Light", location=(2, -2, 5), size=0.3)
    scene.collection.objects.unlink(light)
    hidden.objects.link(light)
    hidden.hide_render = True
    bpy.ops.wm.save_as_mainfile(filepath=blend)
    run = sstest.blender_batch(folder, blend, ["-f", "2"])
    sstest.check(run.returncode == 0, "exit %d\n%s" % (run.returncode, run.log[-2000:]))
    bpy.data.collections.remove(hidden)


def test_a_scene_that_did_not_opt_in_computes_nothing():
    folder = sstest.tempdir("optin")
    scene, blend = _blend(folder, enabled=False)
    sstest.check(not scene.softshadow.enabled, "passes are off in a new scene")
    run = sstest.blender_batch(folder, blend, ["-f", "1"])
    sstest.check(run.returncode == 0, "exit %d\n%s" % (run.returncode, run.log[-2000:]))
    sstest.check(os.path.exists(os.path.join(folder, "render_0001.png")), "the frame rendered")
    exrs = [os.path.join(r, f) for r, _, fs in os.walk(folder) for f in fs if f.endswith(".exr")]
    sstest.check(exrs == [], "no pass file anywhere: %s" % exrs)
    sstest.check("softshadow: frame" not in run.log, "nothing computed:\n%s" % run.log[-2000:])


def test_default_names_follow_the_render_output_for_every_view_layer():
    folder = sstest.tempdir("naming")
    scene, blend = _blend(folder)
    scene.softshadow.output_path = ""
    scene.render.filepath = os.path.join(folder, "out", "shot_###")
    scene.view_layers.new("Second Layer")
    bpy.ops.wm.save_as_mainfile(filepath=blend)
    run = sstest.blender_batch(folder, blend, ["-f", "2"])
    sstest.check(run.returncode == 0, "exit %d\n%s" % (run.returncode, run.log[-3000:]))
    got = _files(folder, os.path.join("out", "softshadow"))
    want = ["shot_Scene_Second Layer_002.exr", "shot_Scene_ViewLayer_002.exr"]
    sstest.check(got == want, "pass files %s, want %s" % (got, want))
    channels = sstest.exr_channels(os.path.join(folder, "out", "softshadow", want[0]))
    sstest.check(channels[0].startswith("Second Layer."), "the layer's own name inside: %s" % channels)


def _flamenco_tasks(settings):
    """The tasks the Flamenco job type compiles (node, the job-compiler stand-in)."""
    import json
    import subprocess
    script = os.path.join(sstest.ROOT, "farm", "flamenco", "tests", "compile_job.js")
    out = subprocess.run(["node", script, json.dumps(settings)], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def _run_task(folder, task, env=None):
    """A task's blender-render command as a Flamenco worker runs it ({blenderArgs}: -b -y)."""
    params = task["commands"][0]["parameters"]
    argv = ["-y"] + params["argsBefore"] + [params["blendfile"]] + params["args"]
    return sstest.blender_batch(folder, None, None, env=env, argv=argv)


def test_flamenco_tasks_run_and_fail_as_a_worker_would():
    if shutil.which("node") is None:
        print("   (no node: skipped)")
        return
    folder = sstest.tempdir("flamenco")
    scene, blend = _blend(folder)
    out = os.path.join(folder, "farm", "shot_####")
    tasks = _flamenco_tasks({"frames": "2-4", "chunk_size": 2, "render_output_root": folder,
                             "render_output_path": out, "fail_on_pass_failure": True,
                             "blendfile": blend, "format": "PNG", "scene": scene.name,
                             "addon_module": sstest.child_blender(folder)[0][1]})
    sstest.check([t["name"] for t in tasks] == ["render-2,3", "render-4"], "chunks: %s" % tasks)
    for task in tasks:
        run = _run_task(folder, task)
        sstest.check(run.returncode == 0, "%s: exit %d\n%s" % (task["name"], run.returncode, run.log[-3000:]))
    frames = sorted(f for f in os.listdir(os.path.join(folder, "farm")) if f.endswith(".png"))
    sstest.check(frames == ["shot_0002.png", "shot_0003.png", "shot_0004.png"], "frames: %s" % frames)
    passes = _files(folder, os.path.join("farm", "softshadow"))
    sstest.check(passes == [], "the file's own template wins over the render output: %s" % passes)
    sstest.check(_files(folder, "passes") == ["softshadow_%04d.exr" % f for f in (1, 2, 3, 4)],
                 "the passes of exactly the frames rendered: %s" % _files(folder, "passes"))
    # A worker whose library is missing: the task fails with exit 3, naming the frame.
    if _library_can_be_hidden():
        run = _run_task(folder, tasks[1], env={"SOFTSHADOW_LIB": os.path.join(folder, "none.so")})
        sstest.check(run.returncode == 3 and "frame 4" in run.stderr,
                     "failed task: %d\n%s" % (run.returncode, run.log[-2000:]))
    # A worker without the add-on: the check fails the task before anything renders.
    os.remove(os.path.join(folder, "farm", "shot_0004.png"))
    lacking = _flamenco_tasks({"frames": "4", "chunk_size": 1, "render_output_root": folder,
                               "render_output_path": out, "blendfile": blend, "format": "PNG",
                               "scene": scene.name, "addon_module": "softshadow_not_installed"})
    run = _run_task(folder, lacking[0])
    sstest.check(run.returncode == 3 and "not installed or not enabled" in run.log,
                 "no add-on: exit %d\n%s" % (run.returncode, run.log[-2000:]))
    sstest.check(not os.path.exists(os.path.join(folder, "farm", "shot_0004.png")), "nothing rendered")


def test_output_templates():
    op = ss.output_paths
    sstest.check(op.default_template("/r/shot_###") == "/r/softshadow/shot_{scene}_{view_layer}_###.exr",
                 op.default_template("/r/shot_###"))
    sstest.check(op.default_template("/r/") == "/r/softshadow/{scene}_{view_layer}_####.exr",
                 op.default_template("/r/"))
    sstest.check(op.expand("/p/{scene}/{view_layer}.#####.exr", "Sc", "VL", 42) == "/p/Sc/VL.00042.exr", "template")
    sstest.check(op.expand("/p/passes", "Sc", "VL", 7) == "/p/passes_0007.exr", "no # and no extension")
    sstest.check(op.expand("/p/a_##_b.exr", "S", "V", 3) == "/p/a_03_b.exr", "the last # run is the frame")
    sstest.check(op.template_problem("/p/x_####.exr", 2) != "", "two layers need {view_layer}")
    sstest.check(op.template_problem("/p/{view_layer}_####.exr", 2) == "", "with {view_layer}: fine")


if __name__ == "__main__":
    sstest.run(dict(globals()))
