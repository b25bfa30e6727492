# Does the add-on installed from the zip load its own library, validate as an extension, and answer
# pipeline scripts at `import softshadow` in this Blender and this install mode?
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import subprocess
import sys

import numpy as np

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


def test_import_softshadow_reaches_render_passes():
    # What pipeline scripts do, whatever the install mode: the enabled add-on answers `softshadow`.
    import softshadow
    sstest.check(softshadow is ss, "import softshadow is the enabled add-on (%s)" % softshadow.__name__)
    scene = sstest.standard_scene(32, 24)
    scene.objects["Key"].data.softshadow.method = "shadow_map"
    result = softshadow.render_passes(scene)
    sstest.check(list(result) == [("Key", "shadow_map")], "passes %s" % list(result))
    array = result[("Key", "shadow_map")]
    dark = float((array < 0.05).mean())
    sstest.check(0.01 < dark < 0.5, "a shadow where the box stands (%.3f of the pixels dark)" % dark)


def test_extension_validates():
    if not (ZIP and EXTENSIONS):
        print("   (no zip or Blender < 4.2: nothing to validate)")
        return
    run = subprocess.run([bpy.app.binary_path, "--background", "--factory-startup", "--command",
                          "extension", "validate", ZIP], capture_output=True, text=True, timeout=300)
    out = run.stdout + run.stderr
    sstest.check(run.returncode == 0 and "Success" in out, "extension validate:\n%s" % out[-2000:])


def test_unregister_leaves_no_public_alias():
    if not sstest.INSTALLED_MODULE or sstest.INSTALLED_MODULE == "softshadow":
        return
    import addon_utils
    addon_utils.disable(sstest.INSTALLED_MODULE, default_set=True)
    sstest.check("softshadow" not in sys.modules, "the plain name goes with the add-on")
    addon_utils.enable(sstest.INSTALLED_MODULE, default_set=True)
    sstest.check(sys.modules.get("softshadow") is sys.modules[sstest.INSTALLED_MODULE], "and comes back")


if __name__ == "__main__":
    sstest.run(dict(globals()))
