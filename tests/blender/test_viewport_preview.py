# Is the live viewport preview drawn in a real Blender window, with its shadow where the scene puts it?
# SPDX-License-Identifier: GPL-3.0-or-later
import json
import os
import shutil
import subprocess
import sys
import time

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


COARSE_MATCH = 0.05  # mean |alpha| difference of the coarse image (scaled up) from the full one
# ... with the coarse settings (texels per pixel as the full image): a small part of COARSE_MATCH
COARSE_LOSS = 0.01


def _wait(predicate, what, seconds=120):
    end = time.time() + seconds
    while not predicate():
        sstest.check(time.time() < end, "timed out waiting for %s" % what)
        time.sleep(0.001)


def _edit(preview, scene):
    """Moves the plate and queues the edit for the preview worker, as the viewport's draw does."""
    scene.objects["Occluder"].location.x += 0.1
    bpy.context.view_layer.update()  # the add-on's depsgraph handler notes the move
    edit = preview.export_edit(bpy.context.evaluated_depsgraph_get(), scene)
    sstest.check(edit is not None and edit[0] == "objects", "the move is an edit of one object: %r" % (edit,))
    with preview._state.lock:
        preview._state.edits.append(edit)


def test_coarse_then_full_and_a_newer_edit_cancels():
    preview = ss.preview
    scene = sstest.standard_scene(64, 48)
    scene.objects["Key"].data.softshadow.method = "pcss"
    bpy.context.view_layer.update()
    full = (1920, 1080)  # large enough that a full render lasts far longer than the polling below
    coarse = (full[0] // preview.COARSE_DIVISOR, full[1] // preview.COARSE_DIVISOR)
    camera = ss.scene_export.scene_camera(scene, bpy.context.evaluated_depsgraph_get(), *full)
    state = preview._state
    state.full = True
    state.edits.append(preview.export_edit(bpy.context.evaluated_depsgraph_get(), scene))
    try:
        first = preview.request_render("first", camera)
        _wait(lambda: (first, full, "full") in state.delivered or state.error, "the first full image")
        sstest.check(state.error == "", "the worker rendered: %s" % state.error)
        mine = [(size, stage) for g, size, stage in state.delivered if g == first]
        sstest.check(mine[:2] == [(coarse, "coarse"), (full, "full")], "coarse then full for one request: %s" % mine)

        # The coarse image shows the shadow where the full one does.
        _edit(preview, scene)
        second = preview.request_render("second", camera)
        images = {}

        def seen():
            done = state.done.get("second")
            if done is not None and done[0] == second:
                images[done[2].shape[:2]] = done[2]
            return (second, full, "full") in state.delivered or state.error
        _wait(seen, "the second full image")
        sstest.check(set(images) == {coarse[::-1], full[::-1]}, "both images were handed over: %s" % list(images))
        scaled = np.repeat(np.repeat(images[coarse[::-1]][..., 3], preview.COARSE_DIVISOR, 0),
                           preview.COARSE_DIVISOR, 1)
        difference = float(np.abs(scaled - images[full[::-1]][..., 3]).mean())
        sstest.check(images[full[::-1]][..., 3].max() > 0.5, "the full image has a shadow")
        sstest.check(difference <= COARSE_MATCH, "the coarse image matches the full one (%.4f)" % difference)

        # An edit arriving once the coarse image is out cancels that request's full render.
        _edit(preview, scene)
        third = preview.request_render("third", camera)
        _wait(lambda: (third, coarse, "coarse") in state.delivered or state.error, "the third coarse image")
        _edit(preview, scene)
        fourth = preview.request_render("fourth", camera)
        _wait(lambda: (fourth, full, "full") in state.delivered or state.error, "the fourth full image")
        sstest.check(state.error == "", "the worker rendered: %s" % state.error)
        sstest.check(not any(g == third and stage != "coarse" for g, _size, stage in state.delivered),
                     "the stale full image was never handed over")
        sstest.check((third, full) in state.cancelled, "the third full render was cancelled: %s" % state.cancelled)
        mine = [(size, stage) for g, size, stage in state.delivered if g == fourth]
        sstest.check(mine[:2] == [(coarse, "coarse"), (full, "full")], "the newer edit got coarse then full: %s" % mine)
        print("   coarse %s then full %s; coarse vs full alpha %.4f; cancelled %s"
              % (coarse, full, difference, state.cancelled))
    finally:
        ss.preview.unregister()
        ss.preview.register()


def test_the_coarse_image_uses_the_coarse_sizes_and_still_matches_the_full_one():
    preview = ss.preview
    scene = sstest.standard_scene(64, 48)
    full = (960, 540)
    camera = ss.scene_export.scene_camera(scene, bpy.context.evaluated_depsgraph_get(), *full)
    coarse_camera = preview.coarse_camera(camera)
    sstest.check(preview.COARSE_SETTINGS == {"occlusion_textures": "resolution=128"},
                 "coarse settings: %s" % preview.COARSE_SETTINGS)
    for method, settings in sorted(preview.COARSE_SETTINGS.items()):
        scene.objects["Key"].data.softshadow.method = method
        bpy.context.view_layer.update()
        preview._state.full = True
        edit = preview.export_edit(bpy.context.evaluated_depsgraph_get(), scene)
        scenes = {"coarse": ss.passes.LiveScene(), "full": ss.passes.LiveScene()}
        images = []
        try:
            preview.progressive_job(scenes, {"coarse": [], "full": []}, [edit], camera, lambda: False,
                                    lambda rgba, _stage, _round: images.append(rgba), stages=("coarse", "full"))
            live = scenes["coarse"]
            index = live.light_indices()["Key"]
            small, default = (live.scene.render(index, method, settings=text) for text in (settings, None))
            try:
                v_small, v_default = small.layers()["V"], default.layers()["V"]
            finally:
                small.close()
                default.close()
        finally:
            for live in scenes.values():
                live.close()
        alpha = images[0][..., 3]
        sstest.check(alpha.shape == (coarse_camera["height"], coarse_camera["width"]),
                     "coarse size %s" % (alpha.shape,))
        expected = np.flipud(preview.PREVIEW_OPACITY * (1.0 - np.clip(v_small, 0.0, 1.0)))
        sstest.check(np.array_equal(alpha, expected), "%s: the coarse image is rendered with %s" % (method, settings))
        changed = float(np.mean(np.abs(v_small - v_default) > 1e-6))
        sstest.check(changed > 0, "%s: %s renders differently from the default size (else this test "
                     "cannot tell them apart)" % (method, settings))
        # no visible loss: the coarse image scaled up matches the full one as closely as with defaults
        scaled = np.repeat(np.repeat(alpha, preview.COARSE_DIVISOR, 0), preview.COARSE_DIVISOR, 1)
        difference = float(np.abs(scaled - images[1][..., 3]).mean())
        with_defaults = np.repeat(np.repeat(np.flipud(preview.PREVIEW_OPACITY * (1.0 - np.clip(v_default, 0.0, 1.0))),
                                            preview.COARSE_DIVISOR, 0), preview.COARSE_DIVISOR, 1)
        baseline = float(np.abs(with_defaults - images[1][..., 3]).mean())
        print("   %s coarse (%s) vs full: mean |alpha| %.4f (defaults %.4f); %.4f of the pixels changed"
              % (method, settings, difference, baseline, changed))
        sstest.check(difference <= COARSE_MATCH, "%s: coarse vs full %.4f" % (method, difference))
        sstest.check(difference <= COARSE_LOSS, "%s: the smaller sizes lose little: %.4f (defaults %.4f)"
                     % (method, difference, baseline))


def _rmse(rgba, truth, mask):
    """RMSE of the V an overlay shows against the truth, over the truth's mask."""
    v = 1.0 - np.flipud(rgba[..., 3]) / ss.preview.PREVIEW_OPACITY
    return float(np.sqrt(np.mean((v - truth)[mask != 0] ** 2)))


def test_the_refined_image_comes_in_rounds_whose_error_falls_to_the_final_render():
    preview = ss.preview
    scene = sstest.standard_scene(64, 48)
    scene.objects["Key"].data.softshadow.method = "pcss"
    bpy.context.view_layer.update()
    camera = ss.scene_export.scene_camera(scene, bpy.context.evaluated_depsgraph_get(), 240, 180)
    preview._state.full = True
    edit = preview.export_edit(bpy.context.evaluated_depsgraph_get(), scene)
    scenes = {"coarse": ss.passes.LiveScene(), "full": ss.passes.LiveScene()}
    images, statuses = [], []
    try:
        preview.progressive_job(scenes, {"coarse": [], "full": []}, [edit], camera, lambda: False,
                                lambda rgba, stage, round_: images.append((preview.stage_label(stage, round_), rgba)),
                                status=statuses.append)
        live = scenes["full"]
        index = live.light_indices()["Key"]
        results = [live.scene.render(index, "reference", samples=4096, extra_layers=True),
                   live.scene.render(index, "pcss", refine=True)]
        try:
            reference = results[0].layers()
            truth, mask, once = reference["V"], reference["mask"], results[1].layers()["V"]
        finally:
            for r in results:
                r.close()
    finally:
        for live in scenes.values():
            live.close()
    labels = [label for label, _rgba in images]
    rounds = ["refined %d" % k for k in range(1, preview.REFINE_ROUNDS)]
    sstest.check(labels == ["coarse", "full"] + rounds + ["refined"], "the rounds land in order: %s" % labels)
    errors = [_rmse(rgba, truth, mask) for _label, rgba in images[1:]]
    print("   error vs the reference: %s" % ", ".join("%s %.4f" % (label, e) for label, e in zip(labels[1:], errors)))
    for before, after, label in zip(errors, errors[1:], labels[2:]):
        sstest.check(after <= before, "%s did not raise the error (%.4f after %.4f)" % (label, after, before))
    sstest.check(errors[1] < 0.75 * errors[0], "the first round corrects the most: %s" % errors)
    sstest.check(errors[-1] <= 0.01, "the last round meets the final render's error target: %.4f" % errors[-1])
    expected = preview.overlay({"Key": once}, camera)
    sstest.check(np.array_equal(images[-1][1], expected), "the last round is the final render's refined pass")
    refining = [text for text in statuses if "refining" in text]
    percents = [int(text.split()[-2]) for text in refining]
    sstest.check(percents == sorted(percents) and set(percents) >= {25, 50, 75},
                 "the corner counts the rounds: %s" % refining)
    sstest.check(statuses[-1] == "soft shadows: refined", "the corner ends refined: %s" % statuses[-1])


def test_an_edit_cancels_the_rounds_at_once():
    preview = ss.preview
    scene = sstest.standard_scene(64, 48)
    scene.objects["Key"].data.softshadow.method = "pcss"
    bpy.context.view_layer.update()
    full = (960, 540)
    camera = ss.scene_export.scene_camera(scene, bpy.context.evaluated_depsgraph_get(), *full)
    state = preview._state
    state.full = True
    state.edits.append(preview.export_edit(bpy.context.evaluated_depsgraph_get(), scene))
    try:
        first = preview.request_render("first", camera)
        _wait(lambda: (first, full, "refined 1") in state.delivered or state.error, "the first round")
        _edit(preview, scene)
        second = preview.request_render("second", camera)
        _wait(lambda: (second, full, "refined") in state.delivered or state.error, "the second refined image")
        sstest.check(state.error == "", "the worker rendered: %s" % state.error)
        mine = [stage for g, _size, stage in state.delivered if g == first]
        sstest.check("refined" not in mine, "the edit stopped the first request's rounds: %s" % mine)
        sstest.check((first, full) in state.cancelled, "the rounds' render was cancelled: %s" % state.cancelled)
        theirs = [stage for g, _size, stage in state.delivered if g == second]
        rounds = ["refined %d" % k for k in range(1, preview.REFINE_ROUNDS)]
        sstest.check(theirs == ["coarse", "full"] + rounds + ["refined"], "the edit's request refined: %s" % theirs)
        print("   first request: %s; cancelled %s" % (mine, state.cancelled))
    finally:
        ss.preview.unregister()
        ss.preview.register()


def test_auto_keeps_its_measured_choice_through_an_orbit():
    preview = ss.preview
    scene = sstest.standard_scene(64, 48)
    scene.objects["Key"].data.softshadow.method = "auto"
    bpy.context.view_layer.update()
    depsgraph = bpy.context.evaluated_depsgraph_get()
    cameras = [ss.scene_export.scene_camera(scene, depsgraph, 160, 120)]
    from mathutils import Matrix
    for _ in range(2):  # an orbit: the camera turned about the vertical axis, nothing edited
        scene.camera.matrix_world = Matrix.Rotation(0.05, 4, "Z") @ scene.camera.matrix_world
        bpy.context.view_layer.update()
        cameras.append(ss.scene_export.scene_camera(scene, bpy.context.evaluated_depsgraph_get(), 160, 120))
    preview._state.full = True
    first = preview.export_edit(bpy.context.evaluated_depsgraph_get(), scene)
    scenes = {"coarse": ss.passes.LiveScene(), "full": ss.passes.LiveScene()}
    backlog = {"coarse": [], "full": []}
    choices = preview.AutoChoices()
    measured = []

    def request(edits, camera):
        images = {}
        preview.progressive_job(scenes, backlog, edits, camera, lambda: False,
                                lambda rgba, stage, round_: images.__setitem__(
                                    preview.stage_label(stage, round_), rgba),
                                choices=choices)
        measured.append(choices.measured)
        return images

    try:
        request([first], cameras[0])
        live = scenes["full"]
        index = live.light_indices()["Key"]
        result = live.scene.render(index, "auto")
        try:
            rendered = result.method
        finally:
            result.close()
        sstest.check(choices.methods == {"Key": rendered}, "the preview keeps the choice a render makes: %s, "
                     "a render %s" % (choices.methods, rendered))
        for camera in cameras[1:]:
            images = request([], camera)
            result = live.scene.render(index, rendered)
            try:
                expected = preview.overlay({"Key": result.layers()["V"]}, camera)
            finally:
                result.close()
            sstest.check(np.array_equal(images["full"], expected), "the orbit's full image is the kept choice's")
        sstest.check(measured == [1, 1, 1], "an orbit measures once: %s" % measured)
        _edit(preview, scene)  # a move of a caster measures again
        with preview._state.lock:
            moved, preview._state.edits = preview._state.edits, []
        request(moved, cameras[-1])
        sstest.check(measured[-1] == 2, "a moved caster measures again: %s" % measured)
        print("   auto kept %s through %d views; measurements %s" % (rendered, len(cameras), measured))
    finally:
        for live in scenes.values():
            live.close()


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
    # The occluder then moves 1.5 along y: its shadow (twice as far from the light) 3.
    moved_centre = list(sstest.shadow_centre(-1.0))
    moved_centre[1] += 3.0
    points = {"shadow": list(sstest.shadow_centre(-1.0)), "far": [-3.5, -2.8, 0.0], "moved": moved_centre}
    addon_args, env = sstest.child_blender(folder)
    fbdir = os.path.join(folder, "screen")
    os.makedirs(fbdir)
    env.update(SOFTSHADOW_PREVIEW_OUT=folder, SOFTSHADOW_PREVIEW_POINTS=json.dumps(points),
               SOFTSHADOW_PREVIEW_MOVE=json.dumps(["Occluder", [0.0, 1.5, 0.0]]), SOFTSHADOW_XVFB_FBDIR=fbdir)
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
    # The window got the coarse image first, then the full one that the screenshot shows.
    last = info["delivered"][-1][0]
    sizes = [tuple(size) for g, size, _stage in info["delivered"] if g == last]
    coarse = tuple(n // ss.preview.COARSE_DIVISOR for n in info["full"])
    sstest.check(sizes[:2] == [coarse, tuple(info["full"])], "coarse then full in the window: %s" % info["delivered"])
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

    # The occluder moved in the running Blender: the overlay's shadow follows to its new place,
    # the old place is lit again, and only images of the newest request were handed over.
    sstest.check(info["error_after_move"] == "", "no preview error after the move: %s" % info["error_after_move"])
    after = info["delivered_after_move"]
    sstest.check(len(after) >= 2 and all(g > info["generation_before_move"] for g, _size, _stage in after)
                 and after[-1][0] == info["generation"],
                 "after the move only newer images were handed over, the last of the newest request: %s (move "
                 "after generation %d, now %d)" % (after, info["generation_before_move"], info["generation"]))
    moved = _screenshot(os.path.join(folder, "moved.xwd"))
    relit = abs(at(moved, "shadow") - at(off, "shadow"))
    sstest.check(relit <= UNCHANGED, "the old shadow is gone after the move (changed %.3f from the lit ground)" % relit)
    followed = 1.0 - at(moved, "moved") / at(off, "moved")
    sstest.check(followed >= DARKENED, "the shadow followed the occluder: its new centre darkened by %.2f" % followed)
    print("   after the move: old centre %.3f from lit, new centre darkened by %.2f" % (relit, followed))

    # Never blank: every frame sampled right after an edit (before the worker answered it)
    # still shows the shadow: the last image stays until a newer one lands.
    sstest.check(len(info["sequence"]) == 6, "the edit sequence ran: %s" % info["sequence"])
    for edit, shot, _generation in info["sequence"]:
        darkened = 1.0 - at(_screenshot(os.path.join(folder, shot)), "moved") / at(off, "moved")
        print("   right after %s: shadow darkened by %.2f" % (edit, darkened))
        sstest.check(darkened >= DARKENED, "the overlay kept its shadow right after '%s' (darkened %.2f)"
                     % (edit, darkened))
    sstest.check(info["error_after_sequence"] == "", "no preview error: %s" % info["error_after_sequence"])

    # Once the scene stays still the image is refined, drawn, and the corner says so.
    sstest.check(info["refined"] and info["status"] == "soft shadows: refined",
                 "the preview refined its image: %s, status %r" % (info["refined"], info["status"]))
    refined = 1.0 - at(_screenshot(os.path.join(folder, "refined.xwd")), "moved") / at(off, "moved")
    sstest.check(refined >= DARKENED, "the refined image shows the shadow (darkened %.2f)" % refined)


if __name__ == "__main__":
    sstest.run(dict(globals()))
