# When the passes are computed for a render: before each frame (F12, animation, background -a).
# SPDX-License-Identifier: GPL-3.0-or-later
"""Before each frame the passes are computed, written as one EXR per frame next to the render
output, and the compositor's Image node is refreshed, so the compositor sees them without clicks.

render_init does the current frame: the render copies the compositor's node tree before the
first render_pre, so the Image node's pass sockets and links must exist by then. render_pre does
every later frame of an animation (the file of each frame is read from disk at compositing).
Nothing here may raise into Blender: every failure becomes a printed, stored message."""
import threading

import bpy

from . import api, native

# The last frame's outcome, for the UI (render handlers may run off the main thread, where
# writing RNA properties is not safe).
last_report = {"frame": None, "path": "", "problems": [], "chosen": {}}


def _sync_frame(scene):
    """The view layer's depsgraph at the frame being rendered.

    An animation render sets the frame without evaluating the view layer's depsgraph; on the
    main thread (always so with `blender -b ... -a`) we evaluate it for the new frame."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    evaluated_frame = depsgraph.scene_eval.frame_current
    if evaluated_frame != scene.frame_current:
        if threading.current_thread() is threading.main_thread():
            scene.frame_set(scene.frame_current)
            depsgraph = bpy.context.evaluated_depsgraph_get()
        else:
            print("softshadow: the passes of frame %d use the scene as evaluated at frame %d "
                  "(render animations from the command line for exact frames)"
                  % (scene.frame_current, evaluated_frame))
    return depsgraph


_done_in_init = {"frame": None}


def _compute(scene):
    report = {"frame": scene.frame_current, "path": "", "problems": [], "chosen": {}}
    try:
        if not native.available():
            report["problems"].append(native.status()["error"])
        else:
            path, problems, chosen = api.render_frame(scene, _sync_frame(scene))
            report.update(path=path, problems=list(problems), chosen=dict(chosen))
    except (native.SoftShadowError, native.LibraryUnavailable) as exc:
        report["problems"].append(str(exc))
    except Exception as exc:  # a bug of ours must not stop the user's render
        report["problems"].append("internal error: %s: %s" % (type(exc).__name__, exc))
    last_report.clear()
    last_report.update(report)
    for problem in report["problems"]:
        print("softshadow: frame %d: %s" % (report["frame"], problem))
    if report["path"]:
        chosen = ", ".join("%s: %s" % item for item in report["chosen"].items())
        print("softshadow: frame %d: wrote %s (%s)" % (report["frame"], report["path"], chosen))


def _enabled(scene):
    props = getattr(scene, "softshadow", None)
    return props is not None and props.enabled


@bpy.app.handlers.persistent
def on_render_init(scene, *_args):
    _done_in_init["frame"] = None
    if _enabled(scene):
        _compute(scene)
        _done_in_init["frame"] = scene.frame_current


@bpy.app.handlers.persistent
def on_render_pre(scene, *_args):
    if _done_in_init["frame"] == scene.frame_current:
        _done_in_init["frame"] = None  # render_init already did this frame
        return
    _done_in_init["frame"] = None
    if _enabled(scene):
        _compute(scene)


_HANDLERS = (("render_init", on_render_init), ("render_pre", on_render_pre))


def register():
    for name, fn in _HANDLERS:
        handlers = getattr(bpy.app.handlers, name)
        if fn not in handlers:
            handlers.append(fn)


def unregister():
    for name, fn in _HANDLERS:
        handlers = getattr(bpy.app.handlers, name)
        while fn in handlers:
            handlers.remove(fn)
