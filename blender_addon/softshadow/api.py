# What pipelines and the add-on's own buttons call: passes as numpy, and the per-frame EXR.
# SPDX-License-Identifier: GPL-3.0-or-later

import bpy

from . import (cancel, compositor, frame_ranges, mesh_cache, native, output_paths, pass_file_target, passes,
               plain_text, replace, scene_export)


def _evaluated_depsgraph(scene, depsgraph=None):
    if depsgraph is not None:
        return depsgraph
    return _layer_depsgraph(scene, context_view_layer(scene))


def context_view_layer(scene):
    """The view layer a call means when it names none: the window's, for the window's scene."""
    return bpy.context.view_layer if bpy.context.scene == scene else scene.view_layers[0]


def _named_view_layer(scene, view_layer):
    """A ViewLayer of `scene` from a name or a ViewLayer (None: the context's)."""
    if view_layer is None:
        return context_view_layer(scene)
    name = view_layer if isinstance(view_layer, str) else view_layer.name
    layer = scene.view_layers.get(name)
    if layer is None:
        raise ValueError("scene '%s' has no view layer '%s' (it has %s)" % (
            scene.name, name, ", ".join("'%s'" % l.name for l in scene.view_layers)))
    return layer


def render_passes(scene, lights=None, methods=None, depsgraph=None, extra_layers=False, final=None,
                  view_layer=None):
    """Soft-shadow passes of `scene`'s current frame from its camera at its render resolution.

    lights: None (every shadow-casting light whose pass is enabled), a name or a list of names.
    methods: None (each light's own setting, 'auto' unless set), a method name or a list.
    final: True for the passes a final render writes (each light's Refine Final Renders applies:
    slower, closer to the truth), False for the methods' own passes; None (default): True when
    `methods` is None (the passes equal the render's pass file), False when methods are named.
    view_layer: a view layer or its name (default: the context's, or `depsgraph`'s): its
    collections, their render switches and Indirect Only flags decide what casts and receives,
    as a render of that layer does.
    Returns {(light name, method that ran): float32 array (height, width), row 0 = top}; a
    render border with Crop gives the border's pixels, as the render does.
    Raises native.LibraryUnavailable or native.SoftShadowError for what cannot be done at all,
    ValueError for a view layer the scene lacks; per-light failures are left out and listed in
    `render_passes.last_problems`; each result's
    expected RMSE (for 'auto', or a method whose settings ask "estimate_rmse=1") is in
    `render_passes.last_estimates` and printed.
    """
    if final is None:
        final = methods is None
    if depsgraph is not None and view_layer is None:
        layer = depsgraph.view_layer
    else:
        layer = _named_view_layer(scene, view_layer)
    graph = depsgraph if depsgraph is not None else _layer_depsgraph(scene, layer)
    exported = scene_export.export(graph, scene, mode="RENDER", view_layer=layer, reuse=mesh_cache.render_meshes)
    result = passes.compute(exported, lights=lights, methods=methods, extra_layers=extra_layers,
                            only_enabled=lights is None, final=final)
    render_passes.last_problems = list(result.problems)
    render_passes.last_chosen = dict(result.chosen)
    render_passes.last_estimates = dict(result.estimates)
    for problem in result.problems:
        plain_text.log(problem)
    for (light, method), rmse in sorted(result.estimates.items()):
        plain_text.log("%s with %s: estimated RMSE %.4f" % (light, method, rmse))
    return result.arrays


render_passes.last_problems = []
render_passes.last_chosen = {}
render_passes.last_estimates = {}  # (light name, method that ran) -> expected RMSE against the reference


def rendering_view_layers(scene):
    """The view layers a render of `scene` renders (only the active one with 'Render Single Layer')."""
    if scene.render.use_single_layer:
        return [context_view_layer(scene)]
    # (EEVEE Replace's helper layers render too, but need no passes of their own)
    return [layer for layer in scene.view_layers if layer.use and not replace.is_helper_layer(layer)]


def pass_file_template(scene):
    """The scene's template for pass files, absolute ({scene}, {view_layer}, # for the frame)."""
    template = scene.softshadow.output_path or output_paths.default_template(scene.render.filepath)
    return bpy.path.abspath(template)


def frame_exr_path(scene, frame=None, view_layer=None, light=None):
    """The pass file of one frame and view layer (default: the current frame, the context's
    layer); with `light`, the file of that light's passes alone (write_pass_files)."""
    frame = scene.frame_current if frame is None else frame
    if view_layer is None:
        view_layer = context_view_layer(scene)
    return output_paths.expand(pass_file_template(scene), scene.name, view_layer.name, frame, light)


def _layer_depsgraph(scene, view_layer):
    if bpy.context.scene == scene and bpy.context.view_layer == view_layer:
        return bpy.context.evaluated_depsgraph_get()
    graph = view_layer.depsgraph
    graph.update()
    return graph


def _remove_stale(path):
    """The frame's old pass file goes before it is recomputed: a failure leaves no file, never
    an earlier run's shadow."""
    pass_file_target.remove_old(path)


def render_frame(scene, depsgraph=None, progress=None, view_layer=None):
    """Computes one view layer's passes at the current frame, writes its EXR and refreshes the
    compositor node. The frame's old file is removed first.

    Returns (exr path or '', problems, chosen methods). Never leaves a half-written file."""
    return _render_layer(scene, view_layer, depsgraph, progress)[:3]


def _render_layer(scene, view_layer, depsgraph=None, progress=None, light=None):
    """One view layer's pass file at the current frame: every enabled light's passes, or with
    `light` that light's alone in a file of its own (the compositor keeps reading the full file)."""
    if view_layer is None:
        view_layer = depsgraph.view_layer if depsgraph is not None else context_view_layer(scene)
    target = frame_exr_path(scene, view_layer=view_layer, light=light)
    try:
        pass_file_target.prepare(target)
    except native.SoftShadowError as exc:
        return "", [str(exc)], {}, []
    graph = depsgraph if depsgraph is not None else _layer_depsgraph(scene, view_layer)
    exported = scene_export.export(graph, scene, mode="RENDER", view_layer=view_layer,
                                   reuse=mesh_cache.render_meshes)
    result = passes.compute(exported, lights=None if light is None else [light],
                            extra_layers=scene.softshadow.extra_layers, keep_results=True,
                            progress=progress, final=True)
    path = ""
    try:
        if result.results:
            try:
                passes.write_exr(result, target)
                path = target
            except (OSError, native.SoftShadowError) as exc:
                result.problems.append("cannot write the pass file %s: %s" % (target, exc))
        elif not result.problems:
            result.problems.append("no light casts a soft-shadow pass (enable one in the light's properties)"
                                   if light is None else "light '%s' casts no shadow" % light)
    finally:
        result.close()
    if path and light is None and _is_compositor_layer(scene, view_layer):
        problem = compositor.refresh(scene, path)
        if problem:
            result.problems.append(problem)
    return path, result.problems, result.chosen, result.failed_lights


def compositor_view_layer(scene):
    """The view layer whose passes the compositor's Image node reads: the first that renders."""
    layers = rendering_view_layers(scene)
    return layers[0] if layers else scene.view_layers[0]


def _is_compositor_layer(scene, view_layer):
    return compositor_view_layer(scene) == view_layer


def remove_frame_files(scene):
    """Removes the current frame's pass file of every rendering view layer."""
    for layer in rendering_view_layers(scene):
        _remove_stale(frame_exr_path(scene, view_layer=layer))


def render_frame_layers(scene, light=None):
    """Every rendering view layer's passes at the current frame, as the render handler needs
    them: [(view layer name, path or '', problems, chosen, failed lights)]. With `light`, that
    light's passes alone, in files of their own."""
    layers = rendering_view_layers(scene)
    problem = output_paths.template_problem(pass_file_template(scene), len(layers))
    if problem:
        return [(layer.name, "", [problem], {}, []) for layer in layers]
    try:
        return [(layer.name,) + tuple(_render_layer(scene, layer, progress=cancel.progress, light=light))
                for layer in layers]
    except native.SoftShadowError as exc:
        if exc.cancelled and cancel.requested():
            raise native.SoftShadowError(exc.status, "the passes were stopped: %s" % cancel.requested())
        raise


def failure_causes(layers):
    """Why a frame's passes failed, from {view layer: (path, problems, chosen, failed lights)}:
    no file, or a light that got no pass. [] when the frame's passes are complete."""
    causes = []
    for name, (path, problems, _chosen, failed) in layers.items():
        where = "view layer '%s': " % name if name else ""
        if not path:
            causes.append(where + ("; ".join(problems) or "no pass file was written"))
        elif failed:
            causes.append(where + "no pass for light(s) %s: %s" % (", ".join(failed), "; ".join(problems)))
    return causes


class PassesFailed(RuntimeError):
    """Some frames of write_pass_files got no complete pass file; the message names each."""


def write_pass_files(scene, frames, lights=None):
    """Only the passes, nothing rendered: for each frame, each rendering view layer's pass file
    as a render of that frame writes it (a compositor can iterate on shadows without re-rendering).

    frames: a range such as '1-12', '3, 5-7' or '1..4', or frame numbers.
    lights: None (every light whose pass is enabled: the render's own files), or light names:
    each light's passes in a file of its own (its name before the frame number), so that farm
    tasks sharing one frame's lights never write the same file.
    Every frame is tried; returns [(frame, view layer name, path)] of the files written, or
    raises PassesFailed naming each frame whose passes failed (ValueError for a bad range,
    native.LibraryUnavailable without the library). The scene is left at its current frame."""
    wanted = frame_ranges.parse(frames)
    names = [None] if lights is None else ([lights] if isinstance(lights, str) else list(lights))
    if not native.available():
        raise native.LibraryUnavailable(native.status()["error"])
    written, causes = [], []
    original = scene.frame_current
    try:
        for frame in wanted:
            scene.frame_set(frame)
            for light in names:
                layers = {row[0]: row[1:] for row in render_frame_layers(scene, light)}
                written += [(frame, name, row[0]) for name, row in layers.items() if row[0]]
                for cause in failure_causes(layers):
                    causes.append("frame %d: %s" % (frame, cause))
    finally:
        scene.frame_set(original)
    for frame, name, path in written:
        plain_text.log("frame %d: wrote %s" % (frame, path))
    if causes:
        raise PassesFailed("the passes failed: " + " | ".join(causes))
    return written


def export_scene_file(scene, path, depsgraph=None):
    """Writes the scene file the CLI reads (`softshadow render FILE`). Returns problems."""
    graph = _evaluated_depsgraph(scene, depsgraph)
    exported = scene_export.export(graph, scene, mode="RENDER")
    live = passes.LiveScene()  # the scene a render builds, so the CLI renders the same pixels
    try:
        live.rebuild(exported)
        try:
            live.set_camera(exported.camera)
        except native.SoftShadowError as exc:
            live.problems.append("camera: %s" % exc)
        live.scene.save(path)
    finally:
        live.close()
    return exported.problems + live.problems
