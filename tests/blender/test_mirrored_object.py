# Does an object with a negative scale (mirrored, as symmetric modelling leaves it) shadow like its
# twins whose mesh data are mirrored instead (by hand, or by applying the scale and turning the
# faces outward), for dbuffer and auto?
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402
import bmesh  # noqa: E402

ss = sstest.addon()
W, H = 96, 72
METHODS = ("dbuffer", "auto")
# The two objects are the same world surface: the passes agree up to the rasterisation of a vertex
# moved by the matrix or already moved (measured: identical).
SAME_MAX = 0.05
SAME_MEAN = 1e-4
REFERENCE_RMSE = 0.05  # dbuffer on an L prism (about 0.02, DbufferQuality's concave scene)


def add_l_prism(name, location, mirrored_data=False):
    """A closed L prism (asymmetric in x and y), 0.3 thick, as triangles (so both objects are cut
    into the same triangles), faces outward. `mirrored_data`: its vertices mirrored in x and
    every face turned, the surface a scale of (-1, 1, 1) gives."""
    outline = [(-0.8, -0.8), (0.8, -0.8), (0.8, -0.2), (-0.2, -0.2), (-0.2, 0.8), (-0.8, 0.8)]
    n = len(outline)
    verts = [(x, y, z) for z in (0.0, 0.3) for x, y in outline]
    # The caps fan from the reflex corner (3), which sees every other vertex.
    fan = [(3, (3 + k) % n, (3 + k + 1) % n) for k in range(1, n - 1)]
    faces = [(a, c, b) for a, b, c in fan] + [(n + a, n + b, n + c) for a, b, c in fan]
    for i in range(n):
        j = (i + 1) % n
        faces += [(i, j, n + j), (i, n + j, n + i)]
    if mirrored_data:
        verts = [(-x, y, z) for x, y, z in verts]
        faces = [(a, c, b) for a, b, c in faces]
    return sstest.add_mesh(name, verts, faces, location)


def signed_volume(mesh):
    mesh.calc_loop_triangles()
    total = 0.0
    for t in mesh.loop_triangles:
        a, b, c = (mesh.vertices[i].co for i in t.vertices)
        total += a.dot(b.cross(c)) / 6.0
    return total


def l_scene(kind):
    """The L mirrored in x: by its scale ("scale"), by its mesh data with the scale 1 ("data"), or
    by its scale applied to the mesh and its faces turned outward ("applied")."""
    scene = sstest.clear_scene()
    sstest.add_plane("Ground", 10, (0, 0, 0))
    obj = add_l_prism("L", (0.15, -0.1, 0.9), mirrored_data=kind == "data")
    if kind != "data":
        obj.scale = (-1.0, 1.0, 1.0)
    if kind == "applied":
        bpy.context.view_layer.objects.active = obj
        obj.select_set(True)
        bpy.ops.object.transform_apply(location=False, rotation=False, scale=True)
        # Blender 3.4 mirrors the vertices but keeps the faces' order, leaving the mesh inside out
        # until its faces are turned (Recalculate Outside, what a user does); 5.x turns them.
        if signed_volume(obj.data) < 0:
            bm = bmesh.new()
            bm.from_mesh(obj.data)
            bmesh.ops.reverse_faces(bm, faces=bm.faces)
            bm.to_mesh(obj.data)
            bm.free()
    sstest.check(signed_volume(obj.data) > 0, "%s: the L's mesh data face outward" % kind)
    light = sstest.add_light("Key", location=(0.3, 0.2, 4.0), size=1.5)
    light.data.softshadow.samples = 128
    sstest.add_camera(location=(0, 0, 9), width=W, height=H)
    bpy.context.view_layer.update()
    return scene, obj


def passes(kind):
    scene, obj = l_scene(kind)
    det = obj.matrix_world.to_3x3().determinant()
    sstest.check((det < 0) == (kind == "scale"), "%s: only the scaled L's matrix mirrors (det %.2f)" % (kind, det))
    out = {}
    for method in METHODS + ("reference",):
        result = ss.render_passes(scene, methods=method)
        sstest.check(len(result) == 1, "%s: one pass, got %s" % (method, list(result)))
        (_, ran), v = next(iter(result.items()))
        sstest.check(np.isfinite(v).all(), "%s: V finite" % method)
        out[method] = (ran, v)
    return out


def test_negative_scale_shadows_like_its_mirrored_twins():
    mirrored = passes("scale")
    for kind in ("data", "applied"):
        twin = passes(kind)
        truth = twin["reference"][1]
        shadowed = float(np.mean(truth < 0.5))
        sstest.check(0.01 < shadowed < 0.5, "the L casts a shadow on %.3f of the image" % shadowed)
        for method in METHODS:
            ran_m, v_m = mirrored[method]
            ran_t, v_t = twin[method]
            sstest.check(ran_m == ran_t, "%s ran %s on the mirrored L, %s on its twin" % (method, ran_m, ran_t))
            diff = np.abs(v_m - v_t)
            rmse = float(np.sqrt(np.mean((v_m - truth) ** 2)))
            print("mirrored %s (ran %s): max %.4f mean %.6f from the %s twin, RMSE %.4f from the reference"
                  % (method, ran_m, float(diff.max()), float(diff.mean()), kind, rmse))
            sstest.check(float(diff.max()) <= SAME_MAX and float(diff.mean()) <= SAME_MEAN,
                         "%s: the mirrored L differs from its %s twin (max %.4f, mean %.6f)"
                         % (method, kind, float(diff.max()), float(diff.mean())))
            sstest.check(rmse <= REFERENCE_RMSE, "%s: RMSE %.4f above %.3f" % (method, rmse, REFERENCE_RMSE))


sstest.run(globals())
