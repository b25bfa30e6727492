# Frame ranges as a farm writes them: "1-12", "3, 5-7", Blender's "1..4", or frame numbers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Pure string work (no bpy), so it tests without Blender. The notation is Flamenco's (its
frameChunker reads and writes it): comma-separated frames and A-B ranges, A..B also accepted."""
import re

_PART = re.compile(r"^\s*(\d+)\s*(?:(?:-|\.\.)\s*(\d+)\s*)?$")


def parse(frames):
    """Sorted unique frame numbers of a range string or an iterable of ints; ValueError naming
    the part that is not a frame or a range."""
    if not isinstance(frames, str):
        found = sorted({int(f) for f in frames})
    else:
        found = set()
        for part in frames.split(","):
            match = _PART.match(part)
            if not match:
                raise ValueError("frame range '%s': '%s' is not a frame or a range A-B" % (frames, part.strip()))
            start = int(match.group(1))
            end = start if match.group(2) is None else int(match.group(2))
            if end < start:
                raise ValueError("frame range '%s': '%s' ends before it starts" % (frames, part.strip()))
            found.update(range(start, end + 1))
        found = sorted(found)
    if not found:
        raise ValueError("frame range %r: no frames" % (frames,))
    return found
