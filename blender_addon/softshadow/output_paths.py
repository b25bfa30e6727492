# Where a frame's pass file goes: the render output path's folder and # padding, or a template.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Pure string work (no bpy), so it tests without Blender.

The frame number is always the last run of digits of the file name: that is how Blender's Image
node finds the frame of an image sequence."""
import os
import re

SUBFOLDER = "softshadow"
DEFAULT_PADDING = 4
_HASHES = re.compile(r"#+")


def _safe(text):
    """A scene or view layer name as a file name part: no path separators or control characters,
    and no leading dot (a name "." or ".." must not name a folder of its own)."""
    text = re.sub(r"[\\/:*?\"<>|\x00-\x1f\x7f]", "_", text)
    return "_" + text[1:] if text.startswith(".") else text


def default_template(render_filepath):
    """The template that follows the render output: its folder plus a `softshadow` subfolder,
    its file name's prefix, scene and view layer, and its # padding for the frame.

    "/out/shot_###" -> "/out/softshadow/shot_{scene}_{view_layer}_###.exr"."""
    folder, base = os.path.split(render_filepath)
    runs = _HASHES.findall(base)
    padding = len(runs[-1]) if runs else DEFAULT_PADDING
    prefix = _HASHES.sub("", base).rstrip("_.- ")
    name = (prefix + "_" if prefix else "") + "{scene}_{view_layer}_" + "#" * padding + ".exr"
    return os.path.join(folder, SUBFOLDER, name)


def expand(template, scene, view_layer, frame, light=None):
    """The file of one frame: the template's last # run replaced by the frame padded to its
    length (no # run: "_####" is added before the extension), then {scene} and {view_layer}
    filled in. Names go in last, so a '#' or a '.exr' in a name stays text. With `light`, the
    file of that light's passes alone: its name goes before the frame number."""
    folder, name = os.path.split(template)
    stem, ext = os.path.splitext(name)
    if ext.lower() != ".exr":
        stem, ext = name, ".exr"
    runs = list(_HASHES.finditer(stem))
    if not runs:
        stem += "_" + "#" * DEFAULT_PADDING
        runs = list(_HASHES.finditer(stem))
    last = runs[-1]
    number = "%0*d" % (len(last.group()), frame)

    def fill(text):
        return text.replace("{scene}", _safe(scene)).replace("{view_layer}", _safe(view_layer))
    before, after = fill(stem[:last.start()]), fill(stem[last.end():])
    if light is not None:
        before += ("" if not before or before[-1] in "_.-" else "_") + _safe(light) + "_"
    return os.path.join(fill(folder), before + number + after + ext)


def template_problem(template, view_layer_count):
    """Why a template cannot name every view layer's files apart, or ''."""
    if view_layer_count > 1 and "{view_layer}" not in template:
        return ("the pass file template '%s' has no {view_layer} but %d view layers render: "
                "their files would overwrite each other" % (template, view_layer_count))
    return ""
