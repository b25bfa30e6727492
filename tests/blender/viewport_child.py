# How the viewport-preview test drives a real Blender window (run by test_viewport_preview.py).
# SPDX-License-Identifier: GPL-3.0-or-later
"""Top view over the scene; a screenshot with the preview off, then one with it on once the
preview worker has delivered its full image, then one after the occluder moved (as an artist
drags it) and the preview delivered again; then a continuous edit sequence (small moves, a light
resize, Render Passes) with a screenshot right after each edit's first redraw, before the worker
can answer it, and one once the refined image landed; writes the region, the projected test
points and the preview's record of the images it handed over as JSON."""
import json
import os
import sys
import time

import bpy
from bpy_extras.view3d_utils import location_3d_to_region_2d
from mathutils import Quaternion, Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import xvfb_screen  # noqa: E402

OUT = os.environ["SOFTSHADOW_PREVIEW_OUT"]
POINTS = json.loads(os.environ["SOFTSHADOW_PREVIEW_POINTS"])
MOVE = json.loads(os.environ["SOFTSHADOW_PREVIEW_MOVE"])  # [object name, [dx, dy, dz]]
# The edit sequence after the move: each a small change that keeps the "moved" point in shadow.
SEQUENCE = ("nudge", "nudge", "resize", "render_passes", "nudge_back", "resize_back")
state = {"step": 0, "t": time.time(), "info": None, "edit": 0}


def _apply(edit, scene, softshadow):
    name = MOVE[0]
    if edit == "nudge":
        scene.objects[name].location.y += 0.1
    elif edit == "nudge_back":
        scene.objects[name].location.y -= 0.1
    elif edit == "resize":
        scene.objects["Key"].data.size = 0.8
    elif edit == "resize_back":
        scene.objects["Key"].data.size = 0.5
    elif edit == "render_passes":
        softshadow.api.render_frame(scene, bpy.context.evaluated_depsgraph_get())
    bpy.context.view_layer.update()


def _view():
    win = bpy.context.window_manager.windows[0]
    area = max((a for a in win.screen.areas if a.type == "VIEW_3D"), key=lambda a: a.width * a.height)
    region = next(r for r in area.regions if r.type == "WINDOW")
    return win, area, region, area.spaces.active


def _shot(name):
    xvfb_screen.snapshot(os.environ["SOFTSHADOW_XVFB_FBDIR"], os.path.join(OUT, name))


def step():
    softshadow = sstest.addon()
    win, area, region, space = _view()
    scene = bpy.context.scene
    s = state["step"]
    if s == 0:
        space.overlay.show_overlays = False
        space.shading.type = "SOLID"
        rv3d = space.region_3d
        rv3d.view_perspective = "PERSP"
        rv3d.view_rotation = Quaternion((1, 0, 0, 0))  # looking down -Z
        rv3d.view_location = (0, 0, 0)
        rv3d.view_distance = 12
        scene.softshadow.preview = False
        area.tag_redraw()
    elif s == 1:
        _shot("off.xwd")
        scene.softshadow.preview = True
        area.tag_redraw()
        state["t"] = time.time()
    elif s in (2, 5):
        if not softshadow.preview.full_image_delivered() and time.time() - state["t"] < 60:
            area.tag_redraw()
            return 0.5  # still computing
        area.tag_redraw()
    elif s == 3:
        _shot("on.xwd")
        rv3d = space.region_3d
        info = {"region": [region.x, region.y, region.width, region.height],
                "window": [win.width, win.height], "error": softshadow.preview._state.error,
                "done": len(softshadow.preview._state.done),
                "delivered": list(softshadow.preview._state.delivered),
                "full": list(next(iter(softshadow.preview._state.keys.values()))[1:3])}
        for name, p in POINTS.items():
            xy = location_3d_to_region_2d(region, rv3d, Vector(p))
            info[name] = [xy.x, xy.y] if xy is not None else None
        state["info"] = info
    elif s == 4:
        name, offset = MOVE
        state["info"]["generation_before_move"] = softshadow.preview._state.generation
        scene.objects[name].location += Vector(offset)
        bpy.context.view_layer.update()  # the add-on's depsgraph handler notes the move
        area.tag_redraw()
        state["t"] = time.time()
    elif s == 6:
        _shot("moved.xwd")
        info = state["info"]
        info["error_after_move"] = softshadow.preview._state.error
        info["delivered_after_move"] = [entry for entry in softshadow.preview._state.delivered
                                        if entry not in info["delivered"]]
        info["generation"] = softshadow.preview._state.generation
        info["sequence"] = []
    elif s == 7:
        # One edit of the sequence, then a redraw at once: the draw callback sees the edit
        # before the worker can have answered it.
        edit = SEQUENCE[state["edit"]]
        _apply(edit, scene, softshadow)
        area.tag_redraw()
        state["step"] += 1
        return 0.02
    elif s == 8:
        shot = "sequence_%d.xwd" % state["edit"]
        _shot(shot)
        state["info"]["sequence"].append([SEQUENCE[state["edit"]], shot, softshadow.preview._state.generation])
        state["edit"] += 1
        state["step"] = 7 if state["edit"] < len(SEQUENCE) else 9
        return 0.3
    elif s == 9:
        if not softshadow.preview.refined_image_delivered() and time.time() - state["t"] < 120:
            area.tag_redraw()
            return 0.5  # still refining
        area.tag_redraw()
    elif s == 10:
        _shot("refined.xwd")
        info = state["info"]
        info["refined"] = softshadow.preview.refined_image_delivered()
        info["status"] = softshadow.preview._state.status
        info["error_after_sequence"] = softshadow.preview._state.error
        info["delivered_at_end"] = list(softshadow.preview._state.delivered)
        with open(os.path.join(OUT, "info.json"), "w") as f:
            json.dump(info, f)
        bpy.ops.wm.quit_blender()
        return None
    state["step"] += 1
    return 1.0


sstest.run_windowed_steps(step)
