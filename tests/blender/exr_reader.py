# How the Blender tests read our EXRs without OpenImageIO: a small reader of scanline OpenEXR files.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Reads single-part scanline EXRs with NONE, ZIPS or ZIP compression (what the library writes),
written from the OpenEXR file layout document: an independent check of the library's writer that
needs nothing but zlib and numpy, so it runs in any Blender's Python (the version matrix too)."""
import struct
import zlib

import numpy as np

_PIXEL_TYPES = {0: np.uint32, 1: np.float16, 2: np.float32}
_LINES_PER_CHUNK = {0: 1, 2: 1, 3: 16}  # NONE, ZIPS, ZIP


class ExrError(ValueError):
    pass


def _cstring(data, at):
    end = data.index(b"\0", at)
    return data[at:end].decode("utf-8"), end + 1


def _header(data):
    if data[:4] != struct.pack("<i", 20000630):
        raise ExrError("not an OpenEXR file")
    flags = struct.unpack_from("<i", data, 4)[0]
    if flags & 0x1A00:  # tiled (0x200), deep (0x800) or multi-part (0x1000)
        raise ExrError("only single-part scanline files are read (flags 0x%x)" % flags)
    at, attributes = 8, {}
    while data[at] != 0:
        name, at = _cstring(data, at)
        kind, at = _cstring(data, at)
        size = struct.unpack_from("<i", data, at)[0]
        attributes[name] = (kind, data[at + 4:at + 4 + size])
        at += 4 + size
    return attributes, at + 1


def _channels(raw):
    channels, at = [], 0
    while raw[at] != 0:
        name, at = _cstring(raw, at)
        pixel_type, _linear, xs, ys = struct.unpack_from("<iB3xii", raw, at)
        if (xs, ys) != (1, 1):
            raise ExrError("channel %s is subsampled" % name)
        channels.append((name, _PIXEL_TYPES[pixel_type]))
        at += 16
    return channels


def _unzip(chunk, raw_size):
    if len(chunk) == raw_size:  # stored as is when compression would not make it smaller
        return chunk
    d = np.frombuffer(zlib.decompress(chunk), np.uint8).astype(np.int64)
    d[1:] -= 128  # the byte predictor stored t[i] - t[i-1] + 128: a running sum undoes it
    t = (np.cumsum(d) % 256).astype(np.uint8)
    half = (len(t) + 1) // 2
    out = np.empty_like(t)
    out[0::2] = t[:half]
    out[1::2] = t[half:]
    return out.tobytes()


def read(path):
    """{channel name: (H, W) array, row 0 = top} of every channel in the file."""
    with open(path, "rb") as f:
        data = f.read()
    attributes, at = _header(data)
    channels = _channels(attributes["channels"][1])
    compression = attributes["compression"][1][0]
    if compression not in _LINES_PER_CHUNK:
        raise ExrError("compression %d is not read here" % compression)
    x0, y0, x1, y1 = struct.unpack("<4i", attributes["dataWindow"][1])
    w, h = x1 - x0 + 1, y1 - y0 + 1
    lines = _LINES_PER_CHUNK[compression]
    chunks = (h + lines - 1) // lines
    offsets = struct.unpack_from("<%dQ" % chunks, data, at)
    out = {name: np.empty((h, w), dtype) for name, dtype in channels}
    for offset in offsets:
        y, size = struct.unpack_from("<ii", data, offset)
        rows = min(lines, y1 - y + 1)
        raw_size = rows * w * sum(np.dtype(t).itemsize for _, t in channels)
        chunk = data[offset + 8:offset + 8 + size]
        raw = chunk if compression == 0 else _unzip(chunk, raw_size)
        if len(raw) != raw_size:
            raise ExrError("chunk at line %d holds %d bytes, expected %d" % (y, len(raw), raw_size))
        at = 0
        for r in range(rows):
            for name, dtype in channels:
                n = w * np.dtype(dtype).itemsize
                out[name][y - y0 + r] = np.frombuffer(raw[at:at + n], dtype)
                at += n
    return out


def attributes(path):
    """The header's attributes as {name: (type name, raw bytes)}."""
    with open(path, "rb") as f:
        return _header(f.read(1 << 20))[0]
