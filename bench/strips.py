# How each benchmark scene's image strip is drawn: rows of method | truth | 4 x |error| (oiiotool).
# SPDX-License-Identifier: GPL-3.0-or-later
# The error cell is masked by the truth's mask, as the metrics are.
# python3 bench/strips.py WORK OUT  ->  OUT/strip_<scene>.png (grey, 128x96 per cell), and
# OUT/strip_<scene>.txt listing the rows top to bottom.
import glob
import json
import os
import subprocess
import sys

CELL_W, CELL_H = 128, 96
BLENDER_ROWS = ("eevee_16", "eevee_64", "cycles_16")


def oiio(*args):
    subprocess.run(["oiiotool", *args], check=True, stdout=subprocess.DEVNULL)


def main():
    work, out = sys.argv[1], sys.argv[2]
    for scene_dir in sorted(glob.glob(os.path.join(work, "scenes", "*", ""))):
        scene = os.path.basename(os.path.dirname(scene_dir))
        with open(os.path.join(scene_dir, "scene.json")) as f:
            light = json.load(f)["lights"][0]["name"].replace(".", "_").replace(" ", "_")
        truth = os.path.join(scene_dir, "truth.exr")
        rows = []  # (label, file, V channel)
        for path in sorted(glob.glob(os.path.join(work, "ours", scene, "*.exr"))):
            method = os.path.basename(path)[:-4]
            if "-" in method:
                continue  # a non-default setting (method-tag): the tables and plots have it
            rows.append((method, path, "ViewLayer.%s_%s.V" % (light, method)))
        rows.append(("reference (default samples)", os.path.join(scene_dir, "reference.exr"),
                     "ViewLayer.%s_reference.V" % light))
        for key in BLENDER_ROWS:
            path = os.path.join(scene_dir, key + ".named.exr")
            if os.path.exists(path):
                rows.append((key, path, "ViewLayer.%s_reference.V" % light))
        # One oiiotool call per scene (each start costs ~0.5 s): labelled images on its stack.
        args = [truth, "--ch", "Y=ViewLayer.%s_reference.V" % light, "--label", "t",
                truth, "--ch", "Y=ViewLayer.%s_reference_mask.V" % light, "--label", "m"]
        for i, (_, path, channel) in enumerate(rows):
            a, d, r = ("%s%d" % (k, i) for k in "adr")
            args += [path, "--ch", "Y=" + channel, "--label", a,
                     a, "t", "--absdiff", "--mulc", "4", "m", "--mul", "--clamp:min=0:max=1", "--label", d,
                     a, "t", d, "--mosaic", "3x1", "--resize", "%dx%d" % (3 * CELL_W, CELL_H), "--label", r]
        args += ["r%d" % i for i in range(len(rows))]
        args += ["--mosaic", "1x%d" % len(rows), "-d", "uint8", "-o", os.path.join(out, "strip_%s.png" % scene)]
        oiio(*args)
        with open(os.path.join(out, "strip_%s.txt" % scene), "w") as f:
            f.write("\n".join(label for label, _, _ in rows) + "\n")


main()
