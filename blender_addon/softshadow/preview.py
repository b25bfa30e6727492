# How the 3D viewport shows a live soft-shadow preview: export on change, render off-thread, draw.
# SPDX-License-Identifier: GPL-3.0-or-later
"""The main thread exports what changed (from depsgraph.updates of edits and frame changes: only
the objects an edit or the animation touched, a moved object as its matrix alone) and reads each
viewport's view in its draw callback; a worker thread applies those edits to the native scenes
kept alive for the preview
(so the library keeps every unchanged mesh's GPU buffers and every unchanged light's shadow maps)
and renders at reduced resolution through the library (which releases the GIL). Each request is
rendered twice, progressively: a coarse image (COARSE_DIVISOR times fewer pixels in each axis) that
the viewport draws scaled up at once, then the full one that replaces it. The two sizes are two
native scenes fed the same edits, so each keeps its own camera pass and neither is redrawn whole
for the other's resolution. While the scene and the view stay as they are, the full image is then
refined: the same GL pass with refinement on, whose rays re-trace the pixels the pass is unsure of
in REFINE_ROUNDS rounds, each drawn as it lands (deterministic sampling, the uncertain pixels'
largest corrections first, the check of the others after them, so the image gets closer to the
truth; the last round is the final render's refined pass). A newer request cancels the running
render, coarse, full or refined, through the progress and round callbacks (within 50 ms: the
library polls them while it traces). A viewport always draws the last image it received until a
newer one lands (an edit, a new view or a failed render never blanks it), and says in its corner
what the preview is doing. Images are drawn with the `gpu` module only (no bgl), as black with alpha 1 - V."""
import itertools
import threading

import blf
import bpy
import gpu
import numpy as np
from gpu_extras.presets import draw_texture_2d

from . import app_handlers, compat, mesh_cache, native, passes, plain_text, scene_export

PREVIEW_OPACITY = 0.75
COARSE_DIVISOR = 4    # the coarse image's width and height are the full one's divided by this
# The coarse image keeps the full one's texels per pixel where that pays: occlusion textures'
# long side shrinks with its pixels, from the library's default 512
# (docs/methods/occlusion_textures.md; the slicing draw, light-side, would otherwise cost the
# coarse image what it costs the full one). Shadow maps keep their size: at a quarter of it
# (512) the test scene's coarse image moved from the full one by 0.014 in mean alpha (0.001 at
# 2048), and shadow_map and pcss are cheap in the coarse image already. `auto` renders its
# choice with that method's defaults.
COARSE_SETTINGS = {"occlusion_textures": "resolution=%d" % (512 // COARSE_DIVISOR)}
RECORD_LENGTH = 64    # entries kept in _State.delivered and _State.cancelled
# The stages of one request, in the order they are delivered: each image is closer to the truth.
STAGES = ("coarse", "full", "refined")
# The refined image comes in rounds, drawn as they land: shares of the uncertain pixels traced
# (the largest corrections first), then the check of the pixels the GL pass called certain and
# those it contradicts; the last is the final render's refined pass.
REFINE_ROUNDS = 4


def fast_methods():
    """The library's methods fast enough to preview: all but the ray-traced reference."""
    return tuple(m for m in native.method_names() if m != "reference")


class AutoChoices:
    """`auto`'s measured choice per light: the method its sparse check picked (the same choice a
    render makes) in the refined stage, which the coarse, full and refined images of later
    requests render by name while no edit touches the light or any object but lights (an orbit
    or another light's edit keeps it; a move of any mesh, its casters among them, measures
    again). Until a light has one its coarse and full images take auto's rule by the light's
    shape. Worker only; `measured` counts the measurements."""

    def __init__(self):
        self.methods = {}
        self.measured = 0

    def forget(self, edits):
        for edit in edits:
            lights = {light["name"] for light in edit[1].lights} if edit[0] == "objects" else set()
            if edit[0] == "full" or not set(edit[2]) <= lights:
                self.methods.clear()
            for name in lights:
                self.methods.pop(name, None)


class _State:
    def __init__(self):
        self.lock = threading.Lock()
        self.wake = threading.Condition(self.lock)
        self.generation = 0         # bumped by every new request; older work is stale
        self.request = None         # (generation, key, camera)
        self.done = {}              # key -> (generation, delivery_order, rgba float32 (h, w, 4))
        self.edits = []             # exports not yet handed to the worker, oldest first (under lock)
        self.live = passes.LiveScene()    # the worker's scene for the full image
        self.coarse = passes.LiveScene()  # the worker's scene for the coarse image
        self.delivered = []         # (generation, (width, height), stage_label) of each image handed over, oldest first
        self.cancelled = []         # (generation, (width, height)) of each render a newer request stopped
        self.full = True            # the next edit is a full export (object set changed, start)
        self.changed = set()        # objects an update touched since the last export
        self.geometry = set()       # of those, the ones whose mesh data changed
        self.object_names = frozenset()
        self.keys = {}              # region pointer -> key last asked for
        self.textures = {}          # region pointer -> ((generation, order), GPUTexture): the last image drawn
        self.thread = None
        self.stop = False
        self.fresh = False          # a result arrived: redraw the viewports
        self.error = ""
        self.status = ""            # what the worker does now, for the viewport's corner
        self.choices = AutoChoices()  # auto's measured choices, the worker's


_state = _State()
_draw_handle = None


def apply_edits(live, edits):
    """Brings the worker's scene up to date: ("full", exported) or ("objects", partial, names)."""
    for edit in edits:
        if edit[0] == "full":
            with live.lock:
                live.rebuild(edit[1])
        else:
            live.apply(edit[1], edit[2])


def _render_job(live, edits, camera, cancelled, coarse=False):
    """Product of every previewed light's V, as an RGBA overlay (_render_lights)."""
    return overlay(_render_lights(live, edits, camera, cancelled, coarse=coarse), camera)


def _render_lights(live, edits, camera, cancelled, coarse=False, refine=False, progress=None, shown=None,
                   landed=None, choices=None):
    """{light name: V} of every previewed light. Runs on the worker.
    coarse: the methods' coarse settings (COARSE_SETTINGS); refine: each light's GL pass refined
    with rays in REFINE_ROUNDS rounds, and after each round but a light's last, landed({light
    name: V}) hears the lights as they are then: those refined so far, the light in its rounds, the
    others as in `shown` (the full image's V). progress(fraction) hears how far the lights are (with
    refine, by the rounds landed). choices (AutoChoices): an auto light renders its kept choice, and
    the refined stage measures and keeps one where it has none."""
    apply_edits(live, edits)
    with live.lock:
        if live.scene is None:
            raise RuntimeError("the preview scene could not be built")
        live.set_camera(camera)
        scene, indices = live.scene, live.light_indices()
        lights = [light for light in live.lights if light["name"] in indices
                  and light.get("options", {}).get("enabled", True) and light["cast_shadows"]]
        vs = dict(shown or {})
        for done, light in enumerate(lights):
            method = light.get("options", {}).get("method", "auto")
            method = method if method in fast_methods() else "auto"
            measure = method == "auto" and refine and choices is not None
            if method == "auto" and choices is not None and light["name"] in choices.methods:
                method, measure = choices.methods[light["name"]], False
            settings = _stage_settings(method, coarse, measure)

            def heard(fraction, _stage, done=done):
                if progress is not None and not refine:
                    progress((done + min(max(fraction, 0.0), 1.0)) / len(lights))
                return cancelled()

            def round_landed(partial, number, count, done=done, name=light["name"]):
                if cancelled():
                    return True
                vs[name] = partial.layers()["V"]
                if landed is not None:
                    landed(dict(vs))
                if progress is not None:
                    progress((done + number / count) / len(lights))
                return cancelled()

            if refine and progress is not None:
                progress(done / len(lights))
            result = scene.render(indices[light["name"]], method, settings=settings, progress=heard,
                                  refine=refine, refine_rounds=REFINE_ROUNDS if refine else 0,
                                  rounds=round_landed if refine else None)
            try:
                v = result.layers().get("V")
                if measure:
                    choices.methods[light["name"]] = result.method
                    choices.measured += 1
            finally:
                result.close()
            if v is not None:
                vs[light["name"]] = v
        return {light["name"]: vs[light["name"]] for light in lights if light["name"] in vs}


def overlay(vs, camera):
    """The RGBA overlay of the lights' V (their product), bottom row first for a texture."""
    shade = np.ones((camera["height"], camera["width"]), np.float32)
    for v in vs.values():
        if v.shape == shade.shape:
            shade *= np.clip(v, 0.0, 1.0)
    rgba = np.zeros(shade.shape + (4,), np.float32)
    rgba[..., 3] = PREVIEW_OPACITY * (1.0 - shade)
    return np.ascontiguousarray(np.flipud(rgba))  # textures start at the bottom row


def _stage_settings(method, coarse, measure=False):
    """The settings string of one light's render in a stage. The coarse and full images cannot
    wait for auto to render every candidate: without a measured choice (measure, the refined
    stage's) auto takes its rule by the light's shape (docs/methods/README.md)."""
    if method == "auto":
        parts = [] if measure else ["check_pixels=0"]
    else:
        parts = [COARSE_SETTINGS[method]] if coarse and method in COARSE_SETTINGS else []
    return ";".join(parts) or None


def coarse_camera(camera):
    """The camera of the coarse image: the same view with fewer pixels."""
    return dict(camera, width=max(1, camera["width"] // COARSE_DIVISOR),
                height=max(1, camera["height"] // COARSE_DIVISOR))


def _record(entries, entry):
    entries.append(entry)
    del entries[:-RECORD_LENGTH]


def progressive_job(scenes, backlog, edits, camera, cancelled, deliver, stages=STAGES, status=None, choices=None):
    """Renders the coarse image, hands it to deliver(rgba, stage, round), then the full one, then
    the refined one in rounds (round 1, 2, ... as each light's rounds but its last land; the
    finished image as round 0), unless cancelled() turns true first. scenes and backlog are keyed
    "coarse" and "full" (the refined image is the full scene's, refined); backlog holds the edits
    a scene has not yet applied (a cancelled request leaves the scenes it did not reach behind).
    status(text) hears the stage and its progress. choices: the AutoChoices kept across requests
    (None: auto by the light's shape in every stage). Returns the (width, height) of the render a
    cancellation stopped, else None."""
    for scene_key in ("coarse", "full"):
        backlog[scene_key].extend(edits)
    if choices is not None:
        choices.forget(edits)
    full_vs = {}
    for stage in stages:
        scene_key = "coarse" if stage == "coarse" else "full"
        view = coarse_camera(camera) if stage == "coarse" else camera
        size = (view["width"], view["height"])
        if cancelled():
            return size
        pending, backlog[scene_key] = backlog[scene_key], []
        numbers = itertools.count(1)

        def heard(fraction, stage=stage):
            if status is not None:
                status(stage_status(stage, fraction))

        def landed(vs, view=view, numbers=numbers):
            deliver(overlay(vs, view), "refined", next(numbers))

        heard(0.0)
        try:
            vs = _render_lights(scenes[scene_key], pending, view, cancelled, coarse=stage == "coarse",
                                refine=stage == "refined", progress=heard, shown=full_vs, landed=landed,
                                choices=choices)
        except native.SoftShadowError as exc:
            if exc.cancelled:
                return size
            raise
        if stage == "full":
            full_vs = vs
        deliver(overlay(vs, view), stage, 0)
    if status is not None:
        status(stage_status("done", 1.0))
    return None


def stage_label(stage, round_):
    """How a delivery is recorded: the stage, with its round for the refined image's rounds."""
    return "%s %d" % (stage, round_) if round_ else stage


def delivery_order(stage, round_):
    """Sorts one request's deliveries: by stage, the refined rounds in order, the last (0) last."""
    return (STAGES.index(stage), round_ if round_ else 1 << 30)


def stage_status(stage, fraction):
    """The viewport's words for what the preview is doing."""
    if stage == "done":
        return "soft shadows: refined"
    if stage == "refined":
        return "soft shadows: refining %d %%" % int(round(100 * fraction))
    return "soft shadows: %s image" % stage


def _worker():
    state = _state
    scenes = {"coarse": state.coarse, "full": state.live}
    backlog = {"coarse": [], "full": []}
    choices = state.choices
    while True:
        with state.lock:
            while state.request is None and not state.stop:
                state.wake.wait()
            if state.stop:
                return
            generation, key, camera = state.request
            state.request = None
            edits, state.edits = state.edits, []

        def cancelled(generation=generation):
            return state.stop or state.generation != generation

        def deliver(rgba, stage, round_, generation=generation, key=key):
            with state.lock:
                if state.generation == generation:
                    state.done[key] = (generation, delivery_order(stage, round_), rgba)
                    _record(state.delivered, (generation, (rgba.shape[1], rgba.shape[0]), stage_label(stage, round_)))
                    state.error = ""
                    state.fresh = True

        def status(text, generation=generation):
            if state.generation == generation:
                state.status = text
                state.fresh = True

        try:
            stopped = progressive_job(scenes, backlog, edits, camera, cancelled, deliver, status=status,
                                      choices=choices)
            if stopped is not None:
                with state.lock:
                    _record(state.cancelled, (generation, stopped))
        except native.SoftShadowError as exc:
            state.error = str(exc)
            state.fresh = True
            if any(live.scene is None for live in scenes.values()):
                state.full = True  # an edit failed and dropped a scene: export it whole
        except Exception as exc:  # the preview must never take Blender down
            state.error = "%s: %s" % (type(exc).__name__, exc)
            state.fresh = True
            for live in scenes.values():
                live.close()
            state.full = True


def full_image_delivered():
    """Whether the newest request's full image was handed over (after its coarse one)."""
    with _state.lock:
        return any(g == _state.generation and stage == "full" for g, _size, stage in _state.delivered)


def refined_image_delivered():
    """Whether the newest request's refined image was handed over (its last)."""
    with _state.lock:
        return any(g == _state.generation and stage == "refined" for g, _size, stage in _state.delivered)


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


def export_edit(depsgraph, scene):
    """The edit the preview's scene needs for what changed since the last call, or None: a full
    export when the object set changed, else the changed objects alone. Main thread."""
    identity = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
    placeholder = scene_export.camera_values(identity, identity, 8, 8)
    names = frozenset(obj.name for obj in scene.objects)  # an added, removed or renamed object
    if _state.full or names != _state.object_names:
        exported = scene_export.export(depsgraph, scene, mode="VIEWPORT", camera=placeholder)
        edit = ("full", exported)
    elif _state.changed:
        changed, geometry = set(_state.changed), set(_state.geometry)
        partial = scene_export.export(depsgraph, scene, mode="VIEWPORT", camera=placeholder,
                                      only=changed, geometry=geometry)
        edit = ("objects", partial, changed)
    else:
        return None
    _state.full = False
    _state.object_names = names
    _state.changed.clear()
    _state.geometry.clear()
    return edit


def _submit(context, region, rv3d):
    scene = context.scene
    edit = export_edit(context.evaluated_depsgraph_get(), scene)
    if edit is not None:
        with _state.lock:
            _state.edits.append(edit)
        _state.done.clear()
        _state.keys.clear()
    camera, key = _view_camera(region, rv3d, scene.softshadow.preview_scale)
    if _state.keys.get(region.as_pointer()) == key:
        return key
    _state.keys[region.as_pointer()] = key
    request_render(key, camera)
    return key


def request_render(key, camera):
    """Asks the worker for the image of `camera` (after the edits queued so far), cancelling
    whatever it renders now. Returns the request's generation."""
    with _state.lock:
        _state.generation += 1
        _state.request = (_state.generation, key, camera)
        _state.wake.notify()
        generation = _state.generation
    _ensure_worker()
    return generation


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
        cached = shown_image(_state.textures, region.as_pointer(), _state.done.get(key),
                             lambda rgba: _texture(rgba))
        if cached is not None:
            gpu.state.blend_set("ALPHA")
            draw_texture_2d(cached[1], (0, 0), region.width, region.height)  # the coarse one scaled up
            gpu.state.blend_set("NONE")
        _draw_status(status_line(_state.status, _state.error))
    except Exception as exc:
        _state.error = "%s: %s" % (type(exc).__name__, exc)


def shown_image(textures, region_key, done, make_texture):
    """The image a viewport draws: the newest one delivered for its request, else the last one it
    drew (an edit, a new view or a failed render keeps it until a newer image lands). textures:
    region -> ((generation, order), texture); done: (generation, order, rgba) or None."""
    cached = textures.get(region_key)
    if done is not None:
        generation, order, rgba = done
        if cached is None or cached[0] != (generation, order):
            cached = ((generation, order), make_texture(rgba))
            textures[region_key] = cached
    return cached


def _texture(rgba):
    h, w = rgba.shape[:2]
    buffer = gpu.types.Buffer("FLOAT", w * h * 4, rgba.reshape(-1))
    return gpu.types.GPUTexture((w, h), format="RGBA16F", data=buffer)


def status_line(status, error):
    """The corner text: the failure first (the image stays the last good one), else the stage."""
    if error:
        return "soft shadows: failed, showing the last image: %s" % error.splitlines()[0][:160]
    return status


def _draw_status(text):
    if not text:
        return
    font = 0
    compat.blf_size(blf, bpy.app, font, 12)
    blf.color(font, 1.0, 1.0, 1.0, 0.9)
    blf.position(font, 12, 12, 0)
    blf.draw(font, plain_text.plain(text))


def note_updates(scene, updates):
    """Records which objects depsgraph.updates touched and how; what cannot be traced to
    objects (collections, materials, instancers) asks for a full export."""
    for update in updates:
        block = getattr(update.id, "original", update.id)
        if isinstance(block, bpy.types.Object):
            if block.is_instancer or block.instance_type != "NONE":
                _state.full = True
                continue
            _state.changed.add(block.name)
            if update.is_updated_geometry or not update.is_updated_transform:
                _state.geometry.add(block.name)
        elif isinstance(block, bpy.types.Light):
            for obj in scene.objects:
                if obj.data == block:
                    _state.changed.add(obj.name)
        elif isinstance(block, (bpy.types.Collection, bpy.types.Material)):
            _state.full = True


@bpy.app.handlers.persistent
def _on_depsgraph_update(scene, depsgraph=None, *_args):
    if depsgraph is None:
        _state.full = True
        return
    note_updates(scene, depsgraph.updates)


@bpy.app.handlers.persistent
def _on_frame_change(scene, depsgraph=None, *_args):
    """A frame change re-evaluates what is animated: the same updates as an edit."""
    if depsgraph is None or mesh_cache.unreported_frame_edits():
        _state.full = True
        return
    note_updates(scene, depsgraph.updates)


def _poll_redraw():
    """Main-thread timer: redraw the viewports when the worker has finished an image."""
    if _state.fresh:
        _state.fresh = False
        for window in getattr(bpy.context.window_manager, "windows", []):
            for area in window.screen.areas:
                if area.type == "VIEW_3D":
                    area.tag_redraw()
    return 0.1


_HANDLERS = (("depsgraph_update_post", _on_depsgraph_update), ("frame_change_post", _on_frame_change))


def register():
    global _draw_handle
    _draw_handle = bpy.types.SpaceView3D.draw_handler_add(_draw, (), "WINDOW", "POST_PIXEL")
    app_handlers.attach(_HANDLERS)
    bpy.app.timers.register(_poll_redraw, first_interval=0.1, persistent=True)


def unregister():
    global _draw_handle
    if _draw_handle is not None:
        bpy.types.SpaceView3D.draw_handler_remove(_draw_handle, "WINDOW")
        _draw_handle = None
    app_handlers.detach(_HANDLERS)
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
    _state.edits = []
    for live in (_state.coarse, _state.live):
        with live.lock:  # a worker that outlived the join above still holds it while rendering
            live.close()
    _state.full = True
    passes.release()
