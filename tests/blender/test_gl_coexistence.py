# Does our GL context leave Blender's own renders alone: the same pixels before and after many
# calls, and a clean exit? (the three conditions of docs/contracts.md "GL", in this Blender)
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402

ss = sstest.addon()
CALLS = 12
METHODS = ("shadow_map", "pcss", "occlusion_textures", "penumbra_map")
# EEVEE's samples: the pixels need not converge to be compared, and EEVEE Next (4.2+) on a
# software GL driver takes minutes per frame at the default 64.
EEVEE_SAMPLES = 4


def _blender_render(scene, engine, folder, name):
    scene.render.engine = engine
    scene.eevee.taa_render_samples = EEVEE_SAMPLES
    scene.render.filepath = os.path.join(folder, name)
    scene.render.image_settings.file_format = "OPEN_EXR"
    bpy.ops.render.render(write_still=True)
    return sstest.exr_channel(scene.render.filepath + ".exr", "R")


def test_blender_renders_unchanged_by_many_calls():
    folder = sstest.tempdir("coexist")
    scene = sstest.standard_scene(48, 36)
    engines = [ss.compat.eevee_engine_id(scene.render), "BLENDER_WORKBENCH"]
    before = {e: _blender_render(scene, e, folder, "before_" + e) for e in engines}
    light = scene.objects["Key"].data.softshadow
    first = None
    for call in range(CALLS):
        light.method = METHODS[call % len(METHODS)]
        result = ss.render_passes(scene)
        array = next(iter(result.values()))
        sstest.check(array.shape == (36, 48) and np.isfinite(array).all(), "call %d: a finite pass" % call)
        if call % len(METHODS) == 0:
            if first is None:
                first = array.copy()
            sstest.check(np.array_equal(array, first), "call %d repeats call 0 exactly" % call)
    for e in engines:
        after = _blender_render(scene, e, folder, "after_" + e)
        sstest.check(np.array_equal(before[e], after), "%s render identical after %d calls (max diff %g)"
                     % (e, CALLS, float(np.abs(before[e] - after).max())))
    print("   %s: %s renders identical around %d calls" % (bpy.app.version_string, engines, CALLS))


EXIT_SCRIPT = r"""
import bpy, sys
sys.path.insert(0, %r)
import sstest
ss = sstest.addon()
scene = sstest.standard_scene(32, 24)
scene.render.engine = ss.compat.eevee_engine_id(scene.render)
scene.eevee.taa_render_samples = %d
scene.render.filepath = %r
ss.render_passes(scene)
bpy.ops.render.render(write_still=True)
ss.render_passes(scene)
print("SCRIPT-DONE")
"""


def test_clean_exit_after_calls_and_a_render():
    folder = sstest.tempdir("coexist-exit")
    here = os.path.dirname(os.path.abspath(__file__))
    script = EXIT_SCRIPT % (here, EEVEE_SAMPLES, os.path.join(folder, "frame.png"))
    run = subprocess.run([sstest.blender_binary(), "--background", "--factory-startup", "--python-exit-code", "1",
                          "--python-expr", script], capture_output=True, text=True, timeout=600)
    log = run.stdout + run.stderr
    sstest.check("SCRIPT-DONE" in log, "the script ran:\n%s" % log[-3000:])
    sstest.check(run.returncode == 0, "Blender exits 0 (got %d):\n%s" % (run.returncode, log[-3000:]))
    sstest.check(not sstest.our_tracebacks(log), "no traceback of ours:\n%s" % log[-3000:])


if __name__ == "__main__":
    sstest.run(dict(globals()))
