# What part of the camera's frame a render makes: the render border's crop, and cameras no method draws.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Pure numpy and attribute reads (no bpy import), so it tests without Blender.

A render border with Crop renders only the border's pixels: Blender's render result, the
compositor's Render Layers and the saved image are border-sized, so the pass must be too (the
compositor centres an input of another size, which would shift the shadow). Without Crop the
render result is full-sized (black and transparent outside the border) and so is the pass.
"""
import numpy as np


def crop_rect(render, width, height):
    """(xmin, ymin, xmax, ymax) in pixels of the full frame (y up from the bottom row, max
    exclusive) when the render is cropped to its border, else None. The pixel edges are
    Blender's own: border fraction x size, truncated (render_init_from_main's disprect)."""
    if not getattr(render, "use_border", False) or not getattr(render, "use_crop_to_border", False):
        return None
    xmin, xmax = int(render.border_min_x * width), int(render.border_max_x * width)
    ymin, ymax = int(render.border_min_y * height), int(render.border_max_y * height)
    if (xmin, ymin, xmax, ymax) == (0, 0, width, height):
        return None
    return xmin, ymin, xmax, ymax


def crop_problem(rect):
    """Why a cropped border cannot render (a message), or None."""
    if rect is not None and (rect[2] <= rect[0] or rect[3] <= rect[1]):
        return "the render border has no pixels with Crop on: no soft-shadow passes"
    return None


def cropped_projection(projection_rows, rect, width, height):
    """The full frame's projection (4x4, row-indexed, OpenGL clip space) narrowed to the pixel
    rectangle `rect`: the rectangle's NDC window is stretched to [-1, 1], so the cropped image's
    pixel (i, j) looks exactly where the full frame's pixel (xmin + i, ymin + j) does."""
    xmin, ymin, xmax, ymax = rect
    sx, sy = width / float(xmax - xmin), height / float(ymax - ymin)
    # NDC window [2 xmin / W - 1, 2 xmax / W - 1] -> [-1, 1]; the offset scales with w (clip space)
    tx = -(xmin + xmax - width) / float(xmax - xmin)
    ty = -(ymin + ymax - height) / float(ymax - ymin)
    window = np.array([[sx, 0, 0, tx], [0, sy, 0, ty], [0, 0, 1, 0], [0, 0, 0, 1]], dtype=np.float64)
    return window @ np.asarray([list(r) for r in projection_rows], dtype=np.float64).reshape(4, 4)


def panorama_type(camera_data):
    """The panorama mapping of a panoramic camera ('EQUIRECTANGULAR', 'FISHEYE_EQUIDISTANT'...),
    or None for a perspective or orthographic one. 4.0+ keep it on the camera, 3.x in Cycles'
    settings of the camera."""
    if getattr(camera_data, "type", "PERSP") != "PANO":
        return None
    kind = getattr(camera_data, "panorama_type", None)
    if kind is None:
        kind = getattr(getattr(camera_data, "cycles", None), "panorama_type", None)
    return kind or "PANORAMIC"


def camera_problem(camera_object):
    """Why no method can draw from this camera (a message), or None. Every method and the
    reference trace or draw through a projection matrix; a panoramic mapping has none, and its
    perspective stand-in would be another picture's shadow."""
    if camera_object is None:
        return None
    kind = panorama_type(camera_object.data)
    if kind is None:
        return None
    return ("camera '%s' is panoramic (%s): no method (nor the reference) renders panoramic cameras, "
            "so there are no soft-shadow passes (use a perspective or orthographic camera)"
            % (camera_object.name, kind.lower().replace("_", " ")))
