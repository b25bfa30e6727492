# Does every method take Blender's own Suzanne (an open mesh: its eyes are separate shells) as a
# caster, within a per-method error of the reference?
# SPDX-License-Identifier: GPL-3.0-or-later
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402
import bmesh  # noqa: E402

ss = sstest.addon()
W, H = 128, 96
# RMSE against the reference over the image (V = 1 where a method's mask is 0, as a composite
# uses it), measured on this scene in brackets, with about 30 % of room for llvmpipe versions;
# every soft method's bound is under shadow_map's error, so one that lost its penumbra fails.
# sweep shades the ground plane only (Suzanne's own shadows stay at 1); dbuffer extrudes volumes
# from a mesh the paper assumes closed, which auto never gives it (docs/methods/dbuffer.md).
BOUNDS = {
    "shadow_map": 0.115,  # (0.0896) the hard shadow: the ceiling
    "pcss": 0.048,  # (0.0367)
    "dbuffer": 0.095,  # (0.0734)
    "sweep": 0.073,  # (0.0559)
    "penumbra_map": 0.097,  # (0.0747)
    "occlusion_textures": 0.066,  # (0.0504)
    "auto": 0.048,  # (0.0367, pcss)
}


def suzanne_scene():
    scene = sstest.clear_scene()
    sstest.add_plane("Ground", 10, (0, 0, 0))
    bpy.ops.mesh.primitive_monkey_add(size=1.8, location=(0, 0, 1.2))
    monkey = bpy.context.active_object
    monkey.name = "Suzanne"
    monkey.rotation_euler = (math.radians(-60), 0, 0)  # the face up to the light: its hollows cast
    sstest.add_light("Key", location=(0.8, 0.5, 4.0), size=1.5)
    sstest.add_camera(location=(0, 0, 9), width=W, height=H)
    bpy.context.view_layer.update()
    return scene, monkey


def open_edges(obj):
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    count = sum(1 for e in bm.edges if len(e.link_faces) < 2)
    bm.free()
    return count


def test_every_method_on_suzanne():
    scene, monkey = suzanne_scene()
    sstest.check(open_edges(monkey) > 0, "Blender's Suzanne is open (boundary edges)")
    scene.objects["Key"].data.softshadow.samples = 256
    truth = ss.render_passes(scene, methods="reference")[("Key", "reference")]
    sstest.check(np.isfinite(truth).all(), "reference finite")
    shadowed = float(np.mean(truth < 0.5))
    sstest.check(0.01 < shadowed < 0.5, "Suzanne casts a shadow on %.3f of the image" % shadowed)
    errors = {}
    for method, bound in sorted(BOUNDS.items()):
        result = ss.render_passes(scene, methods=method)
        sstest.check(len(result) == 1, "%s: one pass, got %s" % (method, list(result)))
        (light, ran), v = next(iter(result.items()))
        sstest.check(np.isfinite(v).all() and v.min() >= 0.0 and v.max() <= 1.0, "%s: V finite in [0, 1]" % method)
        if method == "auto":
            sstest.check(ran != "dbuffer", "auto gave dbuffer the open Suzanne")
        errors[method] = float(np.sqrt(np.mean((v - truth) ** 2)))
        print("suzanne %s (ran %s): RMSE %.4f, bound %.3f" % (method, ran, errors[method], bound))
    for method, bound in sorted(BOUNDS.items()):
        sstest.check(errors[method] <= bound, "%s: RMSE %.4f above its bound %.3f" % (method, errors[method], bound))
    # The soft methods beat the hard shadow they start from, and auto is within 1.25x of the best
    # method it may take (dbuffer excluded).
    for method in ("pcss", "sweep", "occlusion_textures"):
        sstest.check(errors[method] < errors["shadow_map"], "%s (%.4f) not below shadow_map (%.4f)"
                     % (method, errors[method], errors["shadow_map"]))
    best = min(e for m, e in errors.items() if m not in ("auto", "dbuffer"))
    sstest.check(errors["auto"] <= 1.25 * best, "auto %.4f above 1.25x the best %.4f" % (errors["auto"], best))


sstest.run(globals())
