# Does an object with a negative scale (mirrored, as symmetric modelling leaves it) shadow like its
# twin whose scale was applied, for dbuffer and auto?
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402

ss = sstest.addon()
W, H = 96, 72
METHODS = ("dbuffer", "auto")
# The two objects are the same world surface: the passes agree up to the rasterisation of a vertex
# moved by the matrix or already moved (measured: identical).
SAME_MAX = 0.05
SAME_MEAN = 1e-4
REFERENCE_RMSE = 0.05  # dbuffer on an L prism (about 0.02, DbufferQuality's concave scene)


def add_l_prism(name, location):
    """A closed L prism (asymmetric in x and y), faces outward, 0.3 thick."""
    outline = [(-0.8, -0.8), (0.8, -0.8), (0.8, -0.2), (-0.2, -0.2), (-0.2, 0.8), (-0.8, 0.8)]
    n = len(outline)
    verts = [(x, y, z) for z in (0.0, 0.3) for x, y in outline]
    faces = [tuple(reversed(range(n))), tuple(range(n, 2 * n))]
    faces += [(i, (i + 1) % n, n + (i + 1) % n, n + i) for i in range(n)]
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    obj = bpy.data.objects.new(name, mesh)
    obj.location = location
    bpy.context.scene.collection.objects.link(obj)
    return obj


def l_scene(applied):
    """The L mirrored in x by its scale; `applied`: the scale applied to the mesh (Blender then
    mirrors the vertices and turns the faces, so the surface stays outward)."""
    scene = sstest.clear_scene()
    sstest.add_plane("Ground", 10, (0, 0, 0))
    obj = add_l_prism("L", (0.15, -0.1, 0.9))
    obj.scale = (-1.0, 1.0, 1.0)
    if applied:
        bpy.context.view_layer.objects.active = obj
        obj.select_set(True)
        bpy.ops.object.transform_apply(location=False, rotation=False, scale=True)
    light = sstest.add_light("Key", location=(0.3, 0.2, 4.0), size=1.5)
    light.data.softshadow.samples = 128
    sstest.add_camera(location=(0, 0, 9), width=W, height=H)
    bpy.context.view_layer.update()
    return scene, obj


def passes(applied):
    scene, obj = l_scene(applied)
    det = obj.matrix_world.to_3x3().determinant()
    sstest.check((det < 0) != applied, "the L's matrix mirrors only before the scale is applied (det %.2f)" % det)
    out = {}
    for method in METHODS + ("reference",):
        result = ss.render_passes(scene, methods=method)
        sstest.check(len(result) == 1, "%s: one pass, got %s" % (method, list(result)))
        (_, ran), v = next(iter(result.items()))
        sstest.check(np.isfinite(v).all(), "%s: V finite" % method)
        out[method] = (ran, v)
    return out


def test_negative_scale_shadows_like_its_applied_twin():
    mirrored = passes(applied=False)
    twin = passes(applied=True)
    truth = twin["reference"][1]
    shadowed = float(np.mean(truth < 0.5))
    sstest.check(0.01 < shadowed < 0.5, "the L casts a shadow on %.3f of the image" % shadowed)
    for method in METHODS:
        ran_m, v_m = mirrored[method]
        ran_t, v_t = twin[method]
        sstest.check(ran_m == ran_t, "%s ran %s on the mirrored L, %s on its twin" % (method, ran_m, ran_t))
        diff = np.abs(v_m - v_t)
        rmse = float(np.sqrt(np.mean((v_m - truth) ** 2)))
        print("mirrored %s (ran %s): max %.4f mean %.6f from the twin, RMSE %.4f from the reference"
              % (method, ran_m, float(diff.max()), float(diff.mean()), rmse))
        sstest.check(float(diff.max()) <= SAME_MAX and float(diff.mean()) <= SAME_MEAN,
                     "%s: the mirrored L differs from its twin (max %.4f, mean %.6f)"
                     % (method, float(diff.max()), float(diff.mean())))
        sstest.check(rmse <= REFERENCE_RMSE, "%s: RMSE %.4f above %.3f" % (method, rmse, REFERENCE_RMSE))


sstest.run(globals())
