# Does the CLI, on a scene file the add-on exported, give the add-on's own passes bit for bit?
# (the source tree's CLI, beside its library: not part of the zip, so not in the version matrix)
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402

ss = sstest.addon()
W, H = 64, 48


def test_cli_on_an_exported_scene_gives_the_add_on_s_pixels():
    # The scene file keeps each mesh's object-space vertices and matrix, and the CLI builds the
    # scene the add-on renders from them: every method's every pixel equal, bit for bit.
    # Rotated, scaled and subdivided meshes make the transforms count (world vertices computed
    # apart from the library's differed in 900 to 2700 of these pixels for each method but
    # shadow_map), a light's sample count the seed.
    cli = os.path.join(sstest.build_dir(), "softshadow")
    sstest.check(os.path.exists(cli), "no CLI at %s (build the softshadow_cli target)" % cli)
    scene = sstest.standard_scene(4 * W, 4 * H)
    scene.objects["Ground"].rotation_euler = (0.01, -0.02, 0.3)
    plate = scene.objects["Occluder"]
    plate.rotation_euler = (0.3, -0.2, 0.7)
    plate.scale = (1.3, 0.8, 1.0)
    plate.modifiers.new("Sub", "SUBSURF").levels = 2
    box = sstest.add_box("Box", 0.6, (1.2, 1.5, 1.1))
    box.rotation_euler = (0.0, 0.4, 1.1)
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.5, location=(-2.1, -1.3, 1.4))
    ball = bpy.context.active_object
    ball.rotation_euler = (0.5, 0.9, 0.2)
    ball.scale = (1.7, 0.6, 1.1)
    scene.objects["Key"].data.softshadow.samples = 24
    bpy.context.view_layer.update()
    folder = sstest.tempdir("cli")
    scene_file = os.path.join(folder, "scene.json")
    problems = ss.api.export_scene_file(scene, scene_file)
    sstest.check(problems == [], "clean export: %s" % problems)
    methods = ss.native.method_names()
    from_api = ss.render_passes(scene, methods=list(methods))
    out = os.path.join(folder, "cli.exr")
    run = subprocess.run([cli, "render", scene_file, "-m", ",".join(methods), "--samples", "24", "--no-extra",
                          "-o", out], capture_output=True, text=True, timeout=600)
    sstest.check(run.returncode == 0, "CLI render failed: %s %s" % (run.stdout, run.stderr))
    for method in methods:
        from_cli = sstest.exr_channel(out, "ViewLayer.Key_%s.V" % method)
        api = from_api[("Key", method)]
        differ = int(np.count_nonzero(from_cli != api))
        sstest.check(differ == 0, "%s: the CLI and the add-on differ at %d of %d pixels (by up to %g)" % (
            method, differ, api.size, float(np.abs(from_cli - api).max())))
        sstest.check(float(api.min()) < 0.5 < float(api.max()), "%s: a shadow in view (%g..%g)" % (
            method, api.min(), api.max()))


if __name__ == "__main__":
    sstest.run(dict(globals()))
