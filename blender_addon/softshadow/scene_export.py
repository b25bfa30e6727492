# How a Blender scene becomes plain arrays for the library: meshes, lights, camera, problems.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Two halves. The top half is pure numpy (no bpy): names, matrices, checks; it is unit-tested
without Blender. The bottom half walks an evaluated depsgraph; it only touches the objects it
is given, so this module never imports bpy itself.
"""
from dataclasses import dataclass, field

import numpy as np

from . import compat, framing

AREA_SHAPES = ("DISK", "ELLIPSE", "SQUARE", "RECTANGLE")
GEOMETRY_TYPES = ("MESH", "CURVE", "SURFACE", "FONT", "META")

# ---------------------------------------------------------------- pure numpy half


@dataclass
class ExportedScene:
    meshes: list = field(default_factory=list)    # dicts: name, local, matrix, triangles, flags, object, instancer
    lights: list = field(default_factory=list)    # dicts: see light_values(), + options, links
    camera: dict = None                           # dict: see camera_values(); None = no camera
    view_layer: str = "ViewLayer"
    problems: list = field(default_factory=list)  # messages for the user's report
    skipped: list = field(default_factory=list)   # names of objects left out on purpose


def column_major(matrix):
    """A 4x4 row-indexed matrix (mathutils or nested lists) -> 16 floats, m[col*4 + row]."""
    rows = np.asarray([list(r) for r in matrix], dtype=np.float64).reshape(4, 4)
    return rows.T.reshape(-1).astype(np.float32)


def normalized_rigid(matrix):
    """A camera matrix with its scale removed (Blender renders from a normalised camera)."""
    m = np.asarray([list(r) for r in matrix], dtype=np.float64).reshape(4, 4).copy()
    for c in range(3):
        length = np.linalg.norm(m[:3, c])
        if length > 0:
            m[:3, c] /= length
    return m


def camera_matrix_problem(name, matrix):
    """Why a camera's world matrix gives no view, or ''. A camera scaled 0 on an axis (or
    flattened by its parents) has no orientation left: Blender renders only the world through
    it, no surface, so there is nothing to shadow."""
    m = normalized_rigid(matrix)
    if not np.all(np.isfinite(m)) or abs(np.linalg.det(m[:3, :3])) < 1e-6:
        return ("camera '%s' is scaled to 0 (or flattened) on an axis: Blender renders no surface "
                "through it, so there are no soft-shadow passes (give it a non-zero scale)" % name)
    return ""


def render_size(resolution_x, resolution_y, percentage):
    """Blender's final pixel size: integer arithmetic as in BKE_render_resolution."""
    return (int(resolution_x) * int(percentage)) // 100, (int(resolution_y) * int(percentage)) // 100


def faceless_problem(name, triangles):
    """Why a Blender object of a geometry type gives no mesh (a message), or None. The library
    takes an empty mesh, which shadows nothing: the user hears why the object does not show.
    Vertices, indices and transforms are the library's to check (LiveScene reports its refusals)."""
    if np.asarray(triangles).size == 0:
        return "object '%s' has no faces: it casts no shadow and was skipped" % name
    return None


def light_values(name, kind, shape, matrix, size=0.0, size_y=0.0, radius=0.0, angle=0.0,
                 spot_size=0.0, spot_blend=0.0, use_shadow=True):
    """A light as the library's ss_light_desc wants it. kind: Blender's light.type."""
    if kind == "AREA":
        light_type = shape if shape in AREA_SHAPES else "SQUARE"
    elif kind in ("POINT", "SPOT", "SUN"):
        light_type = kind
    else:
        raise ValueError("light '%s' has an unknown type %r" % (name, kind))
    return {
        "name": name, "type": light_type, "light_to_world": column_major(matrix),
        "size": float(size), "size_y": float(size_y if light_type in ("ELLIPSE", "RECTANGLE") else size),
        "radius": float(radius), "angle": float(angle), "spot_size": float(spot_size),
        "spot_blend": float(spot_blend), "cast_shadows": bool(use_shadow),
    }


def camera_values(world_to_camera_rows, projection_rows, width, height, pixel_aspect=1.0):
    return {
        "world_to_camera": column_major(world_to_camera_rows),
        "projection": column_major(projection_rows),
        "width": int(width), "height": int(height), "pixel_aspect": float(pixel_aspect),
    }


def same_alpha(a, b):
    """Whether two meshes' material alphas (material_alpha.mesh_alpha's dicts or None) agree."""
    if a is None or b is None:
        return a is b
    if not (np.array_equal(a["uvs"], b["uvs"]) and np.array_equal(a["triangle_material"], b["triangle_material"])
            and len(a["materials"]) == len(b["materials"])):
        return False
    for x, y in zip(a["materials"], b["materials"]):
        if (x["alpha"], x["wrap"], x["closest"]) != (y["alpha"], y["wrap"], y["closest"]):
            return False
        tx, ty = x.get("texture"), y.get("texture")
        if (tx is None) != (ty is None) or (tx is not None and tx is not ty and not np.array_equal(tx, ty)):
            return False
    return True


def unreadable_materials_line(names):
    """The one report line naming the materials whose alpha could not be read."""
    if not names:
        return None
    return ("shadows treat %d material(s) as opaque, their alpha needs shading to know: %s"
            % (len(names), "; ".join(sorted(names))))


def unique_name(name, used):
    """name, or name.001, name.002 ... so every light and mesh name is unique."""
    candidate, n = name, 0
    while candidate in used:
        n += 1
        candidate = "%s.%03d" % (name, n)
    used.add(candidate)
    return candidate


# ---------------------------------------------------------------- depsgraph half


def _render_visible_collections(view_layer):
    """Collections whose objects render: not excluded, not hidden for render, nor a parent."""
    visible = set()

    def walk(layer_collection, parent_visible):
        coll = layer_collection.collection
        ok = parent_visible and not layer_collection.exclude and not coll.hide_render
        if ok:
            visible.add(coll.name)
        for child in layer_collection.children:
            walk(child, ok)

    walk(view_layer.layer_collection, True)
    return visible


def _object_visible(obj, mode, view_layer, render_collections):
    original = obj.original
    if mode == "RENDER":
        if original.hide_render:
            return False
        return any(c.name in render_collections for c in original.users_collection)
    try:
        return original.visible_get(view_layer=view_layer)
    except (TypeError, RuntimeError):
        return original.visible_get()


def rendering_objects(view_layer):
    """The view layer's own objects that a render includes (instances left aside)."""
    collections = _render_visible_collections(view_layer)
    return [obj for obj in view_layer.objects if _object_visible(obj, "RENDER", view_layer, collections)]


def _local_mesh_arrays(obj):
    """(vertices (N,3) float32 local, triangles (M,3) uint32) of an evaluated object."""
    mesh = obj.to_mesh()
    try:
        if mesh is None:
            return np.zeros((0, 3), np.float32), np.zeros((0, 3), np.uint32)
        mesh.calc_loop_triangles()
        vertices = np.empty(len(mesh.vertices) * 3, dtype=np.float32)
        mesh.vertices.foreach_get("co", vertices)
        triangles = np.empty(len(mesh.loop_triangles) * 3, dtype=np.int32)
        mesh.loop_triangles.foreach_get("vertices", triangles)
        return vertices.reshape(-1, 3), triangles.reshape(-1, 3).astype(np.uint32)
    finally:
        obj.to_mesh_clear()


def _mesh_flags(obj):
    from . import native
    materials = [slot.material for slot in getattr(obj, "material_slots", [])]
    cast = compat.object_casts_shadow(obj.original) and compat.materials_cast_shadow(materials)
    seen = compat.object_camera_visible(obj.original)
    return ((native.MESH_CAST if cast else 0) | (native.MESH_RECEIVE if seen else 0)
            | (0 if seen else native.MESH_CAMERA_HIDDEN))


def _layer_flags(flags, obj, parent, view_layer, engine):
    """The view layer's say on a mesh: Cycles shows an object of an Indirect Only collection
    only through its shadows and reflections, so the camera sees past it (EEVEE ignores it)."""
    from . import native
    owner = (parent or obj).original
    if engine == "CYCLES" and flags & native.MESH_RECEIVE and owner.indirect_only_get(view_layer=view_layer):
        flags = (flags & ~native.MESH_RECEIVE) | native.MESH_CAMERA_HIDDEN
    return flags if flags & (native.MESH_CAST | native.MESH_RECEIVE) else 0  # (hidden, casting nothing)


def _mesh_alpha(obj, engine, readings, unreadable):
    """material_alpha.mesh_alpha for an object with see-through materials, else None.
    `readings` caches each material's reading for the export; unreadable ones are added to
    `unreadable` (names with the reason)."""
    from . import material_alpha
    slots = []
    for slot in getattr(obj, "material_slots", []):
        material = slot.material
        if material is None:
            slots.append(None)
            continue
        key = material.name
        if key not in readings:
            try:
                readings[key] = material_alpha.material_alpha(material, engine)
            except material_alpha.Unreadable as exc:
                readings[key] = None
                unreadable.add("'%s' (%s)" % (material.name, exc))
            except Exception as exc:  # a tree this reader did not foresee: opaque, and said so
                readings[key] = None
                unreadable.add("'%s' (%s: %s)" % (material.name, type(exc).__name__, exc))
        slots.append(readings[key])
    if all(alpha is None for alpha in slots):
        return None
    try:
        return material_alpha.mesh_alpha(obj, slots)
    except RuntimeError as exc:  # no mesh to read UVs from: opaque, and said so
        unreadable.add("on object '%s' (%s)" % (obj.name, exc))
        return None


def _light_from_object(name, obj, matrix):
    data = obj.data
    return light_values(
        name, data.type, getattr(data, "shape", "SQUARE"), matrix,
        size=getattr(data, "size", 0.0), size_y=getattr(data, "size_y", 0.0),
        radius=compat.light_radius(data) if data.type in ("POINT", "SPOT") else 0.0,
        angle=getattr(data, "angle", 0.0) if data.type == "SUN" else 0.0,
        spot_size=getattr(data, "spot_size", 0.0) if data.type == "SPOT" else 0.0,
        spot_blend=getattr(data, "spot_blend", 0.0) if data.type == "SPOT" else 0.0,
        use_shadow=compat.light_use_shadow(data) or _replaces_shadow(obj))


def _replaces_shadow(obj):
    """A light whose renderer shadow the Replace composite switched off still casts our pass."""
    props = getattr(obj.original.data, "softshadow", None)
    return bool(props is not None and props.replaces_shadow)


def _light_settings(obj):
    props = getattr(obj.original.data, "softshadow", None)
    if props is None:
        return {"enabled": True, "method": "auto", "samples": 0, "settings": "", "refine_final": True}
    return {"enabled": bool(props.enabled), "method": props.method, "samples": int(props.samples),
            "settings": props.settings, "refine_final": bool(props.refine_final)}


def frame_problem(scene):
    """Why the scene camera's render gets no passes (a panoramic camera, an empty cropped
    border), or None."""
    render = scene.render
    size = render_size(render.resolution_x, render.resolution_y, render.resolution_percentage)
    return framing.camera_problem(scene.camera) or framing.crop_problem(framing.crop_rect(render, *size))


def scene_camera(scene, depsgraph, width=None, height=None):
    """The scene camera at the render resolution (percentage and pixel aspect applied; a border
    with Crop narrows it to the border's pixels)."""
    camera = scene.camera
    if camera is None:
        return None
    render = scene.render
    crop = None
    if width is None:
        width, height = render_size(render.resolution_x, render.resolution_y, render.resolution_percentage)
        crop = framing.crop_rect(render, width, height)
    evaluated = camera.evaluated_get(depsgraph)
    projection = evaluated.calc_matrix_camera(depsgraph, x=width, y=height,
                                              scale_x=render.pixel_aspect_x,
                                              scale_y=render.pixel_aspect_y)
    if crop is not None:  # the render is the border's pixels alone (framing.py)
        projection = framing.cropped_projection(projection, crop, width, height)
        width, height = crop[2] - crop[0], crop[3] - crop[1]
    view = np.linalg.inv(normalized_rigid(evaluated.matrix_world))
    return camera_values(view, projection, width, height,
                         render.pixel_aspect_y / render.pixel_aspect_x if render.pixel_aspect_x else 1.0)


def _instances(depsgraph, view_layer, mode):
    """(instance or None, evaluated object, is_instance, parent, world matrix) of what to export.

    A viewport depsgraph leaves out objects hidden in the viewport (eye icon) although they
    render: in RENDER mode those are added from the view layer, evaluated (their own instances
    are not expanded)."""
    seen = set()
    for inst in depsgraph.object_instances:
        obj = inst.object
        if obj is None:
            continue
        if not inst.is_instance:
            seen.add(obj.original.name)
        yield inst, obj, inst.is_instance, inst.parent, inst.matrix_world.copy()
    if mode != "RENDER":
        return
    for original in view_layer.objects:
        if original.name in seen or original.type not in GEOMETRY_TYPES + ("LIGHT",):
            continue
        evaluated = original.evaluated_get(depsgraph)
        yield None, evaluated, False, None, evaluated.matrix_world.copy()


def export(depsgraph, scene, mode="RENDER", view_layer=None, camera=None, only=None, geometry=None,
           reuse=None):
    """An evaluated depsgraph -> ExportedScene. mode: 'RENDER' (hide_render, collections'
    render switches) or 'VIEWPORT' (what the viewport shows). camera overrides the scene camera
    (the viewport preview passes its own view).

    Each mesh carries its object-space "local" vertices, "triangles" and column-major "matrix"
    (the library places the vertices by it). only: names of the objects to export (the preview's changed
    objects; no instances); of those, the ones not in `geometry` are exported without reading
    their mesh ("local" and "triangles" None: a moved object costs its matrix). reuse: a
    mesh_cache.MeshCache: an object's mesh comes from it while the depsgraph reports no change
    of the object's geometry, and goes into it when read (instances are always read)."""
    view_layer = view_layer or depsgraph.view_layer
    out = ExportedScene(view_layer=view_layer.name)
    render_collections = _render_visible_collections(view_layer) if mode == "RENDER" else set()
    used_mesh_names, used_light_names = set(), set()
    local_cache = {}
    engine = getattr(getattr(scene, "render", None), "engine", "CYCLES")
    alpha_readings, unreadable = {}, set()
    if reuse is not None:
        reuse.bind(depsgraph)

    for inst, obj, is_instance, parent, matrix in _instances(depsgraph, view_layer, mode):
        if only is not None and (is_instance or obj.original.name not in only):
            continue
        if is_instance:
            if parent is not None and not _object_visible(parent, mode, view_layer, render_collections):
                continue
            if mode == "RENDER" and obj.original.hide_render:
                continue
        else:
            if not _object_visible(obj, mode, view_layer, render_collections):
                out.skipped.append(obj.name)
                continue
            if obj.is_instancer:
                show = obj.original.show_instancer_for_render if mode == "RENDER" else inst.show_self
                if not show:
                    continue
        base_name = obj.name if not is_instance else "%s/%s" % (parent.name, obj.name)

        if obj.type == "LIGHT":
            try:
                light = _light_from_object(unique_name(base_name, used_light_names), obj, matrix)
            except ValueError as exc:
                out.problems.append(str(exc))
                continue
            light["options"] = _light_settings(obj)
            light["links"] = compat.light_links(obj.original)
            out.lights.append(light)
            continue
        if obj.type not in GEOMETRY_TYPES:
            continue

        if only is not None and obj.original.name not in (geometry or ()):
            flags = _layer_flags(_mesh_flags(obj), obj, parent if is_instance else None, view_layer,
                                 scene.render.engine)
            if flags:
                out.meshes.append({"name": base_name, "local": None, "triangles": None, "flags": flags,
                                   "matrix": column_major(matrix), "object": obj.original.name})
            continue
        # An object the viewport's depsgraph does not show (added for a render, inst None) may
        # not be evaluated there, so no update vouches for its mesh: it is read every time.
        cacheable = reuse is not None and inst is not None and not is_instance
        arrays = reuse.get(obj) if cacheable else None
        fresh = arrays is None
        if fresh:
            key = (obj.type, obj.data.as_pointer() if obj.data is not None else obj.as_pointer())
            if key not in local_cache or not is_instance:
                try:
                    local_cache[key] = _local_mesh_arrays(obj)
                except RuntimeError as exc:
                    out.problems.append("object '%s': %s" % (base_name, exc))
                    continue
            arrays = local_cache[key]
        name = unique_name(base_name, used_mesh_names)
        if fresh:
            problem = faceless_problem(name, arrays[1])
            if problem:
                out.problems.append(problem)
                continue
            if cacheable:
                reuse.put(obj, *arrays)
        vertices, triangles = arrays
        flat = column_major(matrix)
        flags = _layer_flags(_mesh_flags(obj), obj, parent if is_instance else None, view_layer,
                             scene.render.engine)
        if flags == 0:
            continue
        # Casters shadow through their materials' alpha; the camera sees through a cut-out's holes.
        alpha = _mesh_alpha(obj, engine, alpha_readings, unreadable)
        if alpha is not None and len(alpha["triangle_material"]) != len(triangles):
            alpha = None
        out.meshes.append({"name": name, "local": vertices, "triangles": triangles, "flags": flags,
                           "matrix": flat, "alpha": alpha, "object": obj.original.name,
                           "instancer": parent.original.name if is_instance and parent is not None else None})

    line = unreadable_materials_line(unreadable)
    if line:
        out.problems.append(line)
    if camera is None and only is None:
        problem = frame_problem(scene) or (scene.camera and camera_matrix_problem(
            scene.camera.name, scene.camera.evaluated_get(depsgraph).matrix_world))
        camera = None if problem else scene_camera(scene, depsgraph)
        if problem:
            out.problems.append(problem)
        elif camera is None:
            out.problems.append("scene '%s' has no camera: no soft-shadow passes" % scene.name)
    out.camera = camera
    return out
