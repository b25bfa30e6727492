# How the user guide's screenshots are taken: a real Blender window under Xvfb (see make_screenshots.py).
# SPDX-License-Identifier: GPL-3.0-or-later
import json
import os
import sys
import time

import bpy
from mathutils import Quaternion

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import xvfb_screen  # noqa: E402

OUT = os.environ["SOFTSHADOW_SHOTS"]
state = {"step": 0, "t": time.time()}


def _areas():
    win = bpy.context.window_manager.windows[0]
    return win, {a.type: a for a in sorted(win.screen.areas, key=lambda a: a.width * a.height)}


def _shot(area, name):
    # The screen as Xvfb holds it, and where the area is: make_screenshots.py crops and saves it.
    base = os.path.join(OUT, os.path.splitext(name)[0])
    xvfb_screen.snapshot(os.environ["SOFTSHADOW_XVFB_FBDIR"], base + ".xwd")
    with open(base + ".json", "w") as f:
        json.dump([area.x, area.y, area.width, area.height], f)


def step():
    softshadow = sstest.addon()
    win, areas = _areas()
    scene = bpy.context.scene
    if "areas" not in state:  # kept: the 3D view becomes the node editor on the way
        state["areas"] = (areas["VIEW_3D"], areas["PROPERTIES"])
    view3d, props = state["areas"]
    s = state["step"]
    if s == 0:
        bpy.ops.softshadow.render_passes()
        bpy.ops.softshadow.setup_compositor()
        key = scene.objects["Key"]
        for obj in scene.objects:
            obj.select_set(obj == key)
        bpy.context.view_layer.objects.active = key
        space = view3d.spaces.active
        space.overlay.show_overlays = False
        space.shading.type = "SOLID"
        rv3d = space.region_3d
        rv3d.view_perspective = "PERSP"
        rv3d.view_rotation = Quaternion((0.94, 0.34, 0.0, 0.0))
        rv3d.view_location = (0.5, 0, 0)
        rv3d.view_distance = 14
        scene.softshadow.preview = True
        view3d.tag_redraw()
    elif s == 1:
        props.spaces.active.context = "DATA"
        props.tag_redraw()
    elif s == 2:
        _shot(props, "light-panel.png")
        props.spaces.active.context = "OUTPUT"
    elif s == 3:
        # Our panel comes after Blender's own output panels: scroll down to it.
        region = next(r for r in props.regions if r.type == "WINDOW")
        with bpy.context.temp_override(window=win, area=props, region=region):
            for _ in range(40):
                bpy.ops.view2d.scroll_down(deltay=100)
        props.tag_redraw()
    elif s == 4:
        _shot(props, "output-panel.png")
        if not softshadow.preview.full_image_delivered() and time.time() - state["t"] < 60:
            view3d.tag_redraw()
            return 0.5
    elif s == 5:
        _shot(view3d, "viewport-preview.png")
        view3d.type = "NODE_EDITOR"
        view3d.ui_type = "CompositorNodeTree"
    elif s == 6:
        editor = view3d.spaces.active
        editor.show_region_ui = False  # the sidebar would hide the final output node
        if hasattr(editor, "show_region_asset_shelf"):
            editor.show_region_asset_shelf = False
        region = next(r for r in view3d.regions if r.type == "WINDOW")
        with bpy.context.temp_override(window=win, area=view3d, region=region):
            bpy.ops.node.view_all()
    elif s == 7:
        _shot(view3d, "compositor.png")
        if bpy.app.version < (4, 2, 0):
            bpy.ops.wm.quit_blender()
            return None
        view3d.type = "PREFERENCES"
        bpy.context.preferences.active_section = "EXTENSIONS"
    elif s == 8:
        _shot(view3d, "extension-5x.png" if bpy.app.version >= (5, 0, 0) else "extension-4x.png")
        bpy.ops.wm.quit_blender()
        return None
    state["step"] += 1
    return 1.5


sstest.run_windowed_steps(step)
