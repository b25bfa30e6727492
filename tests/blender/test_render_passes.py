# Does softshadow.render_passes return camera-aligned arrays with the shadow where the geometry puts it?
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402

ss = sstest.addon()
W, H = 64, 48
# The shadow centre is 1.25 inside the umbra edge (penumbra 0.5 wide): every light sample is
# blocked there. (-3.5, -2.8, 0) is 3.5+ away from the shadow: fully lit.
UNDER = sstest.shadow_centre(-1.0)
FAR = (-3.5, -2.8, 0.0)
# A far ground pixel whose hemisphere sees all of the light: V is exactly 1 up to float error.
LIT_TOLERANCE = 1e-3
# Deep in the umbra every light sample is blocked: 0 up to float error.
UMBRA_MAX = 1e-3


def _check_pass(array, scene, what):
    sstest.check(array.dtype == np.float32, "%s: float32, got %s" % (what, array.dtype))
    sstest.check(array.shape == (H, W), "%s: shape %s, want %s" % (what, array.shape, (H, W)))
    sstest.check(np.isfinite(array).all(), "%s: finite" % what)
    sstest.check(array.min() >= 0.0 and array.max() <= 1.0, "%s: in [0,1]: %s..%s" % (what, array.min(), array.max()))
    under = array[sstest.pixel_of(scene, UNDER)]
    far = array[sstest.pixel_of(scene, FAR)]
    sstest.check(under <= UMBRA_MAX, "%s: under the occluder V=%.4f, want <= %s" % (what, under, UMBRA_MAX))
    sstest.close(far, 1.0, LIT_TOLERANCE, "%s: far ground pixel" % what)
    # row 0 = top, column 0 = left: the shadow (x = +2) is in the right half, not mirrored.
    row, col = sstest.pixel_of(scene, UNDER)
    sstest.check(col > W // 2, "shadow pixel in the right half: col %d" % col)
    mirrored = array[row, W - 1 - col]
    sstest.check(mirrored > 0.9, "%s: mirror image of the shadow is lit (%.3f): not flipped" % (what, mirrored))


def test_reference_and_shadow_map():
    scene = sstest.standard_scene(W, H)
    scene.objects["Key"].data.softshadow.samples = 16
    result = ss.render_passes(scene, methods=["reference", "shadow_map"])
    sstest.check(set(result) == {("Key", "reference"), ("Key", "shadow_map")}, "keys: %s" % list(result))
    for key, array in result.items():
        _check_pass(array, scene, "%s/%s" % key)
    # A hard shadow map is 0 or 1 away from edges; both must agree on the umbra core and far field.
    a, b = result[("Key", "reference")], result[("Key", "shadow_map")]
    agree = np.mean(np.abs(a - b) < 0.5)
    sstest.check(agree > 0.9, "reference and shadow_map agree on %.3f of the pixels" % agree)


def test_default_every_light_with_its_method():
    scene = sstest.standard_scene(W, H)
    rim = sstest.add_light("Rim.Light 2", location=(-4, 2, 6), size=0.3)
    off = sstest.add_light("NoShadow", location=(2, 2, 5))
    off.data.use_shadow = False
    disabled = sstest.add_light("Disabled", location=(-2, 2, 5))
    disabled.data.softshadow.enabled = False
    rim.data.softshadow.method = "shadow_map"
    bpy.context.view_layer.update()
    result = ss.render_passes(scene)
    lights = sorted(k[0] for k in result)
    sstest.check(lights == ["Key", "Rim.Light 2"], "shadow-casting enabled lights only, real names: %s" % list(result))
    sstest.check(("Rim.Light 2", "shadow_map") in result, "own method setting used: %s" % list(result))
    auto = [k for k in result if k[0] == "Key"][0][1]
    sstest.check(auto in ss.native.method_names(), "auto resolved to a real method: %r" % auto)
    estimates = ss.render_passes.last_estimates
    key_estimate = estimates.get(("Key", auto))
    sstest.check(key_estimate is not None and 0.0 <= key_estimate < 0.2,
                 "auto's result carries its estimated RMSE: %s" % estimates)
    sstest.check(("Rim.Light 2", "shadow_map") not in estimates, "no estimate unless asked: %s" % estimates)
    only = ss.render_passes(scene, lights="Rim.Light 2", methods="shadow_map")
    sstest.check(list(only) == [("Rim.Light 2", "shadow_map")], "lights= filter: %s" % list(only))


def test_render_percentage_and_aspect():
    scene = sstest.standard_scene(W * 2, H * 2)
    scene.render.resolution_percentage = 50
    result = ss.render_passes(scene, methods="shadow_map")
    array = result[("Key", "shadow_map")]
    sstest.check(array.shape == (H, W), "50%% of %dx%d is %s" % (2 * W, 2 * H, array.shape))
    scene.render.resolution_percentage = 100
    scene.render.resolution_x, scene.render.resolution_y = W, H
    scene.render.pixel_aspect_x = 2.0
    array = ss.render_passes(scene, methods="shadow_map")[("Key", "shadow_map")]
    sstest.check(array[sstest.pixel_of(scene, UNDER)] <= UMBRA_MAX, "pixel aspect 2: shadow still under the box")


def test_orthographic_and_shift():
    scene = sstest.standard_scene(W, H)
    cam = scene.camera.data
    cam.type = "ORTHO"
    cam.ortho_scale = 8.0
    cam.shift_x = 0.1
    array = ss.render_passes(scene, methods="shadow_map")[("Key", "shadow_map")]
    sstest.check(array[sstest.pixel_of(scene, UNDER)] <= UMBRA_MAX, "ortho + shift: shadow under the box")
    sstest.close(array[sstest.pixel_of(scene, FAR)], 1.0, LIT_TOLERANCE, "ortho far pixel")


def test_auto_and_the_method_it_resolves_to_make_one_pass():
    # 'auto' resolving to a method also asked for must not drop or overwrite a result: the two
    # are the same (light, method, settings), so one pass is made and 'chosen' names it once.
    scene = sstest.standard_scene(W, H)
    resolved = list(ss.render_passes(scene, lights="Key", methods="auto"))[0][1]
    for methods in (["auto", resolved], [resolved, "auto"]):
        result = ss.render_passes(scene, lights="Key", methods=methods)
        sstest.check(list(result) == [("Key", resolved)], "%s: %s" % (methods, list(result)))
        sstest.check(ss.render_passes.last_chosen == {"Key": resolved},
                     "%s: chosen %s" % (methods, ss.render_passes.last_chosen))
        sstest.check(ss.render_passes.last_problems == [], "%s: %s" % (methods, ss.render_passes.last_problems))
    both = ss.render_passes(scene, lights="Key", methods=["auto", "shadow_map"] if resolved != "shadow_map"
                            else ["auto", "pcss"])
    sstest.check(len(both) == 2, "two methods, two passes: %s" % list(both))
    sstest.check(", " in ss.render_passes.last_chosen["Key"], "chosen names both: %s" % ss.render_passes.last_chosen)


def test_a_setting_typo_is_a_problem_naming_the_key():
    scene = sstest.standard_scene(W, H)
    scene.objects["Key"].data.softshadow.method = "pcss"
    scene.objects["Key"].data.softshadow.settings = "blocker_sample=64"
    result = ss.render_passes(scene)
    sstest.check(("Key", "pcss") not in result, "the typo rendered the default: %s" % list(result))
    problems = " ".join(ss.render_passes.last_problems)
    sstest.check("no setting 'blocker_sample'" in problems and "blocker_samples" in problems,
                 "problem names the key and the known keys: %s" % problems)


def test_sweep_ring_fill_from_the_method_settings():
    # The sweep's paper fill (fill=rings) is one entry in the light's method settings; a
    # misspelt value is a problem naming the choices, never the default rendered.
    scene = sstest.standard_scene(W, H)
    scene.render.pixel_aspect_x = 1.0  # another test may have left it at 2
    key = scene.objects["Key"].data.softshadow
    key.method = "sweep"
    smooth = ss.render_passes(scene, final=False)[("Key", "sweep")]
    key.settings = "fill=rings"
    rings = ss.render_passes(scene, final=False)[("Key", "sweep")]
    _check_pass(rings, scene, "sweep fill=rings")
    diff = np.abs(rings - smooth)
    sstest.check(diff.max() > 1e-3 and diff.mean() < 0.02,
                 "rings differ from smooth in the penumbra only: max %.4f mean %.4f" % (diff.max(), diff.mean()))
    key.settings = "fill=ring"
    result = ss.render_passes(scene)
    sstest.check(("Key", "sweep") not in result, "the typo rendered the default: %s" % list(result))
    problems = " ".join(ss.render_passes.last_problems)
    sstest.check("is not one of: smooth, steps, rings" in problems, "problem names the choices: %s" % problems)


def test_dbuffer_paper_formula_from_the_light_settings():
    # formula=paper (eq. 3 as printed) gives the centre's hard shadow: the penumbra the default
    # formula draws is gone. A misspelt value is a problem naming the setting.
    scene = sstest.standard_scene(W, H)
    light = scene.objects["Key"].data.softshadow
    light.method = "dbuffer"
    exact = ss.render_passes(scene, final=False)[("Key", "dbuffer")]
    light.settings = "formula=paper"
    paper = ss.render_passes(scene, final=False)[("Key", "dbuffer")]
    soft_exact = int(np.sum((exact > 0.05) & (exact < 0.95)))
    soft_paper = int(np.sum((paper > 0.05) & (paper < 0.95)))
    sstest.check(soft_exact > 20 and soft_paper < soft_exact // 4,
                 "penumbra pixels: default %d, formula=paper %d" % (soft_exact, soft_paper))
    sstest.check(np.isfinite(paper).all() and paper.min() >= 0.0 and paper.max() <= 1.0, "paper V in [0, 1]")
    light.settings = "formula=printed"
    result = ss.render_passes(scene)
    sstest.check(("Key", "dbuffer") not in result, "a bad formula rendered: %s" % list(result))
    problems = " ".join(ss.render_passes.last_problems)
    sstest.check("'formula'" in problems and "paper" in problems, "problem names the setting: %s" % problems)


def test_the_settings_tooltip_lists_the_chosen_methods_keys():
    # The ? button beside Method Settings: its tooltip is the library's list for the light's method.
    sstest.check(hasattr(bpy.ops.softshadow, "method_settings"), "the settings-keys operator is registered")
    pcss = ss.ui.method_settings_text("pcss")
    keys = [entry[0] for entry in ss.native.method_settings("pcss")]
    sstest.check(keys[:4] == ["blocker_samples", "pcf_samples", "shadow_map_size", "max_search"]
                 and "refine_margin" in keys, "pcss's keys, its own first: %s" % keys)
    sstest.check("blocker_samples (default 16, 1..1024)" in pcss and "refine_margin (default 3, 0..32)" in pcss,
                 "each key with default and range: %s" % pcss)
    occlusion = ss.ui.method_settings_text("occlusion_textures")
    sstest.check("filter (default sat, sat|mipmap|nbuffer)" in occlusion and "blocker_samples" not in occlusion,
                 "another method, its own keys: %s" % occlusion)
    sstest.check("debug." not in pcss + occlusion + ss.ui.method_settings_text("dbuffer"), "test switches not listed")
    sstest.check("check_pixels" in ss.ui.method_settings_text("auto"), "auto's own keys")
    tip = ss.ui.SOFTSHADOW_OT_method_settings.description(bpy.context, type("Props", (), {"method": "sweep"})())
    sstest.check("fill (default smooth, smooth|steps|rings)" in tip, "sweep's tooltip: %s" % tip)
    # Refinement is a render option (Refine Final Renders), not a key of any method.
    sstest.check("refine" not in keys and "refine_rounds" not in keys, "no refine key: %s" % keys)


def test_method_list_comes_from_the_library():
    names = ss.native.method_names()
    sstest.check(names[0] == "shadow_map" and names[-1] == "reference" and len(names) == 7, "%s" % (names,))
    items = [item[0] for item in ss.properties.method_items()]
    sstest.check(items == ["auto"] + list(names), "the light's method menu follows the library: %s" % items)
    sstest.check(list(ss.properties.METHOD_LABELS) == items,
                 "the labels (the stand-in list without a library) are the same list: %s"
                 % list(ss.properties.METHOD_LABELS))
    light = bpy.data.lights.new("MenuProbe", "AREA")
    try:
        shown = [item.identifier for item in light.softshadow.bl_rna.properties["method"].enum_items]
        sstest.check(light.softshadow.method == "auto", "an unset method is auto: %r" % light.softshadow.method)
        for name in names:
            light.softshadow.method = name
            sstest.check(light.softshadow.method == name, "%s round-trips: %r" % (name, light.softshadow.method))
        numbers = [item[3] for item in ss.properties.method_items()]
        sstest.check(numbers == list(range(len(items))), "numbers of the earlier fixed menu: %s" % numbers)
    finally:
        bpy.data.lights.remove(light)
    sstest.check(shown in ([], items), "Blender's menu lists the same items: %s" % shown)
    sstest.check(set(ss.preview.fast_methods()) == set(names) - {"reference"}, "%s" % (ss.preview.fast_methods(),))
    sstest.check(ss.native.pass_name("Key. Light", "pcss") == "Key__Light_pcss" and
                 ss.native.pass_name("Key", "auto", "mask") == "Key_auto_mask" and
                 ss.native.pass_name("Key", "auto", "V") == "Key_auto", "pass names from the library")


if __name__ == "__main__":
    sstest.run(dict(globals()))
