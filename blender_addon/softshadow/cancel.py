# How a render's pass computation is stopped from outside it: a file loaded during F12.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Blender waits for a running render job before it loads a file, and the job waits for its
render_pre handler, which waits for the library. load_pre comes first: request() cancels the
library's renders on the shared context (ss_context_cancel_renders, which its loops poll) and
makes `progress` answer "stop" from then on, so the handler returns within a second. A request
lasts until the next render starts (render_init) or the loaded file is in (load_post).

Esc and quitting cannot reach here: Esc sets Blender's G.is_break, which no Python API shows
(bpy.app.is_job_running stays true until the handler returns); the interface that a render with
these passes locks runs no Python modal handler, and the timers it still runs see nothing of the
Esc; quitting waits for the render job before any Python runs (docs/reliability.md, the evidence)."""
import threading

import bpy

from . import app_handlers, native

_requested = threading.Event()
_reason = {"text": ""}


def request(reason):
    """Stops the pass computation in progress (and any started before the next render)."""
    _reason["text"] = reason
    _requested.set()
    native.cancel_renders()  # the library's CPU loops poll this between items


def reset():
    _reason["text"] = ""
    _requested.clear()


def requested():
    """The reason a stop was requested, or ''."""
    return _reason["text"] if _requested.is_set() else ""


def progress(_fraction, _stage):
    """A native.Scene.render progress callback: True (stop) once a stop was requested."""
    return _requested.is_set()


@bpy.app.handlers.persistent
def _on_load_pre(*_args):
    request("a file is being loaded")


@bpy.app.handlers.persistent
def _on_load_post(*_args):
    reset()


@bpy.app.handlers.persistent
def _on_render_init(*_args):
    reset()


_HANDLERS = (("load_pre", _on_load_pre), ("load_post", _on_load_post), ("render_init", _on_render_init))


def register():
    app_handlers.attach(_HANDLERS)


def unregister():
    app_handlers.detach(_HANDLERS)
