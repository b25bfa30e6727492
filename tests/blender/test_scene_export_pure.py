# Are the numpy parts of scene export right: names, matrices, sizes, checks? (no bpy needed)
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
from softshadow import scene_export as se  # noqa: E402


def test_column_major_layout():
    rows = [[1, 2, 3, 4], [5, 6, 7, 8], [9, 10, 11, 12], [13, 14, 15, 16]]
    flat = se.column_major(rows)
    # m[col*4 + row]: the translation (column 3) is at 12, 13, 14.
    sstest.check(list(flat[12:15]) == [4, 8, 12], "translation in elements 12..14: %s" % flat)
    sstest.check(list(flat[0:4]) == [1, 5, 9, 13], "first column first")
    sstest.check(flat.dtype == np.float32, "float32")


def test_normalized_rigid_removes_scale_keeps_translation():
    m = [[2, 0, 0, 5], [0, 3, 0, 6], [0, 0, 4, 7], [0, 0, 0, 1]]
    n = se.normalized_rigid(m)
    sstest.check(np.allclose(n[:3, :3], np.eye(3)) and np.allclose(n[:3, 3], [5, 6, 7]), "%s" % n)


def test_render_size_integer_like_blender():
    sstest.check(se.render_size(1920, 1080, 50) == (960, 540), "50%")
    sstest.check(se.render_size(1001, 333, 33) == (330, 109), "truncating integer percentage")


def test_faceless_problem():
    sstest.check(se.faceless_problem("a", np.array([[0, 1, 2]], np.uint32)) is None, "a mesh with a face")
    sstest.check("'a' has no faces" in se.faceless_problem("a", np.zeros((0, 3), np.uint32)), "no faces")


def test_light_values_and_problems():
    eye = np.eye(4)
    disk = se.light_values("K", "AREA", "DISK", eye, size=0.5, size_y=9.0)
    sstest.check(disk["type"] == "DISK" and disk["size_y"] == 0.5, "disk ignores size_y: %s" % disk)
    rect = se.light_values("R", "AREA", "RECTANGLE", eye, size=1.0, size_y=2.0)
    sstest.check(rect["size_y"] == 2.0, "rectangle keeps size_y")
    spot = se.light_values("S", "SPOT", "", eye, radius=0.1, spot_size=1.0, spot_blend=0.2,
                           use_shadow=False)
    sstest.check(spot["type"] == "SPOT" and spot["cast_shadows"] is False, "spot without shadow")
    try:
        se.light_values("X", "HEMI", "", eye)
        sstest.check(False, "unknown type must raise")
    except ValueError as exc:
        sstest.check("X" in str(exc), "the message names the light")


def test_unique_names():
    used = set()
    names = [se.unique_name("A", used) for _ in range(3)]
    sstest.check(names == ["A", "A.001", "A.002"], "%s" % names)


def test_same_alpha_and_the_unreadable_materials_line():
    def alpha(texture=None, value=0.5):
        return {"uvs": np.zeros((6, 2), np.float32), "triangle_material": np.zeros(2, np.int32),
                "materials": [{"alpha": value, "texture": texture, "wrap": 0, "closest": False}]}
    t = np.ones((2, 2), np.float32)
    sstest.check(se.same_alpha(None, None) and not se.same_alpha(alpha(), None), "None only equals None")
    sstest.check(se.same_alpha(alpha(t), alpha(t.copy())), "equal textures")
    sstest.check(not se.same_alpha(alpha(t), alpha(t * 0.5)), "other texels")
    sstest.check(not se.same_alpha(alpha(), alpha(value=0.25)), "other constant")
    sstest.check(se.unreadable_materials_line(set()) is None, "no line when every material was read")
    line = se.unreadable_materials_line({"'B' (node 'N' (TEX_NOISE))", "'A' (node 'G' (GROUP))"})
    sstest.check(line.startswith("shadows treat 2 material(s) as opaque") and line.index("'A'") < line.index("'B'"),
                 line)


if __name__ == "__main__":
    sstest.run(dict(globals()))
