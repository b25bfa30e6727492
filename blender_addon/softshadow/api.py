# What pipelines and the add-on's own buttons call: passes as numpy, and the per-frame EXR.
# SPDX-License-Identifier: GPL-3.0-or-later
import os

import bpy

from . import compositor, native, passes, scene_export


def _evaluated_depsgraph(scene, depsgraph=None):
    if depsgraph is not None:
        return depsgraph
    if bpy.context.scene == scene:
        return bpy.context.evaluated_depsgraph_get()
    graph = scene.view_layers[0].depsgraph
    graph.update()
    return graph


def render_passes(scene, lights=None, methods=None, depsgraph=None, extra_layers=False):
    """Soft-shadow passes of `scene`'s current frame from its camera at its render resolution.

    lights: None (every shadow-casting light whose pass is enabled), a name or a list of names.
    methods: None (each light's own setting, 'auto' unless set), a method name or a list.
    Returns {(light name, method that ran): float32 array (height, width), row 0 = top}.
    Raises native.LibraryUnavailable or native.SoftShadowError for what cannot be done at all;
    per-light failures are left out and listed in `render_passes.last_problems`.
    """
    graph = _evaluated_depsgraph(scene, depsgraph)
    exported = scene_export.export(graph, scene, mode="RENDER")
    result = passes.compute(exported, lights=lights, methods=methods, extra_layers=extra_layers,
                            only_enabled=lights is None)
    render_passes.last_problems = list(result.problems)
    render_passes.last_chosen = dict(result.chosen)
    for problem in result.problems:
        print("softshadow:", problem)
    return result.arrays


render_passes.last_problems = []
render_passes.last_chosen = {}


def output_directory(scene):
    """Where the frame EXRs go: the scene setting, else the render output's folder."""
    setting = scene.softshadow.output_dir
    if setting:
        return bpy.path.abspath(setting)
    frame_path = scene.render.frame_path(frame=scene.frame_current)
    return os.path.dirname(bpy.path.abspath(frame_path)) or bpy.app.tempdir


def frame_exr_path(scene, frame=None):
    frame = scene.frame_current if frame is None else frame
    return passes.exr_path_for_frame(output_directory(scene), frame)


def render_frame(scene, depsgraph=None, progress=None):
    """Computes the current frame's passes, writes its EXR and refreshes the compositor node.

    Returns (exr path or '', problems, chosen methods). Never leaves a half-written file."""
    graph = _evaluated_depsgraph(scene, depsgraph)
    exported = scene_export.export(graph, scene, mode="RENDER")
    result = passes.compute(exported, extra_layers=scene.softshadow.extra_layers, keep_results=True,
                            progress=progress)
    path = ""
    try:
        if result.results:
            path = frame_exr_path(scene)
            passes.write_exr(result, path)
        elif not result.problems:
            result.problems.append("no light casts a soft-shadow pass (enable one in the light's properties)")
    finally:
        result.close()
    if path:
        compositor.refresh(scene, path)
    return path, result.problems, result.chosen


def export_scene_file(scene, path, depsgraph=None):
    """Writes the scene file the CLI reads (`softshadow render FILE`). Returns problems."""
    graph = _evaluated_depsgraph(scene, depsgraph)
    exported = scene_export.export(graph, scene, mode="RENDER")
    native_scene, _ = passes.build_native_scene(exported)
    try:
        native_scene.save(path)
    finally:
        native_scene.close()
    return exported.problems
