"""Making text from a submission inert before it is shown."""

from __future__ import annotations

import re

# C0 controls but tab and newline, DEL, C1 controls (ESC and CSI start terminal
# commands), and the bidirectional overrides that make text read other than it is.
_CONTROL = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f\u200e\u200f\u202a-\u202e\u2066-\u2069]")


def printable(text) -> str:
    """``text`` with every control character removed (newlines and tabs kept).

    >>> printable("ok\\x1b[2J\\x1b[H73/73\\r\\n")
    'ok[2J[H73/73\\n'
    """
    return _CONTROL.sub("", str(text).replace("\r\n", "\n"))
