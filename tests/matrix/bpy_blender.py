# The part of Blender's command line the tests and the farm use, over Blender as a Python module
# (the `bpy` wheels from PyPI), so that tests/blender/run.sh and every child Blender a test starts
# run unchanged: `python bpy_blender.py ARGS...` behaves as `blender ARGS...`.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Arguments are handled in order, as Blender does: a .blend opens when it is reached, a frame
renders when -f/-a is reached, --python runs when reached. What differs from the program:

- there is no window and no GPU context of Blender's own (the module is always in the
  background; `--background` is accepted and changes nothing);
- `--factory-startup` reloads the factory settings after the module has loaded the user's
  preferences (the program never loads them);
- `--command extension ...` calls the bundled Extensions add-on's command handler (bl_pkg), the
  one the program's `--command extension` calls;
- `bpy.app.binary_path` is empty: the tests read the Blender to start from SOFTSHADOW_BLENDER
  (tests/blender/sstest.py), which the wrapper tests/matrix/bpy.sh writes sets to itself;
- the end is os._exit, after flushing: the module's own teardown at interpreter exit breaks once
  any PropertyGroup with a Python callback (an update, an items function) is registered on an
  ID type, add-on or not (4.2.23: SIGSEGV in ~SpaceType -> bpy_class_free after Python is
  finalized; 4.5.15: hangs), so the exit code is the run's own and Blender's teardown after the
  last argument (test_gl_coexistence's clean exit) is checked in the programs only.
Anything else on the command line is refused with exit code 1, never ignored."""
import os
import runpy
import sys
import traceback

import bpy

FLAGS = {"-b", "--background", "-noaudio", "-y", "--enable-autoexec"}


class State:
    exit_code = 0  # --python-exit-code: 0 means "go on after a failing script", as Blender
    scene_name = None


def _scene():
    if State.scene_name is not None:
        scene = bpy.data.scenes.get(State.scene_name)
        if scene is None:
            _fail("no scene named '%s'" % State.scene_name)
        return scene
    return bpy.context.scene


def _exit(code):
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)


def _fail(message, code=1):
    print("bpy_blender: %s" % message, file=sys.stderr)
    _exit(code)


def _run_python(run):
    """A --python/--python-expr: a failure ends Blender with --python-exit-code when it is set."""
    try:
        run()
    except SystemExit as exc:  # sys.exit() in a script ends Blender with its code
        if exc.code is not None and not isinstance(exc.code, int):
            print(exc.code, file=sys.stderr)
        _exit(exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1))
    except BaseException:
        traceback.print_exc()
        if State.exit_code:
            _fail("Python script failed, exiting with code %d" % State.exit_code, State.exit_code)


def _frames(spec, scene):
    """Blender's -f notation: "7", "1..4", "3,5..6", "+1" (relative to the start), "-1" (to the end)."""
    frames = []
    for part in spec.split(","):
        ends = part.split("..")
        values = []
        for end in ends:
            end = end.strip()
            if end.startswith("+"):
                values.append(scene.frame_start + int(end[1:]))
            elif end.startswith("-"):
                values.append(scene.frame_end - int(end[1:]))
            else:
                values.append(int(end))
        frames.extend(range(values[0], values[-1] + 1))
    return frames


def _render(scene, start, end):
    """Renders frames start..end as the program's -f/-a does: one animation render (render_init
    once, render_pre per frame) writing to the scene's output path; the frame range restored."""
    old = scene.frame_start, scene.frame_end
    scene.frame_start, scene.frame_end = start, end
    try:
        with bpy.context.temp_override(scene=scene):
            result = bpy.ops.render.render(animation=True, scene=scene.name)
    finally:
        scene.frame_start, scene.frame_end = old
    if result != {"FINISHED"}:
        _fail("render of frames %d..%d: %s" % (start, end, result))


def _command(argv):
    if not argv or argv[0] != "extension":
        _fail("--command: only 'extension' is provided over the bpy module, not %r" % argv[:1])
    import bl_pkg
    sys.stdout.flush()
    _exit(bl_pkg.cli_extension(argv[1:]) or 0)


def main(args):
    sys.argv = [os.environ.get("SOFTSHADOW_BLENDER", "blender")] + args
    i = 0

    def value():
        nonlocal i
        i += 1
        if i >= len(args):
            _fail("%s needs a value" % args[i - 1])
        return args[i]

    while i < len(args):
        arg = args[i]
        if arg == "--":
            break
        if arg in FLAGS:
            pass
        elif arg in ("-v", "--version"):
            print("Blender %s" % bpy.app.version_string)
            print("\tbuild: the bpy module (%s)" % os.path.dirname(bpy.__file__))
            _exit(0)
        elif arg == "--factory-startup":
            bpy.ops.wm.read_factory_settings()
        elif arg == "--python-exit-code":
            State.exit_code = int(value())
        elif arg in ("-P", "--python"):
            path = value()
            _run_python(lambda: runpy.run_path(path, run_name="__main__"))
        elif arg == "--python-expr":
            expr = value()
            _run_python(lambda: exec(compile(expr, "<string>", "exec"), {"__name__": "__main__"}))
        elif arg == "--addons":
            import addon_utils
            for name in value().split(","):
                if name and addon_utils.enable(name, default_set=True) is None:
                    print("bpy_blender: add-on '%s' could not be enabled" % name, file=sys.stderr)
        elif arg == "--command":
            _command(args[i + 1:])
        elif arg in ("-S", "--scene"):
            State.scene_name = value()
            bpy.context.window.scene = _scene()
        elif arg in ("-o", "--render-output"):
            _scene().render.filepath = value()
        elif arg in ("-F", "--render-format"):
            _scene().render.image_settings.file_format = value()
        elif arg in ("-s", "--frame-start"):
            _scene().frame_start = int(value())
        elif arg in ("-e", "--frame-end"):
            _scene().frame_end = int(value())
        elif arg in ("-f", "--render-frame"):
            scene = _scene()
            for frame in _frames(value(), scene):
                _render(scene, frame, frame)
        elif arg in ("-a", "--render-anim"):
            scene = _scene()
            _render(scene, scene.frame_start, scene.frame_end)
        elif arg.endswith(".blend") and not arg.startswith("-"):
            if bpy.ops.wm.open_mainfile(filepath=arg) != {"FINISHED"}:
                _fail("cannot open %s" % arg)
            State.scene_name = None
        else:
            _fail("argument not provided over the bpy module: %r" % arg)
        i += 1
    _exit(0)


if __name__ == "__main__":
    main(sys.argv[1:])
