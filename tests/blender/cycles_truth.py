# What Cycles itself says a light's shadow ratio is: its render with the light's shadow over its
# render without it, for the tests that hold the passes to Blender's own truth.
# SPDX-License-Identifier: GPL-3.0-or-later
"""One light renders (every other is hidden for the render), the world is black and rays do not
bounce, so each pixel is that light's direct diffuse light on the surface the camera sees; the
shadowed render divided by the unshadowed one is the fraction of the light the surface sees, the
visibility V the passes stand for. Both renders use the same seed, so their noise largely cancels
in the ratio. The pixel filter is narrowed to the pixel's centre, where the passes sample."""
import os

import numpy as np

import sstest

bpy = sstest.bpy

# Below this the unshadowed render is too dark to divide by (background, faces turned away).
LIT_MIN = 1e-3


def _render_exr(scene, path):
    scene.render.filepath = path
    result = bpy.ops.render.render(write_still=True)
    sstest.check(result == {"FINISHED"}, "Cycles render: %s" % result)
    return sstest.exr_rgb(path).mean(axis=2)


def shadow_ratio(scene, light, samples=256, layer=""):
    """(ratio, lit) for `light` (an object) as Cycles renders the scene's camera (of view layer
    `layer`, default the first that renders): ratio per pixel (row 0 = top), lit where it is
    defined. The scene's settings are put back."""
    compat = sstest.addon().compat
    render, cycles = scene.render, scene.cycles
    others = [o for o in scene.objects if o.type == "LIGHT" and o != light and not o.hide_render]
    saved = (render.engine, render.filepath, render.image_settings.file_format,
             render.image_settings.color_depth, render.image_settings.exr_codec, render.use_compositing,
             render.use_sequencer, scene.world, cycles.samples, cycles.use_denoising, cycles.max_bounces,
             cycles.seed, cycles.filter_width, cycles.device, compat.renderer_shadow(light.data))
    folder = sstest.tempdir("cycles")
    # Only `layer` renders (its Use for Rendering alone on): the saved image is that layer's.
    uses = {l.name: l.use for l in scene.view_layers}
    try:
        for view_layer in scene.view_layers:
            view_layer.use = view_layer.name == layer if layer else uses[view_layer.name]
        render.engine = "CYCLES"
        render.image_settings.file_format = "OPEN_EXR"
        render.image_settings.color_depth = "32"
        render.image_settings.exr_codec = "ZIP"
        render.use_compositing = False
        render.use_sequencer = False
        scene.world = None
        cycles.device = "CPU"
        cycles.samples = samples
        cycles.use_denoising = False
        cycles.max_bounces = 0
        cycles.seed = 1
        cycles.filter_width = 0.01
        for other in others:
            other.hide_render = True
        compat.set_renderer_shadow(light.data, True)
        shadowed = _render_exr(scene, os.path.join(folder, "shadowed.exr"))
        compat.set_renderer_shadow(light.data, False)
        unshadowed = _render_exr(scene, os.path.join(folder, "unshadowed.exr"))
    finally:
        for view_layer in scene.view_layers:
            view_layer.use = uses[view_layer.name]
        for other in others:
            other.hide_render = False
        (render.engine, render.filepath, render.image_settings.file_format, render.image_settings.color_depth,
         render.image_settings.exr_codec, render.use_compositing, render.use_sequencer, scene.world,
         cycles.samples, cycles.use_denoising, cycles.max_bounces, cycles.seed, cycles.filter_width,
         cycles.device, shadow) = saved
        compat.set_renderer_shadow(light.data, shadow)
    lit = unshadowed > LIT_MIN
    ratio = np.where(lit, shadowed / np.maximum(unshadowed, LIT_MIN), 1.0)
    return np.clip(ratio, 0.0, 1.0), lit


def rmse(a, b, where):
    """Root mean square difference of two images over the pixels `where` is true."""
    sstest.check(a.shape == b.shape, "shapes %s and %s" % (a.shape, b.shape))
    sstest.check(where.any(), "no pixel to compare")
    return float(np.sqrt(np.mean((a[where] - b[where]) ** 2)))
