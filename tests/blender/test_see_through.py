# Do see-through materials shadow as Cycles' shadow rays see them? A leaf-like cut-out card (an
# Image Texture's alpha into the Principled BSDF's Alpha) and a 50 % card (a Mix Shader with a
# Transparent BSDF), each against Cycles' own shadow ratio; does the camera see the ground through
# a cut-out's holes as Cycles' camera rays do; and which materials the export reads.
# SPDX-License-Identifier: GPL-3.0-or-later
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cycles_truth  # noqa: E402
import sstest  # noqa: E402
import bpy  # noqa: E402

ss = sstest.addon()
W, H = 64, 48
CYCLES_SAMPLES = 1024
TEXTURE = 32


def _scene():
    scene = sstest.clear_scene()
    for image in list(bpy.data.images):
        if image.name.startswith("leaf"):
            bpy.data.images.remove(image)
    sstest.add_plane("Ground", 10, (0, 0, 0))
    sstest.add_light("Key", location=(-3.0, 0.2, 6), size=0.6, energy=1000)
    sstest.add_camera(location=(0, 0, 9), width=W, height=H, lens=40)
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.max_bounces = 0  # direct light only: the pass's contract is the direct light's ratio
    scene.cycles.seed = 3
    world = bpy.data.worlds.new("Black")
    world.color = (0.0, 0.0, 0.0)
    for node in (world.node_tree.nodes if world.node_tree else ()):
        if node.type == "BACKGROUND":
            node.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    scene.world = world
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.exr_codec = "ZIP"
    scene.render.film_transparent = False
    return scene


def _card(name, material, size=1.6, location=(0, 0, 2.5)):
    """A square card with UVs (0, 0) .. (1, 1). Its shadow falls mostly beside it as the camera
    sees it (the comparison leaves out the pixels where the camera sees the card: there Cycles
    shows the card, or the ground through its holes)."""
    card = sstest.add_plane(name, size, location)
    uv = card.data.uv_layers.new(name="UVMap")
    corners = {0: (0, 0), 1: (1, 0), 2: (1, 1), 3: (0, 1)}
    for loop in card.data.loops:
        uv.data[loop.index].uv = corners[loop.vertex_index]
    card.data.materials.append(material)
    return card


def _card_pixels(scene, card):
    """The pixels where the camera sees the card's square, grown by one."""
    h = card.dimensions.x / 2.0
    x, y, z = card.location
    corners = [sstest.pixel_of(scene, (x + sx * h, y + sy * h, z)) for sx in (-1, 1) for sy in (-1, 1)]
    rows, cols = [r for r, _ in corners], [c for _, c in corners]
    out = np.zeros((H, W), bool)
    out[max(min(rows) - 1, 0):max(rows) + 2, max(min(cols) - 1, 0):max(cols) + 2] = True
    return out


def _leaf_image():
    """A leaf-like alpha: an ellipse with a vein-shaped slit and holes, in a float image."""
    image = bpy.data.images.new("leaf", TEXTURE, TEXTURE, alpha=True, float_buffer=True)
    image.alpha_mode = "STRAIGHT"
    y, x = np.mgrid[0:TEXTURE, 0:TEXTURE]
    u, v = (x + 0.5) / TEXTURE - 0.5, (y + 0.5) / TEXTURE - 0.5
    inside = (u / 0.45) ** 2 + (v / 0.3) ** 2 < 1.0
    slit = np.abs(v - 0.15 * np.sin(6.0 * u)) < 0.03
    holes = ((u - 0.2) ** 2 + (v + 0.1) ** 2 < 0.01) | ((u + 0.22) ** 2 + (v - 0.08) ** 2 < 0.006)
    alpha = (inside & ~slit & ~holes).astype(np.float32)
    pixels = np.ones((TEXTURE, TEXTURE, 4), np.float32)
    pixels[..., 3] = alpha
    image.pixels.foreach_set(pixels.reshape(-1))
    image.update()
    return image, alpha


def _leaf_material(image):
    material = bpy.data.materials.new("LeafCut")
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    principled = next(n for n in nodes if n.type == "BSDF_PRINCIPLED")
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = image
    texture.interpolation = "Closest"
    texture.extension = "CLIP"
    links.new(texture.outputs["Alpha"], principled.inputs["Alpha"])
    return material


def _half_material():
    material = bpy.data.materials.new("HalfTransparent")
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    principled = next(n for n in nodes if n.type == "BSDF_PRINCIPLED")
    output = next(n for n in nodes if n.type == "OUTPUT_MATERIAL")
    transparent = nodes.new("ShaderNodeBsdfTransparent")
    mix = nodes.new("ShaderNodeMixShader")
    mix.inputs["Fac"].default_value = 0.5
    links.new(principled.outputs[0], mix.inputs[1])
    links.new(transparent.outputs[0], mix.inputs[2])
    links.new(mix.outputs[0], output.inputs["Surface"])
    return material


def _cycles_ratio(scene, card, folder):
    """Cycles' shadow ratio on the ground: the render with the card over the render without."""
    def render(name):
        scene.render.filepath = os.path.join(folder, name)
        bpy.ops.render.render(write_still=True)
        return sstest.exr_rgb(scene.render.filepath + ".exr").mean(axis=2)
    scene.cycles.samples = CYCLES_SAMPLES
    shadowed = render("with_" + card.name)
    card.hide_render = True
    lit = render("without_" + card.name)
    card.hide_render = False
    seen = (lit > 0.02 * lit.max()) & ~_card_pixels(scene, card)  # the ground the light reaches
    return np.where(seen, shadowed / np.maximum(lit, 1e-12), 1.0), seen


def _final_pass(scene):
    result = ss.api.render_passes(scene)
    sstest.check(len(result) == 1, "one pass: %s" % sorted(result))
    (light, method), v = next(iter(result.items()))
    sstest.check(light == "Key", "the Key light's pass")
    return v, method


def _compare(name, scene, card, folder, bound):
    truth, seen = _cycles_ratio(scene, card, folder)
    v, method = _final_pass(scene)
    rmse = float(np.sqrt(np.mean((v - truth)[seen] ** 2)))
    print("   %s: final pass (%s) RMSE %.4f vs Cycles over %d pixels; mean V %.3f, Cycles %.3f"
          % (name, method, rmse, seen.sum(), v[seen].mean(), truth[seen].mean()))
    sstest.check(rmse <= bound, "%s: RMSE %.4f vs Cycles (bound %.3f)" % (name, rmse, bound))
    return np.where(seen, truth, 1.0), np.where(seen, v, 1.0)


def test_cut_out_card_matches_cycles():
    folder = sstest.tempdir("see-through-leaf")
    scene = _scene()
    image, alpha = _leaf_image()
    card = _card("Leaf", _leaf_material(image))
    truth, v = _compare("leaf cut-out", scene, card, folder, 0.015)
    # The cut-out matters: light through the slit and the holes, where an opaque card is dark.
    under = truth < 0.05
    sstest.check(under.sum() > 10, "the leaf's umbra covers pixels: %d" % under.sum())
    through = (truth > 0.5) & (truth < 0.999)  # light through the cut-outs inside the shadow
    sstest.check(through.sum() > 20, "Cycles lets light through the cut-outs: %d pixels" % through.sum())
    sstest.check(ss.api.render_passes.last_problems == [], "no report: %s" % ss.api.render_passes.last_problems)


def test_half_transparent_card_matches_cycles():
    folder = sstest.tempdir("see-through-half")
    scene = _scene()
    card = _card("Half", _half_material())
    truth, v = _compare("50 % card", scene, card, folder, 0.015)
    covered = np.abs(truth - 0.5) < 0.01
    sstest.check(covered.sum() > 100, "Cycles gives 0.5 under the card: %d pixels" % covered.sum())
    sstest.close(float(v[covered].mean()), 0.5, 0.01, "V under the 50 % card")


# The stripes card: the camera looks straight down through its holes at the ground, which the
# light, to one side, shadows through the card's opaque stripes.
STRIPES_W, STRIPES_H = 128, 96
STRIPES_CARD = 1.6  # size; at z = 2.5, UVs (0, 0) .. (1, 1)
STRIPES_LENS = 40.0
# Measured in Blender 3.4 against Cycles at 256 samples over the pixels through the holes (476,
# Cycles' mean V 0.029): the final pass 0.0047 (0.975 where the camera sees the lit card there);
# the GL passes shadow_map, penumbra_map and dbuffer 0.097 (hard or outline-grown edges in the
# stripes' shadow), pcss 0.012, occlusion_textures 0.027.
THROUGH_HOLES_RMSE = 0.015
THROUGH_HOLES_GL_RMSE = {"shadow_map": 0.15, "pcss": 0.04, "occlusion_textures": 0.06, "penumbra_map": 0.15,
                         "dbuffer": 0.15}


def _stripes_image():
    """Four stripes across u: opaque, hole, opaque, hole (8 texels each)."""
    image = bpy.data.images.new("leaf_stripes", TEXTURE, TEXTURE, alpha=True, float_buffer=True)
    image.alpha_mode = "STRAIGHT"
    alpha = np.zeros((TEXTURE, TEXTURE), np.float32)
    alpha[:, (np.arange(TEXTURE) // 8) % 2 == 0] = 1.0
    pixels = np.ones((TEXTURE, TEXTURE, 4), np.float32)
    pixels[..., 3] = alpha
    image.pixels.foreach_set(pixels.reshape(-1))
    image.update()
    return image, alpha


def _through_holes(scene, card, alpha, margin=1.0):
    """The pixels whose camera ray crosses the card inside a hole, `margin` pixels away from any
    edge of it (the camera looks straight down: a pixel's footprint on the card is a square)."""
    camera = scene.camera
    depth = camera.location.z - card.location.z
    # Sensor fit AUTO, wider than high: the width spans 36 mm at the lens.
    per_pixel = depth * 36.0 / STRIPES_LENS / STRIPES_W
    h = STRIPES_CARD / 2.0
    rows, cols = np.mgrid[0:STRIPES_H, 0:STRIPES_W]
    out = np.ones((STRIPES_H, STRIPES_W), bool)
    for dr in (-margin, 0.0, margin):
        for dc in (-margin, 0.0, margin):
            x = camera.location.x + (cols + 0.5 + dc - STRIPES_W / 2.0) * per_pixel
            y = camera.location.y + (STRIPES_H / 2.0 - rows - 0.5 - dr) * per_pixel
            u, v = (x - card.location.x + h) / (2 * h), (y - card.location.y + h) / (2 * h)
            inside = (u >= 0) & (u < 1) & (v >= 0) & (v < 1)
            i = np.clip((u * TEXTURE).astype(int), 0, TEXTURE - 1)
            j = np.clip((v * TEXTURE).astype(int), 0, TEXTURE - 1)
            out &= inside & (alpha[j, i] == 0.0)
    # The mapping is Blender's: a point of the card maps back to its own pixel.
    bpy.context.view_layer.update()  # the objects' matrices
    r, c = np.argwhere(out)[len(np.argwhere(out)) // 2]
    x = camera.location.x + (c + 0.5 - STRIPES_W / 2.0) * per_pixel
    y = camera.location.y + (STRIPES_H / 2.0 - r - 0.5) * per_pixel
    back = sstest.pixel_of(scene, (x, y, card.location.z))
    sstest.check(back == (r, c), "pixel (%d, %d) maps back: %s" % (r, c, back))
    return out


def test_camera_sees_the_ground_through_cut_out_holes_as_cycles_does():
    scene = _scene()
    scene.render.resolution_x, scene.render.resolution_y = STRIPES_W, STRIPES_H
    key = scene.objects["Key"]
    key.location = (-0.85, 0.0, 6.0)
    key.data.size = 0.2
    scene.camera.data.lens = STRIPES_LENS
    image, alpha = _stripes_image()
    card = _card("Stripes", _leaf_material(image), size=STRIPES_CARD)
    holes = _through_holes(scene, card, alpha)
    truth, lit = cycles_truth.shadow_ratio(scene, key)
    where = holes & lit
    sstest.check(where.sum() > 100, "pixels through the holes: %d" % where.sum())
    # Through the holes Cycles shows the ground in the opaque stripes' shadow (the card itself,
    # with nothing above it, is lit): a pass that sees the card there is far off.
    sstest.check(float(truth[where].mean()) < 0.2, "Cycles' ground through the holes: mean %.3f"
                 % truth[where].mean())
    final = _final_pass(scene)[0]
    errors = {"final": cycles_truth.rmse(final, truth, where)}
    gl = ss.api.render_passes(scene, methods=list(THROUGH_HOLES_GL_RMSE))
    for method in THROUGH_HOLES_GL_RMSE:
        errors[method] = cycles_truth.rmse(gl[("Key", method)], truth, where)
    print("   through the holes (%d pixels), RMSE vs Cycles: %s; mean V %.3f, Cycles %.3f"
          % (where.sum(), ", ".join("%s %.4f" % kv for kv in errors.items()), final[where].mean(),
             truth[where].mean()))
    sstest.check(errors["final"] <= THROUGH_HOLES_RMSE, "final pass through the holes: RMSE %.4f > %.3f"
                 % (errors["final"], THROUGH_HOLES_RMSE))
    for method, bound in THROUGH_HOLES_GL_RMSE.items():
        sstest.check(errors[method] <= bound,
                     "%s through the holes: RMSE %.4f > %.3f" % (method, errors[method], bound))


def test_a_card_that_casts_no_shadow_keeps_its_holes_for_the_camera():
    scene = _scene()
    image, _ = _leaf_image()
    card = _card("Leaf", _leaf_material(image))
    card.visible_shadow = False
    exported = ss.scene_export.export(bpy.context.evaluated_depsgraph_get(), scene)
    leaf = next(m for m in exported.meshes if m["name"] == "Leaf")
    sstest.check(not leaf["flags"] & ss.native.MESH_CAST, "the card casts nothing: flags %d" % leaf["flags"])
    sstest.check(leaf["alpha"] is not None, "its alpha is exported: the camera sees through its holes")


def test_unreadable_material_is_reported_once():
    scene = _scene()
    material = bpy.data.materials.new("Procedural")
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    principled = next(n for n in nodes if n.type == "BSDF_PRINCIPLED")
    noise = nodes.new("ShaderNodeTexNoise")
    links.new(noise.outputs["Fac"], principled.inputs["Alpha"])
    _card("A", material, location=(-2, 0, 2.5), size=1.0)
    _card("B", material, location=(2, 1, 2.5), size=1.0)
    graph = bpy.context.evaluated_depsgraph_get()
    exported = ss.scene_export.export(graph, scene)
    lines = [p for p in exported.problems if "opaque" in p]
    sstest.check(len(lines) == 1, "one line: %s" % exported.problems)
    sstest.check("'Procedural'" in lines[0] and "TEX_NOISE" in lines[0], lines[0])
    sstest.check(all(m.get("alpha") is None for m in exported.meshes), "treated opaque")


def test_eevee_shadow_settings_are_read_as_blender_means_them():
    scene = _scene()
    image, _ = _leaf_image()
    material = _leaf_material(image)
    _card("Leaf", material)
    graph = bpy.context.evaluated_depsgraph_get()
    cycles = ss.scene_export.export(graph, scene)
    leaf = next(m for m in cycles.meshes if m["name"] == "Leaf")
    sstest.check(leaf["alpha"] is not None, "Cycles honours the alpha")
    scene.render.engine = ss.compat.eevee_engine_id(scene.render)
    if hasattr(material, "use_transparent_shadow"):  # 4.2+
        material.use_transparent_shadow = False
        opaque = ss.scene_export.export(bpy.context.evaluated_depsgraph_get(), scene)
        material.use_transparent_shadow = True
    else:
        material.shadow_method = "OPAQUE"
        opaque = ss.scene_export.export(bpy.context.evaluated_depsgraph_get(), scene)
        material.shadow_method = "CLIP"
    sstest.check(next(m for m in opaque.meshes if m["name"] == "Leaf")["alpha"] is None,
                 "EEVEE's opaque shadows ignore the alpha")
    see_through = ss.scene_export.export(bpy.context.evaluated_depsgraph_get(), scene)
    sstest.check(next(m for m in see_through.meshes if m["name"] == "Leaf")["alpha"] is not None,
                 "EEVEE's clipped/transparent shadows honour it")


sstest.run(globals())
