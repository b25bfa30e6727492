# How the cancel test stops an interface render's pass computation (run by test_render_cancel.py).
# SPDX-License-Identifier: GPL-3.0-or-later
"""Presses F12 on a scene whose passes take minutes, waits until the render handler computes
them, then loads a file, and writes how long Blender took to load it and what the handler
reported."""
import json
import os
import sys
import time

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402

OUT = os.environ["SOFTSHADOW_GUI_OUT"]
OTHER = os.environ["SOFTSHADOW_OTHER_BLEND"]
state = {"phase": "start", "t0": time.time(), "asked": None, "info": {}}
softshadow = sstest.addon()
handler_threads = sstest.watch_render_handlers()


def _finish(**info):
    report = softshadow.handlers.last_report
    info.update(problems=report.get("problems"), path=report.get("path"))
    with open(os.path.join(OUT, "cancel.json"), "w") as f:
        json.dump(info, f)
    bpy.ops.wm.quit_blender()
    return None


def step():
    now = time.time()
    if now - state["t0"] > 300:
        return _finish(error="nothing happened in 300 s (phase %s)" % state["phase"])
    if state["phase"] == "start":
        bpy.context.scene.softshadow.enabled = True
        win = bpy.context.window_manager.windows[0]
        with bpy.context.temp_override(window=win):
            bpy.ops.render.render("INVOKE_DEFAULT")
        state["phase"] = "rendering"
        return 0.2
    if state["phase"] == "rendering":
        if "render_pre" not in handler_threads:
            return 0.2
        time.sleep(2.0)  # well inside the pass computation, the library's loops running
        state["asked"] = time.time()
        bpy.ops.wm.open_mainfile(filepath=OTHER)  # Blender waits for the render job first
        return _finish(error="", seconds=time.time() - state["asked"], loaded=bpy.data.filepath)
    return 0.2


bpy.app.timers.register(step, first_interval=2.0)
