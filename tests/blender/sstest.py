# What every Blender test shares: loading the add-on, a small scene, pixel look-ups, a runner.
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import subprocess
import sys
import tempfile
import traceback

ROOT = os.environ.get("SOFTSHADOW_ROOT") or os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
ADDON_PATH = os.environ.get("SOFTSHADOW_ADDON_PATH") or os.path.join(ROOT, "blender_addon")
# Set by `run.sh --zip` (the version matrix): the module name of the add-on installed from the zip
# ("softshadow" as a legacy add-on, "bl_ext.user_default.softshadow" as an extension). Unset,
# the tests import the source tree and load SOFTSHADOW_LIB.
INSTALLED_MODULE = os.environ.get("SOFTSHADOW_ADDON_MODULE")
if not INSTALLED_MODULE and ADDON_PATH not in sys.path:
    sys.path.insert(0, ADDON_PATH)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

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
    """The add-on's package, registered."""
    if INSTALLED_MODULE:
        import addon_utils

        def fail(exc):
            raise exc
        if not hasattr(bpy.types.Scene, "softshadow"):
            addon_utils.enable(INSTALLED_MODULE, default_set=True, handle_error=fail)
        return sys.modules[INSTALLED_MODULE]
    import softshadow
    if not hasattr(bpy.types.Scene, "softshadow"):
        softshadow.register()
    return softshadow


def watch_render_handlers():
    """Where the add-on's render handlers run: a recorder placed just before each of them in
    Blender's handler list (so called on the same thread, with the same scene) fills the returned
    dict: {"render_init" / "render_pre": {main_thread, lock_interface, frame}}."""
    import threading
    seen = {}
    for name in ("render_init", "render_pre"):
        handlers = getattr(bpy.app.handlers, name)

        @bpy.app.handlers.persistent
        def record(scene, *_args, name=name):
            seen[name] = {"main_thread": threading.current_thread() is threading.main_thread(),
                          "lock_interface": bool(scene.render.use_lock_interface),
                          "frame": scene.frame_current}
        handlers.insert(handlers.index(getattr(addon().handlers, "on_" + name)), record)
    return seen


def child_blender(folder):
    """(arguments, environment) for a child Blender that loads the add-on the way this one does."""
    if INSTALLED_MODULE:
        return ["--addons", INSTALLED_MODULE], dict(os.environ)
    scripts = os.path.join(folder, "scripts")
    os.makedirs(os.path.join(scripts, "addons"), exist_ok=True)
    link = os.path.join(scripts, "addons", "softshadow")
    if not os.path.exists(link):
        os.symlink(os.path.join(ADDON_PATH, "softshadow"), link)
    return ["--addons", "softshadow"], dict(os.environ, BLENDER_USER_SCRIPTS=scripts)


def run_windowed_steps(step, first_interval=2.0):
    """Drives a windowed Blender by a timer calling `step` (it returns the seconds to the next
    call, or None at the end). A failing step ends Blender, or the test would wait for its timeout."""
    def guarded():
        try:
            return step()
        except Exception:
            traceback.print_exc()
            bpy.ops.wm.quit_blender()
            return None
    bpy.app.timers.register(guarded, first_interval=first_interval)


def our_tracebacks(log):
    """The Python tracebacks in a Blender log that pass through the add-on. Blender's own add-ons
    may fail on a distribution's packaging (Debian sid's 5.2 lacks cattrs for bl_pkg): not ours."""
    found = []
    for block in log.split("Traceback (most recent call last):")[1:]:
        lines = block.splitlines()[1:]
        frames = []
        for line in lines:
            frames.append(line)
            if not line.startswith(" "):  # the exception line ends the traceback
                break
        if any("softshadow" in line for line in frames):
            found.append("\n".join(frames))
    return found


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
    compat = addon().compat
    tree = compat.compositor_tree(scene)
    if tree is not None:  # back to a new file's compositor: Render Layers -> final output
        tree.nodes.clear()
        layers = tree.nodes.new("CompositorNodeRLayers")
        output, _ = compat.compositor_output(tree, bpy.types)
        output.location = (400, 0)
        tree.links.new(layers.outputs["Image"], output.inputs["Image"])
    for layer in list(scene.view_layers)[1:]:
        scene.view_layers.remove(layer)
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for block in (bpy.data.meshes, bpy.data.lights, bpy.data.cameras):
        for item in list(block):
            block.remove(item)
    return bpy.context.scene


def add_mesh(name, verts, faces, location):
    """A mesh object of these vertices and faces at `location`, in the scene's collection."""
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    obj = bpy.data.objects.new(name, mesh)
    obj.location = location
    bpy.context.scene.collection.objects.link(obj)
    return obj


def add_plane(name, size, location, faces=True):
    h = size / 2
    verts = [(-h, -h, 0), (h, -h, 0), (h, h, 0), (-h, h, 0)]
    return add_mesh(name, verts, [(0, 1, 2, 3)] if faces else [], location)


def add_box(name, size, location):
    h = size / 2
    verts = [(x, y, z) for z in (-h, h) for y in (-h, h) for x in (-h, h)]
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    return add_mesh(name, verts, faces, location)


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


def world_vertices(mesh):
    """An exported mesh's vertices placed by its column-major matrix, (N, 3) float32 (to check
    where the export puts things; the library places them itself)."""
    import numpy as np
    m = np.asarray(mesh["matrix"], dtype=np.float64).reshape(4, 4).T
    p = np.asarray(mesh["local"], dtype=np.float64).reshape(-1, 3)
    return (p @ m[:3, :3].T + m[:3, 3]).astype(np.float32)


def build_dir():
    return os.environ.get("SOFTSHADOW_BUILD_DIR") or os.path.dirname(os.environ.get("SOFTSHADOW_LIB", ""))


def exr_channels(path):
    """Channel names of an EXR, in the file's order (tests/blender/exr_reader.py)."""
    import exr_reader
    return list(exr_reader.read(path))


def exr_channel(path, channel):
    """One EXR channel as a numpy (H, W) float32 array, row 0 = top."""
    import exr_reader
    channels = exr_reader.read(path)
    check(channel in channels, "channel %s in %s: %s" % (channel, path, sorted(channels)))
    return channels[channel].astype("float32")


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


def blender_binary():
    """The Blender a test starts as a child: this one. Over the bpy module (tests/matrix/bpy.sh),
    whose bpy.app.binary_path is empty, the wrapper that runs it names itself here."""
    return os.environ.get("SOFTSHADOW_BLENDER") or bpy.app.binary_path


def blender_batch(folder, blend, args, env=None, argv=None):
    """`blender -b blend <the add-on> args...`, or `blender -b argv...` as given, with the add-on
    reachable the way this Blender loads it -> CompletedProcess (stdout+stderr in .log)."""
    addon_args, full_env = child_blender(folder)
    full_env.update(env or {})
    tail = list(argv) if argv is not None else [blend] + addon_args + list(args)
    run = subprocess.run([blender_binary(), "-b"] + tail, capture_output=True, text=True,
                         env=full_env, timeout=900)
    run.log = run.stdout + run.stderr
    return run


def exr_rgb(path):
    """An RGB(A) EXR's colour as a numpy (H, W, 3) array, row 0 = top."""
    import numpy as np
    return np.stack([exr_channel(path, c) for c in "RGB"], axis=2)
