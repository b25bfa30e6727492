# Where does the time go on the second frame of an animation where one object moved: render_passes
# per GL method, and the preview's edit-to-overlay latency?
# SPDX-License-Identifier: GPL-3.0-or-later
# Usage: blender -b --factory-startup --python bench/warm_render_passes.py -- OUT.md [SIZE] [FRAMES] [SCENES] [PARTS]
#        [PREVIEW_METHODS]
# SOFTSHADOW_LIB and SOFTSHADOW_ADDON_PATH (or an installed add-on) as for tests/blender.
# SCENES: comma-separated torus counts (default "1,9"): one torus of 110,592 triangles, or nine
# (~1M triangles), over a ground plane, one disk light, a small box that moves 0.05 along x every
# frame. For each scene:
#   - render_passes per GL method at SIZE² on the kept scene (the add-on's path): the median over
#     FRAMES moved frames of each stage: the export (Python, render_passes' own: meshes whose geometry
#     the depsgraph did not report changed come from mesh_cache; beside it the full export that reads
#     every mesh), the C API update (LiveScene.sync),
#     the library's mesh upload, camera pass, shadow map and the method's own work (timed by
#     ss_context_cache_stat), the rest of ss_render (thread hand-off, checks), the copy of the
#     layers into numpy and the EXR write of a final render; and the floor: the same render on an
#     unchanged scene (every cache kept: the method's own passes and the read-back, which no edit
#     tracking removes); and the sweep once more with the box where its shadow stays apart from
#     the tori's (then a move fills again only the box's part of the shadow);
# PARTS: comma-separated, of "render", "preview" and "final" (default all): which of those below run.
#   - the preview after a move at 960x540 (shadow_map, pcss, occlusion_textures, and auto, the
#     preview's default, which takes its method by the light's shape): edit-to-overlay
#     latency of the coarse image and of the full one (main thread's export of the edit + the
#     worker's updates, renders and overlays, `preview.progressive_job`) over an animated sequence
#     of 2 x FRAMES moves, median and 95th percentile, with its stages; and the floor of each image:
#     a request with no edit (a new view of the same scene costs at least this); then a camera
#     orbit: 2 x FRAMES views, each the last turned 2 degrees about the scene's vertical axis
#     (nothing moved: the camera pass is redrawn whole, the shadow maps kept); and the converging
#     preview over FRAMES moves: seconds from the move to the refined image's first round and to
#     its last (the final render's error target), and the shadow rays per second it traces.
#   - a final render's frame (auto with refine=on, what F12 and `blender -b -a` give) at SIZE² after
#     a move: its seconds, the mesh BVHs it built (the ray tracer's scene keeps each mesh's BVH
#     under a new instance), and the same render on an unchanged scene.
import math
import os
import statistics
import sys
import tempfile
import time

import bpy

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
out_path = argv[0] if argv else "warm_render_passes.md"
size = int(argv[1]) if len(argv) > 1 else 1024
frames = int(argv[2]) if len(argv) > 2 else 5
torus_counts = [int(n) for n in (argv[3] if len(argv) > 3 else "1,9").split(",")]
parts = set((argv[4] if len(argv) > 4 else "render,preview,final").split(","))
FINAL_FRAMES = 3  # a final frame takes seconds: fewer of them

sys.path.insert(0, os.environ.get("SOFTSHADOW_ADDON_PATH", ""))
import softshadow  # noqa: E402
if not hasattr(bpy.types.Scene, "softshadow"):
    softshadow.register()
from softshadow import mesh_cache, native, passes, scene_export  # noqa: E402

preview = sys.modules["softshadow.preview"]
# auto: what the preview renders by default (docs/user-guide.md: by the light's shape, dbuffer
# for this disk light), so the report holds for what users get.
PREVIEW_METHODS = tuple((argv[5] if len(argv) > 5 else "shadow_map,pcss,occlusion_textures,auto").split(","))
TARGET_RENDER = {1: 0.100, 9: 1.0}    # render_passes per light (issue 16)
TARGET_PREVIEW = 0.150                # edit-to-overlay at 960x540 on 1M triangles
TARGET_COARSE = 0.050                 # edit-to-coarse-overlay on 1M triangles
TARGET_CONVERGED = {1: 2.0, 9: 5.0}   # edit to the refined image's last round at 960x540 (issue 28)
# Where the box's shadow stays clear of the tori's while it moves: the sweep fills again only the
# part of its shadow the move reached (in the main rows the box's shadow meets the torus's).
BOX_APART = {1: (-4.0, 0.8), 9: (-5.8, -5.8)}
SWEEP_APART = "sweep, shadows apart"


def build_scene(tori):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    bpy.ops.mesh.primitive_plane_add(size=14, location=(0, 0, 0))
    side = int(math.ceil(math.sqrt(tori)))
    for i in range(tori):
        x, y = (i % side - (side - 1) / 2) * 3.0, (i // side - (side - 1) / 2) * 3.0
        bpy.ops.mesh.primitive_torus_add(major_segments=256, minor_segments=216, major_radius=1.2,
                                         minor_radius=0.35, location=(x, y, 1.2))
    bpy.ops.mesh.primitive_cube_add(size=0.4, location=(-1.8, 0.8, 0.6))
    mover = bpy.context.active_object
    bpy.ops.object.light_add(type="AREA", location=(-2, -1, 6))
    light = bpy.context.active_object
    light.data.shape = "DISK"
    light.data.size = 0.8
    distance = 7.0 if tori == 1 else 13.0
    bpy.ops.object.camera_add(location=(0, -distance, distance * 6 / 7), rotation=(0.85, 0, 0))
    scene.camera = bpy.context.active_object
    scene.render.resolution_x = scene.render.resolution_y = size
    scene.render.resolution_percentage = 100
    bpy.context.view_layer.update()
    return scene, mover, light


def stats_delta(before, after):
    return {k: after[k] - before[k] for k in after}


def move(mover):
    mover.location.x += 0.05
    bpy.context.view_layer.update()


def render_passes_frame(scene, mover, method, live, exr_path):
    """Seconds per stage of one moved frame of render_passes (and its EXR)."""
    move(mover)
    t0 = time.perf_counter()
    exported = scene_export.export(bpy.context.evaluated_depsgraph_get(), scene, reuse=mesh_cache.render_meshes)
    t1 = time.perf_counter()
    live.sync(exported)
    t2 = time.perf_counter()
    before = native.cache_stats()
    result = live.scene.render(live.light_indices()[exported.lights[0]["name"]], method)
    t3 = time.perf_counter()
    after = stats_delta(before, native.cache_stats())
    try:
        layers = result.layers()
        t4 = time.perf_counter()
        native.write_exr(exr_path, exported.view_layer, [result])
        t5 = time.perf_counter()
    finally:
        result.close()
    if "V" not in layers:
        raise RuntimeError("%s made no V layer" % method)
    t6 = time.perf_counter()
    scene_export.export(bpy.context.evaluated_depsgraph_get(), scene)  # what every frame read before mesh_cache
    full_export = time.perf_counter() - t6
    shared = (after["upload_ms"] + after["camera_pass_ms"] + after["shadow_map_ms"]) / 1e3
    return {"export": t1 - t0, "full export": full_export, "update": t2 - t1, "upload": after["upload_ms"] / 1e3,
            "camera pass": after["camera_pass_ms"] / 1e3, "shadow map": after["shadow_map_ms"] / 1e3,
            "method": after["method_ms"] / 1e3 - shared, "ss_render rest": (t3 - t2) - after["method_ms"] / 1e3,
            "copy out": t4 - t3, "total": t4 - t0, "EXR write": t5 - t4,
            "uploads": after["mesh_uploads"]}


def render_row(scene, mover, method, triangles):
    """Median seconds per stage of render_passes over the moved frames, and the floor."""
    live = passes.LiveScene()
    render_passes_frame(scene, mover, method, live, exr_path)  # the first frame builds the kept scene
    runs = [render_passes_frame(scene, mover, method, live, exr_path) for _ in range(frames)]
    floor = statistics.median(render_floor(scene, method, live) for _ in range(frames))
    live.close()
    row = {k: statistics.median(r[k] for r in runs) for k in runs[0]}
    row["floor"] = floor
    print("BENCH warm %d tris %s: %s" % (triangles, method, " ".join(
        "%s=%.3f" % (k, v) for k, v in row.items())), flush=True)
    return row


def render_floor(scene, method, live):
    """Seconds of render_passes' render and copy-out on an unchanged scene."""
    t0 = time.perf_counter()
    result = live.scene.render(live.light_indices()[live.lights[0]["name"]], method)
    try:
        result.layers()
    finally:
        result.close()
    return time.perf_counter() - t0


def preview_request(scenes, camera):
    """Seconds to the coarse and to the full image of a request with no edit (at a new camera:
    a new view), and the seconds of the camera pass each image drew."""
    t0 = time.perf_counter()
    images, passes_ms = [], [native.cache_stats()["camera_pass_ms"]]

    def deliver(rgba, _stage, _round):
        images.append(time.perf_counter())
        passes_ms.append(native.cache_stats()["camera_pass_ms"])

    preview.progressive_job(scenes, {"coarse": [], "full": []}, [], camera, lambda: False, deliver,
                            stages=("coarse", "full"), choices=choices)
    return (images[0] - t0, images[1] - t0, (passes_ms[1] - passes_ms[0]) / 1e3,
            (passes_ms[2] - passes_ms[1]) / 1e3)


def preview_frame(scene, mover, scenes, camera):
    """Seconds per stage of one move in the preview (coarse and full image together): main
    thread, worker; and the edit-to-overlay latency of each image."""
    move(mover)  # the preview's depsgraph handler notes the move
    depsgraph = bpy.context.evaluated_depsgraph_get()
    t0 = time.perf_counter()
    edit = preview.export_edit(depsgraph, scene)
    t1 = time.perf_counter()
    before = native.cache_stats()
    images = []
    preview.progressive_job(scenes, {"coarse": [], "full": []}, [edit], camera, lambda: False,
                            lambda rgba, _stage, _round: images.append(time.perf_counter()), stages=("coarse", "full"),
                            choices=choices)
    t2 = time.perf_counter()
    after = stats_delta(before, native.cache_stats())
    shared = (after["upload_ms"] + after["camera_pass_ms"] + after["shadow_map_ms"]) / 1e3
    return {"main thread": t1 - t0, "camera pass": after["camera_pass_ms"] / 1e3,
            "shadow map": after["shadow_map_ms"] / 1e3, "method": after["method_ms"] / 1e3 - shared,
            "worker rest": (t2 - t1) - after["method_ms"] / 1e3, "full render": images[1] - images[0],
            "coarse": images[0] - t0, "latency": images[1] - t0}


# What the converging preview delivers after a move: the coarse and the full GL image, each
# refinement round but the last, and the last (the final render's error target).
CONVERGED_STAGES = (("coarse", "full") + tuple("refined %d" % k for k in range(1, preview.REFINE_ROUNDS))
                    + ("refined",))


def preview_converged(scene, mover, scenes, camera):
    """Seconds from a move to each image of CONVERGED_STAGES (the GL pass refined with rays in
    rounds while nothing changes, to the final render's error target, what the viewport
    converges to)."""
    move(mover)
    t0 = time.perf_counter()
    edit = preview.export_edit(bpy.context.evaluated_depsgraph_get(), scene)
    images = {}

    def deliver(rgba, stage, round_):
        images.setdefault(preview.stage_label(stage, round_), time.perf_counter() - t0)

    preview.progressive_job(scenes, {"coarse": [], "full": []}, [edit], camera, lambda: False, deliver,
                            choices=choices)
    return [images[label] for label in CONVERGED_STAGES]


def refine_rays(scenes):
    """Shadow rays the refined image traces for the preview's light (its "rays" layer, summed)."""
    full = scenes["full"]
    light = full.lights[0]
    method = light.get("options", {}).get("method", "auto")
    result = full.scene.render(full.light_indices()[light["name"]], method, extra_layers=True,
                               settings=preview._stage_settings(method, False), refine=True,
                               refine_rounds=preview.REFINE_ROUNDS)
    try:
        return float(result.layers()["rays"].sum())
    finally:
        result.close()


def final_frame(scene, mover, live, moved=True):
    """Seconds of a final render's frame (auto, refine=on) and the mesh BVHs it built."""
    if moved:
        move(mover)
    exported = scene_export.export(bpy.context.evaluated_depsgraph_get(), scene, reuse=mesh_cache.render_meshes)
    t0 = time.perf_counter()
    live.sync(exported)
    before = native.cache_stats()
    result = live.scene.render(live.light_indices()[exported.lights[0]["name"]], "auto", refine=True)
    try:
        result.layers()
    finally:
        result.close()
    return time.perf_counter() - t0, stats_delta(before, native.cache_stats())["mesh_bvh_builds"]


def orbit_frame(scene, scenes, step):
    """Seconds from a camera turned by `step` radians about the vertical axis to the coarse and
    to the full image, and the camera passes' seconds of both (drawn whole: the view changed)."""
    from mathutils import Matrix
    scene.camera.matrix_world = Matrix.Rotation(step, 4, "Z") @ scene.camera.matrix_world
    bpy.context.view_layer.update()
    t0 = time.perf_counter()
    camera = scene_export.scene_camera(scene, bpy.context.evaluated_depsgraph_get(), 960, 540)
    view = time.perf_counter() - t0
    coarse, full, coarse_pass, full_pass = preview_request(scenes, camera)
    return view + coarse, view + full, coarse_pass, full_pass


def p95(values):
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(math.ceil(0.95 * len(ordered))) - 1)]


RENDER_COLUMNS = ("export", "full export", "update", "upload", "camera pass", "shadow map", "method", "ss_render rest",
                  "copy out", "total", "EXR write")
PREVIEW_COLUMNS = ("main thread", "camera pass", "shadow map", "method", "worker rest", "full render")
report = []
exr_path = os.path.join(tempfile.mkdtemp(prefix="ss_warm_"), "frame.exr")
for tori in torus_counts:
    scene, mover, light = build_scene(tori)
    exported = scene_export.export(bpy.context.evaluated_depsgraph_get(), scene)
    triangles = sum(len(m["triangles"]) for m in exported.meshes)
    methods = [m for m in native.method_names() if m != "reference"]
    rows = []
    for method in methods if "render" in parts else ():
        rows.append((method, render_row(scene, mover, method, triangles)))
    if "render" in parts and "sweep" in methods:
        home = mover.location.copy()
        mover.location.x, mover.location.y = BOX_APART[tori]
        rows.append((SWEEP_APART, render_row(scene, mover, "sweep", triangles)))
        mover.location = home
        bpy.context.view_layer.update()

    preview_rows = []
    for method in PREVIEW_METHODS if "preview" in parts else ():
        choices = preview.AutoChoices()  # auto's measured choice, as the preview's worker keeps it
        light.data.softshadow.method = method
        bpy.context.view_layer.update()
        depsgraph = bpy.context.evaluated_depsgraph_get()
        camera = scene_export.scene_camera(scene, depsgraph, 960, 540)
        preview._state.full = True
        scenes = {"coarse": passes.LiveScene(), "full": passes.LiveScene()}
        preview.progressive_job(scenes, {"coarse": [], "full": []}, [preview.export_edit(depsgraph, scene)],
                                camera, lambda: False, lambda rgba, _stage, _round: None, stages=("coarse", "full"))
        runs = [preview_frame(scene, mover, scenes, camera) for _ in range(2 * frames)]
        refined = [preview_converged(scene, mover, scenes, camera) for _ in range(frames)]
        rays = refine_rays(scenes)
        floors = [preview_request(scenes, camera) for _ in range(frames)]
        stages_floor = (statistics.median(f[0] for f in floors), statistics.median(f[1] for f in floors))
        home = scene.camera.matrix_world.copy()
        orbit = [orbit_frame(scene, scenes, math.radians(2.0)) for _ in range(2 * frames)]
        scene.camera.matrix_world = home
        bpy.context.view_layer.update()
        label = method
        if method == "auto":  # name what the preview's auto ran: by the light's shape after a move, then measured
            full = scenes["full"]
            result = full.scene.render(full.light_indices()[full.lights[0]["name"]], "auto", settings="check_pixels=0")
            try:
                label = "auto (%s, measured %s)" % (result.method, "/".join(sorted(set(choices.methods.values()))))
            finally:
                result.close()
        for live in scenes.values():
            live.close()
        latencies = [r["latency"] for r in runs]
        coarse = [r["coarse"] for r in runs]
        stages = {k: statistics.median(r[k] for r in runs) for k in PREVIEW_COLUMNS}
        preview_rows.append((label, statistics.median(coarse), p95(coarse), statistics.median(latencies),
                             p95(latencies), stages, stages_floor,
                             tuple(f([o[k] for o in orbit]) for k in (0, 1) for f in (statistics.median, p95))
                             + tuple(statistics.median(o[k] for o in orbit) for k in (2, 3)),
                             [(statistics.median(column), p95(column)) for column in zip(*refined)],
                             (rays, rays / statistics.median(r[-1] - r[1] for r in refined))))
        print("BENCH preview %d tris %s: coarse median %.3f s p95 %.3f s, full median %.3f s p95 %.3f s, "
              "full render alone %.3f s, floor coarse %.3f s full %.3f s" % (triangles, label, *preview_rows[-1][1:5],
                                                                             stages["full render"], *stages_floor),
              flush=True)
    final = None
    if "final" in parts:
        live = passes.LiveScene()
        first = final_frame(scene, mover, live)  # builds the kept scene and every mesh's BVH
        runs = [final_frame(scene, mover, live) for _ in range(FINAL_FRAMES)]
        floor = statistics.median(final_frame(scene, mover, live, moved=False)[0] for _ in range(FINAL_FRAMES))
        live.close()
        final = (first, statistics.median(r[0] for r in runs), max(r[1] for r in runs), floor)
        print("BENCH final %d tris: first %.3f s (%d mesh BVHs), moved %.3f s (%d mesh BVHs), unchanged %.3f s"
              % (triangles, first[0], first[1], final[1], final[2], floor), flush=True)
    report.append((tori, triangles, rows, preview_rows, final))

load = os.getloadavg()
with open(out_path, "w") as f:
    f.write("# The warm path: one object moved per frame\n\n")
    f.write("bench/warm_render_passes.py. A ground plane, tori of 110,592 triangles each, one disk light, a "
            "small box moved 0.05 along x every frame; the scene kept between frames (`passes.LiveScene`: the "
            "moved box sends its matrix). Seconds, median over %d moved frames (after one frame that builds "
            "the kept scene). Machine load average while it ran: %.1f / %.1f / %.1f on %d cores (the GL is "
            "Mesa llvmpipe: every stage is CPU work, shared with whatever else runs).\n\n"
            % (frames, load[0], load[1], load[2], os.cpu_count()))
    f.write("Stages: *export* render_passes' export in Python (every object's matrix; a mesh read from Blender "
            "only when the depsgraph reported its geometry changed, `mesh_cache`); *full export* beside it, not in "
            "the total: the export that reads every mesh (what each frame cost before `mesh_cache`); "
            "*update* the C API edits of what differs; *upload*, *camera pass*, *shadow map* the library's "
            "shared passes, each until the GL finished it; *method* the method's own passes, read-back "
            "included; *ss_render rest* the rest of the call; *copy out* the layers into numpy; *total* what "
            "`render_passes` costs per light; *EXR write* what a final render adds for its pass file; *floor* "
            "render and copy-out on an unchanged scene (every cache kept): the method's own passes and read-back "
            "at that size, which every frame redoes whatever changed; where the floor is above the target, "
            "llvmpipe running the method's own passes is the limit. *%s*: the sweep with the box moved "
            "where its shadow does not meet the tori's; the sweep fills again only the part of the shadow "
            "a move reached (`fillShadowParts`), where in the sweep row above the box's shadow touches the "
            "torus's and the whole shadow is filled again every frame.\n\n" % SWEEP_APART)
    for tori, triangles, rows, preview_rows, final in report:
        if rows:
            target = TARGET_RENDER.get(tori)
            f.write("## %d triangles: render_passes at %d² per light\n\n" % (triangles, size))
            if target:
                f.write("Target: total ≤ %.0f ms per light.\n\n" % (target * 1e3))
            f.write("| method | " + " | ".join(RENDER_COLUMNS) + " | target | floor | meshes uploaded per frame |\n")
            f.write("|---" * (len(RENDER_COLUMNS) + 4) + "|\n")
            for method, row in rows:
                f.write("| %s | " % method + " | ".join("%.3f" % row[k] for k in RENDER_COLUMNS)
                        + " | %s | %.3f | %d |\n" % ("%.3f" % target if target else "-", row["floor"], row["uploads"]))
            camera = statistics.median(row["camera pass"] for m, row in rows if m != SWEEP_APART)
            maps = statistics.median(row["shadow map"] for m, row in rows if row["shadow map"] > 0)
            f.write("\nThe shared passes a move redraws (only inside the screen rectangle of the box's old and new "
                    "place, drawing the meshes that reach it: `SceneCache` patches them), medians over the methods "
                    "that draw them: camera pass %.3f s, light-centre shadow map (2048²) %.3f s; together %.3f s%s. "
                    "The rest of each total is the method's own GL or CPU work, which every moved frame redoes.\n\n"
                    % (camera, maps, camera + maps,
                       ", above the target by themselves" if target and camera + maps > target else ""))
        if final:
            (first, first_bvhs), moved, moved_bvhs, unchanged = final
            f.write("### A final render's frame after a move (%d², auto with refine=on), %d triangles\n\n"
                    "What F12 and `blender -b -a` render per light: the first frame %.2f s (it builds the ray "
                    "tracer's scene: %d mesh BVHs); a frame after the box moved %.2f s, building %d mesh BVHs (the "
                    "moved box keeps its BVH: only its instance changes); the same render on an unchanged scene "
                    "%.2f s. Medians over %d frames.\n\n"
                    % (size, triangles, first, first_bvhs, moved, moved_bvhs, unchanged, FINAL_FRAMES))
        if not preview_rows:
            continue
        f.write("### The preview after a move (960x540), %d triangles\n\n" % triangles)
        f.write("Edit-to-overlay latency over %d consecutive moves, of the coarse image (%dx%d) and of the full "
                "one after it: the main thread's export of the edit (`preview.export_edit`: the moved object's "
                "matrix) and the worker's updates, renders and overlays (`preview.progressive_job`); stage "
                "medians of both renders together beside, and the full render alone (coarse image to full "
                "image); the floors: the coarse and the full image of a request with no edit (the methods' own "
                "passes at those sizes; a new view costs at least this). Targets on 1M triangles: coarse ≤ %.0f "
                "ms, full ≤ %.0f ms.\n\n"
                % (2 * frames, 960 // preview.COARSE_DIVISOR, 540 // preview.COARSE_DIVISOR,
                   TARGET_COARSE * 1e3, TARGET_PREVIEW * 1e3))
        f.write("| method | coarse median | coarse floor | coarse p95 | full median | full floor | full p95 | "
                + " | ".join(PREVIEW_COLUMNS) + " |\n")
        f.write("|---" * (len(PREVIEW_COLUMNS) + 7) + "|\n")
        for method, coarse, coarse_high, median, high, stages, floor, _orbit, _refined, _rays in preview_rows:
            f.write("| %s | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | " % (method, coarse, floor[0], coarse_high,
                                                                           median, floor[1], high)
                    + " | ".join("%.3f" % stages[k] for k in PREVIEW_COLUMNS) + " |\n")
        f.write("\nA camera orbit (%d views, each turned 2° about the vertical axis from the last; nothing "
                "moved: the camera pass is redrawn whole, the shadow maps are kept), view-to-overlay seconds "
                "(the same targets); the median seconds of the camera pass each image draws (until the GL "
                "finished it); the floors of a new view: the request with no edit above plus the camera "
                "passes it draws (the coarse image's, and for the full image both):\n\n" % (2 * frames))
        f.write("| method | coarse median | coarse p95 | coarse camera pass | coarse floor | full median | full p95 "
                "| full camera pass | full floor |\n|---|---|---|---|---|---|---|---|---|\n")
        for row in preview_rows:
            coarse_median, coarse_high, full_median, full_high, coarse_pass, full_pass = row[7]
            floor = row[6]
            f.write("| %s | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f |\n"
                    % (row[0], coarse_median, coarse_high, coarse_pass, floor[0] + coarse_pass, full_median,
                       full_high, full_pass, floor[1] + coarse_pass + full_pass))
        target = TARGET_CONVERGED.get(tori)
        f.write("\nThe converging preview: seconds from a move to each image, median / p95 over %d moves: the "
                "coarse and the full GL image, then the full image refined with rays in %d rounds (round 1: "
                "the largest expected corrections among the pixels the GL pass is unsure of; the check of the "
                "pixels it called certain (a few rays each) and the tracing of those it contradicts in the later "
                "rounds; the last is `refine=on`, bit for bit, at the final render's error target, estimate ≤ "
                "0.01); the shadow rays the last round's pixels rest on (its `rays` layer, the check's "
                "included) and their rate over the seconds from the full image to the last round. Target "
                "for the last round: %s.\n\n"
                % (frames, preview.REFINE_ROUNDS, "≤ %.0f s" % target if target else "none at this size"))
        f.write("| method | " + " | ".join(CONVERGED_STAGES[:-1]) + " | target (last round) | target | rays | "
                "rays/s |\n" + "|---" * (len(CONVERGED_STAGES) + 4) + "|\n")
        for row in preview_rows:
            rays, rate = row[9]
            f.write("| %s | " % row[0] + " | ".join("%.2f / %.2f" % stage for stage in row[8])
                    + " | %s | %.0f | %.3g |\n" % ("%.0f" % target if target else "-", rays, rate))
        f.write("\n")
print("BENCH-WARM-OK")
