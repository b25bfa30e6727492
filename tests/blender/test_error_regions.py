# Does bench/error_regions.py (the docs' "Where the error is" numbers) split the error as it says?
# SPDX-License-Identifier: GPL-3.0-or-later
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402

sys.path.insert(0, os.path.join(sstest.ROOT, "bench"))
import error_regions as er  # noqa: E402
import bpy  # noqa: E402


def _helpers(receivers, surfaces, occluders=None):
    return {"receivers": receivers, "surfaces": surfaces, "occluders": occluders,
            "occluder_count": 2 if occluders is not None else 0}


def test_shares_and_rmse_per_region():
    truth = np.array([[1.0, 0.5, 0.0, 1.0]])
    method = np.array([[1.0, 0.3, 0.4, 0.8]])  # errors 0, -0.2, +0.4, -0.2
    mask = np.array([[True, True, True, False]])
    regs = er.regions(truth, mask, _helpers(np.array([[True, True, False, False]]), mask))
    rows = er.split_error(method - truth, regs)
    sstest.close(rows["all"]["rmse"], np.sqrt((0.04 + 0.16) / 3), 1e-12, "RMSE over the mask")
    sstest.close(rows["receivers"]["share"], 0.2, 1e-12, "receivers' share")
    sstest.close(rows["casters"]["share"], 0.8, 1e-12, "casters' share")
    sstest.close(rows["penumbra"]["rmse"], 0.2, 1e-12, "RMSE in the penumbra")
    sstest.close(rows["umbra"]["share"], 0.8, 1e-12, "umbra's share")
    sstest.close(rows["lit"]["pixels"], 1 / 3, 1e-12, "lit pixels")
    sstest.close(rows["all"]["too_dark_share"], 0.2, 1e-12, "too dark")
    sstest.close(rows["all"]["too_light_share"], 0.8, 1e-12, "too light")


def test_sharp_steps_only_between_receiver_pixels():
    truth = np.array([[1.0, 1.0, 0.0, 0.0],
                      [1.0, 0.95, 0.9, 0.0]])
    receivers = np.array([[True, True, True, False],
                          [True, True, True, True]])
    sharp = er.sharp_steps(truth, receivers)
    expected = np.array([[False, True, True, False],   # 1.0 | 0.0 inside; 0.0 | 0.0 to a caster
                         [False, False, True, True]])  # 0.9 | 0.0; 1.0 -> 0.95 -> 0.9 is gentle
    sstest.check((sharp == expected).all(), "sharp steps:\n%s" % sharp.astype(int))


def test_terminator_band_is_casters_near_unlit_caster_pixels():
    n = 16
    mask = np.zeros((n, n), bool)
    mask[:, :8] = True                  # lit part of a caster ...
    surfaces = np.ones((n, n), bool)    # ... whose right half the light does not reach
    regs = er.regions(np.ones((n, n)), mask, _helpers(np.zeros((n, n), bool), surfaces))
    band = regs["terminator band on casters"]
    sstest.check(band[:, 4:8].all() and not band[:, :4].any(),
                 "band of %d px: columns %s" % (er.TERMINATOR_PX, np.nonzero(band[0])[0]))
    receivers = np.zeros((n, n), bool)
    receivers[:, 8:] = True             # the unlit half is a receiver: no caster terminator
    regs = er.regions(np.ones((n, n)), mask, _helpers(receivers, surfaces))
    sstest.check(not regs["terminator band on casters"].any(), "receiver counted as a caster's unlit side")


def test_components_of_a_mesh():
    mesh = {"positions": [0] * 3 * 7, "triangles": [0, 1, 2, 0, 2, 3, 4, 5, 6]}
    parts = sorted(er.components(mesh))
    sstest.check(parts == [[0, 1], [2]], "components %s" % parts)


def test_camera_pose_from_world_to_camera():
    # The bench scenes' camera (as the add-on exports it): at (0, -5.5, 6) looking down 45 degrees.
    m = [1.0, 0.0, 0.0, 0.0, 0.0, 0.7071067094802856, -0.7071068286895752, 0.0,
         0.0, 0.7071068286895752, 0.7071067094802856, 0.0, 0.0, -0.3535540699958801, -8.131728172302246, 1.0]
    pos, direction = er.camera_pose({"camera": {"world_to_camera": m}})
    sstest.check(np.allclose(pos, [0.0, -5.5, 6.0], atol=1e-4), "position %s" % pos)
    sstest.check(np.allclose(direction, [0.0, 0.70710678, -0.70710678], atol=1e-6),
                 "direction %s" % direction)
    pos, direction = er.camera_pose({"camera": {"look_from": [6.5, -7.5, 5.0], "look_at": [0.0, 0.0, 0.4]}})
    sstest.check(pos == [6.5, -7.5, 5.0] and np.allclose(direction, [-6.5, 7.5, -4.6]),
                 "look_from: %s %s" % (pos, direction))


def test_heat_tile_colours_and_png():
    truth = np.ones((512, 512))
    mask = np.ones((512, 512), bool)
    err = np.zeros((512, 512))
    err[10, 10] = -0.5     # one too-dark pixel survives the 2x2 reduction, at full strength
    err[300, 301] = 0.5
    tile = er.heat_tile(truth, mask, err)
    sstest.check(tile.shape == (256, 256, 3), "tile %s" % (tile.shape,))
    sstest.check(tile[5, 5, 0] > 200 and tile[5, 5, 2] < 40, "too dark is red: %s" % tile[5, 5])
    sstest.check(tile[150, 150, 2] > 200 and tile[150, 150, 0] < 40, "too light is blue: %s" % tile[150, 150])
    sstest.check((tile[0, 0] == tile[0, 0, 0]).all(), "no error is grey: %s" % tile[0, 0])
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "t.png")
        er.write_png(path, tile)
        image = bpy.data.images.load(path)
        sstest.check(tuple(image.size) == (256, 256), "PNG size %s" % (tuple(image.size),))
        px = np.array(image.pixels[:]).reshape(256, 256, 4)[::-1]  # Blender's rows start at the bottom
        sstest.check(np.abs(px[5, 5, :3] * 255 - tile[5, 5]).max() < 1.5, "PNG pixel %s" % px[5, 5])


def _cli():
    build = os.environ.get("SOFTSHADOW_BUILD_DIR") or os.path.join(sstest.ROOT, "build")
    return os.path.join(build, "softshadow")


def test_end_to_end_on_a_small_scene():
    """The demo scene at 96x72 with the cube set on the ground (a contact): the regions exist, the
    partitions add up and the RMSE over the mask is `softshadow compare`'s."""
    cli = _cli()
    sstest.check(os.path.exists(cli), "no CLI at %s (build the softshadow target)" % cli)
    with open(os.path.join(sstest.ROOT, "examples", "scenes", "demo.json")) as f:
        scene = json.load(f)
    scene["camera"]["width"], scene["camera"]["height"] = 96, 72
    for mesh in scene["meshes"]:
        if mesh["name"] == "Cube":
            mesh["translate"][2] = 0.3  # its 0.6 box stands on the ground
    with tempfile.TemporaryDirectory() as folder:
        os.makedirs(os.path.join(folder, "demo"))
        with open(os.path.join(folder, "demo", "scene.json"), "w") as f:
            json.dump(scene, f)
        results, tiles = er.measure(cli, os.path.join(folder, "work"), [os.path.join(folder, "demo")],
                                    ["shadow_map", "sweep"], truth_samples=64)
        r = results["demo"]
        px = r["pixels"]
        sstest.check(px["receivers"] + px["casters"] == px["all"], "receivers + casters: %s" % px)
        sstest.check(px["lit"] + px["penumbra"] + px["umbra"] == px["all"], "classes: %s" % px)
        for region in ("casters", "penumbra", "umbra", "sharp penumbra on receivers",
                       "terminator band on casters", "receivers under one occluder"):
            sstest.check(px.get(region, 0) > 0, "no pixels in %s: %s" % (region, px))
        sm = r["shadow_map"]
        sstest.close(sm["receivers"]["share"] + sm["casters"]["share"], 1.0, 1e-9, "shares")
        sstest.check(sm["penumbra"]["share"] > 0.5, "a hard shadow's error is in the penumbra: %s" % sm["penumbra"])
        # sweep leaves everything off its ground plane at 1: too light on the casters, never too dark there.
        sstest.check(r["sweep"]["casters"]["too_dark_share"] == 0.0, "sweep on casters: %s" % r["sweep"]["casters"])
        out = subprocess.run([cli, "compare", os.path.join(folder, "work", "demo", "shadow_map.exr"),
                              os.path.join(folder, "work", "demo", "truth.exr"), "--mask", "Area_reference_mask",
                              "--json"], check=True, capture_output=True, text=True).stdout
        compared = json.loads(out)[0]
        sstest.check(compared["pixels"] == px["all"],
                     "mask pixels %d vs compare's %d" % (px["all"], compared["pixels"]))
        sstest.close(sm["all"]["rmse"], compared["rmse"], 1e-6, "RMSE against compare's")
        sstest.check(tiles["shadow_map"][0].shape == (72, 96, 3), "tile %s" % (tiles["shadow_map"][0].shape,))


sstest.run(globals())
