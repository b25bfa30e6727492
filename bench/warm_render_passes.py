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
bpy.ops.mesh.primitive_torus_add(major_segments=256, minor_segments=216, major_radius=1.2, minor_radius=0.35,
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
    """(total, export) seconds of one moved frame."""
    mover.location.x += 0.05
    bpy.context.view_layer.update()
    start = time.perf_counter()
    exported = scene_export.export(bpy.context.evaluated_depsgraph_get(), scene)
    exported_at = time.perf_counter()
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
    return seconds, exported_at - start


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
    rows.append((method, statistics.median(t for t, _ in cold), statistics.median(t for t, _ in warm),
                 statistics.median(e for _, e in warm), uploads))
    print("BENCH warm_render_passes %s cold %.3f s warm %.3f s (export %.3f s) uploads/frame %.1f" % rows[-1],
          flush=True)

# The preview after a move (960x540, the viewport's path): the main thread's export of the edit
# and the worker's update + render, against the path that exported and built the whole scene.
preview = sys.modules["softshadow.preview"]
preview_rows = []
for method in ("shadow_map", "pcss", "occlusion_textures"):
    light.data.softshadow.method = method
    bpy.context.view_layer.update()
    depsgraph = bpy.context.evaluated_depsgraph_get()
    camera = scene_export.scene_camera(scene, depsgraph, 960, 540)
    preview._state.full = True
    live = passes.LiveScene()
    preview._render_job(live, [preview.export_edit(depsgraph, scene)], camera, lambda: False)
    main, worker, cold = [], [], []
    for _ in range(frames + 2):
        mover.location.x += 0.05
        bpy.context.view_layer.update()  # the preview's handler notes the move
        start = time.perf_counter()
        edit = preview.export_edit(depsgraph, scene)
        exported_at = time.perf_counter()
        preview._render_job(live, [edit], camera, lambda: False)
        done = time.perf_counter()
        main.append(exported_at - start)
        worker.append(done - exported_at)
        start = time.perf_counter()
        fresh = passes.LiveScene()
        full = scene_export.export(depsgraph, scene, mode="VIEWPORT", camera=camera)
        preview._render_job(fresh, [("full", full)], camera, lambda: False)
        fresh.close()
        cold.append(time.perf_counter() - start)
    live.close()
    preview_rows.append((method, statistics.median(cold), statistics.median(main), statistics.median(worker)))
    print("BENCH preview_move %s cold %.3f s main thread %.4f s worker %.3f s" % preview_rows[-1], flush=True)

with open(out_path, "w") as f:
    f.write("# render_passes on a warm scene (one object moved per frame)\n\n")
    f.write("%d triangles, one disk light, %d² pixels; median of %d moved frames of export + "
            "`passes.compute` per method. cold: a native scene built per call; warm: the kept scene "
            "(the moved box alone sent). bench/warm_render_passes.py.\n\n" % (triangles, size, frames))
    f.write("| method | cold (s) | warm (s) | of which export (s) | meshes uploaded per warm frame |\n"
            "|---|---|---|---|---|\n")
    for method, c, w, e, u in rows:
        f.write("| %s | %.3f | %.3f | %.3f | %.1f |\n" % (method, c, w, e, u))
    f.write("\n## The preview after a move (960x540)\n\nMedian over %d moves. cold: export the whole "
            "scene and build a native scene (the path before scenes were kept); main thread: "
            "`preview.export_edit` (the moved object's matrix); worker: applying it to the kept "
            "scene and rendering.\n\n| method | cold (s) | main thread (s) | worker (s) |\n|---|---|---|---|\n"
            % (frames + 2))
    for method, c, m, w in preview_rows:
        f.write("| %s | %.3f | %.4f | %.3f |\n" % (method, c, m, w))
print("BENCH-WARM-OK")
