"""Making text from a submission inert before it is shown."""

from __future__ import annotations

import re

# C0 controls but tab and newline, DEL, C1 controls (ESC and CSI start terminal
# commands), the bidirectional marks and overrides that make text read other than it is,
# invisible operators (word joiner, byte-order mark), and what only hides text or tells names
# apart unseen: the soft hyphen, zero-width space, the blank fillers of Hangul and Mongolian,
# variation selectors and the tag characters (an instruction spelt invisibly). Zero-width
# joiners stay: names in Persian or Hindi need them to be written right.
_CONTROL = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f\u00ad\u061c\u115f\u1160\u180e\u200b\u200e\u200f"
                      "\u202a-\u202e\u2060-\u2064\u2066-\u2069\u3164\ufe00-\ufe0f\ufeff\uffa0"
                      "\U000e0000-\U000e007f\U000e0100-\U000e01ef]")
# Unicode's line and paragraph separators: a line break like any other, shown as one.
_SEPARATOR = re.compile("[\u2028\u2029]")


def printable(text) -> str:
    """``text`` with every control character removed (newlines and tabs kept).

    >>> printable("ok\\x1b[2J\\x1b[H73/73\\r\\n")
    'ok[2J[H73/73\\n'
    """
    return _CONTROL.sub("", _SEPARATOR.sub("\n", str(text).replace("\r\n", "\n")))


_SURROGATE = re.compile("[\udc80-\udcff]")


def shown(name, limit: int = 160) -> str:
    """A name from an upload, safe to store and show: the bytes that are not UTF-8 and
    every control character written as escapes (``\\xff``), at most ``limit`` characters.

    >>> shown("ali\\x1bce\\udcff.py")
    'ali\\\\x1bce\\\\xff.py'
    """
    text = _SURROGATE.sub(lambda m: f"\\x{ord(m.group()) - 0xDC00:02x}", str(name))
    text = re.sub("[\x00-\x1f\u2028\u2029]|" + _CONTROL.pattern, lambda m: f"\\x{ord(m.group()):02x}"
                  if ord(m.group()) < 256 else f"\\u{ord(m.group()):04x}" if ord(m.group()) < 0x10000
                  else f"\\U{ord(m.group()):08x}", text)
    return text if len(text) <= limit else text[:limit - 1] + "…"


def one_line(text, limit: int = 100) -> str:
    """``text`` as one short line for a name: controls removed, whitespace runs made one space,
    undecodable bytes replaced, at most ``limit`` characters."""
    text = _SURROGATE.sub("\ufffd", str(text))
    text = " ".join(printable(text).split())
    return text if len(text) <= limit else text[:limit - 1] + "…"
