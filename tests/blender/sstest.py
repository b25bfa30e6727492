# What every Blender test shares: loading the add-on, a small scene, pixel look-ups, a runner.
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import shutil
import subprocess
import sys
import tempfile
import traceback

ROOT = os.environ.get("SOFTSHADOW_ROOT") or os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
ADDON_PATH = os.environ.get("SOFTSHADOW_ADDON_PATH") or os.path.join(ROOT, "blender_addon")
if ADDON_PATH not in sys.path:
    sys.path.insert(0, ADDON_PATH)

try:
    import bpy
except ImportError:
    bpy = None


class Failure(AssertionError):
    pass


def check(condition, message):
    if not condition:
        raise Failure(message)


def close(a, b, tolerance, what):
    check(abs(a - b) <= tolerance, "%s: %r vs %r (tolerance %r)" % (what, a, b, tolerance))


def run(namespace):
    """Runs every test_* function of the calling module; exits 1 on any failure."""
    tests = sorted((k, v) for k, v in namespace.items() if k.startswith("test_") and callable(v))
    failed = 0
    for name, fn in tests:
        try:
            fn()
            print("  ok   %s" % name)
        except Exception:
            failed += 1
            print("  FAIL %s" % name)
            traceback.print_exc()
    print("%d of %d test functions failed" % (failed, len(tests)))
    if failed:
        sys.exit(1)
    print("SOFTSHADOW-TEST-OK")
    sys.stdout.flush()


def addon():
    import softshadow
    if not hasattr(bpy.types.Scene, "softshadow"):
        softshadow.register()
    return softshadow


def tempdir(tag):
    path = tempfile.mkdtemp(prefix="softshadow-%s-" % tag)
    return path


def clear_scene():
    """An empty scene (factory startup has a cube, a light and a camera), add-on settings reset."""
    scene = bpy.context.scene
    props = getattr(scene, "softshadow", None)
    if props is not None:
        for key in props.bl_rna.properties.keys():
            if key != "rna_type":
                props.property_unset(key)
    scene.frame_current = 1
    tree = getattr(scene, "node_tree", None)
    if tree is not None:  # back to a new file's compositor: Render Layers -> Composite
        tree.nodes.clear()
        layers = tree.nodes.new("CompositorNodeRLayers")
        composite = tree.nodes.new("CompositorNodeComposite")
        composite.location = (400, 0)
        tree.links.new(layers.outputs["Image"], composite.inputs["Image"])
    for layer in list(scene.view_layers)[1:]:
        scene.view_layers.remove(layer)
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for block in (bpy.data.meshes, bpy.data.lights, bpy.data.cameras):
        for item in list(block):
            block.remove(item)
    return bpy.context.scene


def add_plane(name, size, location, faces=True):
    h = size / 2
    mesh = bpy.data.meshes.new(name)
    verts = [(-h, -h, 0), (h, -h, 0), (h, h, 0), (-h, h, 0)]
    mesh.from_pydata(verts, [], [(0, 1, 2, 3)] if faces else [])
    obj = bpy.data.objects.new(name, mesh)
    obj.location = location
    bpy.context.scene.collection.objects.link(obj)
    return obj


def add_box(name, size, location):
    h = size / 2
    verts = [(x, y, z) for z in (-h, h) for y in (-h, h) for x in (-h, h)]
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    obj = bpy.data.objects.new(name, mesh)
    obj.location = location
    bpy.context.scene.collection.objects.link(obj)
    return obj


def add_light(name, kind="AREA", location=(0, 0, 4), shape="DISK", size=0.5, energy=500):
    data = bpy.data.lights.new(name, kind)
    if kind == "AREA":
        data.shape = shape
        data.size = size
    data.energy = energy
    obj = bpy.data.objects.new(name, data)
    obj.location = location
    bpy.context.scene.collection.objects.link(obj)
    return obj


def add_camera(location=(0, 0, 10), width=64, height=48, lens=35):
    data = bpy.data.cameras.new("Camera")
    data.lens = lens
    obj = bpy.data.objects.new("Camera", data)
    obj.location = location
    bpy.context.scene.collection.objects.link(obj)
    scene = bpy.context.scene
    scene.camera = obj
    scene.render.resolution_x = width
    scene.render.resolution_y = height
    scene.render.resolution_percentage = 100
    return obj


def standard_scene(width=64, height=48):
    """Ground 10x10 at z=0; a 1.5 x 1.5 plate at z=3 centred at (-1, 0); a 0.5 disk light at
    (-4, 0, 6) aiming down; a camera at z=10 looking down. The plate's shadow is centred at
    (2, 0, 0) (half-width 1.5, penumbra 0.5 wide), where the camera sees the ground beside the
    plate (which it sees over x in [-2.5, -0.4]); the ground near (-3.5, -2.8, 0) is lit."""
    scene = clear_scene()
    add_plane("Ground", 10, (0, 0, 0))
    add_plane("Occluder", 1.5, (-1, 0, 3))
    add_light("Key", location=(-4, 0, 6), size=0.5)
    add_camera(width=width, height=height)
    bpy.context.view_layer.update()
    return scene


def shadow_centre(occluder_x):
    """Where the standard light puts the centre of the plate's shadow on the ground."""
    return (2.0 * occluder_x + 4.0, 0.0, 0.0)


def pixel_of(scene, point):
    """(row, col) of the pixel through which the camera sees a world point (row 0 = top)."""
    from bpy_extras.object_utils import world_to_camera_view
    from mathutils import Vector
    ndc = world_to_camera_view(scene, scene.camera, Vector(point))
    w = scene.render.resolution_x * scene.render.resolution_percentage // 100
    h = scene.render.resolution_y * scene.render.resolution_percentage // 100
    return int((1.0 - ndc.y) * h), int(ndc.x * w)


def build_dir():
    return os.environ.get("SOFTSHADOW_BUILD_DIR") or os.path.dirname(os.environ.get("SOFTSHADOW_LIB", ""))


def exr_channels(path):
    """Channel names of an EXR, through OpenImageIO's oiiotool."""
    out = subprocess.run(["oiiotool", "--info", "-v", path], capture_output=True, text=True, check=True).stdout
    for line in out.splitlines():
        line = line.strip()
        if line.startswith("channel list:"):
            return [c.strip() for c in line.split(":", 1)[1].split(",")]
    raise Failure("no channel list in oiiotool output for %s:\n%s" % (path, out))


def exr_channel(path, channel):
    """One EXR channel as a numpy (H, W) array, row 0 = top (through oiiotool --dumpdata, which
    prints 9 decimals: exact to 5e-10, far below any tolerance used here)."""
    import re
    import numpy as np
    folder = tempfile.mkdtemp(prefix="softshadow-ch-")
    try:
        single = os.path.join(folder, "c.exr")
        subprocess.run(["oiiotool", path, "--ch", channel, "-o", single],
                       capture_output=True, text=True, check=True)
        text = subprocess.run(["oiiotool", "--dumpdata", single], capture_output=True, text=True,
                              check=True).stdout
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    size = re.search(r":\s*(\d+) x\s*(\d+), 1 channel", text)
    check(size is not None, "oiiotool could not read channel %s of %s" % (channel, path))
    w, h = int(size.group(1)), int(size.group(2))
    out = np.full((h, w), np.nan, np.float32)
    for x, y, v in re.findall(r"Pixel \((\d+), (\d+)\): (\S+)", text):
        out[int(y), int(x)] = float(v)
    check(np.isfinite(out).all(), "every pixel of %s read" % channel)
    return out


def addon_scripts(folder):
    """A user scripts folder holding the add-on, so `--addons softshadow` finds it."""
    scripts = os.path.join(folder, "scripts", "addons")
    os.makedirs(scripts)
    os.symlink(os.path.join(ADDON_PATH, "softshadow"), os.path.join(scripts, "softshadow"))
    return os.path.join(folder, "scripts")


def png_gray(path):
    """A PNG's mean of R, G, B as a numpy (H, W) array, row 0 = top."""
    import numpy as np
    image = bpy.data.images.load(path, check_existing=False)
    w, h = image.size
    pixels = np.empty(w * h * 4, np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    return np.flipud(pixels.reshape(h, w, 4))[..., :3].mean(axis=2)


def flat_white_workbench(scene):
    """Workbench, flat white, no shadows of its own: any darkening comes from the pass."""
    scene.render.engine = "BLENDER_WORKBENCH"
    shading = scene.display.shading
    shading.light = "FLAT"
    shading.color_type = "SINGLE"
    shading.single_color = (1.0, 1.0, 1.0)
    shading.show_shadows = False
    shading.show_cavity = False
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "PNG"


def blender_batch(blend, args, scripts, env=None, addon=True, argv=None):
    """`blender -b blend [--addons softshadow] args...` (or `blender -b argv...`) ->
    CompletedProcess (stdout+stderr in .log)."""
    import bpy as _bpy
    full_env = dict(os.environ, BLENDER_USER_SCRIPTS=scripts)
    full_env.update(env or {})
    if argv is not None:
        command = [_bpy.app.binary_path, "-b"] + list(argv)
    else:
        command = [_bpy.app.binary_path, "-b", blend] + (["--addons", "softshadow"] if addon else []) + list(args)
    run = subprocess.run(command, capture_output=True, text=True, env=full_env, timeout=900)
    run.log = run.stdout + run.stderr
    return run


def exr_rgb(path):
    """An RGB(A) EXR's colour as a numpy (H, W, 3) array, row 0 = top."""
    import numpy as np
    return np.stack([exr_channel(path, c) for c in "RGB"], axis=2)
