# Which scene files and Cycles visibility the exact-penumbrae benchmark compares with (runs inside Blender).
# SPDX-License-Identifier: GPL-3.0-or-later
# blender -b --factory-startup --python bench/exact_penumbrae_blender.py -- OUT_DIR SIZE SAMPLES NAME[,NAME...]
# Builds the named scenes of bench/scenes.py exactly as it does (same builders, light, camera,
# compositor and Cycles settings), and writes per scene OUT_DIR/<name>/scene.json,
# OUT_DIR/<name>/cycles_<SAMPLES>.exr (R = V, G = mask) and OUT_DIR/<name>/cycles.json (seconds
# of the shadowed render, triangles). Needs SOFTSHADOW_LIB.
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import scenes as s  # noqa: E402  bench/scenes.py: its builders, light, camera and Cycles settings


def main():
    argv = sys.argv[sys.argv.index("--") + 1:]
    out_root, size, samples, names = argv[0], int(argv[1]), int(argv[2]), argv[3].split(",")
    known = {entry[0]: entry for entry in s.SCENES}
    unknown = [n for n in names if n not in known]
    if unknown:
        raise SystemExit("exact_penumbrae: no scene %s in bench/scenes.py (it has %s)" %
                         (", ".join(unknown), ", ".join(known)))
    for name in names:
        _, build, light_kw = known[name]
        scene = s.reset()
        build()
        s.area_light(**light_kw)
        s.camera()
        scene.render.resolution_x = scene.render.resolution_y = size
        scene.render.resolution_percentage = 100
        scene.render.filter_size = 0.0
        out_dir = os.path.join(out_root, name)
        os.makedirs(out_dir, exist_ok=True)
        problems = s.api.export_scene_file(scene, os.path.join(out_dir, "scene.json"))
        scene.softshadow.enabled = False  # the add-on's passes must not ride on Cycles' time
        s.setup_compositor(scene)
        seconds = s.render_engine(scene, "cycles", samples, out_dir, "cycles_%d" % samples)
        info = {"scene": name, "size": size, "samples": samples, "seconds": seconds,
                "triangles": s.triangle_count(scene), "problems": problems}
        with open(os.path.join(out_dir, "cycles.json"), "w") as f:
            json.dump(info, f, indent=1)
        print("EXACT %s cycles %d at %d: %.2f s, %d triangles" % (name, samples, size, seconds, info["triangles"]),
              flush=True)
    print("EXACT-BLENDER-OK", flush=True)


main()
