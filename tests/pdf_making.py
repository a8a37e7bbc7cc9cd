"""Small PDFs written by hand for the tests (no binary fixtures): text lines per page,
grey pictures, and the hostile shapes a student could hand in."""

from __future__ import annotations

import zlib

import numpy as np


def _escaped(line: str) -> str:
    return line.replace("\\", "\\\\").replace("(", "\\(").replace(")", "\\)")


def pdf(pages: list[list[str]], pictures: dict[int, list[np.ndarray]] | None = None,
        raw_objects: list[bytes] | None = None, trailer_extra: bytes = b"") -> bytes:
    """A PDF whose page ``i`` shows the lines ``pages[i]`` (Helvetica, top to bottom) and the
    grey ``uint8`` pictures ``pictures[i]`` (H x W) below them. ``raw_objects``: more
    objects, numbered after these, written as given (for hostile files)."""
    pictures = pictures or {}
    objects: list[bytes] = [b"", b"", b"<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica >>"]
    kids = []
    for number, lines in enumerate(pages):
        stream = ["BT /F1 12 Tf 14 TL 72 760 Td"] + [f"({_escaped(line)}) Tj T*" for line in lines] + ["ET"]
        names = []
        for k, image in enumerate(pictures.get(number, [])):
            height, width = image.shape
            data = zlib.compress(np.ascontiguousarray(image, dtype=np.uint8).tobytes())
            objects.append(b"<< /Type /XObject /Subtype /Image /Width %d /Height %d /ColorSpace /DeviceGray "
                           b"/BitsPerComponent 8 /Filter /FlateDecode /Length %d >>\nstream\n" % (width, height, len(data))
                           + data + b"\nendstream")
            names.append((f"Im{k}", len(objects)))
            stream.append(f"q {width} 0 0 {height} 72 {400 - 150 * k} cm /Im{k} Do Q")
        content = "\n".join(stream).encode("latin-1")
        objects.append(b"<< /Length %d >>\nstream\n" % len(content) + content + b"\nendstream")
        content_number = len(objects)
        xobjects = b" ".join(b"/%s %d 0 R" % (name.encode(), n) for name, n in names)
        objects.append(b"<< /Type /Page /Parent 2 0 R /MediaBox [0 0 612 792] /Contents %d 0 R "
                       b"/Resources << /Font << /F1 3 0 R >> /XObject << %s >> >> >>" % (content_number, xobjects))
        kids.append(len(objects))
    objects[0] = b"<< /Type /Catalog /Pages 2 0 R >>"
    objects[1] = b"<< /Type /Pages /Kids [%s] /Count %d >>" % (b" ".join(b"%d 0 R" % k for k in kids), len(kids))
    objects += raw_objects or []
    return assemble(objects, trailer_extra)


def assemble(objects: list[bytes], trailer_extra: bytes = b"") -> bytes:
    """Objects 1..n (object 1 the catalog) with a correct cross-reference table."""
    out, offsets = bytearray(b"%PDF-1.4\n%\xe2\xe3\xcf\xd3\n"), []
    for number, body in enumerate(objects, 1):
        offsets.append(len(out))
        out += b"%d 0 obj\n" % number + body + b"\nendobj\n"
    xref = len(out)
    out += b"xref\n0 %d\n0000000000 65535 f \n" % (len(objects) + 1)
    out += b"".join(b"%010d 00000 n \n" % offset for offset in offsets)
    out += b"trailer\n<< /Size %d /Root 1 0 R %s>>\nstartxref\n%d\n%%%%EOF\n" % (len(objects) + 1, trailer_extra, xref)
    return bytes(out)
