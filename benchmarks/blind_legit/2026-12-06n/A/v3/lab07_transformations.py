"""Lab 7 - 2D transformations.

My choices where the lab leaves room:
- Simple matrices (translation, rotation, scaling, shear, 3-point affine) are
  returned as float32: they are small, exact enough and what cv2 likes.
- Whole-pixel shifts are done by array slicing (exact copy, no resampling);
  fractional shifts and the other warps are done by inverse mapping with
  ``cv2.remap``. Rotation uses bicubic interpolation, scaling nearest
  neighbour, shear my own per-row linear interpolation.
- Inputs (images, points, matrices) may be lists, read-only or non-contiguous
  arrays; they are never modified.

Points are (x, y) with x the column and y the row, origin at the centre of the
top-left pixel, y pointing down. Angles are degrees, positive = counter-clockwise
as displayed (the lecture's R(theta) with theta -> -theta because y points down).
"""

import cv2
import numpy as np


# ----------------------------------------------------------------- helpers
def _as_image(image):
    """A C-contiguous uint8 view/copy of ``image`` that cv2 accepts."""
    return np.ascontiguousarray(np.asarray(image))


def _remap_inverse(image, Minv, dsize, interpolation):
    """Sample ``image`` at ``Minv @ (x, y, 1)`` for every output pixel (x, y).

    ``Minv`` is the 3x3 output-to-source matrix (affine). Pixels whose source
    falls outside the image are black.
    """
    img = _as_image(image)
    w, h = int(dsize[0]), int(dsize[1])
    xs, ys = np.meshgrid(np.arange(w, dtype=np.float64),
                         np.arange(h, dtype=np.float64))
    Minv = np.asarray(Minv, dtype=np.float64)
    map_x = Minv[0, 0] * xs + Minv[0, 1] * ys + Minv[0, 2]
    map_y = Minv[1, 0] * xs + Minv[1, 1] * ys + Minv[1, 2]
    out = cv2.remap(img, map_x.astype(np.float32), map_y.astype(np.float32),
                    interpolation, borderMode=cv2.BORDER_CONSTANT, borderValue=0)
    return out.reshape((h, w) + img.shape[2:])


# --------------------------------------------------------------------- ex1
def translation_matrix(tx, ty):
    """The 3x3 translation matrix ``[[1, 0, tx], [0, 1, ty], [0, 0, 1]]``."""
    T = np.eye(3, dtype=np.float32)
    T[0, 2] = tx
    T[1, 2] = ty
    return T


def translate(image, tx=100, ty=50):
    """Shift ``image`` right by ``tx`` and down by ``ty`` pixels, black fill."""
    img = np.asarray(image)
    h, w = img.shape[:2]
    if float(tx).is_integer() and float(ty).is_integer():
        # whole pixels: plain array copy, no interpolation at all
        tx, ty = int(tx), int(ty)
        out = np.zeros_like(img)
        # destination rows/cols that receive a source pixel
        y0, y1 = max(ty, 0), min(h + ty, h)
        x0, x1 = max(tx, 0), min(w + tx, w)
        if y0 < y1 and x0 < x1:
            out[y0:y1, x0:x1] = img[y0 - ty:y1 - ty, x0 - tx:x1 - tx]
        return out
    # fractional shift: output (x, y) reads source (x - tx, y - ty)
    Tinv = translation_matrix(-tx, -ty)
    return _remap_inverse(img, Tinv, (w, h), cv2.INTER_LINEAR)


# --------------------------------------------------------------------- ex2
def rotation_matrix(angle_deg, center=(0.0, 0.0)):
    """3x3 rotation by ``angle_deg`` (counter-clockwise as displayed) about ``center``.

    With y pointing down the displayed counter-clockwise rotation is
    ``[[cos, sin], [-sin, cos]]``; about ``c`` it is ``T(c) R T(-c)``.
    """
    cx, cy = (float(v) for v in np.asarray(center, dtype=np.float64).ravel()[:2])
    t = np.deg2rad(float(angle_deg))
    c, s = np.cos(t), np.sin(t)
    R = np.array([[c, s, 0.0],
                  [-s, c, 0.0],
                  [0.0, 0.0, 1.0]])
    M = np.array([[1.0, 0.0, cx], [0.0, 1.0, cy], [0.0, 0.0, 1.0]]) @ R @ \
        np.array([[1.0, 0.0, -cx], [0.0, 1.0, -cy], [0.0, 0.0, 1.0]])
    return M.astype(np.float32)


def rotate(image, angle_deg=45):
    """Rotate about the image centre ``((W-1)/2, (H-1)/2)``, same size, black fill.

    Bicubic resampling (``cv2.INTER_CUBIC``) by inverse mapping.
    """
    img = np.asarray(image)
    h, w = img.shape[:2]
    center = ((w - 1) / 2.0, (h - 1) / 2.0)
    # inverse of a rotation about c is the rotation by -angle about c
    Minv = rotation_matrix(-angle_deg, center).astype(np.float64)
    return _remap_inverse(img, Minv, (w, h), cv2.INTER_CUBIC)


# --------------------------------------------------------------------- ex3
def scaling_matrix(sx, sy):
    """``diag(sx, sy, 1)``."""
    return np.diag([sx, sy, 1.0]).astype(np.float32)


def scale(image, sx=1.5, sy=1.5):
    """Scale about the top-left pixel centre, same size (cropped / black fill).

    Nearest-neighbour resampling: output (x, y) takes source pixel
    ``round(x / sx), round(y / sy)``.
    """
    img = np.asarray(image)
    h, w = img.shape[:2]
    Sinv = np.diag([1.0 / sx, 1.0 / sy, 1.0])
    return _remap_inverse(img, Sinv, (w, h), cv2.INTER_NEAREST)


# --------------------------------------------------------------------- ex4
def shear_matrix(s):
    """``x' = x + s*y, y' = y``."""
    S = np.eye(3, dtype=np.float32)
    S[0, 1] = s
    return S


def shear(image, s=0.5):
    """Horizontal shear: row y moves right by ``s*y`` pixels, black fill.

    A shear is a different translation per row, so each row is resampled on
    its own with linear interpolation between its two neighbouring pixels.
    """
    img = np.asarray(image)
    h, w = img.shape[:2]
    src = img.astype(np.float64)
    if src.ndim == 2:
        src = src[:, :, None]
    out = np.zeros_like(src)
    xs = np.arange(w, dtype=np.float64)
    for y in range(h):
        xsrc = xs - s * y                      # where output pixel x comes from
        x0 = np.floor(xsrc).astype(np.int64)
        a = (xsrc - x0)[:, None]               # weight of the right neighbour
        row = src[y]
        left_ok = (x0 >= 0) & (x0 < w)
        right_ok = (x0 + 1 >= 0) & (x0 + 1 < w)
        left = np.where(left_ok[:, None], row[np.clip(x0, 0, w - 1)], 0.0)
        right = np.where(right_ok[:, None], row[np.clip(x0 + 1, 0, w - 1)], 0.0)
        val = (1.0 - a) * left + a * right
        # pixels whose source lies entirely outside the image stay black
        inside = (xsrc > -1.0) & (xsrc < w)
        out[y] = np.where(inside[:, None], val, 0.0)
    out = np.clip(np.rint(out), 0, 255).astype(img.dtype)
    return out.reshape(img.shape)


# --------------------------------------------------------------------- ex5
def affine_from_points(src, dst):
    """Affine 2x3 ``A`` with ``dst[i] = A @ [src[i], 1]`` from exactly three pairs.

    Two 3x3 systems share the same matrix ``[x y 1]``: solve them together.
    """
    src = np.asarray(src, dtype=np.float64).reshape(-1, 2)[:3]
    dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)[:3]
    M = np.hstack([src, np.ones((3, 1))])         # rows [x, y, 1]
    sol = np.linalg.solve(M, dst)                  # (3, 2): columns for x', y'
    return sol.T.astype(np.float32)


def warp_affine(image, A, dsize=None):
    """Warp ``image`` by the 2x3 (or 3x3) affine ``A``, source -> output, black fill."""
    img = _as_image(image)
    A = np.asarray(A, dtype=np.float64)
    if A.shape == (3, 3):
        A = A[:2] / A[2, 2]
    A = A.reshape(2, 3)
    if dsize is None:
        dsize = (img.shape[1], img.shape[0])
    dsize = (int(dsize[0]), int(dsize[1]))
    out = cv2.warpAffine(img, A, dsize, flags=cv2.INTER_LINEAR,
                         borderMode=cv2.BORDER_CONSTANT, borderValue=0)
    return out.reshape((dsize[1], dsize[0]) + img.shape[2:])


# --------------------------------------------------------------------- ex6
def affine_lstsq(src, dst):
    """Least-squares affine 2x3 from N >= 3 pairs, via the 2N x 6 system.

    I stack all the x'-equations first and then all the y'-equations (same
    system, rows in another order) and solve with ``np.linalg.lstsq``.
    """
    src = np.asarray(src, dtype=np.float64).reshape(-1, 2)
    dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
    n = len(src)
    ones = np.ones(n)
    zeros = np.zeros((n, 3))
    top = np.hstack([np.column_stack([src, ones]), zeros])    # x' rows
    bottom = np.hstack([zeros, np.column_stack([src, ones])])  # y' rows
    M = np.vstack([top, bottom])
    b = np.concatenate([dst[:, 0], dst[:, 1]])
    params, *_ = np.linalg.lstsq(M, b, rcond=None)
    return params.reshape(2, 3)
