# Is the framing arithmetic Blender's: the cropped border's pixels, the narrowed projection that
# lands each cropped pixel where the full frame's does, the panorama types? (no bpy needed)
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import sys
from types import SimpleNamespace

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
from softshadow import framing  # noqa: E402


def _render(use_border=True, crop=True, border=(0.25, 0.8, 0.1, 0.6)):
    return SimpleNamespace(use_border=use_border, use_crop_to_border=crop, border_min_x=border[0],
                           border_max_x=border[1], border_min_y=border[2], border_max_y=border[3])


def test_crop_rect_truncates_like_blender():
    # Measured in Blender 3.4: this border with Crop renders 35 x 24 pixels.
    rect = framing.crop_rect(_render(), 64, 48)
    sstest.check(rect == (16, 4, 51, 28), "%s" % (rect,))
    sstest.check(framing.crop_rect(_render(crop=False), 64, 48) is None, "no Crop: the full frame")
    sstest.check(framing.crop_rect(_render(use_border=False), 64, 48) is None, "no border: the full frame")
    sstest.check(framing.crop_rect(_render(border=(0, 1, 0, 1)), 64, 48) is None, "a full border is no crop")
    sstest.check(framing.crop_problem(framing.crop_rect(_render(border=(0.5, 0.5, 0, 1)), 64, 48)) is not None,
                 "an empty border is a problem")
    sstest.check(framing.crop_problem(rect) is None, "a real border is none")


def _ndc_of_pixel(projection, px, py, width, height):
    """Where pixel (px, py) (y up from the bottom) of an image looks, as a camera-space direction
    at depth -1 (perspective), through the inverse projection."""
    x = 2.0 * (px + 0.5) / width - 1.0
    y = 2.0 * (py + 0.5) / height - 1.0
    near = np.linalg.inv(projection) @ np.array([x, y, -1.0, 1.0])
    far = np.linalg.inv(projection) @ np.array([x, y, 1.0, 1.0])
    direction = far[:3] / far[3] - near[:3] / near[3]
    return direction / -direction[2]


def _perspective(shift_x=0.1):
    n, f, r, t = 0.1, 100.0, 0.05, 0.0375
    return np.array([[n / r, 0, shift_x, 0], [0, n / t, 0, 0],
                     [0, 0, -(f + n) / (f - n), -2 * f * n / (f - n)], [0, 0, -1, 0]])


def test_cropped_projection_lands_each_pixel_where_the_full_frame_does():
    width, height = 64, 48
    rect = (16, 4, 51, 28)
    for projection in (_perspective(), np.diag([0.2, 0.25, -0.02, 1.0])):
        cropped = framing.cropped_projection(projection, rect, width, height)
        w, h = rect[2] - rect[0], rect[3] - rect[1]
        for px, py in ((0, 0), (w - 1, h - 1), (7, 13)):
            if projection[3, 3] == 0:
                a = _ndc_of_pixel(cropped, px, py, w, h)
                b = _ndc_of_pixel(projection, rect[0] + px, rect[1] + py, width, height)
            else:  # orthographic: the pixel's point on the near plane
                a = np.linalg.inv(cropped) @ np.array([2 * (px + 0.5) / w - 1, 2 * (py + 0.5) / h - 1, 0, 1])
                b = np.linalg.inv(projection) @ np.array([2 * (rect[0] + px + 0.5) / width - 1,
                                                          2 * (rect[1] + py + 0.5) / height - 1, 0, 1])
            sstest.check(np.allclose(a, b, atol=1e-9), "pixel (%d, %d): %s vs %s" % (px, py, a, b))


def test_panorama_types_in_both_places():
    sstest.check(framing.panorama_type(SimpleNamespace(type="PERSP")) is None, "perspective")
    sstest.check(framing.panorama_type(SimpleNamespace(type="ORTHO")) is None, "orthographic")
    new = SimpleNamespace(type="PANO", panorama_type="FISHEYE_EQUIDISTANT")
    sstest.check(framing.panorama_type(new) == "FISHEYE_EQUIDISTANT", "4.0+: on the camera")
    old = SimpleNamespace(type="PANO", cycles=SimpleNamespace(panorama_type="EQUIRECTANGULAR"))
    sstest.check(framing.panorama_type(old) == "EQUIRECTANGULAR", "3.x: in Cycles' settings")
    sstest.check(framing.panorama_type(SimpleNamespace(type="PANO")) == "PANORAMIC", "Cycles off in 3.x")
    problem = framing.camera_problem(SimpleNamespace(name="Cam", data=old))
    sstest.check("'Cam'" in problem and "equirectangular" in problem and "no soft-shadow passes" in problem, problem)
    sstest.check(framing.camera_problem(SimpleNamespace(name="Cam", data=SimpleNamespace(type="PERSP"))) is None, "")


if __name__ == "__main__":
    sstest.run(dict(globals()))
