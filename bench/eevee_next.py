# How EEVEE Next (Blender 4.2 and later) sees the benchmark scenes' shadows (runs inside that Blender).
# SPDX-License-Identifier: GPL-3.0-or-later
# blender -b --factory-startup --python bench/eevee_next.py -- SCENES_DIR
# For each SCENES_DIR/<scene>/scene.blend that bench/scenes.py saved in Blender 3.4 (the same
# geometry, light and camera as every other figure), it writes <scene>/eevee_next_<setting>.exr (R = V,
# G = mask, as bench/visibility_pass.py computes it for 3.4's EEVEE) and <scene>/blender_next.json
# with the render times, the settings used and any skipped (BENCH_NEXT_BUDGET_S). Needs bpy and
# numpy only, not the library. BENCH_NEXT_SETTINGS=default,64j picks the settings (SETTINGS).
import json
import os
import sys
import time

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from visibility_pass import diffuse_direct, save_rg, visibility  # noqa: E402

# "default": what an artist has in a new file of this Blender: the render samples, shadow rays
# and steps, resolution scale, and each light's shadow settings (no jitter) of a fresh scene and
# a fresh area light. "64j": 64 samples with jittered soft shadows and 4 rays x 16 steps, the
# setting issue 28 measured EEVEE Next at its best with.
SETTINGS = {
    "default": {},
    "64j": {"taa_render_samples": 64, "shadow_ray_count": 4, "shadow_step_count": 16, "use_shadow_jitter": True},
}
LIGHT_KEYS = ("use_shadow_jitter",)


def engine_id():
    items = [e.identifier for e in bpy.types.RenderSettings.bl_rna.properties["engine"].enum_items]
    return "BLENDER_EEVEE_NEXT" if "BLENDER_EEVEE_NEXT" in items else "BLENDER_EEVEE"  # 4.2-4.x : 5.x


def copy_settings(src, dst):
    """Every plain writable property of src onto dst (and of its pointer structs, one level down)."""
    for prop in src.bl_rna.properties:
        key = prop.identifier
        if key == "rna_type":
            continue
        if prop.type == "POINTER":
            sub_src, sub_dst = getattr(src, key), getattr(dst, key)
            if sub_src is not None and sub_dst is not None and not isinstance(sub_src, bpy.types.ID):
                copy_settings(sub_src, sub_dst)
        elif prop.type != "COLLECTION" and not prop.is_readonly:
            setattr(dst, key, getattr(src, key))


def factory_defaults(scene):
    """The shot's EEVEE settings and its lights' shadow settings as a new file has them: a file
    saved in 3.4 carries 3.4's values, which versioning maps onto EEVEE Next's (soft shadows ->
    jitter)."""
    fresh = bpy.data.scenes.new("bench_fresh")
    copy_settings(fresh.eevee, scene.eevee)
    bpy.data.scenes.remove(fresh)
    fresh_light = bpy.data.lights.new("bench_fresh", "AREA")
    for obj in scene.objects:
        if obj.type == "LIGHT":
            for prop in fresh_light.bl_rna.properties:
                key = prop.identifier
                if key.startswith(("shadow_", "use_shadow_")) and key != "shadow_soft_size" and not prop.is_readonly:
                    setattr(obj.data, key, getattr(fresh_light, key))
    bpy.data.lights.remove(fresh_light)


def setup_compositor(scene):
    """Render Layers' Diffuse Direct -> the compositor's output: 5.x's node group, or 4.x's tree."""
    scene.view_layers[0].use_pass_diffuse_direct = True
    scene.render.use_compositing = True
    if hasattr(scene, "compositing_node_group"):
        tree = bpy.data.node_groups.new("Bench", "CompositorNodeTree")
        tree.interface.new_socket("Image", in_out="OUTPUT", socket_type="NodeSocketColor")
        scene.compositing_node_group = tree
        out = tree.nodes.new("NodeGroupOutput")
    else:
        scene.use_nodes = True
        tree = scene.node_tree
        tree.nodes.clear()
        out = tree.nodes.new("CompositorNodeComposite")
    rl = tree.nodes.new("CompositorNodeRLayers")
    src = rl.outputs.get("Diffuse Direct") or rl.outputs.get("DiffDir")
    tree.links.new(src, out.inputs[0])


def set_shadows(scene, on):
    for obj in scene.objects:
        if obj.type == "LIGHT":
            obj.data.use_shadow = on


def settings_of(scene):
    e = scene.eevee
    light = next(o.data for o in scene.objects if o.type == "LIGHT")
    return {"taa_render_samples": e.taa_render_samples, "shadow_ray_count": e.shadow_ray_count,
            "shadow_step_count": e.shadow_step_count, "shadow_resolution_scale": e.shadow_resolution_scale,
            "use_raytracing": e.use_raytracing, "use_shadow_jitter": light.use_shadow_jitter,
            "shadow_jitter_overblur": light.shadow_jitter_overblur,
            "shadow_filter_radius": light.shadow_filter_radius,
            "shadow_maximum_resolution": light.shadow_maximum_resolution, "filter_size": scene.render.filter_size}


def render_setting(scene, key, out_dir):
    """Returns the seconds of the shadowed render and the settings it ran with."""
    factory_defaults(scene)
    lights = [o.data for o in scene.objects if o.type == "LIGHT"]
    for name, value in SETTINGS[key].items():
        for target in (lights if name in LIGHT_KEYS else [scene.eevee]):
            setattr(target, name, value)
    samples = scene.eevee.taa_render_samples
    tmp = os.path.join(out_dir, "_next_pass.exr")
    # Warm-up at one shadowed sample: the shader variants compile on the first frame (minutes on
    # llvmpipe), a one-off cost that is not the per-frame time.
    set_shadows(scene, True)
    scene.eevee.taa_render_samples = 1
    diffuse_direct(scene, tmp)
    # Unshadowed, the area light is analytic (LTC) and the 0-width filter leaves nothing to
    # jitter: one sample is the converged unshadowed pass, as for 3.4's EEVEE (measured against
    # 16 samples in 5.2 on the stepped scene: 0.012 % of its maximum at worst, 0.00005 % on average).
    set_shadows(scene, False)
    _, unshadowed = diffuse_direct(scene, tmp)
    set_shadows(scene, True)
    scene.eevee.taa_render_samples = samples
    cpu0 = time.process_time()
    seconds, shadowed = diffuse_direct(scene, tmp)
    cpu = time.process_time() - cpu0
    v, mask = visibility(shadowed, unshadowed)
    save_rg(os.path.join(out_dir, "eevee_next_%s.exr" % key), v, mask)
    # CPU seconds of the whole process (llvmpipe's threads included): less load-bound than wall time.
    return seconds, dict(settings_of(scene), cpu_seconds=cpu)


def pixels(out_dir):
    """The scene's pixel count as 3.4 rendered it (bench/scenes.py's blender.json), 0 if unknown."""
    try:
        with open(os.path.join(out_dir, "blender.json")) as f:
            info = json.load(f)
        return info["width"] * info["height"]
    except (OSError, ValueError, KeyError):
        return 0


def main():
    argv = sys.argv[sys.argv.index("--") + 1:]
    root = argv[0]
    keys = os.environ.get("BENCH_NEXT_SETTINGS", ",".join(SETTINGS)).split(",")
    unknown = [k for k in keys if k not in SETTINGS]
    if unknown:
        raise SystemExit("eevee_next: no setting %s (known: %s)" % (", ".join(unknown), ", ".join(SETTINGS)))
    # No new render starts after this many seconds: the run waits for this script, and one
    # setting on every scene is worth more than every setting on some.
    budget = float(os.environ.get("BENCH_NEXT_BUDGET_S", "inf"))
    names = [n for n in os.listdir(root) if os.path.isfile(os.path.join(root, n, "scene.blend"))]
    names.sort(key=lambda n: (pixels(os.path.join(root, n)), n))  # cheapest first: a budget cuts the costliest
    if not names:
        raise SystemExit("eevee_next: no <scene>/scene.blend under %s" % root)
    t0 = time.perf_counter()
    for key in keys:  # each setting on every scene before the next setting
        for name in names:
            out_dir = os.path.join(root, name)
            path = os.path.join(out_dir, "blender_next.json")
            info = json.load(open(path)) if os.path.exists(path) else {"renders": {}, "settings": {}, "skipped": []}
            if time.perf_counter() - t0 > budget:
                info["skipped"].append("eevee_next_" + key)
                print("BENCH %s eevee_next %s: skipped, past BENCH_NEXT_BUDGET_S=%g" % (name, key, budget), flush=True)
            else:
                bpy.ops.wm.open_mainfile(filepath=os.path.join(out_dir, "scene.blend"))
                scene = bpy.context.scene
                scene.render.engine = engine_id()
                setup_compositor(scene)
                seconds, used = render_setting(scene, key, out_dir)
                import gpu  # after a render: the GPU context exists
                info.update({"scene": name, "blender": bpy.app.version_string, "engine": scene.render.engine,
                             "width": scene.render.resolution_x, "height": scene.render.resolution_y,
                             "gpu": "%s / %s / %s" % (gpu.platform.backend_type_get(), gpu.platform.vendor_get(),
                                                      gpu.platform.renderer_get())})
                info["renders"]["eevee_next_" + key] = seconds
                info["settings"]["eevee_next_" + key] = used
                print("BENCH %s eevee_next %s: %.2f s (%.2f s CPU) %s" % (name, key, seconds, used["cpu_seconds"],
                                                                          json.dumps(used)), flush=True)
            with open(path, "w") as f:
                json.dump(info, f, indent=1)
    print("BENCH-NEXT-OK", flush=True)


if __name__ == "__main__":  # Blender runs --python scripts as __main__
    main()
