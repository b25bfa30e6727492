# Does the add-on register, unregister and register again, and say why when the library is missing?
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402
import softshadow  # noqa: E402


def _unregistered():
    if hasattr(bpy.types.Scene, "softshadow"):
        softshadow.unregister()


def test_register_unregister_register():
    _unregistered()
    softshadow.register()
    sstest.check(hasattr(bpy.types.Scene, "softshadow") and hasattr(bpy.types.Light, "softshadow"),
                 "properties registered")
    sstest.check(hasattr(bpy.ops.softshadow, "render_passes") and hasattr(bpy.ops.softshadow, "method_settings"),
                 "operators registered (the Method Settings keys' button too)")
    softshadow.unregister()
    sstest.check(not hasattr(bpy.types.Scene, "softshadow"), "scene properties removed")
    sstest.check(softshadow.handlers.on_render_pre not in bpy.app.handlers.render_pre, "handler removed")
    softshadow.register()
    sstest.check(softshadow.handlers.on_render_pre in bpy.app.handlers.render_pre, "handler back")
    sstest.check(bpy.app.handlers.render_pre.count(softshadow.handlers.on_render_pre) == 1, "only once")


def test_status_with_library():
    info = softshadow.native.status()
    sstest.check(info["loaded"], "library loads from SOFTSHADOW_LIB: %s" % info)
    sstest.check(info["error"] == "", "no error: %s" % info["error"])
    sstest.check(info["version"].count(".") == 2, "a version like 0.1.0: %r" % info["version"])
    sstest.check(info["backend"] != "" and info["renderer"] != "", "backend and renderer shown: %s" % info)
    if info["backend"] == "egl":
        # Mesa lists its software device; with no GPU the surfaceless platform renders.
        sstest.check(any("software" in d for d in info["egl_devices"]), "EGL devices listed: %s" % info)
        sstest.check(info["device"] != "", "the EGL device used is named: %s" % info)
    print("   library", info["version"], "backend", info["backend"], "renderer", info["renderer"],
          "device", info.get("device"))


def test_library_works_after_reregister():
    # unregister calls ss_shutdown; the next use must still work.
    _unregistered()
    softshadow.register()
    softshadow.unregister()
    softshadow.register()
    scene = sstest.standard_scene(32, 24)
    result = softshadow.render_passes(scene, methods="reference")
    sstest.check(len(result) == 1, "one pass after re-register: %s" % list(result))


SCRIPT_WITHOUT_LIBRARY = r"""
import sys, bpy
sys.path.insert(0, %r)
import softshadow
softshadow.register()
info = softshadow.native.status()
print("LOADED", info["loaded"])
print("ERROR", info["error"])
print("LOOKED", "|".join(info["looked"]))
try:
    bpy.ops.softshadow.render_passes()
except RuntimeError as exc:
    print("REPORT", str(exc).replace("\n", " "))
try:
    softshadow.render_passes(bpy.context.scene)
except softshadow.native.LibraryUnavailable as exc:
    print("API", exc)
softshadow.unregister()
print("DONE")
"""


def test_status_without_library():
    env = dict(os.environ, SOFTSHADOW_LIB="/nonexistent/dir/libsoftshadow.so")
    out = subprocess.run([sstest.blender_binary(), "--background", "--factory-startup", "--python-expr",
                          SCRIPT_WITHOUT_LIBRARY % sstest.ADDON_PATH],
                         capture_output=True, text=True, env=env, timeout=300).stdout
    lines = dict((line + " ").split(" ", 1) for line in out.splitlines()
                 if line.split(" ", 1)[0] in ("LOADED", "ERROR", "LOOKED", "REPORT", "API"))
    lines = {k: v.strip() for k, v in lines.items()}
    sstest.check(lines.get("LOADED") == "False", "not loaded:\n%s" % out)
    sstest.check("/nonexistent/dir/libsoftshadow.so" in lines.get("LOOKED", ""), "says where it looked")
    sstest.check("not found" in lines.get("ERROR", ""), "says why: %r" % lines.get("ERROR"))
    sstest.check("could not be loaded" in lines.get("REPORT", ""), "operator reports, no traceback")
    sstest.check("could not be loaded" in lines.get("API", ""), "API raises LibraryUnavailable")
    sstest.check("Traceback" not in out, "no traceback:\n%s" % out)
    sstest.check("DONE" in out, "Blender survived:\n%s" % out)


if __name__ == "__main__":
    sstest.run(dict(globals()))
