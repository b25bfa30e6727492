# How one frame's soft-shadow passes are computed: export, per-light render, EXR, arrays.
# SPDX-License-Identifier: GPL-3.0-or-later
import os
from dataclasses import dataclass, field

from . import native, scene_export


@dataclass
class FrameResult:
    arrays: dict = field(default_factory=dict)    # (light name, method) -> (H, W) float32
    results: list = field(default_factory=list)   # native.Result, for ss_write_exr
    chosen: dict = field(default_factory=dict)    # light name -> the methods that ran, 'auto' resolved ("a, b")
    estimates: dict = field(default_factory=dict)  # (light name, method that ran) -> expected RMSE
    problems: list = field(default_factory=list)
    failed_lights: list = field(default_factory=list)  # wanted lights that got no pass
    view_layer: str = "ViewLayer"
    exr_path: str = ""

    def close(self):
        for result in self.results:
            result.close()
        self.results = []


def build_native_scene(exported):
    """ExportedScene -> (native.Scene, {light name: index}); failures go to exported.problems."""
    scene = native.Scene()
    scene.set_view_layer(exported.view_layer)
    for mesh in exported.meshes:
        try:
            scene.add_mesh(mesh["name"], mesh["vertices"], mesh["triangles"], mesh["flags"])
        except native.SoftShadowError as exc:
            exported.problems.append("object '%s' skipped: %s" % (mesh["name"], exc))
    indices = {}
    for light in exported.lights:
        problem = scene_export.light_problem(light)
        if problem:
            exported.problems.append(problem)
            continue
        try:
            indices[light["name"]] = scene.add_light(light)
        except native.SoftShadowError as exc:
            exported.problems.append("light '%s' gets no pass: %s" % (light["name"], exc))
    if exported.camera is not None:
        try:
            scene.set_camera(exported.camera)
        except native.SoftShadowError as exc:
            exported.problems.append("camera: %s" % exc)
            exported.camera = None
    return scene, indices


def _wanted(exported, lights, methods, only_enabled):
    """[(light dict, [method names])] in scene order."""
    if isinstance(lights, str):
        lights = [lights]
    if isinstance(methods, str):
        methods = [methods]
    chosen = []
    names = {l["name"] for l in exported.lights}
    for name in lights or ():
        if name not in names:
            exported.problems.append("no light named '%s' in the scene" % name)
    for light in exported.lights:
        options = light.get("options", {})
        if lights is not None and light["name"] not in lights:
            continue
        if not light["cast_shadows"]:
            continue  # a light with shadows off gets no pass
        if lights is None and only_enabled and not options.get("enabled", True):
            continue
        chosen.append((light, list(methods) if methods else [options.get("method", "auto") or "auto"]))
    return chosen


def compute(exported, lights=None, methods=None, extra_layers=False, only_enabled=True,
            keep_results=False, progress=None):
    """Renders every wanted (light, method). Failures become problems; the rest is produced."""
    out = FrameResult(problems=exported.problems, view_layer=exported.view_layer)
    if exported.camera is None:
        return out
    scene, indices = build_native_scene(exported)
    if exported.camera is None:
        scene.close()
        return out
    try:
        jobs = [(l, m) for l, ms in _wanted(exported, lights, methods, only_enabled) for m in ms]
        for number, (light, method) in enumerate(jobs):
            if light["name"] not in indices:
                out.failed_lights.append(light["name"])
                continue
            options = light.get("options", {})

            def step(fraction, stage, number=number):
                return progress((number + fraction) / max(1, len(jobs)), stage) if progress else False

            try:
                result = scene.render(indices[light["name"]], method, samples=options.get("samples", 0),
                                      extra_layers=extra_layers, settings=options.get("settings") or None,
                                      progress=step if progress else None)
            except native.SoftShadowError as exc:
                if exc.cancelled:
                    raise
                out.problems.append("light '%s' with %s: %s" % (light["name"], method, exc))
                out.failed_lights.append(light["name"])
                continue
            ran = result.method
            # Arrays are keyed by the method that ran, so 'auto' resolving to a method also asked
            # for gives one array; the EXR names passes by the method asked for ('<light>_auto'
            # stays wired whatever auto picks), so there both results are kept.
            if (light["name"], ran) not in out.arrays:
                ran_before = out.chosen.get(light["name"])
                out.chosen[light["name"]] = ran if not ran_before else ran_before + ", " + ran
                if result.estimated_rmse is not None:
                    out.estimates[(light["name"], ran)] = result.estimated_rmse
                layers = result.layers()
                if "V" in layers:
                    out.arrays[(light["name"], ran)] = layers["V"]
            if keep_results:
                out.results.append(result)
            else:
                result.close()
    finally:
        scene.close()
    return out


def write_exr(frame_result, path):
    """One multilayer EXR for the frame's results (written atomically by the library)."""
    if not frame_result.results:
        return False
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    native.write_exr(path, frame_result.view_layer, frame_result.results)
    frame_result.exr_path = path
    return True
