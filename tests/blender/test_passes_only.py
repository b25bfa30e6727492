# Do passes-only runs (scene.softshadow.write_pass_files, and the Flamenco job type's passes-only
# tasks, one per light or not) write exactly the render's pass files for the frames asked, render
# nothing, and fail (exit 3 on a farm) naming the frame whose passes fail?
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import shutil
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402

ss = sstest.addon()
W, H = 48, 36
XS = (-3.0, -2.0, -1.0, -1.5)  # the occluder's x on frames 1..4


def _blend(folder):
    """Two lights (Key with shadow_map, Rim with pcss), the occluder moving over frames 1..4,
    the passes not enabled for renders: a passes-only run needs no opt-in."""
    scene = sstest.standard_scene(W, H)
    scene.objects["Key"].data.softshadow.method = "shadow_map"
    rim = sstest.add_light("Rim", location=(-3, 1, 6), size=0.4)
    rim.data.softshadow.method = "pcss"
    box = scene.objects["Occluder"]
    for frame, x in enumerate(XS, start=1):
        box.location.x = x
        box.keyframe_insert("location", index=0, frame=frame)
    scene.frame_start, scene.frame_end = 1, len(XS)
    sstest.flat_white_workbench(scene)
    scene.render.filepath = os.path.join(folder, "out", "shot_####")
    scene.softshadow.output_path = ""
    scene.frame_set(1)
    path = os.path.join(folder, "passes.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    return scene, path


def _files(folder):
    path = os.path.join(folder, "out", "softshadow")
    return sorted(os.listdir(path)) if os.path.isdir(path) else []


def _pictures(folder):
    return sorted(f for r, _, fs in os.walk(folder) for f in fs if not f.endswith((".exr", ".blend", ".blend1")))


def test_the_render_pass_files_of_the_frames_asked_and_nothing_rendered():
    folder = sstest.tempdir("passes-only")
    scene, _ = _blend(folder)
    written = scene.softshadow.write_pass_files("2-3, 4")
    names = ["shot_Scene_ViewLayer_%04d.exr" % f for f in (2, 3, 4)]
    sstest.check(_files(folder) == names, "pass files %s" % _files(folder))
    sstest.check([(f, layer) for f, layer, _ in written] == [(2, "ViewLayer"), (3, "ViewLayer"), (4, "ViewLayer")],
                 "written %s" % written)
    sstest.check(scene.frame_current == 1, "the scene is back at its frame (%d)" % scene.frame_current)
    sstest.check(_pictures(folder) == [], "nothing rendered: %s" % _pictures(folder))
    for frame in (2, 4):
        path = os.path.join(folder, "out", "softshadow", "shot_Scene_ViewLayer_%04d.exr" % frame)
        channels = sstest.exr_channels(path)
        for light, method in (("Key", "shadow_map"), ("Rim", "pcss")):
            sstest.check("ViewLayer.%s_%s.V" % (light, method) in channels, "frame %d channels %s" % (frame, channels))
        v = sstest.exr_channel(path, "ViewLayer.Key_shadow_map.V")
        scene.frame_set(frame)
        expect = scene.softshadow.render_passes(lights="Key")[("Key", "shadow_map")]
        scene.frame_set(1)
        sstest.check(np.abs(v - expect).max() < 1e-5, "frame %d: the file is the frame's pass (max diff %.2g)"
                     % (frame, np.abs(v - expect).max()))
        at = sstest.pixel_of(scene, sstest.shadow_centre(XS[frame - 1]))
        sstest.check(v[at] < 0.05, "frame %d: the shadow where the occluder is that frame (V=%.3f)" % (frame, v[at]))


def test_one_light_in_files_of_its_own():
    folder = sstest.tempdir("passes-light")
    scene, _ = _blend(folder)
    scene.softshadow.write_pass_files([1, 2], lights=["Rim"])
    scene.softshadow.write_pass_files("1..2", lights="Key")
    want = ["shot_Scene_ViewLayer_%s_%04d.exr" % (l, f) for l in ("Key", "Rim") for f in (1, 2)]
    sstest.check(_files(folder) == want, "pass files %s, want %s" % (_files(folder), want))
    channels = sstest.exr_channels(os.path.join(folder, "out", "softshadow", want[2]))
    sstest.check("ViewLayer.Rim_pcss.V" in channels and all(c.startswith("ViewLayer.Rim_") for c in channels),
                 "only the light's own passes: %s" % channels)


def test_bad_requests_raise_naming_the_cause():
    folder = sstest.tempdir("passes-bad")
    scene, _ = _blend(folder)
    for frames in ("", "3-1", "1,,2", "a"):
        try:
            scene.softshadow.write_pass_files(frames)
        except ValueError as exc:
            sstest.check("frame range" in str(exc), "%r: %s" % (frames, exc))
        else:
            raise sstest.Failure("%r: no error" % frames)
    try:
        scene.softshadow.write_pass_files("2", lights=["No Such Light"])
    except ss.api.PassesFailed as exc:
        sstest.check("frame 2" in str(exc) and "No Such Light" in str(exc), str(exc))
    else:
        raise sstest.Failure("an unknown light: no error")
    sstest.check(_files(folder) == [], "no file: %s" % _files(folder))


def _flamenco_tasks(settings):
    import json
    import subprocess
    script = os.path.join(sstest.ROOT, "farm", "flamenco", "tests", "compile_job.js")
    out = subprocess.run(["node", script, json.dumps(settings)], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def _run_task(folder, task):
    """A task's blender-render command as a Flamenco worker runs it ({blenderArgs}: -b -y)."""
    params = task["commands"][0]["parameters"]
    argv = ["-y"] + params["argsBefore"] + [params["blendfile"]] + params["args"]
    return sstest.blender_batch(folder, None, None, argv=argv)


def test_flamenco_passes_only_tasks_per_light():
    if shutil.which("node") is None:
        print("   (no node: skipped)")
        return
    folder = sstest.tempdir("passes-farm")
    scene, blend = _blend(folder)
    farm_out = os.path.join(folder, "farm", "shot_####")
    settings = {"frames": "1-3", "chunk_size": 2, "render_output_root": folder, "render_output_path": farm_out,
                "blendfile": blend, "format": "PNG", "scene": scene.name, "passes_only": True,
                "task_per_light": True, "lights": "Key\nRim",
                "addon_module": sstest.child_blender(folder)[0][1]}
    tasks = _flamenco_tasks(settings)
    sstest.check([t["name"] for t in tasks] == ["passes-1,2-Key", "passes-1,2-Rim", "passes-3-Key", "passes-3-Rim"],
                 "tasks %s" % [t["name"] for t in tasks])
    for task in tasks:
        run = _run_task(folder, task)
        sstest.check(run.returncode == 0, "%s: exit %d\n%s" % (task["name"], run.returncode, run.log[-3000:]))
    got = sorted(os.listdir(os.path.join(folder, "farm", "softshadow")))
    want = ["shot_Scene_ViewLayer_%s_%04d.exr" % (l, f) for l in ("Key", "Rim") for f in (1, 2, 3)]
    sstest.check(got == want, "per-light pass files %s, want %s" % (got, want))
    sstest.check(_pictures(folder) == [], "nothing rendered: %s" % _pictures(folder))
    # A frame whose passes cannot be written fails its task with exit 3, naming the frame.
    blocker = os.path.join(folder, "a_file")
    open(blocker, "w").close()
    scene.softshadow.output_path = os.path.join(blocker, "p_####.exr")
    bpy.ops.wm.save_as_mainfile(filepath=blend)
    run = _run_task(folder, _flamenco_tasks(dict(settings, task_per_light=False, frames="3"))[0])
    sstest.check(run.returncode == 3 and "frame 3" in run.log and "cannot write the pass file" in run.log,
                 "failed task: exit %d\n%s" % (run.returncode, run.log[-2000:]))


if __name__ == "__main__":
    sstest.run(dict(globals()))
