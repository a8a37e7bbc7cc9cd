"""Lab 8 extensions: can the outputs tell two realistic mistakes from legitimate work? (issue 35)

1. ext1 -- ORB's binary descriptors matched with a float norm (``cv2.NORM_L2``/``NORM_L1``,
   ``cv2.BFMatcher()``'s default, or FLANN's KD-tree on ``np.float32(descriptors)``) instead of
   the Hamming distance. Measured per pair: matches returned / matches within 3 px of the true
   H / that fraction, for legitimate matchers (BFMatcher with NORM_HAMMING with and without
   crossCheck and the ratio test, FLANN's LSH index, nfeatures 300 to 2000, WTA_K=3 with
   NORM_HAMMING2) and the mistakes, on the grader's pairs (``fixtures.lab08.matching_pair``:
   the public chelsea pair, the hidden check's grey camera pairs) and harder ones (rotation
   and scale).
2. ext3 -- a multi-band blend whose mask pyramid is not smoothed (``mask[::2, ::2]``,
   ``cv2.resize`` to each level, nearest or linear) instead of the mask's Gaussian pyramid.
   Measured: (a) across a step mask between two exposures (``exposure_pair``, levels=5), the
   10-90 % width of the brightness transition (px) and the largest step per column (the
   check "no visible seam" accepts 5); (b) with a fine-grained mask (``grain_mask``: 0/1
   pixels, local mean 0.5), the spread (standard deviation over the interior) of
   ``(blend - dark) / offset``: a blend whose coarse levels use the mask's Gaussian pyramid
   gives about 0.5 everywhere; one whose coarse weights are single mask pixels does not.
   Legitimate: OpenCV pyramids (float32, float64, BORDER_REPLICATE, truncation to uint8), the
   mask's pyramid by ``cv2.pyrDown``, ``GaussianBlur`` + ``[::2, ::2]`` (sigma 0.6 to 2),
   skimage's ``pyramid_gaussian``, a uint8 mask pyramid (x 255), ``cv2.resize(INTER_AREA)`` of
   the full mask to each level (an area mean), skimage pyramids throughout
   (``pyramid_gaussian`` + ``resize``, ``pyramid_reduce``/``pyramid_expand``), GaussianBlur +
   ``cv2.resize`` pyramids; and ``levels - 1`` pyramid levels (an off-by-one convention that
   other checks name) as a worst case.

    python benchmarks/spread_lab08_extensions.py

3. ext3 -- the collapsed pyramid cast to uint8 without a clip: beside a black-and-white chessboard
   (``chessboard_colour``) a multi-band blend overshoots 0..255 near the seam. Largest distance
   from the clipped yardstick over four scenes (photos, square sizes, grey, levels 4 and 5):
   legitimate pyramids (the list of 2.) 0-80 grey levels, at no pixel more than 128; values wrapped
   around (the cast without the clip) 255, farther than 128 at 2.0-10.2 % of the pixels (the check's
   scene: 4.2 %). The check accepts 128 grey levels, at up to 0.1 % of the pixels.

Printed figures (OpenCV 5.0.0, skimage 0.25.2), in short:

- ORB: no output measure separates the mistake. With the ratio test, NORM_L2 keeps 0.95-0.98
  of its matches correct on the grader's pairs (legitimate matchers: 0.92-1.00) and returns
  about half as many matches as NORM_HAMMING with the same keypoints (101 against 193 on the
  public pair), but legitimate matchers return as few (nfeatures=300: 140; the best 30 % of a
  crossCheck match: 64); NORM_L1 loses only 10-20 % of the matches. So ext1 gives a 0-point
  tip read from the code, never a lost point.
- Multi-band, step mask: the unsmoothed mask pyramid is no hard seam (the collapse's pyrUp
  smooths each level): 19-22 px wide against 29-57 px for legitimate pyramids of the right
  depth (18-19 px with one level fewer), at most 4 grey levels per column (legitimate 1-3,
  one level fewer 4-5): no margin.
- Multi-band, grain mask, levels=5: legitimate 0.005-0.021 of the offset (0.023 with one level
  fewer), the unsmoothed mask pyramid 0.112-0.299 (slicing or nearest: 0.21 and more). The
  check "coarse levels are weighted by the mask's local mean" accepts 0.05. A mask halved by
  ``cv2.resize`` with INTER_LINEAR/INTER_AREA is a 2x2 mean at each level (a box pyramid,
  smoothed): 0.013-0.037, it passes. A mask pyramid in uint8 without scaling (0/1 levels)
  fails it too (about 0.3), for another cause.
"""

from __future__ import annotations

import sys
from pathlib import Path

import cv2
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from fixtures import lab08 as truth   # noqa: E402
from fixtures.images import photo, warp   # noqa: E402


# ------------------------------------------------------------------ ORB
def _grey(image):
    return image if image.ndim == 2 else cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)


def _orb(image, n=1000, **options):
    keypoints, descriptors = cv2.ORB_create(nfeatures=n, **options).detectAndCompute(_grey(image), None)
    return np.array([k.pt for k in keypoints]).reshape(-1, 2), descriptors


def _ends(p1, p2, matches):
    return (p1[[m.queryIdx for m in matches]].reshape(-1, 2), p2[[m.trainIdx for m in matches]].reshape(-1, 2))


def ratio_matcher(norm, n=1000, ratio=0.75, **options):
    """BFMatcher(norm).knnMatch(k=2) and Lowe's ratio test."""
    def match(a, b):
        (p1, d1), (p2, d2) = _orb(a, n, **options), _orb(b, n, **options)
        pairs = cv2.BFMatcher(norm).knnMatch(d1, d2, k=2)
        return _ends(p1, p2, [m for m, s in (p for p in pairs if len(p) == 2) if m.distance < ratio * s.distance])
    return match


def cross_matcher(norm, n=1000, keep=1.0):
    """BFMatcher(norm, crossCheck=True).match, keeping the best ``keep`` share by distance."""
    def match(a, b):
        (p1, d1), (p2, d2) = _orb(a, n), _orb(b, n)
        found = sorted(cv2.BFMatcher(norm, crossCheck=True).match(d1, d2), key=lambda m: m.distance)
        return _ends(p1, p2, found[: int(len(found) * keep)])
    return match


def flann_matcher(lsh: bool, n=1000, ratio=0.75):
    """FLANN with its LSH index (binary descriptors), or its KD-tree on float32 copies (a mistake)."""
    def match(a, b):
        (p1, d1), (p2, d2) = _orb(a, n), _orb(b, n)
        if lsh:
            index, d1, d2 = dict(algorithm=6, table_number=6, key_size=12, multi_probe_level=1), d1, d2
        else:
            index, d1, d2 = dict(algorithm=1, trees=5), np.float32(d1), np.float32(d2)
        pairs = cv2.FlannBasedMatcher(index, dict(checks=50)).knnMatch(d1, d2, k=2)
        return _ends(p1, p2, [p[0] for p in pairs if len(p) == 2 and p[0].distance < ratio * p[1].distance])
    return match


ORB_LEGITIMATE = {
    "BFMatcher NORM_HAMMING + ratio, nfeatures=1000 (the reference)": ratio_matcher(cv2.NORM_HAMMING),
    "  the same, nfeatures=300": ratio_matcher(cv2.NORM_HAMMING, 300),
    "  the same, nfeatures=500 (ORB_create's default)": ratio_matcher(cv2.NORM_HAMMING, 500),
    "  the same, nfeatures=2000": ratio_matcher(cv2.NORM_HAMMING, 2000),
    "  the same, ratio 0.8": ratio_matcher(cv2.NORM_HAMMING, ratio=0.8),
    "  the same, FAST score": ratio_matcher(cv2.NORM_HAMMING, scoreType=cv2.ORB_FAST_SCORE),
    "BFMatcher NORM_HAMMING2, WTA_K=3": ratio_matcher(cv2.NORM_HAMMING2, WTA_K=3),
    "BFMatcher NORM_HAMMING crossCheck": cross_matcher(cv2.NORM_HAMMING),
    "  the same, nfeatures=300": cross_matcher(cv2.NORM_HAMMING, 300),
    "  the same, best 30 % by distance": cross_matcher(cv2.NORM_HAMMING, keep=0.3),
    "FLANN LSH + ratio": flann_matcher(True),
    "  the same, nfeatures=500": flann_matcher(True, 500),
}
ORB_MISTAKES = {
    "BFMatcher NORM_L2 + ratio (or BFMatcher()'s default)": ratio_matcher(cv2.NORM_L2),
    "  the same, nfeatures=500": ratio_matcher(cv2.NORM_L2, 500),
    "  the same, ratio 0.8": ratio_matcher(cv2.NORM_L2, ratio=0.8),
    "BFMatcher NORM_L1 + ratio": ratio_matcher(cv2.NORM_L1),
    "BFMatcher NORM_L2 crossCheck": cross_matcher(cv2.NORM_L2),
    "FLANN KD-tree on float32 descriptors": flann_matcher(False),
}


def _turned(name, angle, scale):
    image = photo(name, (240, 180))
    H = np.vstack([cv2.getRotationMatrix2D((120, 90), angle, scale), [0, 0, 1]])
    return image, warp(image, H), H


def orb_pairs() -> dict:
    pairs = {"chelsea (public)": truth.matching_pair("chelsea", (240, 180), seed=3)}
    for seed in (11, 12, 13):   # as the hidden check draws them: grey camera, strength 0.1
        pairs[f"camera grey {seed}"] = truth.matching_pair("camera", (240, 180), seed=seed, strength=0.1, grey=True)
    pairs.update({"astronaut": truth.matching_pair("astronaut", (240, 180), seed=1),
                  "coffee": truth.matching_pair("coffee", (240, 180), seed=4),
                  "rocket": truth.matching_pair("rocket", (240, 180), seed=5),
                  "chelsea 0.2": truth.matching_pair("chelsea", (240, 180), seed=3, strength=0.2),
                  "chelsea 30deg x0.8": _turned("chelsea", 30, 0.8),
                  "astronaut 45deg x0.7": _turned("astronaut", 45, 0.7)})
    return pairs


def orb_table():
    pairs = orb_pairs()
    print("ext1 ORB: matches / correct (3 px) / fraction correct, per pair")
    print(" " * 56 + " ".join(f"{k[:14]:>14s}" for k in pairs))
    summary = {}
    for title, group in (("legitimate", ORB_LEGITIMATE), ("mistake", ORB_MISTAKES)):
        for name, matcher in group.items():
            row, counts, fractions = [], [], []
            for img1, img2, H in pairs.values():
                pts1, pts2 = matcher(img1, img2)
                good = truth.consistent(H, pts1, pts2)
                fraction = float(good.mean()) if len(good) else 0.0
                counts.append(len(pts1))
                fractions.append(fraction)
                row.append(f"{len(pts1):4d}/{int(good.sum()):3d}/{fraction:4.2f}")
            summary.setdefault(title, []).append((counts, fractions))
            print(f"{name[:55]:55s}", " ".join(f"{cell:>14s}" for cell in row))
        print()
    for title, rows in summary.items():
        counts = np.array([c for c, _ in rows])
        fractions = np.array([f for _, f in rows])
        print(f"{title:10s}: matches on the public pair {counts[:, 0].min()}-{counts[:, 0].max()}, "
              f"fraction correct on the grader's pairs {fractions[:, :4].min():.2f}-{fractions[:, :4].max():.2f}")
    print()


# ------------------------------------------------------------------ multi-band blending
def _uint8(x, truncate=False):
    return (np.clip(x, 0, 255) if truncate else np.clip(np.round(x), 0, 255)).astype(np.uint8)


def _weighted(w, a, b):
    w = w[..., None] if a.ndim == 3 else w
    return w * a + (1 - w) * b


def opencv_blend(mask_pyramid=None, dtype=np.float32, border=cv2.BORDER_DEFAULT, truncate=False, depth=0):
    """OpenCV pyramids; ``mask_pyramid(mask, shapes)`` the mask's levels (default: pyrDown);
    ``depth`` added to ``levels`` (-1: one level fewer)."""
    def blend(img1, img2, mask, levels):
        levels += depth

        def gaussian(x):
            pyramid = [x]
            for _ in range(levels - 1):
                pyramid.append(cv2.pyrDown(pyramid[-1], borderType=border))
            return pyramid

        def laplacian(x):
            g = gaussian(x)
            return [f - cv2.pyrUp(c, dstsize=(f.shape[1], f.shape[0])) for f, c in zip(g[:-1], g[1:])] + [g[-1]]
        a, b = img1.astype(dtype), img2.astype(dtype)
        m = np.clip(mask.astype(dtype), 0, 1)
        weights = gaussian(m) if mask_pyramid is None else mask_pyramid(m, [x.shape[:2] for x in gaussian(a)])
        bands = [_weighted(w, x, y) for x, y, w in zip(laplacian(a), laplacian(b), weights)]
        out = bands[-1]
        for band in reversed(bands[:-1]):
            out = cv2.pyrUp(out, dstsize=(band.shape[1], band.shape[0])) + band
        return _uint8(out, truncate)
    return blend


def blurred_halving(sigma):
    def pyramid(mask, shapes):
        levels = [mask]
        for _ in shapes[1:]:
            levels.append(cv2.GaussianBlur(levels[-1], (0, 0), sigma)[::2, ::2])
        return levels
    return pyramid


def uint8_mask_pyramid(mask, shapes):
    levels = [np.round(mask * 255).astype(np.uint8)]
    for _ in shapes[1:]:
        levels.append(cv2.pyrDown(levels[-1]))
    return [level.astype(np.float32) / 255 for level in levels]


def uint8_01_mask_pyramid(mask, shapes):
    """The mask's pyramid in uint8 without scaling: each level of a 0/1 mask rounds back to 0 or 1."""
    levels = [mask.astype(np.uint8)]
    for _ in shapes[1:]:
        levels.append(cv2.pyrDown(levels[-1]))
    return [level.astype(np.float32) for level in levels]


def skimage_mask_pyramid(mask, shapes):
    from skimage.transform import pyramid_gaussian
    return list(pyramid_gaussian(mask, max_layer=len(shapes) - 1))


def sliced(mask, shapes):
    levels = [mask]
    for _ in shapes[1:]:
        levels.append(levels[-1][::2, ::2])
    return levels


def halved(interpolation):
    def pyramid(mask, shapes):
        levels = [mask]
        for h, w in shapes[1:]:
            levels.append(cv2.resize(levels[-1], (w, h), interpolation=interpolation))
        return levels
    return pyramid


def resized_from_full(interpolation):
    def pyramid(mask, shapes):
        return [cv2.resize(mask, (w, h), interpolation=interpolation) for h, w in shapes]
    return pyramid


def skimage_blend(mask_pyramid=None):
    """skimage's pyramid_gaussian for images (and mask), bands against a linear resize up."""
    from skimage.transform import pyramid_gaussian, resize

    def blend(img1, img2, mask, levels):
        channels = -1 if img1.ndim == 3 else None

        def gaussian(x):
            return list(pyramid_gaussian(x, max_layer=levels - 1, channel_axis=channels, preserve_range=True))

        def laplacian(x):
            g = gaussian(x)
            return [f - resize(c, f.shape, order=1, preserve_range=True) for f, c in zip(g[:-1], g[1:])] + [g[-1]]
        a, b = img1.astype(float), img2.astype(float)
        m = np.clip(mask.astype(float), 0, 1)
        weights = (list(pyramid_gaussian(m, max_layer=levels - 1)) if mask_pyramid is None
                   else mask_pyramid(m, [x.shape[:2] for x in gaussian(a)]))
        bands = [_weighted(w, x, y) for x, y, w in zip(laplacian(a), laplacian(b), weights)]
        out = bands[-1]
        for band in reversed(bands[:-1]):
            out = resize(out, band.shape, order=1, preserve_range=True) + band
        return _uint8(out)
    return blend


def skimage_reduce_expand(img1, img2, mask, levels):
    """skimage's pyramid_reduce / pyramid_expand pair for images and mask."""
    from skimage.transform import pyramid_expand, pyramid_reduce, resize
    channels = -1 if img1.ndim == 3 else None

    def gaussian(x, axis):
        pyramid = [x]
        for _ in range(levels - 1):
            pyramid.append(pyramid_reduce(pyramid[-1], channel_axis=axis, preserve_range=True))
        return pyramid

    def up(c, shape):
        e = pyramid_expand(c, channel_axis=channels, preserve_range=True)
        return resize(e, shape, order=1, preserve_range=True) if e.shape != shape else e

    def laplacian(x):
        g = gaussian(x, channels)
        return [f - up(c, f.shape) for f, c in zip(g[:-1], g[1:])] + [g[-1]]
    a, b = img1.astype(float), img2.astype(float)
    weights = gaussian(np.clip(mask.astype(float), 0, 1), None)
    bands = [_weighted(w, x, y) for x, y, w in zip(laplacian(a), laplacian(b), weights)]
    out = bands[-1]
    for band in reversed(bands[:-1]):
        out = up(out, band.shape) + band
    return _uint8(out)


def blur_resize_blend(img1, img2, mask, levels):
    """GaussianBlur(5x5) + cv2.resize halving down, cv2.resize (linear) up, for images and mask."""
    def gaussian(x):
        pyramid = [x]
        for _ in range(levels - 1):
            h, w = pyramid[-1].shape[:2]
            pyramid.append(cv2.resize(cv2.GaussianBlur(pyramid[-1], (5, 5), 0), (max(w // 2, 1), max(h // 2, 1))))
        return pyramid

    def up(c, f):
        return cv2.resize(c, (f.shape[1], f.shape[0]))

    def laplacian(x):
        g = gaussian(x)
        return [f - up(c, f) for f, c in zip(g[:-1], g[1:])] + [g[-1]]
    a, b = np.float32(img1), np.float32(img2)
    weights = gaussian(np.float32(np.clip(mask, 0, 1)))
    bands = [_weighted(w, x, y) for x, y, w in zip(laplacian(a), laplacian(b), weights)]
    out = bands[-1]
    for band in reversed(bands[:-1]):
        out = up(out, band) + band
    return _uint8(out)


BLEND_LEGITIMATE = {
    "reference: pyrDown mask pyramid, float32": opencv_blend(),
    "float64": opencv_blend(dtype=np.float64),
    "pyrDown with BORDER_REPLICATE": opencv_blend(border=cv2.BORDER_REPLICATE),
    "truncated to uint8 (no rounding)": opencv_blend(truncate=True),
    "mask: GaussianBlur(sigma 1) + [::2, ::2]": opencv_blend(blurred_halving(1.0)),
    "mask: GaussianBlur(sigma 2) + [::2, ::2]": opencv_blend(blurred_halving(2.0)),
    "mask: GaussianBlur(3x3, sigma 0.8) + [::2, ::2]": opencv_blend(blurred_halving(0.8)),
    "mask: GaussianBlur(sigma 0.6) + [::2, ::2]": opencv_blend(blurred_halving(0.6)),
    "mask: skimage pyramid_gaussian": opencv_blend(skimage_mask_pyramid),
    "mask: uint8 pyramid (x 255)": opencv_blend(uint8_mask_pyramid),
    "mask: cv2.resize INTER_AREA of the full mask": opencv_blend(resized_from_full(cv2.INTER_AREA)),
    "skimage pyramid_gaussian + resize throughout": skimage_blend(),
    "skimage pyramid_reduce / pyramid_expand": skimage_reduce_expand,
    "GaussianBlur + cv2.resize pyramids": blur_resize_blend,
    "reference with one level fewer (named elsewhere)": opencv_blend(depth=-1),
}
BLEND_MISTAKES = {
    "mask[::2, ::2] at each level": opencv_blend(sliced),
    "mask halved by cv2.resize INTER_NEAREST": opencv_blend(halved(cv2.INTER_NEAREST)),
    "full mask cv2.resize INTER_NEAREST to each level": opencv_blend(resized_from_full(cv2.INTER_NEAREST)),
    "full mask cv2.resize (linear) to each level": opencv_blend(resized_from_full(cv2.INTER_LINEAR)),
    "skimage pyramids, mask[::2, ::2]": skimage_blend(sliced),
    "mask pyramid in uint8, not scaled (another cause)": opencv_blend(uint8_01_mask_pyramid),
}
BOX_PYRAMIDS = {   # a 2x2 mean at each level: smoothed (a box pyramid), not counted as the mistake
    "mask halved by cv2.resize INTER_LINEAR": opencv_blend(halved(cv2.INTER_LINEAR)),
    "mask halved by cv2.resize INTER_AREA": opencv_blend(halved(cv2.INTER_AREA)),
}


def _mean_difference(got, dark):
    d = got.astype(np.float64) - dark
    return d.mean(axis=2) if d.ndim == 3 else d


def transition(got, dark, column) -> tuple[int, float]:
    """(10-90 % width in px, largest step per column) of the brightness change across a step seam."""
    profile = _mean_difference(got, dark).mean(axis=0)
    low, high = np.median(profile[5:30]), np.median(profile[-30:-5])
    q = (profile - low) / (high - low)
    x = np.arange(len(q))
    width = int(x[q > 0.9].min() - (x[q < 0.1].max() if (q < 0.1).any() else 0))
    step = float(np.abs(np.diff(profile[column - 68 : column + 68])).max())
    return width, step


def grain_spread(got, dark, offset, margin=16) -> float:
    """Standard deviation of (blend - dark) / offset over the interior."""
    return float(_mean_difference(got, dark)[margin:-margin, margin:-margin].std() / offset)


# (photo, size, gain, offset, grain seed or step column) -- the check's scene first
GRAIN_SCENES = [("coffee", (256, 192), 0.7, 60, 8), ("astronaut", (224, 176), 0.6, 50, 2),
                ("chelsea", (250, 170), 0.6, 70, 3), ("camera", (237, 181), 0.6, 60, 4),
                ("rocket", (256, 192), 0.6, 60, 5)]
STEP_SCENES = [("coffee", (256, 192), 0.7, 60, 128), ("coffee", (256, 192), 0.7, 60, 100),
               ("astronaut", (224, 176), 0.6, 50, 100), ("chelsea", (256, 192), 0.6, 70, 127)]


def _exposures(name, size, gain, offset):
    dark, bright = truth.exposure_pair(name, size, gain, offset)
    if name == "camera":   # a grey pair
        dark, bright = np.ascontiguousarray(dark[..., 0]), np.ascontiguousarray(bright[..., 0])
    return dark, bright


def blend_table():
    print("ext3 multi-band: step seam (levels=5) width px / largest step per column; "
          "grain mask spread of (blend - dark) / offset at levels=5 and levels=4")
    print(" " * 50 + " ".join(f"{n[:5]}@{c:<3d}  " for n, _, _, _, c in STEP_SCENES)
          + " | " + " ".join(f"{n[:9]:>9s}" for n, *_ in GRAIN_SCENES) + " | levels=4")
    worst = {}
    for title, group in (("legitimate", BLEND_LEGITIMATE), ("mistake", BLEND_MISTAKES), ("box pyramid", BOX_PYRAMIDS)):
        for name, blend in group.items():
            steps = []
            for photo_name, size, gain, offset, column in STEP_SCENES:
                dark, bright = _exposures(photo_name, size, gain, offset)
                steps.append(transition(blend(dark, bright, truth.step_mask(size, column), 5), dark, column))
            spreads = {5: [], 4: []}
            for photo_name, size, gain, offset, seed in GRAIN_SCENES:
                dark, bright = _exposures(photo_name, size, gain, offset)
                mask = truth.grain_mask(size, seed)
                for levels in spreads:
                    spreads[levels].append(grain_spread(blend(dark, bright, mask, levels), dark, offset))
            worst.setdefault(title, []).append((steps, spreads))
            print(f"{name[:49]:49s} " + " ".join(f"{w:3d}/{s:3.1f} " for w, s in steps) + " | "
                  + " ".join(f"{s:9.3f}" for s in spreads[5]) + " | " + " ".join(f"{s:.3f}" for s in spreads[4]))
        print()
    for title, rows in worst.items():
        widths = [w for steps, _ in rows for w, _ in steps]
        jumps = [s for steps, _ in rows for _, s in steps]
        five = [s for _, spreads in rows for s in spreads[5]]
        four = [s for _, spreads in rows for s in spreads[4]]
        print(f"{title:11s}: step seam {min(widths)}-{max(widths)} px wide, steps {min(jumps):.0f}-{max(jumps):.0f}; "
              f"grain spread levels=5 {min(five):.3f}-{max(five):.3f}, levels=4 {min(four):.3f}-{max(four):.3f}")


# ------------------------------------------------------------------ clip
# The check "where the blend passes 0 or 255, it is clipped": a black-and-white chessboard beside a
# photo (the check's scene first, then other photos, square sizes, grey, levels=5).
CLIP_SCENES = [("coffee", 16, 4, False), ("astronaut", 12, 4, False), ("chelsea", 16, 5, False),
               ("camera", 20, 4, True)]


def wrapped_blend(img1, img2, mask, levels):
    """The yardstick's collapse cast to uint8 without the clip (values past 0..255 wrap around)."""
    return np.round(truth.multiband(img1, img2, mask, levels, clip=False)).astype(np.int64).astype(np.uint8)


def clip_table():
    print("ext3 clip: largest |blend - clipped yardstick| (grey levels) / share of pixels farther than 128")
    for title, group in (("legitimate", BLEND_LEGITIMATE), ("mistake", {"cast without the clip": wrapped_blend})):
        for name, blend in group.items():
            row = []
            for photo_name, square, levels, grey in CLIP_SCENES:
                size = (256, 192)
                board, other = truth.chessboard_colour(size, square), photo(photo_name, size)
                if grey:
                    board, other = board[..., 0].copy(), cv2.cvtColor(other, cv2.COLOR_BGR2GRAY)
                mask = truth.step_mask(size, 128)
                due = truth.multiband(board, other, mask, levels).astype(np.float64)
                off = np.abs(blend(board, other, mask, levels).astype(np.float64) - due)
                far = off > 128
                row.append(f"{off.max():3.0f} / {(far.any(axis=2) if far.ndim == 3 else far).mean():.4f}")
            print(f"  {title:10s} {name[:49]:49s} " + "  ".join(row))
    print()


if __name__ == "__main__":
    orb_table()
    blend_table()
    clip_table()
