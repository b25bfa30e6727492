# When the passes are computed for a render: before each frame that renders, at that frame.
# SPDX-License-Identifier: GPL-3.0-or-later
"""render_pre is the one place: it fires once for each frame that renders (F12, animation,
`-f N`, `-s A -e B -a`, `-f A..B`) with the scene already at that frame. render_init is too
early: it fires before `-f N` sets the frame, so work there would compute the file's current
frame instead.

In the background (`blender -b`) a frame whose passes failed stops Blender with EXIT_FAILED
before that frame renders (scene setting On Failure); nothing here may raise into Blender.

Where the handlers run: on the main thread with `blender -b`; on the render thread for F12 and
Ctrl+F12 in the interface. There they touch Blender data only with Lock Interface on, Blender's
documented condition for handlers that read and change data during a render (turning the passes
on sets it); the GUI render test records where each handler ran."""
import os
import sys
import threading

import bpy

from . import api, app_handlers, compositor, native, plain_text

# Blender exits 0 on success and 1 on its own errors (e.g. a failed --python script); 3 says
# "the soft-shadow passes of a frame failed".
EXIT_FAILED = 3

# The last frame's outcome, for the UI (render handlers may run off the main thread, where
# writing RNA properties is not safe).
last_report = {"frame": None, "path": "", "problems": [], "chosen": {}, "layers": {}, "failed": {}}


def _sync_frame(scene):
    """Evaluates the scene at the frame being rendered (an animation render sets the frame
    without evaluating the view layers' depsgraphs)."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    if depsgraph.scene_eval.frame_current == scene.frame_current:
        return
    if threading.current_thread() is threading.main_thread():
        scene.frame_set(scene.frame_current)
    else:
        print("softshadow: the passes of frame %d use the scene as evaluated at frame %d "
              "(render animations from the command line for exact frames)"
              % (scene.frame_current, depsgraph.scene_eval.frame_current))


def _data_access_allowed(scene):
    """Blender data may be read and changed here: on the main thread (always so with `blender
    -b`), or on the render thread while the interface is locked (Blender's rule for handlers)."""
    return threading.current_thread() is threading.main_thread() or scene.render.use_lock_interface


def _compute(scene):
    """{view layer: (path, problems, chosen, failed lights)}; every failure becomes a problem."""
    if not _data_access_allowed(scene):
        return {"": ("", ["the passes were not computed: Render > Lock Interface is off, and this "
                          "render runs its handlers beside the interface (turn it on, or turn the "
                          "passes off and on again)"], {}, [])}
    try:
        api.remove_frame_files(scene)
        if not native.available():
            return {layer.name: ("", [native.status()["error"]], {}, [])
                    for layer in api.rendering_view_layers(scene)}
        _sync_frame(scene)
        return {name: (path, list(problems), dict(chosen), list(failed))
                for name, path, problems, chosen, failed in api.render_frame_layers(scene)}
    except (native.SoftShadowError, native.LibraryUnavailable) as exc:
        return {"": ("", [str(exc)], {}, [])}
    except Exception as exc:  # a bug of ours must not stop the user's render uncontrolled
        return {"": ("", ["internal error: %s: %s" % (type(exc).__name__, exc)], {}, [])}


def _stop(frame, causes):
    """Ends a background render before the frame renders: no picture from missing passes."""
    where = "before the first frame" if frame is None else "frame %d" % frame
    plain_text.log("%s: the passes failed, stopping the render (exit code %d): %s" % (
        where, EXIT_FAILED, " | ".join(causes)), file=sys.stderr)
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(EXIT_FAILED)  # (a SystemExit raised in a handler is caught and printed by Blender)


def _enabled(scene):
    props = getattr(scene, "softshadow", None)
    return props is not None and props.enabled


def failed_light_causes(problems, failed_lights):
    """{light: the problem that names it} for each light that got no pass."""
    causes = {}
    for light in failed_lights:
        named = [p for p in problems if "'%s'" % light in p]
        causes[light] = named[0] if named else "no pass was produced"
    return causes


def _record(frame, layers):
    problems, chosen, paths, failed = [], {}, [], {}
    for name, (path, layer_problems, layer_chosen, layer_failed) in layers.items():
        problems += layer_problems
        chosen.update(layer_chosen)
        failed.update(failed_light_causes(layer_problems, layer_failed))
        if path:
            paths.append(path)
    last_report.clear()
    last_report.update(frame=frame, path=paths[0] if paths else "", problems=problems, chosen=chosen,
                       layers=dict(layers), failed=failed)
    for problem in problems:
        plain_text.log("frame %d: %s" % (frame, problem))
    for path in paths:
        plain_text.log("frame %d: wrote %s (%s)" % (
            frame, path, ", ".join("%s: %s" % item for item in chosen.items())))


@bpy.app.handlers.persistent
def on_render_init(scene, *_args):
    """Before any frame: the checks that need no frame (the frame is not set yet here)."""
    if not _enabled(scene):
        return
    causes = []
    try:
        missing = compositor.missing_sockets(scene, api.compositor_view_layer(scene))
        if missing:
            causes.append("the compositor's '%s' node has no socket for %s yet: run Set Up "
                          "Compositor again (and save) before rendering"
                          % (compositor.IMAGE_NODE, ", ".join(missing)))
    except Exception as exc:
        causes.append("internal error: %s: %s" % (type(exc).__name__, exc))
    for cause in causes:
        plain_text.log(cause)
    try:
        for name in compositor.unguarded_groups(scene):
            plain_text.log("the compositor's '%s' is from an older version of the add-on: a failed "
                           "pass would darken the frame through it; run Set Up Compositor again" % name)
    except Exception as exc:
        print("softshadow: internal error: %s: %s" % (type(exc).__name__, exc))
    if causes and bpy.app.background and scene.softshadow.on_failure == "STOP":
        _stop(None, causes)


@bpy.app.handlers.persistent
def on_render_pre(scene, *_args):
    if not _enabled(scene):
        return
    frame = scene.frame_current
    layers = _compute(scene)
    _record(frame, layers)
    causes = api.failure_causes(layers)
    if causes and bpy.app.background and scene.softshadow.on_failure == "STOP":
        _stop(frame, causes)


_HANDLERS = (("render_init", on_render_init), ("render_pre", on_render_pre))


def register():
    app_handlers.attach(_HANDLERS)


def unregister():
    app_handlers.detach(_HANDLERS)
