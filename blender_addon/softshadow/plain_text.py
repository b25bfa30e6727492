# SPDX-License-Identifier: GPL-3.0-or-later
"""Messages as they reach the console, the status bar and the panels: object, light and file
names are the user's, and a control or bidirectional formatting character in one (U+202E, say)
would reorder or hide the rest of the line. Such characters are shown as escapes (\\u202E), the
way the library's own messages name them; every other character is kept."""

import sys

# The C0 and C1 controls and the bidirectional formatting characters (Unicode's Bidi_Control):
# the same set the library refuses in names on the command line (native/src/core/names.cpp).
_BIDI = {0x061C, 0x200E, 0x200F, 0x202A, 0x202B, 0x202C, 0x202D, 0x202E, 0x2066, 0x2067, 0x2068, 0x2069}


def _hidden(code):
    return code < 0x20 or 0x7F <= code <= 0x9F or code in _BIDI


def plain(text):
    """`text` with each control and bidirectional formatting character written as \\uXXXX."""
    text = str(text)
    if not any(_hidden(ord(c)) for c in text):
        return text
    return "".join("\\u%04X" % ord(c) if _hidden(ord(c)) else c for c in text)


def log(message, file=None):
    """Prints one add-on line ("softshadow: ...") to stdout, or `file`."""
    print("softshadow: " + plain(message), file=file or sys.stdout)
