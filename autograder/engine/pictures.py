"""Pictures for feedback: PNG encoding, difference heat maps, point plots (SVG).

Arrays drawn here may come from a submission: every entry point first checks
shape and dtype and thins the input to at most :data:`MAX_SIDE` pixels a side
(:func:`bounded`, a strided view: no copy), so no picture costs more than a few
megabytes whatever the submission returned.
"""

from __future__ import annotations

import base64
import collections
import hashlib
import html
import threading

import cv2
import numpy as np

from .compare import largest_channel

MIN_SIDE = 160  # small images are enlarged (nearest neighbour) so pixels stay visible
MAX_SIDE = 1024  # longest side of any picture, in pixels (larger inputs are thinned)


def _steps(shape, max_side: int = MAX_SIDE) -> tuple[int, int]:
    return tuple(max(1, -(-int(side) // max_side)) for side in shape[:2])


def bounded(image, steps=None) -> np.ndarray:
    """``image`` as a drawable array: numeric (not complex), 2-D or 3-D with at most 4
    channels, not empty, thinned by ``steps`` (default: to at most :data:`MAX_SIDE` a side).

    Raises
    ------
    ValueError
        For anything else; the picture is then left out, never the verdict.
    """
    image = np.asarray(image)
    if image.dtype.kind not in "biuf":
        raise ValueError(f"cannot draw an array of dtype {image.dtype}")
    if image.ndim not in (2, 3) or image.size == 0 or (image.ndim == 3 and image.shape[2] > 4):
        raise ValueError(f"cannot draw an array of shape {image.shape}")
    rows, cols = steps or _steps(image.shape)
    return image[::rows, ::cols]


def as_displayable(image) -> np.ndarray:
    """Any numeric 2-D/3-D array as a uint8 image that a browser can show."""
    image = bounded(image)
    if image.ndim == 3 and image.shape[2] == 1:
        image = image[:, :, 0]
    if image.ndim not in (2, 3) or (image.ndim == 3 and image.shape[2] not in (3, 4)):
        raise ValueError(f"cannot display an array of shape {image.shape}")
    if image.dtype != np.uint8:
        finite = np.nan_to_num(image.astype(np.float64), nan=0.0, posinf=0.0, neginf=0.0)
        if finite.min() >= 0 and finite.max() <= 255 and image.dtype.kind in "iub":
            image = finite.astype(np.uint8)
        else:
            lo, hi = float(finite.min()), float(finite.max())
            image = ((finite - lo) * (255.0 / (hi - lo if hi > lo else 1.0))).astype(np.uint8)
    if 0 < min(image.shape[:2]) < MIN_SIDE:
        factor = int(np.ceil(MIN_SIDE / min(image.shape[:2])))
        factor = max(1, min(factor, MAX_SIDE // max(image.shape[:2])))  # a 1 x 20000 strip stays small
        image = cv2.resize(image, None, fx=factor, fy=factor, interpolation=cv2.INTER_NEAREST)
    return image


def png_base64(image) -> str:
    """Encode an image (BGR or grey) as base64 PNG text for a data: URI."""
    ok, data = cv2.imencode(".png", as_displayable(image))
    if not ok:
        raise ValueError("PNG encoding failed")
    return base64.b64encode(data.tobytes()).decode("ascii")


def difference_heatmap(expected, got, valid=None, full_scale: float = 64.0) -> np.ndarray:
    """Colour-coded |expected - got| (dark = equal, bright = differ); grey outside ``valid``."""
    return deferred_heatmap(expected, got, valid, full_scale)()


def deferred_heatmap(expected, got, valid=None, full_scale: float = 64.0):
    """:func:`difference_heatmap` in two steps: the inputs are checked now (raising
    ValueError as it would), the picture is drawn when the returned function is called."""
    steps = _steps(np.shape(expected))
    a, b = bounded(expected, steps), bounded(got, steps)  # strided views: no copy yet
    if a.shape != b.shape:
        raise ValueError(f"cannot compare arrays of shapes {np.shape(expected)} and {np.shape(got)}")
    if valid is not None:
        valid = np.asarray(valid, dtype=bool)[::steps[0], ::steps[1]]
    return lambda: _heatmap(a, b, valid, full_scale)


def _heatmap(a, b, valid, full_scale: float) -> np.ndarray:
    diff = largest_channel(cv2.absdiff(a.astype(np.float32), b.astype(np.float32)))
    scaled = np.clip(diff * (255.0 / full_scale), 0, 255).astype(np.uint8)
    heat = cv2.applyColorMap(scaled, cv2.COLORMAP_INFERNO)
    if valid is not None:
        heat[~valid] = (96, 96, 96)
    return heat


def side_by_side(*images, gap: int = 4) -> np.ndarray:
    """Images next to each other on a black strip (3 channels)."""
    tiles = [cv2.cvtColor(i, cv2.COLOR_GRAY2BGR) if i.ndim == 2 else i
             for i in (as_displayable(i) for i in images)]
    height = max(t.shape[0] for t in tiles)
    padded = []
    for t in tiles:
        pad = np.zeros((height, t.shape[1] + gap, 3), np.uint8)
        pad[: t.shape[0], : t.shape[1]] = t
        padded.append(pad)
    return np.hstack(padded)[:, :-gap]


def svg_points(series: dict[str, np.ndarray], width: int = 360, height: int = 300,
               flip_y: bool = True, lines=()) -> str:
    """A scatter plot of 2-D point sets as inline SVG.

    Parameters
    ----------
    series : dict of label -> (N, 2) float array
        At most four sets, drawn as circles in distinct colours with a legend.
    flip_y : bool
        Draw y downwards, as in image coordinates.
    lines : iterable of ((x0, y0), (x1, y1))
        Segments drawn in grey, e.g. from the true to the student's point.
    """
    colours = ["#1b9e77", "#d95f02", "#7570b3", "#e7298a"]
    data = [np.asarray(p, float).reshape(-1, 2) for p in series.values()]
    finite = np.vstack([p[np.all(np.isfinite(p), axis=1)] for p in data] + [np.zeros((0, 2))])
    if len(finite) == 0:
        finite = np.array([[0.0, 0.0], [1.0, 1.0]])
    lo, hi = finite.min(axis=0), finite.max(axis=0)
    span = np.where(hi - lo > 0, hi - lo, 1.0)
    margin, legend = 16, 18 * len(series)
    scale = min((width - 2 * margin) / span[0], (height - 2 * margin - legend) / span[1])

    def xy(p):
        x = margin + (p[0] - lo[0]) * scale
        y = (p[1] - lo[1]) * scale
        y = legend + margin + (y if flip_y else (span[1] * scale - y))
        return x, y

    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {width} {height}" '
             f'width="{width}" height="{height}" role="img">',
             f'<rect width="{width}" height="{height}" fill="#fff" stroke="#ccc"/>']
    for (a, b) in lines:
        if np.all(np.isfinite(a)) and np.all(np.isfinite(b)):
            (x0, y0), (x1, y1) = xy(a), xy(b)
            parts.append(f'<line x1="{x0:.1f}" y1="{y0:.1f}" x2="{x1:.1f}" y2="{y1:.1f}" stroke="#999"/>')
    for i, ((label, _), points) in enumerate(zip(series.items(), data)):
        colour = colours[i % len(colours)]
        for p in points[np.all(np.isfinite(points), axis=1)][:2000]:
            x, y = xy(p)
            parts.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="{3 if i == 0 else 2}" '
                         f'fill="{colour if i else "none"}" stroke="{colour}"/>')
        parts.append(f'<circle cx="{margin}" cy="{12 + 18 * i}" r="4" fill="{colour}"/>'
                     f'<text x="{margin + 10}" y="{16 + 18 * i}" font-size="12" '
                     f'font-family="sans-serif">{html.escape(label)} ({len(points)})</text>')
    parts.append("</svg>")
    return "".join(parts)


def rasterise_svg(svg: str) -> np.ndarray:
    """A plot of :func:`svg_points` as a BGR image, for places that show no SVG
    (Gradescope's sanitised HTML keeps PNG and JPEG pictures only).

    Draws what :func:`svg_points` draws -- ``rect``, ``line``, ``circle`` and ``text``
    in document order, colours as ``#rgb`` or ``#rrggbb`` -- and ignores any other
    element. Raises ValueError for markup that is not an ``<svg>`` of at most
    :data:`MAX_SIDE` pixels a side.
    """
    import xml.etree.ElementTree as ElementTree

    try:
        root = ElementTree.fromstring(svg)
    except ElementTree.ParseError as exc:
        raise ValueError(f"not SVG markup ({exc})") from None
    width, height = (int(_svg_number(root.get(key), 0)) for key in ("width", "height"))
    if root.tag.rpartition("}")[2] != "svg" or not (0 < width <= MAX_SIDE and 0 < height <= MAX_SIDE):
        raise ValueError("not an <svg> element with a width and height of at most "
                         f"{MAX_SIDE} pixels")
    canvas = np.full((height, width, 3), 255, np.uint8)
    sub = 16  # coordinates in 1/16 pixels (cv2's shift=4): points keep their place

    def at(*values):
        return tuple(int(round(np.clip(v, -4 * MAX_SIDE, 4 * MAX_SIDE) * sub)) for v in values)

    for element in root.iter():
        tag, get = element.tag.rpartition("}")[2], element.get
        fill, stroke = _svg_colour(get("fill")), _svg_colour(get("stroke"))
        if tag == "rect":
            corners = at(_svg_number(get("x"), 0), _svg_number(get("y"), 0))
            far = at(_svg_number(get("x"), 0) + _svg_number(get("width"), 0),
                     _svg_number(get("y"), 0) + _svg_number(get("height"), 0))
            for colour, thickness in ((fill, -1), (stroke, 1)):
                if colour is not None:
                    cv2.rectangle(canvas, corners, far, colour, thickness, cv2.LINE_AA, 4)
        elif tag == "line" and stroke is not None:
            cv2.line(canvas, at(_svg_number(get("x1"), 0), _svg_number(get("y1"), 0)),
                     at(_svg_number(get("x2"), 0), _svg_number(get("y2"), 0)), stroke, 1, cv2.LINE_AA, 4)
        elif tag == "circle":
            centre = at(_svg_number(get("cx"), 0), _svg_number(get("cy"), 0))
            radius = int(round(min(max(_svg_number(get("r"), 0), 0), MAX_SIDE) * sub))
            for colour, thickness in ((fill, -1), (stroke, 1)):
                if colour is not None:
                    cv2.circle(canvas, centre, radius, colour, thickness, cv2.LINE_AA, 4)
        elif tag == "text" and element.text:
            scale = _svg_number(get("font-size"), 12) / 30  # Hershey simplex: 30 px a unit
            text = element.text.encode("ascii", "replace").decode("ascii")
            origin = tuple(int(v) for v in (_svg_number(get("x"), 0), _svg_number(get("y"), 0)))
            cv2.putText(canvas, text, origin, cv2.FONT_HERSHEY_SIMPLEX, min(scale, 4.0),
                        fill or (0, 0, 0), 1, cv2.LINE_AA)
    return canvas


def _svg_number(text, default: float) -> float:
    try:
        value = float(text)
    except (TypeError, ValueError):
        return default
    return value if np.isfinite(value) else default


def _svg_colour(text) -> tuple[int, int, int] | None:
    """``#rgb`` / ``#rrggbb`` as a BGR tuple; None for ``none``, a missing or another colour."""
    text = (text or "").strip().lower()
    if len(text) == 4 and text.startswith("#"):
        text = "#" + "".join(c * 2 for c in text[1:])
    if len(text) != 7 or not text.startswith("#"):
        return None
    try:
        red, green, blue = (int(text[i:i + 2], 16) for i in (1, 3, 5))
    except ValueError:
        return None
    return blue, green, red


def disparity_picture(disparity, max_disparity=None) -> np.ndarray:
    """A disparity (or depth) map in false colour; invalid pixels (<= 0, NaN) black."""
    d = bounded(disparity).astype(np.float64)
    if d.ndim != 2:
        raise ValueError(f"a disparity map is 2-D, not of shape {d.shape}")
    valid = np.isfinite(d) & (d > 0)
    top = float(max_disparity) if max_disparity else (float(d[valid].max()) if valid.any() else 1.0)
    scaled = np.clip(np.where(valid, d, 0.0) * (255.0 / max(top, 1e-9)), 0, 255).astype(np.uint8)
    picture = cv2.applyColorMap(scaled, cv2.COLORMAP_TURBO)
    picture[~valid] = 0
    return picture


def disparity_error_picture(truth, got, threshold: float = 1.0) -> np.ndarray:
    """Colour-coded disparity error: green within ``threshold``, yellow to red beyond
    (red = 4 x threshold or more), blue where ``got`` is invalid, grey where the truth is unknown."""
    steps = _steps(np.shape(truth))
    truth = bounded(truth, steps).astype(np.float64)
    got = bounded(got, steps).astype(np.float64)
    if truth.ndim != 2 or truth.shape != got.shape:
        raise ValueError(f"cannot compare disparity maps of shapes {truth.shape} and {got.shape}")
    known = np.isfinite(truth) & (truth > 0)
    answered = np.isfinite(got) & (got > 0)
    error = np.abs(np.where(answered & known, got - truth, 0.0))
    picture = np.empty(truth.shape + (3,), np.uint8)
    picture[:] = (96, 96, 96)
    good = known & answered & (error <= threshold)
    picture[good] = (60, 170, 60)
    bad = known & answered & (error > threshold)
    amount = np.clip((error - threshold) / (3.0 * threshold), 0.0, 1.0)
    green = (220 * (1.0 - amount)).astype(np.uint8)
    picture[bad] = np.stack([np.zeros_like(green), green, np.full_like(green, 255)], axis=-1)[bad]
    picture[known & ~answered] = (200, 80, 0)
    return picture


def matches_picture(img1, img2, pts1, pts2, good=None, max_lines: int = 300) -> np.ndarray:
    """Two images side by side with a line per match: green where ``good``, red elsewhere.

    Parameters
    ----------
    img1, img2 : (H, W[, 3]) arrays
    pts1, pts2 : (M, 2) float arrays
        Matched points ``(x, y)`` in each image; ``pts2`` is drawn shifted right
        by ``img1``'s width.
    good : (M,) bool array, optional
        Which matches are right (e.g. agree with a true homography). All green
        when omitted.
    """
    step = max(_steps(np.shape(img1)) + _steps(np.shape(img2)))  # one scale for both, and the points
    a, b = (np.clip(bounded(i, (step, step)).astype(np.float64), 0, 255).astype(np.uint8)
            for i in (img1, img2))
    a = cv2.cvtColor(a, cv2.COLOR_GRAY2BGR) if a.ndim == 2 else a[:, :, :3]
    b = cv2.cvtColor(b, cv2.COLOR_GRAY2BGR) if b.ndim == 2 else b[:, :, :3]
    h1, w1 = a.shape[:2]
    canvas = np.zeros((max(h1, b.shape[0]), w1 + b.shape[1], 3), np.uint8)
    canvas[:h1, :w1] = a
    canvas[: b.shape[0], w1:] = b
    canvas = (canvas * 0.7).astype(np.uint8)  # dimmed, so the lines stand out
    pts1 = np.asarray(pts1, dtype=np.float64).reshape(-1, 2) / step
    pts2 = np.asarray(pts2, dtype=np.float64).reshape(-1, 2) / step
    n = min(len(pts1), len(pts2))
    good = np.ones(n, bool) if good is None else np.asarray(good, bool)[:n]
    order = np.concatenate([np.flatnonzero(good), np.flatnonzero(~good)])  # bad ones on top
    if len(order) > max_lines:
        order = order[np.linspace(0, len(order) - 1, max_lines).astype(int)]
    for i in order:
        p, q = pts1[i], pts2[i]
        if not (np.all(np.isfinite(p)) and np.all(np.isfinite(q))):
            continue
        colour = (0, 200, 0) if good[i] else (0, 0, 255)
        a_pt = (int(round(np.clip(p[0], -1e4, 1e4))), int(round(np.clip(p[1], -1e4, 1e4))))
        b_pt = (int(round(np.clip(q[0] + w1, -1e4, 1e4))), int(round(np.clip(q[1], -1e4, 1e4))))
        cv2.line(canvas, a_pt, b_pt, colour, 1, cv2.LINE_AA)
        cv2.circle(canvas, a_pt, 2, colour, -1)
        cv2.circle(canvas, b_pt, 2, colour, -1)
    return canvas


# ------------------------------------------------------------------ presentation
JPEG_QUALITY = 82
PAGE_SIZE = (1000, 360)  # largest encoded picture (width, height): about twice the size it is drawn at


def picture_item(label: str, image) -> dict:
    """One picture of an artifact, encoded once, in the form a page embeds:
    ``{"label", "mime", "data", "width", "height", "encoded_size"}``.

    ``width`` and ``height`` are the array's own size (before any enlargement or
    shrinking), so a page can draw pictures at their relative sizes and say how large
    each is; ``encoded_size`` is ``[width, height]`` of the encoded picture (see
    :func:`compact`).
    """
    shape = np.shape(image)
    mime, data, width, height = compact(as_displayable(image))
    return {"label": label, "mime": mime, "data": data,
            "width": int(shape[1]) if len(shape) > 1 else 0, "height": int(shape[0]) if shape else 0,
            "encoded_size": [width, height]}


def compact_encoding(png: str, max_width: int = PAGE_SIZE[0], max_height: int = PAGE_SIZE[1]
                     ) -> tuple[str, str, int, int]:
    """:func:`compact` of a base64 PNG (a figure, or a picture of results written before
    pictures were encoded once)."""
    image = cv2.imdecode(np.frombuffer(base64.b64decode(png), np.uint8), cv2.IMREAD_UNCHANGED)
    if image is None:
        return "image/png", png, 1, 1
    return compact(image, max_width, max_height)


def compact(image: np.ndarray, max_width: int = PAGE_SIZE[0], max_height: int = PAGE_SIZE[1]
            ) -> tuple[str, str, int, int]:
    """``(mime type, base64 data, width, height)``: a displayable image (uint8, grey, BGR
    or BGRA) made small enough for a page that stays small.

    Shrunk (area averaging) to fit ``max_width`` x ``max_height`` pixels, then kept
    as PNG when that is about as small (drawings, masks, enlarged small images stay
    crisp), else JPEG (photos are several times smaller so). The same image is
    encoded once per process (pages show the same input in many checks).
    """
    key = (hashlib.blake2b(np.ascontiguousarray(image).data, digest_size=16).digest(),
           image.shape, image.dtype.str, max_width, max_height)
    with _ENCODED_LOCK:
        if key in _ENCODED:
            _ENCODED.move_to_end(key)
            return _ENCODED[key]
    encoded = _compact(image, max_width, max_height)
    with _ENCODED_LOCK:
        _ENCODED[key] = encoded
        while len(_ENCODED) > _ENCODED_KEPT:
            _ENCODED.popitem(last=False)
    return encoded


_ENCODED: collections.OrderedDict = collections.OrderedDict()  # the last few encodings, by content
_ENCODED_KEPT = 64
_ENCODED_LOCK = threading.Lock()


def _compact(image: np.ndarray, max_width: int, max_height: int) -> tuple[str, str, int, int]:
    height, width = image.shape[:2]
    factor = min(1.0, max_width / max(width, 1), max_height / max(height, 1))
    if factor < 1.0:
        image = cv2.resize(image, (max(1, round(width * factor)), max(1, round(height * factor))),
                           interpolation=cv2.INTER_AREA)
    size = image.shape[1], image.shape[0]
    if (image.ndim == 3 and image.shape[2] == 4) or _mostly_flat(image):
        # Transparency, or a drawing, mask or enlarged small image: PNG, unless JPEG is far smaller.
        as_png = cv2.imencode(".png", image, [cv2.IMWRITE_PNG_COMPRESSION, 6])[1]
        if image.ndim == 3 and image.shape[2] == 4:
            return "image/png", base64.b64encode(as_png.tobytes()).decode("ascii"), *size
        as_jpeg = cv2.imencode(".jpg", image, [cv2.IMWRITE_JPEG_QUALITY, JPEG_QUALITY])[1]
        if len(as_png) <= 1.5 * len(as_jpeg):
            return "image/png", base64.b64encode(as_png.tobytes()).decode("ascii"), *size
    else:  # a photo: PNG would be several times larger (and slow to compress)
        as_jpeg = cv2.imencode(".jpg", image, [cv2.IMWRITE_JPEG_QUALITY, JPEG_QUALITY])[1]
    return "image/jpeg", base64.b64encode(as_jpeg.tobytes()).decode("ascii"), *size


def _mostly_flat(image: np.ndarray, share: float = 0.5) -> bool:
    """Whether most pixels equal their left neighbour: drawings, yes; photos, no."""
    same = image[:, 1:] == image[:, :-1]
    if same.ndim == 3:
        same = same.all(axis=2)
    return bool(same.mean() >= share) if same.size else True


def heat_scale_stops(count: int = 6) -> list[str]:
    """CSS colours of the difference heat map's scale, from equal (0) to ``full_scale``."""
    levels = np.linspace(0, 255, count).astype(np.uint8).reshape(-1, 1)
    colours = cv2.applyColorMap(levels, cv2.COLORMAP_INFERNO).reshape(-1, 3)
    return [f"rgb({r},{g},{b})" for b, g, r in colours]
