# How a pass file's path is made ready before a view layer renders (old file gone, folder made, writable).
# SPDX-License-Identifier: GPL-3.0-or-later
"""Each problem is a native.SoftShadowError worded as an output error ("cannot write the pass
file PATH: REASON"), found before any render time is spent."""
import os

from . import native


def _error(path, reason):
    return native.SoftShadowError(native.SS_ERROR_IO, "cannot write the pass file %s: %s" % (path, reason))


def remove_old(path):
    """Removes an earlier run's file at `path` (none there is fine); a folder there, or a
    read-only mount, is an output error."""
    try:
        os.remove(path)
    except (FileNotFoundError, NotADirectoryError):
        pass
    except OSError as exc:
        raise _error(path, exc.strerror or exc)


def prepare(path):
    """remove_old, then the folder made and the path checked as the library will write it
    (ss_check_output_path: a regular file or a new name in a folder this process may write)."""
    remove_old(path)
    folder = os.path.dirname(os.path.abspath(path))
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError as exc:
        raise _error(path, "its folder %s cannot be made (%s)" % (folder, exc.strerror or exc))
    try:
        native.check_output_path(path)
    except native.SoftShadowError as exc:
        reason = str(exc)
        said = "cannot write '%s': " % path
        raise _error(path, reason[len(said):] if reason.startswith(said) else reason)
