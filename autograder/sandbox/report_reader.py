"""Reading what a student's report holds -- a PDF's text and pictures, a notebook's images --
inside a sandbox worker, never in the grader's process.

This module is copied into a worker's submission folder (as :data:`MODULE`) and called
there through :class:`~.supervisor.Sandbox` (see :mod:`autograder.loading.pdf_report`):
a PDF or an image is input an attacker writes, and parsing it (pypdf, Pillow, zlib) is
where a decompression bomb, an endless object graph or a parser bug would strike. The
worker's limits (memory, CPU, wall clock) bound it; what comes back is plain data
(strings, numbers, small ``uint8`` arrays) through :mod:`.transport`, never pickle.

Every entry point returns, never raises for what the file holds: a fault is the
``"error"`` entry of its answer, one sentence ("it is encrypted ...").

Pictures come back as *thumbnails* (:func:`thumbnail`): the picture in grey, resized to
``THUMB x THUMB`` (128) with area averaging, ``uint8``; with the picture's own width and
height. The grader compares them with the figures the student's code made
(:mod:`autograder.instructor.review.provenance`), which it thumbnails the same way.

Imports: the standard library, NumPy, OpenCV, and (inside the functions) pypdf and
Pillow; nothing of the grader's.
"""

from __future__ import annotations

import io
import warnings

import numpy as np

MODULE = "ag_report_reader"      # its name in the worker's submission folder
THUMB = 128                      # a thumbnail's side, pixels (fine enough to tell a panel changed)
MIN_FIGURE_SIDE = 48             # a picture narrower or lower is an icon or a rule: not a figure
MAX_PAGES = 200                  # pages read; the rest is noted
MAX_TEXT_CHARS = 400_000         # characters of text kept over the whole PDF
MAX_PAGE_CHARS = 100_000         # characters kept of one page
MAX_IMAGES = 60                  # pictures thumbnailed per PDF (or per call of read_images)
MAX_IMAGE_PIXELS = 40_000_000    # a larger picture is not decoded (Pillow's bomb check at that size)


def thumbnail(image: np.ndarray) -> np.ndarray:
    """``image`` (H x W grey, H x W x 3 BGR/RGB or x 4 with alpha; any numeric dtype) as a
    ``THUMB x THUMB`` grey ``uint8`` picture: channels averaged (the order of the colours does
    not matter then), values scaled to 0..255 as ``uint8`` images are, resized by area.
    The aspect ratio is not kept here: it is compared apart (the width and height)."""
    if image.ndim == 3:
        image = image[..., :3].astype(np.float32).mean(axis=2)
    image = np.asarray(image, dtype=np.float32)
    if image.ndim != 2 or min(image.shape) < 1:
        raise ValueError(f"a picture must be 2-D or 3-D with pixels; got shape {image.shape}")
    import cv2

    # Shrunk by area averaging along each axis longer than THUMB, enlarged linearly along the others:
    # area "enlarging" repeats pixels, which shifts a small picture's thumbnail against a large one's.
    height, width = image.shape
    image = cv2.resize(image, (min(width, THUMB), min(height, THUMB)), interpolation=cv2.INTER_AREA)
    if image.shape != (THUMB, THUMB):
        image = cv2.resize(image, (THUMB, THUMB), interpolation=cv2.INTER_LINEAR)
    return np.clip(image + 0.5, 0, 255).astype(np.uint8)


def read_pdf(data: np.ndarray) -> dict:
    """The text of each page of the PDF ``data`` (its bytes as a 1-D ``uint8`` array) and its
    pictures' thumbnails.

    Returns ``{"pages": [str, ...], "images": [{"page", "number", "width", "height",
    "thumb"}], "notes": [str, ...], "error": str}``: ``pages`` one text per page read (page 1
    first), ``images`` the pictures at least :data:`MIN_FIGURE_SIDE` a side (``number``: its
    place in the PDF's pictures, from 1), ``notes`` what was left out and why, ``error`` the
    sentence saying why nothing could be read ("" when the text was read).
    """
    out = {"pages": [], "images": [], "notes": [], "error": ""}
    raw = bytes(np.ascontiguousarray(data, dtype=np.uint8))
    if b"%PDF-" not in raw[:1024]:
        out["error"] = "it is not a PDF (no '%PDF-' header at its start)"
        return out
    try:
        reader = _open(raw)
    except _Refused as refused:
        out["error"] = str(refused)
        return out
    except RecursionError:
        out["error"] = "its objects are nested too deeply to be read"
        return out
    except Exception as exc:  # noqa: BLE001 - any parser fault of a hostile file is one sentence
        out["error"] = f"it is not a readable PDF ({_reason(exc)})"
        return out
    try:
        pages = reader.pages
        count = len(pages)
    except RecursionError:
        out["error"] = "its page tree is nested too deeply to be read"
        return out
    except Exception as exc:  # noqa: BLE001
        out["error"] = f"its pages cannot be found ({_reason(exc)})"
        return out
    if count > MAX_PAGES:
        out["notes"].append(f"it has {count} pages; the first {MAX_PAGES} were read")
    total, failed, why, unread = 0, [], "", []   # unread: pages with a picture that could not be read
    for number in range(min(count, MAX_PAGES)):
        text = ""
        try:
            page = pages[number]
            text = page.extract_text() or ""
        except RecursionError:
            failed.append(number + 1)
            why, page = why or "its objects are nested too deeply", None
        except Exception as exc:  # noqa: BLE001 - one page's fault leaves the others readable
            failed.append(number + 1)
            why, page = why or _reason(exc), None
        text = text[:MAX_PAGE_CHARS][: max(MAX_TEXT_CHARS - total, 0)]
        total += len(text)
        out["pages"].append(text)
        if page is not None and len(out["images"]) < MAX_IMAGES:
            _page_images(page, number + 1, out, unread)
    if failed:
        out["notes"].append(f"the text of {_pages(failed)} could not be read")
    if unread:
        out["notes"].append(f"a picture on {_pages(unread)} could not be read; it was not compared")
    if total >= MAX_TEXT_CHARS:
        out["notes"].append(f"its text is longer than {MAX_TEXT_CHARS:,} characters; the rest was not read")
    if not count:
        out["error"] = "it has no pages that can be found"
    elif failed and not any(text.strip() for text in out["pages"]):
        out["error"] = f"the text of its pages cannot be read ({why})"
    elif not any(text.strip() for text in out["pages"]):
        out["error"] = ("it holds no text (scanned pages or pictures only?); export the report "
                        "from a text editor so that its words can be read")
    return out


def read_images(blobs: list) -> list:
    """Thumbnails of encoded pictures (PNG, JPEG ...: each a 1-D ``uint8`` array of its file's
    bytes), in order: ``{"width", "height", "thumb"}``, or ``{"error": sentence}``."""
    answers = []
    for blob in blobs[:MAX_IMAGES]:
        try:
            answers.append(_decoded(bytes(np.ascontiguousarray(blob, dtype=np.uint8))))
        except _Refused as refused:
            answers.append({"error": str(refused)})
        except Exception as exc:  # noqa: BLE001 - a picture that is no picture is one sentence
            answers.append({"error": f"it is not a readable picture ({_reason(exc)})"})
    return answers


# ------------------------------------------------------------------ helpers
class _Refused(Exception):
    """What the file holds is refused; the message is the sentence."""


def _open(raw: bytes):
    import pypdf

    # pypdf bounds what a compressed stream may expand to (75 MB a stream) and how many items
    # an array or dictionary may hold: a decompression bomb stops there, inside the worker's memory.
    reader = pypdf.PdfReader(io.BytesIO(raw), strict=False)
    if reader.is_encrypted:
        try:
            opened = reader.decrypt("")   # "protected" against editing only: an empty user password
        except Exception:  # noqa: BLE001 - an unsupported cipher is as closed as a password
            opened = 0
        if not opened:
            raise _Refused("it is encrypted (protected by a password); hand in a PDF without one")
    return reader


def _pages(numbers: list[int]) -> str:
    """``[3]`` -> "page 3", ``[1, 2, ...]`` -> "pages 1, 2, 3, 4, 5 ..." (five at most)."""
    shown = ", ".join(map(str, numbers[:5])) + (" ..." if len(numbers) > 5 else "")
    return f"page{'s' if len(numbers) > 1 else ''} {shown}"


def _page_images(page, page_number: int, out: dict, unread: list) -> None:
    """Thumbnails of the pictures on ``page``, appended to ``out["images"]`` (bounded); the
    page's number is appended to ``unread`` once if a picture of it could not be read."""
    try:
        images = page.images
        keys = list(images.keys()) if hasattr(images, "keys") else list(range(len(images)))
    except Exception:  # noqa: BLE001
        unread.append(page_number)
        return
    for key in keys:
        if len(out["images"]) >= MAX_IMAGES:
            out["notes"].append(f"it holds more than {MAX_IMAGES} pictures; the rest were not compared")
            return
        number = len(out["images"]) + 1
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("error")   # Pillow's DecompressionBombWarning stops the picture
                image = images[key].image
                if image is None:
                    continue
                _check_size(*image.size)
                found = _from_pil(image)
        except Exception:  # noqa: BLE001 - one picture's fault leaves the others
            if unread[-1:] != [page_number]:
                unread.append(page_number)
            continue
        if found is not None:
            out["images"].append({"page": page_number, "number": number, **found})


def _decoded(raw: bytes) -> dict:
    from PIL import Image

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        image = Image.open(io.BytesIO(raw))
        _check_size(*image.size)       # read from the header, before any pixel is decoded
        found = _from_pil(image)
    if found is None:
        raise _Refused(f"it is smaller than {MIN_FIGURE_SIDE} pixels a side (an icon, not a figure)")
    return found


def _check_size(width: int, height: int) -> None:
    if width * height > MAX_IMAGE_PIXELS:
        raise _Refused(f"it is {width} x {height} pixels, more than the {MAX_IMAGE_PIXELS:,} read")


def _from_pil(image) -> dict | None:
    """``{"width", "height", "thumb"}`` of a Pillow image, None when it is too small to be a figure."""
    width, height = image.size
    if min(width, height) < MIN_FIGURE_SIDE:
        return None
    if image.mode not in ("L", "RGB", "RGBA", "LA"):
        image = image.convert("RGBA" if "A" in image.mode or "transparency" in image.info else "RGB")
    pixels = np.asarray(image)
    if pixels.ndim == 3 and pixels.shape[2] in (2, 4):   # transparent parts shown on white, as a page does
        alpha = pixels[..., -1:].astype(np.float32) / 255
        pixels = pixels[..., :-1].astype(np.float32) * alpha + 255 * (1 - alpha)
    return {"width": int(width), "height": int(height), "thumb": thumbnail(pixels)}


def _reason(exc: BaseException) -> str:
    """An exception as a short phrase for a sentence (its type and its first words)."""
    words = " ".join(str(exc).split())[:120]
    return f"{type(exc).__name__}: {words}" if words else type(exc).__name__
