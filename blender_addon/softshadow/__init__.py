# What the softshadow add-on is: its registration and its Python API (render_passes).
# SPDX-License-Identifier: GPL-3.0-or-later
bl_info = {
    "name": "Soft Shadow Passes",
    "author": "softshadow contributors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Properties > Light > Soft Shadow; Properties > Output > Soft Shadow Passes",
    "description": "Soft shadows from area lights as compositing passes (multilayer EXR)",
    "doc_url": "https://example.invalid/softshadow/docs/user-guide.md",
    "category": "Render",
}

try:
    import bpy  # noqa: F401
except ImportError:  # imported by the pure-Python tests: only scene_export/compat are used
    bpy = None

if bpy is not None:
    from . import cancel, handlers, mesh_cache, native, operators, preview, properties, ui
    from .api import render_passes  # noqa: F401  (the public API)

    _MODULES = (properties, operators, ui, handlers, cancel, mesh_cache, preview)

    def register():
        native.reset_after_shutdown()
        for module in _MODULES:
            module.register()
        if not native.available():
            print("softshadow: passes disabled: %s" % native.status()["error"])

    def unregister():
        for module in reversed(_MODULES):
            try:
                module.unregister()
            except (RuntimeError, ValueError) as exc:
                print("softshadow: unregister %s: %s" % (module.__name__, exc))
        native.shutdown()
