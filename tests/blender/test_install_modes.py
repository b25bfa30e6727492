# Does the add-on installed from the zip load its own library, validate as an extension without
# warnings, and answer pipeline scripts through scene.softshadow in this Blender and install mode?
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402

ss = sstest.addon()
ZIP = os.environ.get("SOFTSHADOW_ZIP")
EXTENSIONS = bpy.app.version >= (4, 2, 0)


def test_installed_copy_and_its_library():
    if not sstest.INSTALLED_MODULE:
        print("   (source tree: the installed copy is tested by tests/matrix/run.sh)")
        return
    home = os.path.realpath(os.path.expanduser("~"))
    package = os.path.realpath(os.path.dirname(ss.__file__))
    sstest.check(package.startswith(home + os.sep), "the add-on runs from the user folder: %s" % package)
    sstest.check(ss.__name__ == sstest.INSTALLED_MODULE, "module %s" % ss.__name__)
    info = ss.native.status()
    sstest.check(info["loaded"], "the bundled library loads: %s" % info)
    sstest.check(os.path.realpath(info["path"]) == os.path.join(package, "lib", "libsoftshadow.so"),
                 "loaded from the add-on's lib folder: %s" % info["path"])
    print("   %s %s: %s, %s" % (ss.__name__, info["version"], info["backend"], info["renderer"]))


def test_scripts_reach_render_passes_through_the_scene():
    # What pipeline scripts do, whatever the version and install mode (docs/user-guide.md).
    scene = sstest.standard_scene(32, 24)
    scene.objects["Key"].data.softshadow.method = "shadow_map"
    result = bpy.context.scene.softshadow.render_passes()
    sstest.check(list(result) == [("Key", "shadow_map")], "passes %s" % list(result))
    array = result[("Key", "shadow_map")]
    dark = float((array < 0.05).mean())
    sstest.check(0.01 < dark < 0.5, "a shadow where the box stands (%.3f of the pixels dark)" % dark)
    sstest.check(scene.softshadow.passes_problems() == [], "no problems: %s" % scene.softshadow.passes_problems())
    result = scene.softshadow.render_passes(lights="Key", methods=["shadow_map", "pcss"])
    sstest.check(sorted(result) == [("Key", "pcss"), ("Key", "shadow_map")], "chosen methods %s" % list(result))


def test_no_extension_policy_warnings():
    import addon_utils
    warnings = getattr(addon_utils, "_extensions_warnings_get", None)
    if not (sstest.INSTALLED_MODULE and warnings):
        print("   (no extension warnings in this Blender or mode)")
        return
    found = warnings().get(sstest.INSTALLED_MODULE, [])
    sstest.check(not found, "Blender warns about the extension: %s" % found)


def test_extension_validates():
    if not (ZIP and EXTENSIONS):
        print("   (no zip or Blender < 4.2: nothing to validate)")
        return
    run = subprocess.run([sstest.blender_binary(), "--background", "--factory-startup", "--command",
                          "extension", "validate", ZIP], capture_output=True, text=True, timeout=300)
    out = run.stdout + run.stderr
    sstest.check(run.returncode == 0 and "Success" in out, "extension validate:\n%s" % out[-2000:])


if __name__ == "__main__":
    sstest.run(dict(globals()))
