# How long does render_passes take on the second frame of an animation where one object moved: a scene built afresh per call against the kept one?
# SPDX-License-Identifier: GPL-3.0-or-later
# Usage: blender -b --factory-startup --python bench/warm_render_passes.py -- OUT.md [SIZE] [FRAMES]
# SOFTSHADOW_LIB and SOFTSHADOW_ADDON_PATH (or an installed add-on) as for tests/blender.
# ~110k triangles (a subdivided torus) over a ground plane, one disk light, a small box that moves
# 0.05 along x every frame. Per GL method: the median over FRAMES moved frames of export + the
# library's work (passes.compute), cold = a new native scene per call (what every call did before
# scenes were kept), warm = the kept scene (only the moved box sent); and the meshes uploaded per
# warm frame (ss_context_cache_stats).
import os
import statistics
import sys
import time

import bpy

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
out_path = argv[0] if argv else "warm_render_passes.md"
size = int(argv[1]) if len(argv) > 1 else 1024
frames = int(argv[2]) if len(argv) > 2 else 3

sys.path.insert(0, os.environ.get("SOFTSHADOW_ADDON_PATH", ""))
import softshadow  # noqa: E402
if not hasattr(bpy.types.Scene, "softshadow"):
    softshadow.register()
from softshadow import native, passes, scene_export  # noqa: E402

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
bpy.ops.mesh.primitive_plane_add(size=10, location=(0, 0, 0))
bpy.ops.mesh.primitive_torus_add(major_segments=384, minor_segments=144, major_radius=1.2, minor_radius=0.35,
                                 location=(0, 0, 1.2))
bpy.ops.mesh.primitive_cube_add(size=0.4, location=(-1.8, 0.8, 0.6))
mover = bpy.context.active_object
bpy.ops.object.light_add(type="AREA", location=(-2, -1, 6))
light = bpy.context.active_object
light.data.shape = "DISK"
light.data.size = 0.8
bpy.ops.object.camera_add(location=(0, -7, 6), rotation=(0.85, 0, 0))
scene.camera = bpy.context.active_object
scene.render.resolution_x = scene.render.resolution_y = size
scene.render.resolution_percentage = 100
bpy.context.view_layer.update()

depsgraph = bpy.context.evaluated_depsgraph_get()
triangles = sum(len(m["triangles"]) for m in scene_export.export(depsgraph, scene).meshes)
methods = [m for m in native.method_names() if m != "reference"]


def one_frame(method, live):
    mover.location.x += 0.05
    bpy.context.view_layer.update()
    start = time.perf_counter()
    exported = scene_export.export(bpy.context.evaluated_depsgraph_get(), scene)
    fresh = live is None
    kept = passes.LiveScene() if fresh else live
    try:
        result = passes.compute(exported, methods=[method], live=kept)
    finally:
        if fresh:
            kept.close()
    seconds = time.perf_counter() - start
    if not result.arrays:
        raise RuntimeError("%s: no pass: %s" % (method, result.problems))
    return seconds


rows = []
for method in methods:
    cold = [one_frame(method, None) for _ in range(frames)]
    live = passes.LiveScene()
    one_frame(method, live)  # the first frame builds the kept scene
    before = native.cache_stats()
    warm = [one_frame(method, live) for _ in range(frames)]
    after = native.cache_stats()
    live.close()
    uploads = (after["mesh_uploads"] - before["mesh_uploads"]) / frames
    rows.append((method, statistics.median(cold), statistics.median(warm), uploads))
    print("BENCH warm_render_passes %s cold %.3f s warm %.3f s uploads/frame %.1f" % rows[-1], flush=True)

with open(out_path, "w") as f:
    f.write("# render_passes on a warm scene (one object moved per frame)\n\n")
    f.write("%d triangles, one disk light, %d² pixels; median of %d moved frames of export + "
            "`passes.compute` per method. cold: a native scene built per call; warm: the kept scene "
            "(the moved box alone sent). bench/warm_render_passes.py.\n\n" % (triangles, size, frames))
    f.write("| method | cold (s) | warm (s) | meshes uploaded per warm frame |\n|---|---|---|---|\n")
    for method, c, w, u in rows:
        f.write("| %s | %.3f | %.3f | %.1f |\n" % (method, c, w, u))
print("BENCH-WARM-OK")
