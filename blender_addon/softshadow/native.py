# How the add-on talks to libsoftshadow: the one ctypes binding (handles, errors, one context).
# SPDX-License-Identifier: GPL-3.0-or-later
"""The only module that uses ctypes.

Every C function's argtypes/restype is declared once, at load. A status other than SS_OK is
turned into SoftShadowError carrying ss_last_error() before any output is used. A missing or
broken library never raises at import: `status()` says why and where we looked.
"""
import atexit
import ctypes
import json
import math
import os
import threading

import numpy as np

SS_OK = 0
STATUS_NAMES = {
    0: "ok", 1: "invalid argument", 2: "invalid scene", 3: "i/o error", 4: "GL error",
    5: "unsupported", 6: "cancelled", 7: "internal error",
}
SS_ERROR_IO = 3
SS_ERROR_CANCELLED = 6

BACKENDS = {"AUTO": 0, "EGL": 1, "OSMESA": 2}
LIGHT_TYPES = {"DISK": 0, "ELLIPSE": 1, "SQUARE": 2, "RECTANGLE": 3, "POINT": 4, "SPOT": 5, "SUN": 6}

MESH_CAST = 1
MESH_RECEIVE = 2
MESH_THIN = 4
MESH_CAMERA_HIDDEN = 8  # the camera sees past it; it still casts

LIBRARY_NAME = "libsoftshadow.so"


class SoftShadowError(RuntimeError):
    """A failed library call: `status` is the ss_status, the message is ss_last_error()."""

    def __init__(self, status, message):
        super().__init__(message)
        self.status = status

    @property
    def cancelled(self):
        return self.status == SS_ERROR_CANCELLED


class LibraryUnavailable(RuntimeError):
    """The library could not be loaded; the message says why and where we looked."""


class _LightDesc(ctypes.Structure):
    _fields_ = [
        ("name", ctypes.c_char_p),
        ("type", ctypes.c_int),
        ("light_to_world", ctypes.c_float * 16),
        ("size", ctypes.c_float),
        ("size_y", ctypes.c_float),
        ("radius", ctypes.c_float),
        ("angle", ctypes.c_float),
        ("spot_size", ctypes.c_float),
        ("spot_blend", ctypes.c_float),
        ("cast_shadows", ctypes.c_int32),
    ]


class _AlphaMaterial(ctypes.Structure):
    _fields_ = [
        ("alpha", ctypes.c_float),
        ("texture", ctypes.POINTER(ctypes.c_float)),
        ("width", ctypes.c_int32),
        ("height", ctypes.c_int32),
        ("wrap", ctypes.c_int32),
        ("closest", ctypes.c_int32),
    ]


class _CameraDesc(ctypes.Structure):
    _fields_ = [
        ("world_to_camera", ctypes.c_float * 16),
        ("projection", ctypes.c_float * 16),
        ("width", ctypes.c_int32),
        ("height", ctypes.c_int32),
        ("pixel_aspect", ctypes.c_float),
    ]


_REFINE_OFF, _REFINE_ON = 0, 1  # ss_refine
_PROGRESS_FN = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_float, ctypes.c_char_p)
_ROUND_FN = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_int32, ctypes.c_int32)


class _RenderOptions(ctypes.Structure):
    _fields_ = [
        ("samples", ctypes.c_int32),
        ("seed", ctypes.c_uint32),
        ("extra_layers", ctypes.c_int32),
        ("progress", _PROGRESS_FN),
        ("progress_user", ctypes.c_void_p),
        ("settings", ctypes.c_char_p),
        ("round", _ROUND_FN),
        ("round_user", ctypes.c_void_p),
        ("refine", ctypes.c_int32),
        ("refine_rounds", ctypes.c_int32),
    ]


class _SettingInfo(ctypes.Structure):
    _fields_ = [("key", ctypes.c_char_p), ("type", ctypes.c_char_p), ("default_value", ctypes.c_char_p),
                ("range", ctypes.c_char_p), ("doc", ctypes.c_char_p)]


_vp = ctypes.c_void_p
_st = ctypes.c_int
_SIGNATURES = {
    "ss_version": (ctypes.c_char_p, []),
    "ss_last_error": (ctypes.c_char_p, []),
    "ss_render_options_default": (None, [ctypes.POINTER(_RenderOptions)]),
    "ss_context_create": (_st, [ctypes.c_int, ctypes.POINTER(_vp)]),
    "ss_context_destroy": (None, [_vp]),
    "ss_context_cancel_renders": (None, [_vp]),
    "ss_context_info": (_st, [_vp, ctypes.c_char_p, ctypes.c_size_t]),
    "ss_shutdown": (None, []),
    "ss_method_count": (ctypes.c_int32, []),
    "ss_method_name": (ctypes.c_char_p, [ctypes.c_int32]),
    "ss_method_setting_count": (ctypes.c_int32, [ctypes.c_char_p]),
    "ss_method_setting_info": (_st, [ctypes.c_char_p, ctypes.c_int32, ctypes.POINTER(_SettingInfo)]),
    "ss_scene_create": (_st, [ctypes.POINTER(_vp)]),
    "ss_scene_destroy": (None, [_vp]),
    "ss_scene_load": (_st, [ctypes.c_char_p, ctypes.POINTER(_vp)]),
    "ss_scene_save": (_st, [_vp, ctypes.c_char_p]),
    "ss_scene_add_mesh": (_st, [_vp, ctypes.c_char_p, ctypes.POINTER(ctypes.c_float), ctypes.c_uint32,
                                ctypes.POINTER(ctypes.c_uint32), ctypes.c_uint32, ctypes.POINTER(ctypes.c_float),
                                ctypes.c_uint32, ctypes.POINTER(ctypes.c_int32)]),
    "ss_scene_add_light": (_st, [_vp, ctypes.POINTER(_LightDesc), ctypes.POINTER(ctypes.c_int32)]),
    "ss_scene_update_mesh": (_st, [_vp, ctypes.c_int32, ctypes.POINTER(ctypes.c_float), ctypes.c_uint32,
                                   ctypes.POINTER(ctypes.c_uint32), ctypes.c_uint32, ctypes.c_uint32]),
    "ss_scene_set_mesh_materials": (_st, [_vp, ctypes.c_int32, ctypes.POINTER(ctypes.c_float),
                                          ctypes.POINTER(ctypes.c_int32), ctypes.POINTER(_AlphaMaterial),
                                          ctypes.c_int32]),
    "ss_scene_set_mesh_transform": (_st, [_vp, ctypes.c_int32, ctypes.POINTER(ctypes.c_float)]),
    "ss_scene_remove_mesh": (_st, [_vp, ctypes.c_int32]),
    "ss_scene_update_light": (_st, [_vp, ctypes.c_int32, ctypes.POINTER(_LightDesc)]),
    "ss_scene_remove_light": (_st, [_vp, ctypes.c_int32]),
    "ss_scene_set_light_links": (_st, [_vp, ctypes.c_int32, ctypes.POINTER(ctypes.c_int32), ctypes.c_int32,
                                       ctypes.POINTER(ctypes.c_int32), ctypes.c_int32]),
    "ss_scene_get_light_links": (_st, [_vp, ctypes.c_int32, ctypes.POINTER(ctypes.c_int32), ctypes.c_int32,
                                       ctypes.POINTER(ctypes.c_int32), ctypes.POINTER(ctypes.c_int32),
                                       ctypes.c_int32, ctypes.POINTER(ctypes.c_int32)]),
    "ss_cache_stat_count": (ctypes.c_int32, []),
    "ss_cache_stat_name": (ctypes.c_char_p, [ctypes.c_int32]),
    "ss_context_cache_stat": (_st, [_vp, ctypes.c_char_p, ctypes.POINTER(ctypes.c_double)]),
    "ss_scene_set_camera": (_st, [_vp, ctypes.POINTER(_CameraDesc)]),
    "ss_scene_set_view_layer": (_st, [_vp, ctypes.c_char_p]),
    "ss_scene_light_count": (ctypes.c_int32, [_vp]),
    "ss_scene_light_name": (ctypes.c_char_p, [_vp, ctypes.c_int32]),
    "ss_scene_mesh_count": (ctypes.c_int32, [_vp]),
    "ss_scene_mesh_report": (_st, [_vp, ctypes.c_int32, ctypes.c_char_p, ctypes.c_size_t]),
    "ss_render": (_st, [_vp, _vp, ctypes.c_int32, ctypes.c_char_p, ctypes.POINTER(_RenderOptions),
                        ctypes.POINTER(_vp)]),
    "ss_result_destroy": (None, [_vp]),
    "ss_result_method": (ctypes.c_char_p, [_vp]),
    "ss_result_light": (ctypes.c_char_p, [_vp]),
    "ss_result_estimated_rmse": (ctypes.c_double, [_vp]),
    "ss_result_warnings": (ctypes.c_char_p, [_vp]),
    "ss_result_layer_count": (ctypes.c_int32, [_vp]),
    "ss_result_layer": (_st, [_vp, ctypes.c_int32, ctypes.POINTER(ctypes.c_char_p),
                              ctypes.POINTER(ctypes.POINTER(ctypes.c_float)),
                              ctypes.POINTER(ctypes.c_int32), ctypes.POINTER(ctypes.c_int32)]),
    "ss_write_exr": (_st, [ctypes.c_char_p, ctypes.c_char_p, ctypes.POINTER(_vp), ctypes.c_int32]),
    "ss_pass_name": (_st, [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_char_p, ctypes.c_char_p, ctypes.c_size_t]),
    "ss_check_output_path": (_st, [ctypes.c_char_p]),
    "ss_remove_temporary_files_on_signals": (ctypes.c_int32, []),
}


def candidate_paths():
    """Where the library is looked for, in order: $SOFTSHADOW_LIB, then lib/ next to the package."""
    paths = []
    env = os.environ.get("SOFTSHADOW_LIB")
    if env:
        paths.append(os.path.join(env, LIBRARY_NAME) if os.path.isdir(env) else env)
    paths.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib", LIBRARY_NAME))
    return paths


_lock = threading.RLock()
_lib = None
_load_error = None
_looked = []
_context = None
_context_error = None
_context_info = None
_shut_down = False


def _bind(cdll):
    for name, (restype, argtypes) in _SIGNATURES.items():
        fn = getattr(cdll, name)  # AttributeError names the missing symbol
        fn.restype = restype
        fn.argtypes = argtypes
    return cdll


# Blender links libraries that define the same C symbols as ours under other ABIs (Blender 4+
# links Embree 4, whose rtcIntersect1 and friends share Embree 3's names): bound through the
# process's global scope, our calls would land in Blender's copy and trace nothing. RTLD_DEEPBIND
# puts the library's own dependencies first; RTLD_LOCAL keeps its symbols out of Blender's way.
_LOAD_MODE = os.RTLD_LOCAL | getattr(os, "RTLD_DEEPBIND", 0)


def _load():
    """Loads the library once. Returns it, or None with _load_error set."""
    global _lib, _load_error, _looked
    with _lock:
        if _lib is not None or _load_error is not None:
            return _lib
        _looked = candidate_paths()
        reasons = []
        for path in _looked:
            if not os.path.exists(path):
                reasons.append("%s: not found" % path)
                continue
            try:
                _lib = _bind(ctypes.CDLL(path, mode=_LOAD_MODE))
                atexit.register(shutdown)
                # A farm's SIGTERM during a pass file's write leaves no temporary file (Blender
                # keeps the default action for it; a signal Blender handles keeps its handler).
                _lib.ss_remove_temporary_files_on_signals()
                return _lib
            except (OSError, AttributeError) as exc:
                reasons.append("%s: %s" % (path, exc))
        _load_error = "libsoftshadow could not be loaded (" + "; ".join(reasons) + ")"
        return None


def available():
    return _load() is not None


def lib():
    """The bound library, or LibraryUnavailable with the reason."""
    loaded = _load()
    if loaded is None:
        raise LibraryUnavailable(_load_error)
    if _shut_down:
        raise LibraryUnavailable("libsoftshadow was shut down (the add-on was unregistered)")
    return loaded


def _check(status):
    if status != SS_OK:
        raw = _lib.ss_last_error()
        message = raw.decode("utf-8", "replace") if raw else STATUS_NAMES.get(status, "error")
        raise SoftShadowError(status, message)


def _text(value):
    return value.encode("utf-8") if isinstance(value, str) else value


def version():
    return lib().ss_version().decode()


def method_names():
    """The library's methods, in its order ("auto" is not one)."""
    loaded = lib()
    return tuple(loaded.ss_method_name(i).decode() for i in range(loaded.ss_method_count()))


def method_settings(method):
    """The settings `method` (or "auto") takes, as the library lists them for users:
    (key, type, default, range, doc) each, the method's own first."""
    loaded = lib()
    count = loaded.ss_method_setting_count(_text(method))
    if count < 0:
        raise SoftShadowError(1, loaded.ss_last_error().decode("utf-8", "replace"))
    out = []
    for i in range(count):
        info = _SettingInfo()
        _check(loaded.ss_method_setting_info(_text(method), i, ctypes.byref(info)))
        out.append(tuple(getattr(info, f).decode() for f, _t in _SettingInfo._fields_))
    return out


def pass_name(light_name, method, layer=None):
    """The EXR pass name of one (light, method[, extra layer]) result, as the library writes it
    (ss_pass_name: dots and spaces of the light's name become '_'; the layer V is the pass)."""
    buffer = ctypes.create_string_buffer(4 * len(_text(light_name)) + len(_text(method)) + 256)
    _check(lib().ss_pass_name(_text(light_name), _text(method), _text(layer) if layer else None,
                              buffer, len(buffer)))
    return buffer.value.decode("utf-8", "replace")


def check_output_path(path):
    """SoftShadowError unless a file could be written at `path` (a regular file or a new name in
    an existing folder this process may write): checked before a long render."""
    _check(lib().ss_check_output_path(_text(os.fspath(path))))


def context():
    """The one long-lived GL context (its render thread belongs to the library)."""
    global _context, _context_error, _context_info
    with _lock:
        if _context is not None:
            return _context
        library = lib()
        backend = BACKENDS.get(os.environ.get("SOFTSHADOW_BACKEND", "AUTO").upper(), 0)
        handle = ctypes.c_void_p()
        try:
            _check(library.ss_context_create(backend, ctypes.byref(handle)))
        except SoftShadowError as exc:
            _context_error = str(exc)
            raise
        _context = handle
        buffer = ctypes.create_string_buffer(8192)
        try:
            _check(library.ss_context_info(handle, buffer, len(buffer)))
            _context_info = json.loads(buffer.value.decode("utf-8", "replace") or "{}")
        except (SoftShadowError, ValueError) as exc:
            _context_info = {"error": str(exc)}
        return _context


def cancel_renders():
    """Cancels the renders running now on the shared context, from any thread, without waiting:
    each raises SoftShadowError (cancelled) within moments. Later renders run as usual."""
    with _lock:
        if _lib is not None and _context is not None and not _shut_down:
            _lib.ss_context_cancel_renders(_context)


def status():
    """A dict for the preferences panel: loaded, version, backend/renderer or the reason."""
    info = {"loaded": False, "looked": list(candidate_paths()), "version": "", "backend": "",
            "renderer": "", "error": ""}
    if _load() is None:
        info["error"] = _load_error or "not loaded"
        info["looked"] = list(_looked) or info["looked"]
        return info
    info["loaded"] = True
    info["path"] = getattr(_lib, "_name", "")
    try:
        info["version"] = version()
        context()
        details = _context_info or {}
        info["backend"] = str(details.get("backend", ""))
        info["renderer"] = str(details.get("renderer", ""))
        info["gl_version"] = str(details.get("gl_version", details.get("version", "")))
        info["device"] = str(details.get("device", ""))
        info["egl_devices"] = [str(d) for d in details.get("egl_devices", [])]
        info["details"] = details
    except (SoftShadowError, LibraryUnavailable) as exc:
        info["error"] = "GL context: %s" % exc
    return info


def shutdown():
    """Destroys our context and joins the library's render threads (unregister and atexit)."""
    global _context, _context_info, _shut_down
    with _lock:
        if _lib is None or _shut_down:
            return
        if _context is not None:
            _lib.ss_context_destroy(_context)
            _context = None
            _context_info = None
        _lib.ss_shutdown()
        _shut_down = True


def reset_after_shutdown():
    """Allows use again after an unregister/register cycle (the library stays loaded)."""
    global _shut_down, _context_error
    with _lock:
        _shut_down = False
        _context_error = None


def cache_stats():
    """What the shared context's caches did so far, every counter the library declares by name
    (ss_cache_stat_name; docs/contracts.md lists them): e.g. mesh_uploads, shadow_maps,
    mesh_bvh_builds (tests count re-uploads and BVH builds with them) and the milliseconds
    upload_ms, camera_pass_ms, shadow_map_ms, method_ms (the benchmark's stages)."""
    names = [lib().ss_cache_stat_name(i) for i in range(lib().ss_cache_stat_count())]
    stats = {}
    value = ctypes.c_double()
    for name in names:
        _check(lib().ss_context_cache_stat(context(), name, ctypes.byref(value)))
        stats[name.decode()] = value.value
    return stats


def _light_desc(light):
    """A light dict (scene_export.light_values) -> ss_light_desc (it keeps the name alive)."""
    desc = _LightDesc()
    desc.name = _text(light["name"])
    desc.type = LIGHT_TYPES[light["type"]]
    desc.light_to_world = _matrix16(light["light_to_world"])
    for key in ("size", "size_y", "radius", "angle", "spot_size", "spot_blend"):
        setattr(desc, key, float(light.get(key, 0.0)))
    desc.cast_shadows = 1 if light.get("cast_shadows", True) else 0
    return desc


def _matrix16(values):
    array = np.asarray(values, dtype=np.float32).reshape(-1)
    if array.size != 16:
        raise ValueError("a matrix needs 16 values, got %d" % array.size)
    return (ctypes.c_float * 16)(*array.tolist())


class _Owned:
    """A handle the library made and this object destroys: once, by close(), `with` or when
    collected. Subclasses name their destroy function and what they are."""

    _destroy = None  # the ss_*_destroy function's name
    _what = "handle"

    def __init__(self, handle):
        self._handle = handle

    def close(self):
        if self._handle is not None and _lib is not None:
            getattr(_lib, self._destroy)(self._handle)
        self._handle = None

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    @property
    def handle(self):
        if self._handle is None:
            raise ValueError("the %s was closed" % self._what)
        return self._handle


class Scene(_Owned):
    """An ss_scene: meshes (object-space vertices placed by a matrix), lights and a camera."""

    _destroy = "ss_scene_destroy"
    _what = "scene"

    def __init__(self, handle=None):
        library = lib()
        if handle is None:
            handle = ctypes.c_void_p()
            _check(library.ss_scene_create(ctypes.byref(handle)))
        super().__init__(handle)

    @classmethod
    def load(cls, path):
        handle = ctypes.c_void_p()
        _check(lib().ss_scene_load(_text(os.fspath(path)), ctypes.byref(handle)))
        return cls(handle)

    def add_mesh(self, name, vertices, triangles, flags, object_to_world=None):
        """vertices: (N, 3) object-space float; triangles: (M, 3) indices; object_to_world: 16
        column-major floats placing them (None: the identity). Returns the index."""
        xyz = np.ascontiguousarray(vertices, dtype=np.float32).reshape(-1, 3)
        tris = np.ascontiguousarray(triangles, dtype=np.uint32).reshape(-1, 3)
        matrix = None if object_to_world is None else _matrix16(object_to_world)
        index = ctypes.c_int32(-1)
        _check(lib().ss_scene_add_mesh(
            self.handle, _text(name), xyz.ctypes.data_as(ctypes.POINTER(ctypes.c_float)), len(xyz),
            tris.ctypes.data_as(ctypes.POINTER(ctypes.c_uint32)), len(tris), matrix, int(flags),
            ctypes.byref(index)))
        return index.value

    def update_mesh(self, index, vertices, triangles, flags):
        """New geometry for mesh `index`, in its object space (its transform is kept)."""
        xyz = np.ascontiguousarray(vertices, dtype=np.float32).reshape(-1, 3)
        tris = np.ascontiguousarray(triangles, dtype=np.uint32).reshape(-1, 3)
        _check(lib().ss_scene_update_mesh(
            self.handle, int(index), xyz.ctypes.data_as(ctypes.POINTER(ctypes.c_float)), len(xyz),
            tris.ctypes.data_as(ctypes.POINTER(ctypes.c_uint32)), len(tris), int(flags)))

    def set_mesh_materials(self, index, alpha):
        """What mesh `index` lets through on shadow rays (material_alpha.mesh_alpha's dict), or
        None to make it opaque."""
        if alpha is None:
            _check(lib().ss_scene_set_mesh_materials(self.handle, int(index), None, None, None, 0))
            return
        uvs = np.ascontiguousarray(alpha["uvs"], dtype=np.float32).reshape(-1)
        material = np.ascontiguousarray(alpha["triangle_material"], dtype=np.int32).reshape(-1)
        keep = []  # the textures must live until the call returns
        descs = (_AlphaMaterial * len(alpha["materials"]))()
        for desc, m in zip(descs, alpha["materials"]):
            desc.alpha = float(m["alpha"])
            desc.wrap = int(m["wrap"])
            desc.closest = 1 if m["closest"] else 0
            texture = m.get("texture")
            if texture is not None:
                texels = np.ascontiguousarray(texture, dtype=np.float32)
                keep.append(texels)
                desc.texture = texels.ctypes.data_as(ctypes.POINTER(ctypes.c_float))
                desc.height, desc.width = texels.shape
        _check(lib().ss_scene_set_mesh_materials(
            self.handle, int(index), uvs.ctypes.data_as(ctypes.POINTER(ctypes.c_float)),
            material.ctypes.data_as(ctypes.POINTER(ctypes.c_int32)), descs, len(descs)))

    def set_mesh_transform(self, index, object_to_world):
        """object_to_world: 16 column-major floats applied to the mesh's object-space vertices."""
        _check(lib().ss_scene_set_mesh_transform(self.handle, int(index), _matrix16(object_to_world)))

    def remove_mesh(self, index):
        _check(lib().ss_scene_remove_mesh(self.handle, int(index)))

    def update_light(self, index, light):
        _check(lib().ss_scene_update_light(self.handle, int(index), ctypes.byref(_light_desc(light))))

    def remove_light(self, index):
        _check(lib().ss_scene_remove_light(self.handle, int(index)))

    def set_light_links(self, index, blockers, receivers):
        """Shadow and light linking of light `index`: blockers, receivers each None (every
        mesh) or a list of mesh indices (exactly those)."""
        def mesh_set(indices):
            if indices is None:
                return None, -1
            array = (ctypes.c_int32 * max(len(indices), 1))(*indices)
            return array, len(indices)
        blocker_array, blocker_count = mesh_set(blockers)
        receiver_array, receiver_count = mesh_set(receivers)
        _check(lib().ss_scene_set_light_links(self.handle, int(index), blocker_array, blocker_count,
                                              receiver_array, receiver_count))

    def light_links(self, index):
        """(blockers, receivers) of light `index` as the library holds them (None: every mesh)."""
        room = max(self.mesh_count(), 1)
        blockers, receivers = (ctypes.c_int32 * room)(), (ctypes.c_int32 * room)()
        blocker_count, receiver_count = ctypes.c_int32(), ctypes.c_int32()
        _check(lib().ss_scene_get_light_links(self.handle, int(index), blockers, room, ctypes.byref(blocker_count),
                                              receivers, room, ctypes.byref(receiver_count)))
        return (None if blocker_count.value < 0 else list(blockers[:blocker_count.value]),
                None if receiver_count.value < 0 else list(receivers[:receiver_count.value]))

    def add_light(self, light):
        """light: a dict as made by scene_export.light_values. Returns the index."""
        index = ctypes.c_int32(-1)
        _check(lib().ss_scene_add_light(self.handle, ctypes.byref(_light_desc(light)), ctypes.byref(index)))
        return index.value

    def set_camera(self, camera):
        """camera: a dict with column-major world_to_camera, projection, width, height."""
        desc = _CameraDesc()
        desc.world_to_camera = _matrix16(camera["world_to_camera"])
        desc.projection = _matrix16(camera["projection"])
        desc.width = int(camera["width"])
        desc.height = int(camera["height"])
        desc.pixel_aspect = float(camera.get("pixel_aspect", 1.0))
        _check(lib().ss_scene_set_camera(self.handle, ctypes.byref(desc)))

    def set_view_layer(self, name):
        _check(lib().ss_scene_set_view_layer(self.handle, _text(name)))

    def save(self, path):
        _check(lib().ss_scene_save(self.handle, _text(os.fspath(path))))

    def light_names(self):
        library = lib()
        return [library.ss_scene_light_name(self.handle, i).decode("utf-8", "replace")
                for i in range(library.ss_scene_light_count(self.handle))]

    def mesh_count(self):
        return lib().ss_scene_mesh_count(self.handle)

    def render(self, light_index, method="auto", samples=0, seed=1, extra_layers=False,
               settings=None, progress=None, refine=False, refine_rounds=0, rounds=None):
        """Renders one light with one method on the shared context. Returns a Result.

        progress(fraction, stage) -> True to cancel; it is called from the library's thread.
        refine: re-trace a GL method's uncertain pixels with rays, in refine_rounds shares (0: 1).
        rounds(partial, round, count) -> True to cancel: with refine and refine_rounds N > 1 it
        hears each refinement round but the last (the returned Result) on this thread; `partial`
        reads like a Result until the call returns.
        """
        library = lib()
        ctx = context()
        options = _RenderOptions()
        library.ss_render_options_default(ctypes.byref(options))
        options.samples = int(samples)
        options.seed = int(seed)
        options.extra_layers = 1 if extra_layers else 0
        options.refine = _REFINE_ON if refine else _REFINE_OFF
        options.refine_rounds = int(refine_rounds)
        callback = None
        if progress is not None:
            def _call(_user, fraction, stage):
                try:
                    return 1 if progress(float(fraction), (stage or b"").decode("utf-8", "replace")) else 0
                except Exception:
                    return 0
            callback = _PROGRESS_FN(_call)
            options.progress = callback
        round_callback = None
        if rounds is not None:
            def _round(_user, partial, number, count):
                view = _PartialResult(ctypes.c_void_p(partial))
                try:
                    return 1 if rounds(view, int(number), int(count)) else 0
                except Exception:
                    return 0
                finally:
                    view.close()
            round_callback = _ROUND_FN(_round)
            options.round = round_callback
        settings_bytes = _text(settings) if settings else None
        options.settings = settings_bytes
        out = ctypes.c_void_p()
        _check(library.ss_render(ctx, self.handle, int(light_index), _text(method),
                                 ctypes.byref(options), ctypes.byref(out)))
        del callback, round_callback  # kept alive until ss_render returned
        return Result(out)


class Result(_Owned):
    """The layers of one (light, method) render."""

    _destroy = "ss_result_destroy"
    _what = "result"

    @property
    def method(self):
        return lib().ss_result_method(self.handle).decode()

    @property
    def light(self):
        return lib().ss_result_light(self.handle).decode("utf-8", "replace")

    @property
    def estimated_rmse(self):
        """Expected RMSE of V against the reference (the library's sparse exact check), or None
        where none was made ('auto' always makes one)."""
        value = lib().ss_result_estimated_rmse(self.handle)
        return None if math.isnan(value) else value

    @property
    def warnings(self):
        """What the render left out, one message each (a mesh beyond the scene range, named)."""
        text = lib().ss_result_warnings(self.handle) or b""
        return [line for line in text.decode("utf-8", "replace").split("\n") if line]

    def layers(self):
        """{layer name: float32 (height, width) copy, row 0 = top}."""
        library = lib()
        out = {}
        for i in range(library.ss_result_layer_count(self.handle)):
            name = ctypes.c_char_p()
            pixels = ctypes.POINTER(ctypes.c_float)()
            width = ctypes.c_int32()
            height = ctypes.c_int32()
            _check(library.ss_result_layer(self.handle, i, ctypes.byref(name), ctypes.byref(pixels),
                                           ctypes.byref(width), ctypes.byref(height)))
            count = width.value * height.value
            flat = np.ctypeslib.as_array(pixels, shape=(count,)) if count else np.zeros(0, np.float32)
            out[name.value.decode()] = flat.reshape(height.value, width.value).copy()
        return out


class _PartialResult(Result):
    """A refinement round's result, the library's until its callback returns: read, never destroyed."""

    def close(self):
        self._handle = None


def write_exr(path, view_layer, results):
    """Writes results as one multilayer EXR (atomically, by the library)."""
    handles = (ctypes.c_void_p * max(1, len(results)))(*[r.handle for r in results])
    _check(lib().ss_write_exr(_text(os.fspath(path)), _text(view_layer), handles, len(results)))
