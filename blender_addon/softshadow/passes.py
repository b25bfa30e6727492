# How one frame's soft-shadow passes are computed: export, per-light render, EXR, arrays.
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import threading
from dataclasses import dataclass, field

import numpy as np

from . import compat, native, scene_export


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


def send_light_links(scene, lights, meshes):
    """Sends the light and shadow linking (Blender 4.0+) of `lights` ({library index: light
    dict}) as mesh indices of `meshes` (the dicts in the library's order); every light is sent,
    those without links as every mesh (the library keeps a light's caches when its links come
    back the same)."""
    links = {index: light.get("links") or (None, None) for index, light in lights.items()}
    receiver_objects = compat.link_objects(meshes, [r for r, _ in links.values()])
    blocker_objects = compat.link_objects(meshes, [b for _, b in links.values()])
    for index, (receivers, blockers) in links.items():
        scene.set_light_links(index, compat.linked_meshes(blockers, blocker_objects),
                              compat.linked_meshes(receivers, receiver_objects))


class LiveScene:
    """The add-on's one builder of native scenes (renders, the preview, exported scene files),
    kept alive across renders and fed only what changed, so that the library's caches (per mesh
    shape: GPU buffers; per light: shadow maps) survive from call to call. Meshes are sent in
    object space with their matrix, so a move sends 16 floats and the library draws the mesh it
    has with the new matrix; a scene built afresh from the same export renders the same numbers,
    and so does its scene file in the CLI. An object the library refuses is remembered as it was
    (with the message that names it) and not sent again until it changes, so one bad object does
    not make every sync a rebuild. A failed edit drops the scene: the next sync rebuilds it."""

    def __init__(self):
        self.lock = threading.Lock()
        self.scene = None
        self.meshes = []      # mesh dicts as sent, in native index order
        self.lights = []      # light dicts as sent, in native index order
        self.camera = None
        self.problems = []
        self.refused = {}     # name: (mesh or light dict as last exported, the problem naming it)

    def close(self):
        if self.scene is not None:
            self.scene.close()
        self.scene, self.meshes, self.lights, self.camera = None, [], [], None

    def light_indices(self):
        return {light["name"]: i for i, light in enumerate(self.lights)}

    def _add_mesh(self, mesh):
        index = self.scene.add_mesh(mesh["name"], mesh["local"], mesh["triangles"], mesh["flags"], mesh["matrix"])
        if mesh.get("alpha") is not None:
            try:
                self.scene.set_mesh_materials(index, mesh["alpha"])
            except native.SoftShadowError:
                self.scene.remove_mesh(index)  # keeps the native indices equal to self.meshes'
                raise
        self.meshes.append(mesh)

    def _add_light(self, light):
        self.scene.add_light(light)
        self.lights.append(light)

    _MESH_REFUSED = "object '%s' skipped: %s"
    _LIGHT_REFUSED = "light '%s' gets no pass: %s"

    def _try_add_mesh(self, mesh):
        self._try_add(self._add_mesh, mesh, self._MESH_REFUSED)

    def _try_add_light(self, light):
        self._try_add(self._add_light, light, self._LIGHT_REFUSED)

    def _try_add(self, add, item, problem):
        try:
            add(item)
            self._forget_refusal(item["name"])
        except native.SoftShadowError as exc:
            self._refuse(item, problem % (item["name"], exc))

    def _refuse(self, item, problem):
        self._forget_refusal(item["name"])
        self.refused[item["name"]] = (item, problem)
        self.problems.append(problem)

    def _forget_refusal(self, name):
        if name in self.refused:
            problem = self.refused.pop(name)[1]
            self.problems = [p for p in self.problems if p != problem]

    def _replaced(self, replace, index, item, problem):
        """Whether `item` took index's place; where the library refused it, the refusal is
        remembered as for an add (the caller removes the old one)."""
        try:
            replace(index, item)
        except native.SoftShadowError as exc:
            self._refuse(item, problem % (item["name"], exc))
            return False
        self._forget_refusal(item["name"])
        return True

    def _still_refused(self, item):
        """Whether the library refused this very object: sent again, it would fail the same way."""
        old = self.refused.get(item["name"], (None,))[0]
        if old is None or ("triangles" in old) != ("triangles" in item):
            return False
        if "triangles" not in item:
            return self._light_key(old) == self._light_key(item)
        local = old["local"] if item["local"] is None else item["local"]  # a move exports no geometry
        triangles = old["triangles"] if item["triangles"] is None else item["triangles"]
        return (old["flags"] == item["flags"] and np.array_equal(old["matrix"], item["matrix"])
                and (local is old["local"] or np.array_equal(local, old["local"]))
                and (triangles is old["triangles"] or np.array_equal(triangles, old["triangles"]))
                and (item["local"] is None or scene_export.same_alpha(old.get("alpha"), item.get("alpha"))))

    def rebuild(self, exported):
        self.close()
        self.problems, self.refused = [], {}
        self.scene = native.Scene()
        self.scene.set_view_layer(exported.view_layer)
        for mesh in exported.meshes:
            self._try_add_mesh(mesh)
        for light in exported.lights:
            self._try_add_light(light)
        self._send_links()

    def _replace_mesh(self, index, mesh):
        old = self.meshes[index]
        same_geometry = old["flags"] == mesh["flags"] and (
            # arrays an export took from its mesh cache are the very ones sent before
            (old["triangles"] is mesh["triangles"] and old["local"] is mesh["local"])
            or (np.array_equal(old["triangles"], mesh["triangles"]) and np.array_equal(old["local"], mesh["local"])))
        if not same_geometry:
            self.scene.update_mesh(index, mesh["local"], mesh["triangles"], mesh["flags"])  # clears materials
        if (mesh.get("alpha") is not None and not same_geometry) or (
                same_geometry and not scene_export.same_alpha(old.get("alpha"), mesh.get("alpha"))):
            self.scene.set_mesh_materials(index, mesh.get("alpha"))
        if not np.array_equal(old["matrix"], mesh["matrix"]):
            self.scene.set_mesh_transform(index, mesh["matrix"])
        self.meshes[index] = mesh

    @staticmethod
    def _light_key(light):
        return {k: (np.asarray(v).tolist() if k == "light_to_world" else v)
                for k, v in light.items() if k not in ("options", "links")}

    def _send_links(self):
        """Every light's links against the meshes as they are now."""
        send_light_links(self.scene, dict(enumerate(self.lights)), self.meshes)

    def _replace_light(self, index, light):
        if self._light_key(self.lights[index]) != self._light_key(light):
            self.scene.update_light(index, light)
        self.lights[index] = light

    def sync(self, exported):
        """Makes the scene equal `exported` (a full export): rebuilt when the set of meshes or
        lights changed, else only the meshes and lights that differ are sent."""
        with self.lock:
            try:
                meshes = [m for m in exported.meshes if not self._still_refused(m)]
                lights = [l for l in exported.lights if not self._still_refused(l)]
                exported_names = {item["name"] for item in exported.meshes + exported.lights}
                if (self.scene is None or [m["name"] for m in self.meshes] != [m["name"] for m in meshes]
                        or [l["name"] for l in self.lights] != [l["name"] for l in lights]
                        or any(name not in exported_names for name in self.refused)
                        or self.scene_view_layer != exported.view_layer):
                    self.rebuild(exported)
                else:
                    try:
                        for index, mesh in enumerate(meshes):
                            self._replace_mesh(index, mesh)
                        for index, light in enumerate(lights):
                            self._replace_light(index, light)
                    except native.SoftShadowError:
                        self.rebuild(exported)  # adds each object anew, remembering the refused ones
                    else:
                        self._send_links()
                self.scene_view_layer = exported.view_layer
                self.set_camera(exported.camera)
            except Exception:
                self.close()
                raise

    scene_view_layer = None

    def apply(self, partial, changed):
        """Applies an export of the `changed` objects alone (scene_export.export(only=...)):
        their meshes and lights are updated, added or (when absent from `partial`) removed."""
        with self.lock:
            try:
                meshes = {m["name"]: m for m in partial.meshes}
                lights = {l["name"]: l for l in partial.lights}
                for name in changed:
                    if name in self.refused and not any(name in found for found in (meshes, lights)):
                        self._forget_refusal(name)  # the refused object is gone
                    index = next((i for i, m in enumerate(self.meshes) if m["name"] == name), None)
                    mesh = meshes.get(name)
                    if mesh is not None and self._still_refused(mesh):
                        mesh = None
                    elif mesh is not None and mesh["local"] is None and name in self.refused:
                        old = self.refused[name][0]  # a refused mesh moved: sent again whole
                        mesh = dict(mesh, local=old["local"], triangles=old["triangles"], alpha=old.get("alpha"))
                    if mesh is not None and mesh["local"] is None and index is not None:
                        mesh = dict(mesh, local=self.meshes[index]["local"], triangles=self.meshes[index]["triangles"],
                                    alpha=self.meshes[index].get("alpha"))
                    if index is None:
                        if mesh is not None and mesh["local"] is not None:
                            self._try_add_mesh(mesh)
                    elif mesh is None or not self._replaced(self._replace_mesh, index, mesh, self._MESH_REFUSED):
                        self.scene.remove_mesh(index)
                        del self.meshes[index]
                    index = next((i for i, l in enumerate(self.lights) if l["name"] == name), None)
                    light = lights.get(name)
                    if light is not None and self._still_refused(light):
                        light = None
                    if index is None:
                        if light is not None:
                            self._try_add_light(light)
                    elif light is None or not self._replaced(self._replace_light, index, light, self._LIGHT_REFUSED):
                        self.scene.remove_light(index)
                        del self.lights[index]
                self._send_links()
            except Exception:
                self.close()
                raise

    def set_camera(self, camera):
        """Sends the camera when it differs from the one the scene has (a resend would redraw
        the camera pass)."""
        if camera is None:
            return
        if self.camera is not None and all(np.array_equal(np.asarray(self.camera[k]), np.asarray(camera[k]))
                                           for k in ("world_to_camera", "projection", "width", "height")):
            return
        self.scene.set_camera(camera)
        self.camera = camera


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


def _refines(options, final):
    """Whether the light's pass is refined: in a final render with its Refine Final Renders on
    (the library leaves the exact reference as it is)."""
    return bool(final and options.get("refine_final"))


# render_passes' scene, kept between calls: the next frame of an animation sends only what moved.
_render_scene = LiveScene()


def release():
    """Frees the scenes kept between calls (unregister)."""
    _render_scene.close()


def compute(exported, lights=None, methods=None, extra_layers=False, only_enabled=True,
            keep_results=False, progress=None, live=None, final=False):
    """Renders every wanted (light, method). Failures become problems; the rest is produced.
    `final`: a final render's passes (the lights' Refine Final Renders applies)."""
    out = FrameResult(problems=exported.problems, view_layer=exported.view_layer)
    if exported.camera is None:
        return out
    live = _render_scene if live is None else live
    try:
        live.sync(exported)
    except native.SoftShadowError as exc:
        exported.problems.append("camera: %s" % exc)
        return out
    exported.problems.extend(live.problems)
    scene, indices = live.scene, live.light_indices()
    with live.lock:
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
                                      refine=_refines(options, final),
                                      progress=step if progress else None)
            except native.SoftShadowError as exc:
                if exc.cancelled:
                    raise
                out.problems.append("light '%s' with %s: %s" % (light["name"], method, exc))
                out.failed_lights.append(light["name"])
                continue
            ran = result.method
            for warning in result.warnings:  # each once, however many lights give it
                if warning not in out.problems:
                    out.problems.append(warning)
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
    return out


def write_exr(frame_result, path):
    """One multilayer EXR for the frame's results (written atomically by the library)."""
    if not frame_result.results:
        return False
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    native.write_exr(path, frame_result.view_layer, frame_result.results)
    frame_result.exr_path = path
    return True
