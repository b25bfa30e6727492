# How a Blender render becomes a visibility pass: Diffuse Direct read back, V = shadowed / unshadowed.
# SPDX-License-Identifier: GPL-3.0-or-later
# Shared by bench/scenes.py (Blender 3.4: EEVEE, Cycles) and bench/eevee_next.py (Blender 5.x:
# EEVEE Next), so both engines' V is computed the same way. Needs only bpy and numpy; the caller
# routes Diffuse Direct to the render result through its version's compositor.
import os
import time

import bpy
import numpy as np


def diffuse_direct(scene, tmp_path):
    """Renders, returns (seconds, float32 HxW Diffuse Direct luminance, row 0 = top). The pass
    goes Render Layers -> compositor output -> Render Result -> EXR -> pixels (the Viewer image is
    not refreshed in --background)."""
    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=False)
    seconds = time.perf_counter() - t0
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_depth = "32"
    settings.exr_codec = "ZIP"
    bpy.data.images["Render Result"].save_render(tmp_path, scene=scene)
    img = bpy.data.images.load(tmp_path)
    w, h = img.size
    px = np.empty(w * h * img.channels, dtype=np.float32)
    img.pixels.foreach_get(px)
    px = px.reshape(h, w, img.channels)[::-1]  # Blender's rows start at the bottom
    bpy.data.images.remove(img)
    os.remove(tmp_path)
    return seconds, px[:, :, :3].mean(axis=2)


def visibility(shadowed, unshadowed):
    """The contract: V = E(shadows) / E(no shadows), 1 and mask 0 where the light does not reach."""
    reach = unshadowed > 1e-6 * max(float(unshadowed.max()), 1e-30)
    v = np.ones_like(shadowed)
    v[reach] = np.clip(shadowed[reach] / unshadowed[reach], 0.0, 1.0)
    return v, reach.astype(np.float32)


def save_rg(path, v, mask):
    """R = V, G = mask as a float EXR (Blender's own image saving; row 0 = top in `v`)."""
    h, w = v.shape
    img = bpy.data.images.new("bench_out", w, h, alpha=True, float_buffer=True)
    px = np.zeros((h, w, 4), dtype=np.float32)
    px[:, :, 0] = v
    px[:, :, 1] = mask
    px[:, :, 3] = 1.0
    img.pixels.foreach_set(px[::-1].ravel())
    img.filepath_raw = path
    img.file_format = "OPEN_EXR"
    settings = bpy.context.scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_depth = "32"
    settings.exr_codec = "ZIP"
    img.save_render(path, scene=bpy.context.scene)
    bpy.data.images.remove(img)
