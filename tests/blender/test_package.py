# Does the packaged zip carry a library that needs nothing a Blender machine lacks, install from
# Preferences and load that library?
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import re
import subprocess
import sys
import zipfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402

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


# What a machine that runs Blender has: glibc's parts, the C++ runtime. GL (libEGL, libOSMesa) is
# opened with dlopen at run time, so it is not a NEEDED entry at all.
SYSTEM_LIBRARIES = {"libc.so.6", "libm.so.6", "libdl.so.2", "libpthread.so.0", "librt.so.1",
                    "ld-linux-x86-64.so.2", "libstdc++.so.6", "libgcc_s.so.1"}
# Ubuntu 22.04 has glibc 2.35 and RHEL 9 glibc 2.34 with GCC 11's libstdc++ (GLIBCXX_3.4.29).
MAX_GLIBC = (2, 34)
MAX_GLIBCXX = (3, 4, 29)
MAX_ZIP_BYTES = 40 * 1024 * 1024


def _make_zip(folder, version):
    script = os.path.join(sstest.ROOT, "blender_addon", "package.sh")
    env = dict(os.environ, SOFTSHADOW_DIST=folder)
    run = subprocess.run(["bash", script, sstest.build_dir(), version], capture_output=True, text=True,
                         env=env, timeout=300)
    sstest.check(run.returncode == 0, "package.sh failed: %s %s" % (run.stdout, run.stderr))
    return os.path.join(folder, "softshadow-%s.zip" % version)


def _highest(text, prefix):
    found = {tuple(int(p) for p in v.split(".")) for v in re.findall(prefix + r"_([0-9.]+[0-9])", text)}
    return max(found) if found else ()


def test_zip_needs_only_system_libraries():
    folder = sstest.tempdir("pkg-needed")
    zip_path = _make_zip(folder, "0.0.1")
    size = os.path.getsize(zip_path)
    sstest.check(size <= MAX_ZIP_BYTES, "zip %.1f MB, at most %.0f MB" % (size / 2**20, MAX_ZIP_BYTES / 2**20))
    with zipfile.ZipFile(zip_path) as z:
        z.extractall(folder)
    lib = os.path.join(folder, "softshadow", "lib")
    shipped = sorted(os.listdir(lib))
    glibc, glibcxx = (), ()
    for name in shipped:
        path = os.path.join(lib, name)
        dynamic = subprocess.run(["readelf", "-d", path], capture_output=True, text=True, check=True).stdout
        needed = re.findall(r"\(NEEDED\)\s+Shared library: \[(.+)\]", dynamic)
        outside = [n for n in needed if n not in SYSTEM_LIBRARIES and n not in shipped]
        sstest.check(not outside, "%s needs %s, neither shipped nor on every system" % (name, outside))
        sstest.check("$ORIGIN" in dynamic, "%s finds its neighbours through RUNPATH $ORIGIN" % name)
        versions = subprocess.run(["readelf", "-V", path], capture_output=True, text=True, check=True).stdout
        glibc = max(glibc, _highest(versions, "GLIBC"))
        glibcxx = max(glibcxx, _highest(versions, "GLIBCXX"))
    print("   zip %.1f MB; lib/: %s" % (size / 2**20, " ".join(shipped)))
    print("   highest symbol versions needed: GLIBC_%s GLIBCXX_%s"
          % (".".join(map(str, glibc)), ".".join(map(str, glibcxx))))
    sstest.check(glibc <= MAX_GLIBC, "GLIBC_%s needed, at most %s" % (glibc, MAX_GLIBC))
    sstest.check(glibcxx <= MAX_GLIBCXX, "GLIBCXX_%s needed, at most %s" % (glibcxx, MAX_GLIBCXX))


def test_zip_installs_and_loads_bundled_library():
    folder = sstest.tempdir("pkg")
    zip_path = _make_zip(folder, "9.8.7")
    sstest.check(os.path.exists(zip_path), "zip made: %s" % zip_path)
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
    run = subprocess.run([sstest.blender_binary(), "--background", "--factory-startup", "--python-expr",
                          INSTALL % zip_path], capture_output=True, text=True, env=env, timeout=300)
    out = run.stdout + run.stderr
    installed = os.path.join(folder, "scripts", "addons", "softshadow", "lib", "libsoftshadow.so")
    sstest.check("LOADED True FROM %s" % installed in out, "bundled library loaded:\n%s" % out[-3000:])
    sstest.check("ENABLED True" in out, "enabled:\n%s" % out[-2000:])
    sstest.check("DONE" in out and "Traceback" not in out, "clean run:\n%s" % out[-2000:])


if __name__ == "__main__":
    sstest.run(dict(globals()))
