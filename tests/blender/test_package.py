# Does the packaged zip install from Preferences and load its own bundled library?
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import subprocess
import sys
import zipfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402

INSTALL = r"""
import os, bpy, addon_utils
bpy.ops.preferences.addon_install(filepath=%r)
bpy.ops.preferences.addon_enable(module="softshadow")
import softshadow
info = softshadow.native.status()
print("LOADED", info["loaded"], "FROM", info.get("path"), "VERSION", info["version"])
print("ENABLED", addon_utils.check("softshadow")[1])
bpy.ops.preferences.addon_disable(module="softshadow")
print("DONE")
"""


def test_zip_installs_and_loads_bundled_library():
    folder = sstest.tempdir("pkg")
    script = os.path.join(sstest.ROOT, "blender_addon", "package.sh")
    env = dict(os.environ, SOFTSHADOW_DIST=folder)
    run = subprocess.run(["bash", script, sstest.build_dir(), "9.8.7"], capture_output=True, text=True,
                         env=env, timeout=300)
    sstest.check(run.returncode == 0, "package.sh failed: %s %s" % (run.stdout, run.stderr))
    zip_path = os.path.join(folder, "softshadow-9.8.7.zip")
    sstest.check(os.path.exists(zip_path), "zip made: %s" % run.stdout)
    names = zipfile.ZipFile(zip_path).namelist()
    for needed in ("softshadow/__init__.py", "softshadow/native.py", "softshadow/blender_manifest.toml",
                   "softshadow/lib/libsoftshadow.so"):
        sstest.check(needed in names, "%s in the zip: %s" % (needed, names))
    sstest.check(not any("__pycache__" in n for n in names), "no caches in the zip")
    manifest = zipfile.ZipFile(zip_path).read("softshadow/blender_manifest.toml").decode()
    sstest.check('version = "9.8.7"' in manifest, "manifest version stamped")
    init = zipfile.ZipFile(zip_path).read("softshadow/__init__.py").decode()
    sstest.check('"version": (9, 8, 7)' in init, "bl_info version stamped")

    # A fresh user config: install as a user would, with no SOFTSHADOW_LIB to fall back on.
    env = {k: v for k, v in os.environ.items() if k not in ("SOFTSHADOW_LIB", "PYTHONPATH")}
    env["BLENDER_USER_SCRIPTS"] = os.path.join(folder, "scripts")
    env["BLENDER_USER_CONFIG"] = os.path.join(folder, "config")
    run = subprocess.run([bpy.app.binary_path, "--background", "--factory-startup", "--python-expr",
                          INSTALL % zip_path], capture_output=True, text=True, env=env, timeout=300)
    out = run.stdout + run.stderr
    installed = os.path.join(folder, "scripts", "addons", "softshadow", "lib", "libsoftshadow.so")
    sstest.check("LOADED True FROM %s" % installed in out, "bundled library loaded:\n%s" % out[-3000:])
    sstest.check("ENABLED True" in out, "enabled:\n%s" % out[-2000:])
    sstest.check("DONE" in out and "Traceback" not in out, "clean run:\n%s" % out[-2000:])


if __name__ == "__main__":
    sstest.run(dict(globals()))
