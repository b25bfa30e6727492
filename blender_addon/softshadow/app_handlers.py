# How the add-on's modules hook their functions into bpy.app.handlers: each once, and all of it gone on unregister.
# SPDX-License-Identifier: GPL-3.0-or-later
import bpy


def attach(pairs):
    """Appends each (handler list name, function) unless it is there already (a reload)."""
    for name, fn in pairs:
        handlers = getattr(bpy.app.handlers, name)
        if fn not in handlers:
            handlers.append(fn)


def detach(pairs):
    """Removes every copy of each (handler list name, function)."""
    for name, fn in pairs:
        handlers = getattr(bpy.app.handlers, name)
        while fn in handlers:
            handlers.remove(fn)
