# How the 3D viewport shows a live soft-shadow preview: export on change, render off-thread, draw.
# SPDX-License-Identifier: GPL-3.0-or-later
"""The main thread exports the scene when the depsgraph changes and reads each viewport's view
in its draw callback; a worker thread renders at reduced resolution through the library (which
releases the GIL); a newer request cancels the running one through the progress callback. The
finished image is drawn with the `gpu` module only (no bgl), as black with alpha 1 - V."""
import threading

import bpy
import gpu
import numpy as np
from gpu_extras.presets import draw_texture_2d

from . import native, passes, scene_export

PREVIEW_OPACITY = 0.75


def fast_methods():
    """The library's methods fast enough to preview: all but the ray-traced reference."""
    return tuple(m for m in native.method_names() if m != "reference")


class _State:
    def __init__(self):
        self.lock = threading.Lock()
        self.wake = threading.Condition(self.lock)
        self.generation = 0         # bumped by every new request; older work is stale
        self.request = None         # (generation, key, exported, camera)
        self.done = {}              # key -> (generation, rgba float32 (h, w, 4))
        self.exported = None        # the scene without a camera, re-exported on depsgraph change
        self.dirty = True
        self.keys = {}              # region pointer -> key last asked for
        self.textures = {}          # region pointer -> (generation, GPUTexture)
        self.thread = None
        self.stop = False
        self.fresh = False          # a result arrived: redraw the viewports
        self.error = ""


_state = _State()
_draw_handle = None


def _render_job(exported, camera, cancelled):
    """Product of every previewed light's V, as an RGBA overlay. Runs on the worker."""
    exported.camera = camera
    exported.problems = []
    scene, indices = passes.build_native_scene(exported)
    try:
        shade = np.ones((camera["height"], camera["width"]), np.float32)
        for light in exported.lights:
            options = light.get("options", {})
            if light["name"] not in indices or not options.get("enabled", True) or not light["cast_shadows"]:
                continue
            method = options.get("method", "auto")
            method = method if method in fast_methods() else "auto"
            # The viewport cannot wait for auto to render every candidate: it takes auto's rule by
            # the light's shape (docs/methods/README.md).
            settings = "check_pixels=0" if method == "auto" else None
            result = scene.render(indices[light["name"]], method, settings=settings,
                                  progress=lambda f, s: cancelled())
            try:
                v = result.layers().get("V")
            finally:
                result.close()
            if v is not None and v.shape == shade.shape:
                shade *= np.clip(v, 0.0, 1.0)
    finally:
        scene.close()
    rgba = np.zeros(shade.shape + (4,), np.float32)
    rgba[..., 3] = PREVIEW_OPACITY * (1.0 - shade)
    return np.ascontiguousarray(np.flipud(rgba))  # textures start at the bottom row


def _worker():
    state = _state
    while True:
        with state.lock:
            while state.request is None and not state.stop:
                state.wake.wait()
            if state.stop:
                return
            generation, key, exported, camera = state.request
            state.request = None

        def cancelled(generation=generation):
            return state.stop or state.generation != generation

        try:
            rgba = _render_job(exported, camera, cancelled)
        except native.SoftShadowError as exc:
            if not exc.cancelled:
                state.error = str(exc)
            continue
        except Exception as exc:  # the preview must never take Blender down
            state.error = "%s: %s" % (type(exc).__name__, exc)
            continue
        with state.lock:
            if state.generation == generation:
                state.done[key] = (generation, rgba)
                state.error = ""
                state.fresh = True


def _ensure_worker():
    if _state.thread is None or not _state.thread.is_alive():
        _state.stop = False
        _state.thread = threading.Thread(target=_worker, name="softshadow-preview", daemon=True)
        _state.thread.start()


def _view_camera(region, rv3d, scale):
    width = max(8, int(region.width * scale / 100))
    height = max(8, int(region.height * scale / 100))
    camera = scene_export.camera_values(rv3d.view_matrix, rv3d.window_matrix, width, height)
    key = (region.as_pointer(), width, height,
           tuple(camera["world_to_camera"].round(5)), tuple(camera["projection"].round(5)))
    return camera, key


def _submit(context, region, rv3d):
    scene = context.scene
    if _state.dirty or _state.exported is None:
        depsgraph = context.evaluated_depsgraph_get()
        identity = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
        placeholder = scene_export.camera_values(identity, identity, 8, 8)
        _state.exported = scene_export.export(depsgraph, scene, mode="VIEWPORT", camera=placeholder)
        _state.dirty = False
        _state.done.clear()
        _state.keys.clear()
    camera, key = _view_camera(region, rv3d, scene.softshadow.preview_scale)
    if _state.keys.get(region.as_pointer()) == key:
        return key
    exported = scene_export.ExportedScene(meshes=_state.exported.meshes, lights=_state.exported.lights,
                                          view_layer=_state.exported.view_layer)
    with _state.lock:
        _state.generation += 1
        _state.request = (_state.generation, key, exported, camera)
        _state.keys[region.as_pointer()] = key
        _state.wake.notify()
    _ensure_worker()
    return key


def _draw():
    context = bpy.context
    scene = context.scene
    props = getattr(scene, "softshadow", None)
    if props is None or not props.preview or not native.available():
        return
    region, rv3d = context.region, context.region_data
    if region is None or rv3d is None:
        return
    try:
        key = _submit(context, region, rv3d)
        done = _state.done.get(key)
        if done is None:
            return
        generation, rgba = done
        cached = _state.textures.get(region.as_pointer())
        if cached is None or cached[0] != generation:
            h, w = rgba.shape[:2]
            buffer = gpu.types.Buffer("FLOAT", w * h * 4, rgba.reshape(-1))
            cached = (generation, gpu.types.GPUTexture((w, h), format="RGBA16F", data=buffer))
            _state.textures[region.as_pointer()] = cached
        gpu.state.blend_set("ALPHA")
        draw_texture_2d(cached[1], (0, 0), region.width, region.height)
        gpu.state.blend_set("NONE")
    except Exception as exc:
        _state.error = "%s: %s" % (type(exc).__name__, exc)


@bpy.app.handlers.persistent
def _on_depsgraph_update(scene, *_args):
    _state.dirty = True


def _poll_redraw():
    """Main-thread timer: redraw the viewports when the worker has finished an image."""
    if _state.fresh:
        _state.fresh = False
        for window in getattr(bpy.context.window_manager, "windows", []):
            for area in window.screen.areas:
                if area.type == "VIEW_3D":
                    area.tag_redraw()
    return 0.1


def register():
    global _draw_handle
    _draw_handle = bpy.types.SpaceView3D.draw_handler_add(_draw, (), "WINDOW", "POST_PIXEL")
    bpy.app.handlers.depsgraph_update_post.append(_on_depsgraph_update)
    bpy.app.timers.register(_poll_redraw, first_interval=0.1, persistent=True)


def unregister():
    global _draw_handle
    if _draw_handle is not None:
        bpy.types.SpaceView3D.draw_handler_remove(_draw_handle, "WINDOW")
        _draw_handle = None
    while _on_depsgraph_update in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.remove(_on_depsgraph_update)
    if bpy.app.timers.is_registered(_poll_redraw):
        bpy.app.timers.unregister(_poll_redraw)
    with _state.lock:
        _state.stop = True
        _state.generation += 1
        _state.wake.notify_all()
    if _state.thread is not None:
        _state.thread.join(timeout=10)
        _state.thread = None
    _state.textures.clear()
    _state.done.clear()
    _state.keys.clear()
    _state.exported = None
    _state.dirty = True
