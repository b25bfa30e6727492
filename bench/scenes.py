# Which benchmark scenes exist, and how EEVEE and Cycles see their shadows (runs inside Blender).
# SPDX-License-Identifier: GPL-3.0-or-later
# blender -b --factory-startup --python bench/scenes.py -- OUT_DIR WIDTH HEIGHT QUICK(0|1)
# For each scene: OUT_DIR/<scene>/scene.json (the add-on's exporter), and for each engine setting
# OUT_DIR/<scene>/<engine>.exr (R = visibility V, G = mask; run.sh renames the channels),
# OUT_DIR/<scene>/receivers.exr (R = 1 where a receiver object is seen) and
# OUT_DIR/<scene>/blender.json with the render times, OUT_DIR/<scene>/scene.blend (the scene as
# rendered, for bench/eevee_next.py). Needs SOFTSHADOW_LIB.
import json
import math
import os
import random
import sys

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "blender_addon"))
sys.path.insert(0, HERE)
import softshadow  # noqa: E402
from softshadow import api  # noqa: E402
from visibility_pass import diffuse_direct, save_rg, visibility  # noqa: E402

# At 512² on llvmpipe EEVEE takes about 1.4 s per sample: EEVEE-64 (the headline) alone.
EEVEE_SAMPLES = (64,)
CYCLES_SAMPLES = (16, 64)
# What the full run renders at 512² (the dense scene at 1024²), to fit in about 20 minutes on 2
# cores: an open Suzanne under a disk, thin casters under a rectangle, a curved and a stepped
# receiver, four open Suzannes. The other scenes run with BENCH_SCENES=name,name.
FULL_SCENES = ("concave", "foliage", "curved_receiver", "stepped", "dense")
# The dense scene renders at the size a dense shot is looked at.
DENSE_SIZE = (1024, 1024)
# The objects shadows fall on (what an artist looks at): the receiver pass marks the pixels that
# see one of them, and report.py gives every method's error there beside its error over all
# surfaces (casters' own self-shadowing included).
RECEIVERS = ("Ground", "Receiver", "Steps")
# The triangle-count series renders at this size when asked for (BENCH_SCENES): its job is time
# against triangles, not the quality at the sizes users render.
SCALED_SIZE = (256, 192)


# ---------------------------------------------------------------- scene building
def reset():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    if not hasattr(bpy.types.Scene, "softshadow"):
        softshadow.register()
    scene = bpy.context.scene
    world = bpy.data.worlds.new("Black")
    world.color = (0.0, 0.0, 0.0)
    world.use_nodes = False
    scene.world = world  # a black world: only the area light reaches Diffuse Direct
    return scene


def link(obj):
    bpy.context.scene.collection.objects.link(obj)
    return obj


def mesh_object(name, verts, faces):
    me = bpy.data.meshes.new(name)
    me.from_pydata([tuple(v) for v in verts], [], [tuple(f) for f in faces])
    me.update()
    return link(bpy.data.objects.new(name, me))


def ground(size=8.0):
    h = size / 2
    return mesh_object("Ground", [(-h, -h, 0), (h, -h, 0), (h, h, 0), (-h, h, 0)], [(0, 1, 2, 3)])


def area_light(shape="DISK", size=1.5, size_y=None, location=(0.8, 0.5, 4.0), energy=500.0):
    data = bpy.data.lights.new("Area", "AREA")
    data.shape = shape
    data.size = size
    if size_y is not None:
        data.size_y = size_y
    data.energy = energy
    obj = link(bpy.data.objects.new("Area", data))
    obj.location = location  # emits down its local -Z
    return obj


def camera(location=(0.0, -5.5, 6.0), target=(0.0, 0.0, 0.5), lens=35.0):
    data = bpy.data.cameras.new("Camera")
    data.lens = lens
    obj = link(bpy.data.objects.new("Camera", data))
    obj.location = location
    direction = np.subtract(target, location)
    from mathutils import Vector
    obj.rotation_euler = Vector(direction).to_track_quat("-Z", "Y").to_euler()
    bpy.context.scene.camera = obj
    return obj


def subdivide(obj, levels):
    if levels <= 0:
        return obj
    mod = obj.modifiers.new("Subdivision", "SUBSURF")
    mod.levels = levels
    mod.render_levels = levels
    return obj


def primitive(op, **kw):
    op(**kw)
    return bpy.context.active_object


def suzanne(levels, location=(0, 0, 1.1), scale=0.9):
    obj = primitive(bpy.ops.mesh.primitive_monkey_add, size=2.0 * scale, location=location)
    obj.rotation_euler = (math.radians(-60), 0, 0)  # face tilted up to the light: concave parts cast
    return subdivide(obj, levels)


def build_convex():
    ground()
    primitive(bpy.ops.mesh.primitive_ico_sphere_add, subdivisions=4, radius=0.7, location=(0, 0, 1.2))


def build_concave():
    ground()
    suzanne(2)


def build_overlapping():
    ground()
    for i, (x, y, z, s) in enumerate([(-0.6, 0.0, 0.6, 0.5), (0.2, 0.3, 1.3, 0.45), (0.5, -0.4, 2.0, 0.35)]):
        obj = primitive(bpy.ops.mesh.primitive_cube_add, size=2 * s, location=(x, y, z))
        obj.rotation_euler = (0.0, 0.0, 0.4 * i)


def build_torus():
    ground()
    primitive(bpy.ops.mesh.primitive_torus_add, major_radius=1.0, minor_radius=0.3, major_segments=64,
              minor_segments=24, location=(0, 0, 1.0))


def build_small_occluder():
    ground()
    primitive(bpy.ops.mesh.primitive_uv_sphere_add, radius=0.12, location=(0, 0, 1.2))


def build_foliage():
    ground()
    rng = random.Random(7)
    verts, faces = [], []
    for _ in range(60):  # thin leaves: 0.3 x 0.08, random orientation, one flat quad each
        c = np.array([rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(1.0, 2.0)])
        a, b = rng.uniform(0, math.pi), rng.uniform(-0.6, 0.6)
        u = np.array([math.cos(a), math.sin(a), b]) * 0.15
        v = np.array([-math.sin(a), math.cos(a), 0.2]) * 0.04
        k = len(verts)
        verts += [c - u - v, c + u - v, c + u + v, c - u + v]
        faces.append((k, k + 1, k + 2, k + 3))
    mesh_object("Leaves", verts, faces)


def build_curved_receiver():
    n = 96  # a wavy receiver: z = 0.3 sin(x) cos(0.7 y) on a 96x96 grid
    xs = np.linspace(-4, 4, n)
    verts = [(x, y, 0.3 * math.sin(1.2 * x) * math.cos(0.7 * y)) for y in xs for x in xs]
    faces = [(j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i)
             for j in range(n - 1) for i in range(n - 1)]
    mesh_object("Receiver", verts, faces)
    primitive(bpy.ops.mesh.primitive_ico_sphere_add, subdivisions=3, radius=0.5, location=(0.2, 0, 1.4))


def build_stepped():
    """Four steps (0.25 rise, 1.0 run) across the light's footprint: a receiver the shadow falls
    on at four heights, with vertical risers in between, under a sphere."""
    ground()
    rise, run, n, half_y = 0.25, 1.0, 4, 3.0
    profile = [(-2.0, 0.0)]  # x, z along the stair's outline, left to right, closed by the floor
    for i in range(n):
        x = -2.0 + i * run
        profile += [(x, (i + 1) * rise), (x + run, (i + 1) * rise)]
    profile.append((-2.0 + n * run, 0.0))
    k = len(profile)
    verts = [(x, -half_y, z) for x, z in profile] + [(x, half_y, z) for x, z in profile]
    faces = [(i, (i + 1) % k, k + (i + 1) % k, k + i) for i in range(k)]  # the outline swept in y
    faces.append(tuple(range(k - 1, -1, -1)))          # the side at -y
    faces.append(tuple(k + i for i in range(k)))       # the side at +y
    mesh_object("Steps", verts, faces)
    primitive(bpy.ops.mesh.primitive_uv_sphere_add, radius=0.45, location=(0.1, 0.0, 2.0))


def build_dense():
    """Four open Suzannes side by side (subdivided twice: about 63k triangles), rendered at
    DENSE_SIZE: a dense scene at the size it is looked at."""
    ground()
    for x, y in ((-1.2, -0.7), (1.2, -0.7), (-1.2, 0.9), (1.2, 0.9)):
        suzanne(2, location=(x, y, 1.0), scale=0.65)


def build_scaled(levels):
    def build():
        ground()
        suzanne(levels)
    return build


SCENES = [
    ("convex", build_convex, {}),
    ("concave", build_concave, {}),
    ("overlapping", build_overlapping, {}),
    ("torus", build_torus, {}),
    ("small_occluder", build_small_occluder, {"size": 3.0, "location": (0.0, 0.0, 3.0)}),
    ("foliage", build_foliage, {"shape": "RECTANGLE", "size": 1.5, "size_y": 1.0}),
    ("curved_receiver", build_curved_receiver, {}),
    ("stepped", build_stepped, {}),
    ("dense", build_dense, {"size": 2.0}),
] + [("scaled_%d" % lv, build_scaled(lv), {}) for lv in (1, 2, 3, 4, 5)]


def triangle_count(scene):
    graph = bpy.context.evaluated_depsgraph_get()
    total = 0
    for obj in scene.objects:
        if obj.type == "MESH":
            ev = obj.evaluated_get(graph)
            me = ev.to_mesh()
            me.calc_loop_triangles()
            total += len(me.loop_triangles)
            ev.to_mesh_clear()
    return total


# ---------------------------------------------------------------- rendering
def setup_compositor(scene):
    """Render Layers' Diffuse Direct -> Viewer: the only render output Python can read in -b."""
    scene.view_layers[0].use_pass_diffuse_direct = True
    scene.use_nodes = True
    tree = scene.node_tree
    tree.nodes.clear()
    rl = tree.nodes.new("CompositorNodeRLayers")
    viewer = tree.nodes.new("CompositorNodeViewer")
    comp = tree.nodes.new("CompositorNodeComposite")
    tree.links.new(rl.outputs["DiffDir"], viewer.inputs[0])
    tree.links.new(rl.outputs["DiffDir"], comp.inputs[0])


def receiver_pass(scene, out_dir):
    """R = G = 1 where the pixel centre sees a receiver object (RECEIVERS), else 0: Cycles' object
    index at one sample with a 0.01 px filter, so each pixel is its centre's object."""
    for obj in scene.objects:
        obj.pass_index = 1 if obj.type == "MESH" and obj.name.split(".")[0] in RECEIVERS else 0
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 1
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.filter_width = 0.01
    layer = scene.view_layers[0]
    layer.use_pass_object_index = True
    tree = scene.node_tree
    tree.nodes.clear()
    rl = tree.nodes.new("CompositorNodeRLayers")
    comp = tree.nodes.new("CompositorNodeComposite")
    tree.links.new(rl.outputs["IndexOB"], comp.inputs[0])
    _, index = diffuse_direct(scene, os.path.join(out_dir, "_index.exr"))
    mask = (index > 0.5).astype(np.float32)
    save_rg(os.path.join(out_dir, "receivers.exr"), mask, mask)
    layer.use_pass_object_index = False
    setup_compositor(scene)
    return int(mask.sum())


def set_shadows(scene, on):
    for obj in scene.objects:
        if obj.type == "LIGHT":
            obj.data.use_shadow = on  # EEVEE
            obj.data.cycles.cast_shadow = on  # Cycles


def render_engine(scene, engine, samples, out_dir, name):
    if engine == "eevee":
        scene.render.engine = "BLENDER_EEVEE"
        scene.eevee.use_soft_shadows = True
        scene.eevee.taa_render_samples = samples
        scene.eevee.shadow_cube_size = "2048"
        scene.eevee.use_gtao = False
        scene.eevee.use_ssr = False
    else:
        scene.render.engine = "CYCLES"
        c = scene.cycles
        c.device = "CPU"
        c.samples = samples
        c.use_adaptive_sampling = False
        c.use_denoising = False
        c.max_bounces = 0  # direct light only: Diffuse Direct is all we read
        c.seed = 1
        c.filter_width = 0.01  # sample at the pixel centre, as the contract does
    set_shadows(scene, False)
    tmp = os.path.join(out_dir, "_pass.exr")
    if engine == "eevee":
        # Warm-up at one sample: EEVEE compiles its shadowed shader variants on the first
        # shadowed frame, a one-off cost that is not the per-frame time.
        set_shadows(scene, True)
        scene.eevee.taa_render_samples = 1
        diffuse_direct(scene, tmp)
        set_shadows(scene, False)  # the warm-up left them on; the next render is the unshadowed one
        # Without shadows EEVEE's area light is analytic and the 0-width filter leaves nothing
        # to jitter: one sample gives the unshadowed pass (measured against 16 samples on the
        # stepped scene: 0.18 % of its maximum at worst, 0.008 % on average).
        _, unshadowed = diffuse_direct(scene, tmp)
        scene.eevee.taa_render_samples = samples
    else:
        _, unshadowed = diffuse_direct(scene, tmp)
    set_shadows(scene, True)
    seconds, shadowed = diffuse_direct(scene, tmp)
    v, mask = visibility(shadowed, unshadowed)
    save_rg(os.path.join(out_dir, name + ".exr"), v, mask)
    return seconds


def main():
    argv = sys.argv[sys.argv.index("--") + 1:]
    out_root, width, height, quick = argv[0], int(argv[1]), int(argv[2]), argv[3] == "1"
    scenes = SCENES
    eevee, cycles = EEVEE_SAMPLES, CYCLES_SAMPLES
    scenes = [s for s in SCENES if s[0] in FULL_SCENES]
    if quick:
        scenes = [s for s in SCENES if s[0] in ("convex", "stepped")]
    only = os.environ.get("BENCH_SCENES")  # names from the whole list, quick or not
    if only:
        scenes = [s for s in SCENES if s[0] in only.split(",")]
    for name, build, light_kw in scenes:
        scene = reset()
        build()
        area_light(**light_kw)
        camera()
        size = (SCALED_SIZE if name.startswith("scaled") else DENSE_SIZE if name == "dense" else (width, height)) \
            if not quick else (width, height)
        scene.render.resolution_x, scene.render.resolution_y = size
        scene.render.resolution_percentage = 100
        scene.render.filter_size = 0.0  # EEVEE: no pixel filter, pixel centres as the contract
        setup_compositor(scene)
        out_dir = os.path.join(out_root, name)
        os.makedirs(out_dir, exist_ok=True)
        problems = api.export_scene_file(scene, os.path.join(out_dir, "scene.json"))
        scene.softshadow.enabled = False  # the add-on's own passes must not ride on Blender's timings
        setup_compositor(scene)
        # The same scene for EEVEE Next in Blender 5.x (bench/eevee_next.py): geometry, light, camera.
        bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out_dir, "scene.blend"), copy=True)
        info = {"scene": name, "triangles": triangle_count(scene), "width": size[0], "height": size[1],
                "problems": problems, "renders": {}, "receiver_pixels": receiver_pass(scene, out_dir)}
        for s in eevee:
            info["renders"]["eevee_%d" % s] = render_engine(scene, "eevee", s, out_dir, "eevee_%d" % s)
            print("BENCH %s eevee %d: %.2f s" % (name, s, info["renders"]["eevee_%d" % s]), flush=True)
        for s in cycles:
            info["renders"]["cycles_%d" % s] = render_engine(scene, "cycles", s, out_dir, "cycles_%d" % s)
            print("BENCH %s cycles %d: %.2f s" % (name, s, info["renders"]["cycles_%d" % s]), flush=True)
        with open(os.path.join(out_dir, "blender.json"), "w") as f:
            json.dump(info, f, indent=1)
    print("BENCH-SCENES-OK", flush=True)


if __name__ == "__main__":  # Blender runs --python scripts as __main__
    main()
