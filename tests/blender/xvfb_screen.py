# How the windowed tests see what Blender drew: Xvfb's own framebuffer file, not Blender's screenshot.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Blender 4.x and 5.x under Xvfb on llvmpipe save black pictures from screen.screenshot and
screenshot_area although the window shows the right thing; Xvfb's `-fbdir` keeps the screen in
an XWD file that any process can read. A child Blender copies that file at the moment it wants
(`snapshot`); the parent reads it (`read`) and crops window areas (`crop`). Blender's window
fills the screen at (0, 0) under Xvfb without a window manager."""
import os
import shutil
import struct

WIDTH, HEIGHT = 1280, 800


def command(fbdir):
    """The xvfb-run prefix for a windowed Blender whose screen is kept in `fbdir`."""
    return ["xvfb-run", "-a", "-s", "-screen 0 %dx%dx24 -fbdir %s" % (WIDTH, HEIGHT, fbdir)]


def snapshot(fbdir, path):
    """Copies the screen as it is now (run in the windowed Blender, after a redraw)."""
    shutil.copyfile(os.path.join(fbdir, "Xvfb_screen0"), path)


def read(path):
    """The screen of an XWD snapshot as float RGB in [0, 1], shape (height, width, 3), row 0 = top."""
    import numpy as np
    with open(path, "rb") as f:
        data = f.read()
    fields = struct.unpack(">25I", data[:100])
    header, width, height, bits, line = fields[0], fields[4], fields[5], fields[11], fields[12]
    if bits != 32:
        raise ValueError("%s: %d bits per pixel, expected 32" % (path, bits))
    start = header + fields[19] * 12  # the colour map follows the header
    pixels = np.frombuffer(data, np.uint8, line * height, start).reshape(height, line // 4, 4)[:, :width]
    masks = fields[14:17]  # red, green, blue masks of the little-endian 32-bit pixels
    order = [{0xff0000: 2, 0xff00: 1, 0xff: 0}[m] for m in masks]
    return pixels[..., order].astype(np.float32) / 255.0


def crop(screen, x, y, width, height):
    """A window rectangle (Blender's coordinates: x, y from the bottom left) of a screen."""
    rows = screen.shape[0]
    return screen[rows - (y + height):rows - y, x:x + width]
