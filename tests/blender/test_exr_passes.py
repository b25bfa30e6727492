# Does Blender open the written EXR as a MULTILAYER image whose passes have the exact contract names?
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402

ss = sstest.addon()


def _scene_with_two_lights(folder):
    scene = sstest.standard_scene(48, 32)
    key = scene.objects["Key"]
    key.data.softshadow.method = "shadow_map"
    rim = sstest.add_light("Rim.Light 2", location=(1, 1, 5), size=0.3)
    rim.data.softshadow.method = "reference"
    rim.data.softshadow.samples = 4
    scene.softshadow.output_path = os.path.join(folder, "softshadow_####.exr")
    bpy.context.view_layer.update()
    return scene


def _image_node_outputs(path):
    image = bpy.data.images.load(path, check_existing=False)
    image.size[:]  # Blender decides MULTILAYER only once the buffer is read (docs/contracts.md)
    kind = image.type
    scene = bpy.context.scene
    tree = ss.compat.compositor_tree(scene, create=True, bpy_data=bpy.data)
    node = tree.nodes.new("CompositorNodeImage")
    node.image = image
    names = [s.name for s in node.outputs if s.enabled]
    tree.nodes.remove(node)
    return kind, names


def test_main_passes_exact_names():
    folder = sstest.tempdir("exr")
    scene = _scene_with_two_lights(folder)
    scene.frame_current = 7
    path, problems, chosen = ss.api.render_frame(scene)
    sstest.check(problems == [], "no problems: %s" % problems)
    sstest.check(path == os.path.join(folder, "softshadow_0007.exr"), "one file per frame: %s" % path)
    sstest.check(os.path.exists(path), "written")
    want = ["Key_shadow_map", "Rim_Light_2_reference"]
    channels = sstest.exr_channels(path)
    # Without extra layers: the V pass of each (light, method), and the mask methods always make.
    allowed = {"ViewLayer.%s%s.V" % (p, suffix) for p in want for suffix in ("", "_mask")}
    sstest.check(all("ViewLayer.%s.V" % p in channels for p in want) and set(channels) <= allowed,
                 "EXR channels are <view layer>.<light>_<method>[_mask].V: %s" % channels)
    kind, names = _image_node_outputs(path)
    sstest.check(kind == "MULTILAYER", "Blender opens it as MULTILAYER, got %s" % kind)
    for name in want:
        sstest.check(name in names, "pass %r listed by the Image node: %s" % (name, names))
    leftovers = [f for f in os.listdir(folder) if not f.endswith(".exr")]
    sstest.check(leftovers == [], "no temporary files left: %s" % leftovers)


def test_extra_layers_and_values():
    folder = sstest.tempdir("exr-extra")
    scene = _scene_with_two_lights(folder)
    scene.softshadow.extra_layers = True
    scene.frame_current = 1
    path, problems, _ = ss.api.render_frame(scene)
    sstest.check(problems == [] and path, "written: %s" % problems)
    channels = sstest.exr_channels(path)
    for suffix in ("", "_mask"):
        name = "ViewLayer.Key_shadow_map%s.V" % suffix
        sstest.check(name in channels, "%s in %s" % (name, channels))
    kind, names = _image_node_outputs(path)
    sstest.check(kind == "MULTILAYER" and "Key_shadow_map_mask" in names, "mask pass listed: %s" % names)
    # The file holds what render_passes returns (row 0 = top in both).
    stored = sstest.exr_channel(path, "ViewLayer.Key_shadow_map.V")
    direct = ss.render_passes(scene, lights="Key")[("Key", "shadow_map")]
    sstest.check(stored.shape == direct.shape, "shape %s vs %s" % (stored.shape, direct.shape))
    sstest.check(float(np.abs(stored - direct).max()) <= 1e-6, "EXR equals the array")


def _header_methods(path):
    import exr_reader
    kind, raw = exr_reader.attributes(path).get("softshadow/methods", (None, b""))
    sstest.check(kind == "string", "softshadow/methods in the header of %s: %s" % (path, kind))
    return dict(item.split("=") for item in raw.decode().split(";"))


def _header_estimates(path):
    import exr_reader
    kind, raw = exr_reader.attributes(path).get("softshadow/estimated_rmse", (None, b""))
    sstest.check(kind == "string", "softshadow/estimated_rmse in the header of %s: %s" % (path, kind))
    return {k: float(v) for k, v in (item.split("=") for item in raw.decode().split(";"))}


def test_auto_keeps_its_pass_name_and_the_header_says_what_ran():
    folder = sstest.tempdir("exr-auto")
    scene = sstest.standard_scene(48, 32)
    scene.softshadow.output_path = os.path.join(folder, "softshadow_####.exr")
    key = scene.objects["Key"].data
    key.softshadow.method = "auto"
    ran = []
    for shape in ("DISK", "RECTANGLE"):
        key.shape = shape
        key.size_y = 1.0
        bpy.context.view_layer.update()
        path, problems, chosen = ss.api.render_frame(scene)
        sstest.check(path and problems == [], "%s: written, no problems: %s" % (shape, problems))
        channels = sstest.exr_channels(path)
        sstest.check("ViewLayer.Key_auto.V" in channels, "%s: stable pass name: %s" % (shape, channels))
        header = _header_methods(path)
        sstest.check(header == {"Key_auto": chosen["Key"]}, "%s: header %s, report %s" % (shape, header, chosen))
        sstest.check(chosen["Key"] in ss.native.method_names(), "a real method ran: %s" % chosen)
        estimates = _header_estimates(path)
        sstest.check(list(estimates) == ["Key_auto"] and 0.0 <= estimates["Key_auto"] < 0.2,
                     "%s: the header keeps auto's estimated RMSE: %s" % (shape, estimates))
        ran.append(chosen["Key"])
    print("   auto ran", ran)


def test_final_renders_refine_by_default_and_only_final_renders():
    folder = sstest.tempdir("exr-refine")
    scene = sstest.standard_scene(48, 32)
    key = scene.objects["Key"].data.softshadow
    key.method = "pcss"
    sstest.check(key.refine_final, "Refine Final Renders is on for a new light")
    scene.softshadow.extra_layers = True
    scene.softshadow.output_path = os.path.join(folder, "softshadow_####.exr")
    bpy.context.view_layer.update()
    scene.frame_current = 1
    path, problems, _ = ss.api.render_frame(scene)
    sstest.check(problems == [] and path, "written: %s" % problems)
    refined = sstest.exr_channel(path, "ViewLayer.Key_pcss_refined.V")
    v_final = sstest.exr_channel(path, "ViewLayer.Key_pcss.V")
    sstest.check(0 < refined.sum() < refined.size / 2, "some pixels traced: %d" % refined.sum())
    # A script's render_passes gives what the render wrote, unless it asks for the fast passes.
    v_default = ss.render_passes(scene)[("Key", "pcss")]
    sstest.check(float(np.abs(v_default - v_final).max()) <= 1e-6, "render_passes() equals the pass file")
    v_plain = ss.render_passes(scene, final=False)[("Key", "pcss")]
    certain = refined == 0
    sstest.check(np.array_equal(v_final[certain], v_plain[certain]), "untouched where pcss is certain")
    sstest.check(not np.array_equal(v_final[~certain], v_plain[~certain]), "traced where it is not")
    # Refine Final Renders off: the final render writes the fast pass.
    key.refine_final = False
    path, problems, _ = ss.api.render_frame(scene)
    sstest.check(problems == [] and path, "written: %s" % problems)
    sstest.check("ViewLayer.Key_pcss_refined.V" not in sstest.exr_channels(path), "Refine Final Renders off")
    v_off = sstest.exr_channel(path, "ViewLayer.Key_pcss.V")
    sstest.check(np.array_equal(v_off, v_plain), "the fast pass, as render_passes(final=False)")
    # Refinement is the checkbox: typed as a setting it is an unknown key, named.
    key.settings = "refine=on"
    _path, problems, _ = ss.api.render_frame(scene)
    sstest.check(any("'refine'" in p for p in problems), "refine as a setting is refused: %s" % problems)


if __name__ == "__main__":
    sstest.run(dict(globals()))
