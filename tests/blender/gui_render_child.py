# How the GUI render test presses F12 in a real Blender window (run by test_gui_render.py).
# SPDX-License-Identifier: GPL-3.0-or-later
"""Turns the passes on (as an artist does), starts an interface render (the render job runs on
its own thread), and once it completes writes where each handler ran and what it produced."""
import json
import os
import sys
import time

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402

OUT = os.environ["SOFTSHADOW_GUI_OUT"]
state = {"started": False, "done": False, "t": time.time()}
handler_threads = sstest.watch_render_handlers()


@bpy.app.handlers.persistent
def _complete(*_args):
    state["done"] = True


def _finish(error=""):
    softshadow = sstest.addon()
    report = softshadow.handlers.last_report
    info = {"error": error, "threads": handler_threads,
            "frame": report.get("frame"), "path": report.get("path"), "problems": report.get("problems"),
            "lock_interface": bpy.context.scene.render.use_lock_interface}
    with open(os.path.join(OUT, "gui.json"), "w") as f:
        json.dump(info, f)
    bpy.ops.wm.quit_blender()


def step():
    scene = bpy.context.scene
    if not state["started"]:
        scene.softshadow.enabled = True  # the artist's click (its update locks the interface)
        bpy.app.handlers.render_complete.append(_complete)
        win = bpy.context.window_manager.windows[0]
        with bpy.context.temp_override(window=win):
            bpy.ops.render.render("INVOKE_DEFAULT")  # F12: a render job on its own thread
        state["started"] = True
        return 0.5
    if state["done"]:
        _finish()
        return None
    if time.time() - state["t"] > 240:
        _finish("the render did not complete in 240 s")
        return None
    return 0.5


bpy.app.timers.register(step, first_interval=2.0)
