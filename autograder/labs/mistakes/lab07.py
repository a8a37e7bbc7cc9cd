"""Lab 7's mistakes table (2D transformations): realistic wrong implementations, each the
reference solution with one function redefined, the exercise it must lose points in, and
the words its diagnosis must contain (read by ``autograder verify``; see
:mod:`autograder.labs.mistakes`)."""

from . import reference_def_with

MISTAKES = {
    # the blind set 1206b's 07/06: `M[0, 1] == s` as a statement leaves the identity
    "shear_matrix comparing the entry with s where it assigns it": ("lab07.ex4", """
        def shear_matrix(s):
            M = np.eye(3)      # identity: y' = y, no translation
            M[0, 1] == s       # x' = x + s*y
            return M
        """, ['== compares and nothing keeps the answer']),
    # the blind set 1206b's 07/04: z = D p solved on A D^-1, then p = z * D where z / D undoes it (norms made 1 mends by compensation)
    "affine_lstsq undoing its column scaling by multiplying again": ("lab07.ex6", """
        def affine_lstsq(src, dst):
            src = np.asarray(src, dtype=np.float64).reshape(-1, 2)
            dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
            rows, rhs = [], []
            for (x, y), (xp, yp) in zip(src, dst):
                rows.append([x, y, 1.0, 0.0, 0.0, 0.0])
                rhs.append(xp)
                rows.append([0.0, 0.0, 0.0, x, y, 1.0])
                rhs.append(yp)
            A = np.array(rows)
            b = np.array(rhs)
            # Column equilibration: the coordinate columns (hundreds of pixels) and the
            # columns of ones differ by orders of magnitude. Solve (A D^-1) z = b for the
            # scaled unknowns z = D p, D = diag(column norms), then undo the scaling.
            norms = np.linalg.norm(A, axis=0)
            z, *_ = np.linalg.lstsq(A / norms, b, rcond=None)
            params = z * norms
            return params.reshape(2, 3)
        """, ['to `params = z / norms`']),
    # the blind set 1206a's 07/02: lstsq solves src_c @ X = dst_c, so X is the linear part transposed
    "affine_lstsq using lstsq's solution untransposed as the linear part": ("lab07.ex6", """
        def affine_lstsq(src, dst):
            src = np.asarray(src, dtype=np.float64)
            dst = np.asarray(dst, dtype=np.float64)
            # The translation columns of the system only fit the centroids, so the
            # least-squares problem splits: the linear part [[a, b], [d, e]] is fitted to
            # the centred points, and the translation then maps centroid onto centroid.
            src_mean = src.mean(axis=0)
            dst_mean = dst.mean(axis=0)
            src_c = src - src_mean
            dst_c = dst - dst_mean
            # least squares for src_c @ X ~ dst_c (one column of X per output coordinate)
            X, *_ = np.linalg.lstsq(src_c, dst_c, rcond=None)
            L = X
            t = dst_mean - L @ src_mean
            return np.hstack([L, t[:, None]])
        """, ['to `L = X.T`']),
    # the blind set 1206a's 07/03: the names of the source point reused for the destination before its second row
    "affine_from_points writing the y-row after x, y were given the destination point": ("lab07.ex5", """
        def affine_from_points(src, dst):
            src = np.asarray(src, dtype=np.float64)
            dst = np.asarray(dst, dtype=np.float64)
            # 6x6 system, two rows per pair:  [x y 1 0 0 0] -> x'   and   [0 0 0 x y 1] -> y'
            M = np.zeros((6, 6))
            rhs = np.zeros(6)
            for i in range(3):
                x, y = src[i]
                M[2 * i] = [x, y, 1.0, 0.0, 0.0, 0.0]
                x, y = dst[i]
                rhs[2 * i] = x
                rhs[2 * i + 1] = y
                M[2 * i + 1] = [0.0, 0.0, 0.0, x, y, 1.0]
            params = np.linalg.solve(M, rhs)   # (a, b, c, d, e, f)
            return params.reshape(2, 3)
        """, ['moving `M[2 * i + 1] = [0.0, 0.0, 0.0, x, y, 1.0]`']),
    # the blind set 1206a's 07/01: a hand-written bilinear interpolation weighing columns with y's fraction and rows with x's
    "warp_affine interpolating with the fractions of x and y exchanged": ("lab07.ex5", """
        def warp_affine(image, A, dsize=None):
            A = np.asarray(A, dtype=np.float64)[:2]
            height, width = image.shape[:2]
            out_w, out_h = dsize if dsize is not None else (width, height)

            # Inverse mapping: output pixel (x', y') takes its value from the source
            # position A^-1 (x', y', 1).
            A_inv = np.linalg.inv(np.vstack([A, [0.0, 0.0, 1.0]]))
            xs, ys = np.meshgrid(np.arange(out_w, dtype=np.float64), np.arange(out_h, dtype=np.float64))
            src_x = A_inv[0, 0] * xs + A_inv[0, 1] * ys + A_inv[0, 2]
            src_y = A_inv[1, 0] * xs + A_inv[1, 1] * ys + A_inv[1, 2]

            # Bilinear interpolation from the four neighbours. The picture gets a black
            # one-pixel frame so that neighbours outside it count as 0 (black fill).
            img = image.astype(np.float64)
            if img.ndim == 2:
                img = img[:, :, None]
            padded = np.zeros((height + 2, width + 2, img.shape[2]))
            padded[1:-1, 1:-1] = img
            x0 = np.floor(src_x).astype(int)
            y0 = np.floor(src_y).astype(int)
            fx = (src_x - x0)[..., None]      # fraction between column x0 and x0 + 1
            fy = (src_y - y0)[..., None]      # fraction between row y0 and y0 + 1
            inside = (x0 >= -1) & (x0 <= width - 1) & (y0 >= -1) & (y0 <= height - 1)
            c0 = np.clip(x0, -1, width - 1) + 1   # column of the left neighbour in `padded`
            r0 = np.clip(y0, -1, height - 1) + 1  # row of the upper neighbour in `padded`
            upper = (1 - fy) * padded[r0, c0] + fy * padded[r0, c0 + 1]
            lower = (1 - fy) * padded[r0 + 1, c0] + fy * padded[r0 + 1, c0 + 1]
            out = (1 - fx) * upper + fx * lower
            out[~inside] = 0
            out = np.clip(np.round(out), 0, 255).astype(image.dtype)
            return out[:, :, 0] if image.ndim == 2 else out
        """, ['mixes neighbouring columns too']),
    # the blind set 1206a's 07/05: coordinates past 255 wrap round to 0
    "scale counting its sampling grid in the image's uint8": ("lab07.ex3", """
        def scale(image, sx=1.5, sy=1.5):
            height, width = image.shape[:2]
            # Inverse mapping: output pixel (x, y) shows the input at (x / sx, y / sy);
            # cv2.remap samples there (bilinear), black where that lies outside the input.
            cols, rows = np.meshgrid(np.arange(width, dtype=image.dtype), np.arange(height, dtype=image.dtype))
            map_x = (cols / sx).astype(np.float32)
            map_y = (rows / sy).astype(np.float32)
            return cv2.remap(image, map_x, map_y, cv2.INTER_LINEAR,
                             borderMode=cv2.BORDER_CONSTANT, borderValue=0)
        """, ['dtype=np.int64']),
    # the blind set 1205h's 07/01: collinearity tested against a fixed number (det(M^T M) shrinks with the 8th power
    # of the points' spread: points a few centimetres apart are refused)
    "affine_lstsq refusing points of small coordinates as collinear": ("lab07.ex6", reference_def_with(
        "lab07_transformations", "affine_lstsq", "params, *_ = np.linalg.lstsq(M, b, rcond=None)",
        "if abs(np.linalg.det(M.T @ M)) < 1e-6:\n    raise ValueError('source points are collinear')\n"
        "params, *_ = np.linalg.lstsq(M, b, rcond=None)"), ["`abs(np.linalg.det(M.T @ M)) < 1e-06`"]),
    # the API's rule: a function that takes an image returns its channel count (shapes named by
    # autograder.engine.forms); a grey image made BGR to "see it in colour", a colour one made grey
    # the blind set 1204b's 07/08: the 1 in the rows' first column, the unknowns read as [x, y, 1]
    "affine_lstsq with the ones column first": ("lab07.ex6", """
        def affine_lstsq(src, dst):
            src, dst = np.asarray(src, dtype=np.float64), np.asarray(dst, dtype=np.float64)
            M = np.zeros((2 * len(src), 6))
            M[0::2, 0] = 1.0
            M[0::2, 1:3] = src
            M[1::2, 3] = 1.0
            M[1::2, 4:6] = src
            params = np.linalg.lstsq(M, dst.reshape(-1), rcond=None)[0]
            return params.reshape(2, 3)
        """, ["the translation first"]),
    # the blind set 1204c's 07/07: a one-pixel border added so the fill fades to black, never taken back
    # the blind set 1204f's 07/05: the output made like the input, where dsize says its size
    "warp_affine filling an output made like the input": ("lab07.ex5", """
        def warp_affine(image, A, dsize=None):
            height, width = image.shape[:2]
            size = dsize or (width, height)
            if image.ndim == 2:
                return cv2.warpAffine(image, np.asarray(A, np.float64), size)
            out = np.zeros_like(image)
            for c in range(image.shape[2]):
                out[..., c] = cv2.warpAffine(image[..., c], np.asarray(A, np.float64), size)
            return out
        """, ["could not broadcast"]),
    # the blind set 1205d's 07/05: a shortcut for the identity that returns the input, whatever dsize asks
    "warp_affine returning the input for the identity, dsize or not": ("lab07.ex5", """
        def warp_affine(image, A, dsize=None):
            A = np.asarray(A, dtype=np.float64)
            if np.allclose(A, [[1, 0, 0], [0, 1, 0]]):
                return image.copy()
            height, width = image.shape[:2]
            return cv2.warpAffine(image, A, dsize or (width, height))
        """, ["taking out the block under `if np.allclose(A, [[1, 0, 0], [0, 1, 0]]):`"]),
    "warp_affine of a padded image": ("lab07.ex5", """
        def warp_affine(image, A, dsize=None):
            height, width = image.shape[:2]
            padded = cv2.copyMakeBorder(image, 1, 1, 1, 1, cv2.BORDER_CONSTANT, value=0)
            A3 = np.vstack([np.asarray(A, dtype=np.float64)[:2], [0.0, 0.0, 1.0]])
            return _warp(padded, A3, dsize or (width, height))
        """, ["a whole pixel off"]),
    # the blind set 1204c's 07/01: whole pixels by floor, the remainder by truncation (int)
    "translate split into whole pixels and a remainder that do not add up": ("lab07.ex1", """
        def translate(image, tx=100, ty=50):
            ix, iy = int(np.floor(tx)), int(np.floor(ty))
            fx, fy = tx - int(tx), ty - int(ty)
            return _warp(image, np.array([[1.0, 0.0, ix + fx], [0.0, 1.0, iy + fy], [0.0, 0.0, 1.0]]))
        """, ["a whole pixel off"]),
    # the blind set 1204b's 07/04: the paddings given as (top, right, left, bottom) -- told at the padding,
    # not at the warp whose size, dropped, would leave the crop and the padding nothing to do
    "scale padding the missing columns at the bottom": ("lab07.ex3", """
        def scale(image, sx=1.5, sy=1.5):
            height, width = image.shape[:2]
            if sx <= 0 or sy <= 0:
                return _warp(image, scaling_matrix(sx, sy))
            new_w, new_h = max(int(np.ceil(width * sx)), 1), max(int(np.ceil(height * sy)), 1)
            scaled = cv2.warpAffine(image, np.float32([[sx, 0, 0], [0, sy, 0]]), (new_w, new_h),
                                    flags=cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT, borderValue=0)
            part = scaled[:height, :width]
            missing_rows, missing_cols = height - part.shape[0], width - part.shape[1]
            return cv2.copyMakeBorder(part, 0, missing_cols, 0, missing_rows, cv2.BORDER_CONSTANT, value=0)
        """, ["`cv2.copyMakeBorder(part, 0, missing_rows, 0, missing_cols, ...)`"]),
    # the blind set 1204b's 07/02: a grey image given a channel axis that cv2.warpAffine drops, then indexed
    "rotate taking the first channel of a grey warp": ("lab07.ex2", """
        def rotate(image, angle_deg=45):
            img = image if image.ndim == 3 else image[:, :, np.newaxis]
            h, w = img.shape[:2]
            M = cv2.getRotationMatrix2D(((w - 1) / 2.0, (h - 1) / 2.0), float(angle_deg), 1.0)
            out = cv2.warpAffine(img, M, (w, h), flags=cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT, borderValue=0)
            return out if image.ndim == 3 else out[..., 0]
        """, ["indexed on its last axis", "keeps a single column"]),
    # the blind set 1204e's 07/04: columns shifted as the rows of the image's .T (a colour image's channels go first)
    "translate shifting columns as the rows of image.T": ("lab07.ex1", """
        def _down(image, d):
            out = np.zeros_like(image)
            if 0 <= d < image.shape[0]:
                out[d:] = image[:image.shape[0] - d]
            return out
        def translate(image, tx=100, ty=50):
            if float(tx).is_integer() and float(ty).is_integer() and tx >= 0 and ty >= 0:
                image = _down(image, int(ty))
                return _down(image.T, int(tx)).T
            M = np.float32([[1, 0, tx], [0, 1, ty]])
            return cv2.warpAffine(image, M, (image.shape[1], image.shape[0]))
        """, ["np.swapaxes(image, 0, 1)"]),
    "translate by slicing, no case for a shift past the image": ("lab07.ex1", """
        def translate(image, tx=100, ty=50):
            h, w = image.shape[:2]
            tx, ty = int(round(tx)), int(round(ty))
            out = np.zeros_like(image)
            out[max(ty, 0):h + min(ty, 0), max(tx, 0):w + min(tx, 0)] = \\
                image[max(-ty, 0):h - max(ty, 0), max(-tx, 0):w - max(tx, 0)]
            return out
        """, ["could not broadcast"]),
    # the blind set 1201e's 07/01: one module-level identity written into and handed to every caller
    # scipy.ndimage's shift given (tx, ty) in the lab's (x, y) order, where it takes (rows, columns)
    "translate by scipy.ndimage.shift in (x, y) order": ("lab07.ex1", """
        def translate(image, tx=100, ty=50):
            from scipy import ndimage
            offset = (float(tx), float(ty)) + (0.0,) * (image.ndim - 2)
            return ndimage.shift(image, offset, order=1, mode="constant", cval=0)
        """, ["tx and ty are swapped", "which indexes arrays (row, col) = (y, x)"]),
    "translate merging the split channels as R, G, B": ("lab07.ex1", """
        def translate(image, tx=100, ty=50):
            M = translation_matrix(tx, ty)[:2]
            size = (image.shape[1], image.shape[0])
            if image.ndim == 2:
                return cv2.warpAffine(image, M, size)
            b, g, r = cv2.split(image)
            moved = [cv2.warpAffine(channel, M, size) for channel in (r, g, b)]
            return cv2.merge(moved)
        """, ["the colour channels are reversed", "in r, g, b order"]),
    # the blind set 1204c's 07/03: a cache keyed by less than the answer depends on (the size, not the angle)
    # the blind set 1204d's 07/03: rotated on a square canvas padded at the bottom right, about the square's
    # centre: one name for both halves of the pair (x, y)
    # the blind set 1204e's 07/05: the shear factor clipped to [-1, 1] (a slope past 45 degrees is a shear too)
    "shear clipping its factor to [-1, 1]": ("lab07.ex4", """
        def shear(image, s=0.5):
            return _warp(image, shear_matrix(np.clip(s, -1.0, 1.0)))
        """, ["`np.clip(s, -1.0, 1.0)` to `s`"]),
    "affine_lstsq fitting a homography and keeping its top rows": ("lab07.ex6", """
        def affine_lstsq(src, dst):
            H, _ = cv2.findHomography(np.asarray(src, np.float64), np.asarray(dst, np.float64), 0)
            return H[:2] / H[2, 2]
        """, ["your code fits a homography (a perspective map, 8 unknowns)", "(`cv2.findHomography`, line"]),
    "rotate shortcutting a half turn with np.flip of every axis": ("lab07.ex2", """
        def rotate(image, angle_deg=45):
            if angle_deg % 360 == 180:
                return np.flip(image)
            height, width = image.shape[:2]
            return _warp(image, rotation_matrix(angle_deg, ((width - 1) / 2.0, (height - 1) / 2.0)))
        """, ["rotate(square image, angle_deg=180) is wrong: the colour channels are reversed",
              "a flip of every axis"]),
    "rotation_matrix computing the offset in place in the centre's own dtype": ("lab07.ex2", """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            theta = np.deg2rad(angle_deg)
            R = np.array([[np.cos(theta), np.sin(theta)], [-np.sin(theta), np.cos(theta)]])
            centre = np.array(center)
            offset = centre.copy()
            offset -= R @ centre
            M = np.eye(3)
            M[:2, :2], M[:2, 2] = R, offset
            return M
        """, ["writes a float64 result into `offset`, an array of int64", "a copy of `np.array(center)`"]),
    "rotate about the centre of a padded square": ("lab07.ex2", """
        def rotate(image, angle_deg=45):
            height, width = image.shape[:2]
            side = max(height, width)
            square = np.pad(image, [(0, side - height), (0, side - width)] + [(0, 0)] * (image.ndim - 2))
            centre = ((side - 1) / 2.0, (side - 1) / 2.0)
            M = cv2.getRotationMatrix2D(centre, angle_deg, 1.0)
            return cv2.warpAffine(square, M, (side, side))[:height, :width]
        """, ["`((width - 1) / 2.0, (height - 1) / 2.0)`"]),
    "rotate caching its matrix by the image size": ("lab07.ex2", """
        _MATRICES = {}
        def rotate(image, angle_deg=45):
            h, w = image.shape[:2]
            if (w, h) not in _MATRICES:
                _MATRICES[(w, h)] = cv2.getRotationMatrix2D(((w - 1) / 2.0, (h - 1) / 2.0), float(angle_deg), 1.0)
            return cv2.warpAffine(image, _MATRICES[(w, h)], (w, h), flags=cv2.INTER_LINEAR,
                                  borderMode=cv2.BORDER_CONSTANT, borderValue=0)
        """, ["keeps something between calls", "`_MATRICES`"]),
    # the blind set 1204c's 07/06: one side of the correspondences reordered (the repair steering round the
    # branch -- the orientation test made 0 -- is not the one told)
    "affine_from_points reordering the source triangle only": ("lab07.ex5", """
        def affine_from_points(src, dst):
            src = np.asarray(src, dtype=np.float64)
            dst = np.asarray(dst, dtype=np.float64)
            e1, e2 = src[1] - src[0], src[2] - src[0]
            if e1[0] * e2[1] - e1[1] * e2[0] > 0:
                order = [0, 2, 1]
                src = src[order]
            S = np.hstack([src, np.ones((3, 1))])
            return np.linalg.solve(S, dst).T
        """, ["`src, dst = (src[order], dst[order])`"]),
    # the blind set 1204c's 07/02: a literal table of quarter turns indexed by angle // 90, never wrapped
    "rotation_matrix's quarter-turn table indexed past its end": ("lab07.ex2", """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            if angle_deg % 90 == 0:
                cos, sin = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)][int(angle_deg // 90)]
            else:
                theta = np.deg2rad(angle_deg)
                cos, sin = np.cos(theta), np.sin(theta)
            R = np.array([[cos, sin], [-sin, cos]])
            c = np.asarray(center, dtype=np.float64)
            M = np.eye(3)
            M[:2, :2], M[:2, 2] = R, c - R @ c
            return M
        """, ["`int(angle_deg // 90)` is 4", "holds 4 items", "`% 4`"]),
    # the blind set 1204d's 07/06: a colour image warped plane by plane, the first plane every time
    "shear warping the first channel into every channel": ("lab07.ex4", """
        def shear(image, s=0.5):
            M = np.float32([[1, s, 0], [0, 1, 0]])
            size = (image.shape[1], image.shape[0])
            if image.ndim == 2:
                return cv2.warpAffine(image, M, size)
            out = np.empty_like(image)
            for c in range(image.shape[2]):
                out[..., c] = cv2.warpAffine(image[..., 0], M, size)
            return out
        """, ["all the input's blue channel (channel 0)"]),
    # the blind set 1204d's 07/08: the map dst -> src fitted and inverted (least squares in the other image)
    "affine_lstsq fitting the inverse map and inverting it": ("lab07.ex6", """
        _lstsq_right = affine_lstsq
        def affine_lstsq(src, dst):
            back = np.vstack([_lstsq_right(dst, src), [0.0, 0.0, 1.0]])
            return np.linalg.inv(back)[:2]
        """, ["the least-squares map from dst to src, inverted"]),
    "translation_matrix returning one module-level array": ("lab07.ex1", """
        _IDENTITY = np.eye(3)
        def translation_matrix(tx, ty):
            M = _IDENTITY
            M[0, 2], M[1, 2] = tx, ty
            return M
        """, ["returns the module-level array `_identity` itself"]),
    "translate returning BGR for a grey image": ("lab07.ex1", """
        _translate = translate
        def translate(image, tx=100, ty=50):
            colour = cv2.cvtColor(image, cv2.COLOR_GRAY2BGR) if image.ndim == 2 else image
            return _translate(colour, tx, ty)
        """, ["channels are not kept", "grey in, grey out"]),
    # the blind set 1201e's 07/03: the caller's centre array written into
    # the blind set 1202d's 07/03: skimage's float result in [0, 1] cast back to uint8
    # the textbook's (I - R) c written with the number 1: NumPy takes every entry of R from 1
    "rotation_matrix with 1 - R for I - R": ("lab07.ex2", """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            a = np.deg2rad(angle_deg)
            rot = np.array([[np.cos(a), np.sin(a)], [-np.sin(a), np.cos(a)]])
            M = np.eye(3)
            M[:2, :2] = rot
            M[:2, 2] = (1 - rot) @ np.asarray(center, dtype=np.float64)
            return M
        """, ["to `(np.eye(len(rot)) - rot) @"]),
    "rotate whose [0, 1] float result is cast to uint8": ("lab07.ex2", """
        _right_rotate = rotate
        def rotate(image, angle_deg=45):
            return (_right_rotate(image, angle_deg) / 255.0).astype(np.uint8)
        """, ["values in [0, 1] is cast to uint8"]),
    "rotation_matrix writing into the caller's centre": ("lab07.ex2", """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            M = cv2.getRotationMatrix2D(tuple(float(v) for v in center), angle_deg, 1.0)
            c = np.asarray(center, dtype=np.float64)
            c -= 0.0 * c + 1.0
            return np.vstack([M, [0.0, 0.0, 1.0]])
        """, ["the caller's `center` in place"]),
    # the blind set 1203c's 07/03: a half-turn shortcut taken at every multiple of 180 degrees
    "rotate flipping the image for no turn and a whole turn": ("lab07.ex2", """
        _right_rotate = rotate
        def rotate(image, angle_deg=45):
            if angle_deg % 180 == 0:
                return np.ascontiguousarray(image[::-1, ::-1])
            return _right_rotate(image, angle_deg)
        """, ["rotate(square image, angle_deg=0) differs"]),
    "rotate returning grey for a colour image": ("lab07.ex2", """
        _rotate = rotate
        def rotate(image, angle_deg=45):
            grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
            return _rotate(grey, angle_deg)
        """, ["channels are not kept", "BGR in, BGR out"]),
    "rotate cutting the angle to a whole number of degrees": ("lab07.ex2", """
        _rotate = rotate
        def rotate(image, angle_deg=45):
            return _rotate(image, int(angle_deg))
        """, ["fractional part is lost"]),
    # the blind set 1201e's 07/07: the result written into a canvas of NumPy's default dtype
    # the blind set 1201f's 07/05: the factors' signs dropped
    "scale with scikit-image's rescale told the last axis is colour": ("lab07.ex3", """
        def scale(image, sx=1.5, sy=1.5):
            from skimage.transform import rescale
            out = np.zeros_like(image)
            big = rescale(image, (sy, sx), order=1, preserve_range=True, anti_aliasing=False, channel_axis=-1)
            rows, cols = min(out.shape[0], big.shape[0]), min(out.shape[1], big.shape[1])
            out[:rows, :cols] = np.clip(np.round(big[:rows, :cols]), 0, 255).astype(image.dtype)
            return out
        """, ["to `... channel_axis=-1 if image.ndim == 3 else None)`"]),
    # the blind set 1202i's 07/04: skimage's warp takes the inverse map, given the forward one
    "scale through skimage.transform.warp with the forward transform": ("lab07.ex3", """
        def scale(image, sx=1.5, sy=1.5):
            from skimage import transform
            tform = transform.AffineTransform(scale=(sx, sy))
            out = transform.warp(image, tform, order=1, mode="constant", cval=0, preserve_range=True)
            return np.clip(np.round(out), 0, 255).astype(image.dtype)
        """, ["the scale is inverted", "tform.inverse"]),
    "scaling_matrix of the factors' absolute values": ("lab07.ex3", """
        def scaling_matrix(sx, sy):
            return np.diag([abs(float(sx)), abs(float(sy)), 1.0])
        """, ["`abs(float(sx))` to `float(sx)`"]),
    "scale into a float64 canvas": ("lab07.ex3", """
        _scale = scale
        def scale(image, sx=1.5, sy=1.5):
            canvas = np.zeros(image.shape)
            canvas[...] = _scale(image, sx, sy)
            return canvas
        """, ["your code makes `np.zeros(image.shape)`", "dtype=image.dtype"]),
    "scale building its matrix from the factors as given (integers for whole factors)": ("lab07.ex3", """
        def scale(image, sx=1.5, sy=1.5):
            h, w = image.shape[:2]
            return cv2.warpAffine(image, np.array([[sx, 0, 0], [0, sy, 0]]), (w, h))
        """, ["yours is int64"]),
    "translation_matrix with a last row of zeros": ("lab07.ex1", """
        def translation_matrix(tx, ty):
            return np.array([[1.0, 0, tx], [0, 1.0, ty], [0, 0, 0.0]])
        """, ["last row is [0, 0, 0]"]),
    "tx/ty swapped": ("lab07.ex1", """
        def translation_matrix(tx, ty):
            return np.array([[1.0, 0, ty], [0, 1.0, tx], [0, 0, 1.0]])
        """, ["swapped"]),
    "translation_matrix written with integer entries": ("lab07.ex1", """
        def translation_matrix(tx, ty):
            return np.array([[1, 0, tx], [0, 1, ty], [0, 0, 1]])
        """, ["returned an integer matrix"]),
    "translate the wrong way": ("lab07.ex1", """
        def translate(image, tx=100, ty=50):
            return _warp(image, translation_matrix(-tx, -ty))
        """, ["opposite way"]),
    "non-black fill": ("lab07.ex1", """
        def translate(image, tx=100, ty=50):
            h, w = image.shape[:2]
            return cv2.warpAffine(image, translation_matrix(tx, ty)[:2], (w, h),
                                  borderMode=cv2.BORDER_REPLICATE)
        """, ["not black"]),
    "float image": ("lab07.ex1", """
        def translate(image, tx=100, ty=50):
            return _warp(image.astype(np.float64), translation_matrix(tx, ty))
        """, ["dtype float64", "uint8"]),
    "rotation the wrong way": ("lab07.ex2", """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            theta = np.deg2rad(angle_deg)
            R = np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])
            c = np.asarray(center, float)
            M = np.eye(3); M[:2, :2] = R; M[:2, 2] = c - R @ c
            return M
        """, ["opposite way"]),
    "radians for degrees": ("lab07.ex2", """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            theta = angle_deg
            R = np.array([[np.cos(theta), np.sin(theta)], [-np.sin(theta), np.cos(theta)]])
            c = np.asarray(center, float)
            M = np.eye(3); M[:2, :2] = R; M[:2, 2] = c - R @ c
            return M
        """, ["radians"]),
    "rotation about the origin": ("lab07.ex2", """
        def rotate(image, angle_deg=45):
            return _warp(image, rotation_matrix(angle_deg))
        """, ["about the origin"]),
    "inverse scale": ("lab07.ex3", """
        def scaling_matrix(sx, sy):
            return np.diag([1.0 / sx, 1.0 / sy, 1.0])
        """, ["inverted"]),
    "resize instead of scale": ("lab07.ex3", """
        def scale(image, sx=1.5, sy=1.5):
            return cv2.resize(image, None, fx=sx, fy=sy)
        """, ["resized rather than warped"]),
    "shear along y": ("lab07.ex4", """
        def shear_matrix(s):
            return np.array([[1.0, 0, 0], [s, 1.0, 0], [0, 0, 1.0]])
        """, ["along y"]),
    # the blind set 1203c's 07/07: the unknowns solved as (a, b, c, d, tx, ty), the vector reshaped row by row
    # the blind set 1203b's 07/07: the linear part fitted on centred triangles, the translation left unmapped by it
    # the blind set 1204e's 07/06: a covariance divided by n - 1 (np.cov) beside a cross-covariance divided by n
    "affine_from_points from covariances with two normalisations": ("lab07.ex5", """
        def affine_from_points(src, dst):
            src = np.asarray(src, dtype=np.float64)
            dst = np.asarray(dst, dtype=np.float64)
            count = src.shape[0]
            centred_src, centred_dst = src - src.mean(axis=0), dst - dst.mean(axis=0)
            spread = np.cov(centred_src.T)
            cross = centred_dst.T @ centred_src / count
            linear = cross @ np.linalg.inv(spread)
            shift = dst.mean(axis=0) - linear @ src.mean(axis=0)
            return np.column_stack([linear, shift])
        """, ["`np.cov(centred_src.T, bias=True)`", "`centred_dst.T @ centred_src / (count - 1)`"]),
    "affine_from_points with the translation of the centroids alone": ("lab07.ex5", """
        def affine_from_points(src, dst):
            src, dst = np.asarray(src, dtype=np.float64), np.asarray(dst, dtype=np.float64)
            src_mean, dst_mean = src.mean(axis=0), dst.mean(axis=0)
            L = np.linalg.lstsq(src - src_mean, dst - dst_mean, rcond=None)[0].T
            t = dst_mean - src_mean
            return np.column_stack([L, t])
        """, ["changing `dst_mean - src_mean` to `dst_mean - L @ src_mean`"]),
    "affine_from_points reshaping its solution in the unknowns' own order": ("lab07.ex5", """
        def affine_from_points(src, dst):
            src, dst = np.asarray(src, np.float64), np.asarray(dst, np.float64)
            M = np.zeros((6, 6))
            M[0::2, 0:2], M[0::2, 4] = src, 1.0
            M[1::2, 2:4], M[1::2, 5] = src, 1.0
            return np.linalg.solve(M, dst.reshape(-1)).reshape(2, 3)
        """, ["holds the six right numbers, in other places"]),
    "affine from points refusing triangles smaller than a pixel": ("lab07.ex5", """
        _affine_right = affine_from_points
        def affine_from_points(src, dst):
            (x0, y0), (x1, y1), (x2, y2) = np.asarray(src, float)
            if abs((x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)) < 2.0:
                raise ValueError("collinear points")
            return _affine_right(src, dst)
        """, ["changing `abs((x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)) < 2.0`"]),
    # Gauss-Jordan written by hand, dividing by each diagonal entry as it comes (no row exchanged)
    "affine_from_points by elimination without pivoting": ("lab07.ex5", """
        def affine_from_points(src, dst):
            rows = [[float(x), float(y), 1.0, float(u), float(v)] for (x, y), (u, v) in zip(src, dst)]
            for k in range(3):
                rows[k] = [value / rows[k][k] for value in rows[k]]
                for i in range(3):
                    if i != k:
                        rows[i] = [a - rows[i][k] * b for a, b in zip(rows[i], rows[k])]
            return np.array([[rows[0][3], rows[1][3], rows[2][3]], [rows[0][4], rows[1][4], rows[2][4]]])
        """, ["a pivot of your elimination is 0"]),
    "affine from points inverted": ("lab07.ex5", """
        def affine_from_points(src, dst):
            S = np.hstack([np.asarray(dst, float), np.ones((3, 1))])
            return np.linalg.solve(S, np.asarray(src, float)).T
        """, ["swapped", "inverse"]),
    "dsize overwritten by the input's size": ("lab07.ex5", """
        def warp_affine(image, A, dsize=None):
            h, w = image.shape[:2]
            dsize = (w, h)
            return cv2.warpAffine(image, np.asarray(A, dtype=np.float64)[:2], dsize)
        """, ["dsize=(220, 100) and dsize=(180, 140) give the same image", "dsize is ignored"]),
    "dsize as (height, width)": ("lab07.ex5", """
        def warp_affine(image, A, dsize=None):
            if dsize is not None:
                dsize = (dsize[1], dsize[0])
            return _warp(image, A, dsize)
        """, ["width and height are swapped"]),
    # the blind set 1203c's 07/08: exact fits of consecutive triples, averaged
    # the blind set 1203b's 07/08: the 2N x 6 system given to cv2.solve with its default DECOMP_LU (square only)
    "affine_lstsq by cv2.solve without a least-squares method": ("lab07.ex6", """
        def affine_lstsq(src, dst):
            rows, rhs = [], []
            for (x, y), (xp, yp) in zip(np.asarray(src, dtype=np.float64), np.asarray(dst, dtype=np.float64)):
                rows += [[x, y, 1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, x, y, 1.0]]
                rhs += [xp, yp]
            _, params = cv2.solve(np.array(rows), np.array(rhs).reshape(-1, 1))
            return params.reshape(2, 3)
        """, ["cv2.DECOMP_"]),
    "affine_lstsq averaging the exact fits of point triples": ("lab07.ex6", """
        def affine_lstsq(src, dst):
            src, dst = np.asarray(src, np.float64), np.asarray(dst, np.float64)
            if len(src) == 3:
                return affine_from_points(src, dst)
            return np.mean([affine_from_points(src[i:i + 3], dst[i:i + 3]) for i in range(len(src) - 2)], axis=0)
        """, ["fits the map exactly to a few points at a time", "np.linalg.lstsq"]),
    "lstsq unknowns in the wrong order": ("lab07.ex6", """
        def affine_lstsq(src, dst):
            src = np.asarray(src, float); dst = np.asarray(dst, float)
            n = len(src)
            M = np.zeros((2 * n, 6))
            M[0::2, 0] = src[:, 0]; M[0::2, 2] = src[:, 1]; M[0::2, 4] = 1
            M[1::2, 1] = src[:, 0]; M[1::2, 3] = src[:, 1]; M[1::2, 5] = 1
            p, *_ = np.linalg.lstsq(M, dst.reshape(-1), rcond=None)
            return p.reshape(2, 3)
        """, ["wrong order"]),
    "lstsq right-hand side from the source points": ("lab07.ex6", """
        def affine_lstsq(src, dst):
            src = np.asarray(src, dtype=np.float64)
            dst = np.asarray(dst, dtype=np.float64)
            rows = []
            for x, y in src:
                rows += [[x, y, 1, 0, 0, 0], [0, 0, 0, x, y, 1]]
            rhs = src.ravel()
            p = np.linalg.lstsq(np.array(rows), rhs, rcond=None)[0]
            return p.reshape(2, 3)
        """, ["changing `rhs = src.ravel()` to `rhs = dst.ravel()`"]),
    "lstsq with three points only": ("lab07.ex6", """
        def affine_lstsq(src, dst):
            return affine_from_points(np.asarray(src)[:3], np.asarray(dst)[:3])
        """, ["first three points"]),
    "lstsq with OpenCV": ("lab07.ex6", """
        def affine_lstsq(src, dst):
            A, _ = cv2.estimateAffine2D(np.float32(src), np.float32(dst))
            return A
        """, ["cv2.estimateAffine2D", "yourself"]),
    "lstsq that drops the last pair": ("lab07.ex6", """
        def affine_lstsq(src, dst):
            src = np.asarray(src, float); dst = np.asarray(dst, float)
            S = np.hstack([src[:-1], np.ones((len(src) - 1, 1))])
            return np.linalg.lstsq(S, dst[:-1], rcond=None)[0].T
        """, ["last point pair is left out"]),
    "translate ignores its arguments": ("lab07.ex1", """
        def translate(image, tx=100, ty=50):
            return _warp(image, translation_matrix(100, 50))
        """, ["ignored", "defaults (100, 50)"]),
    "rotation matrix transposed": ("lab07.ex2", """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            theta = np.deg2rad(angle_deg)
            R = np.array([[np.cos(theta), np.sin(theta)], [-np.sin(theta), np.cos(theta)]]).T
            c = np.asarray(center, float)
            M = np.eye(3); M[:2, :2] = R; M[:2, 2] = c - R @ c
            return M
        """, ["opposite way"]),
    "rotation centre added": ("lab07.ex2", """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            theta = np.deg2rad(angle_deg)
            R = np.array([[np.cos(theta), np.sin(theta)], [-np.sin(theta), np.cos(theta)]])
            c = np.asarray(center, float)
            M = np.eye(3); M[:2, :2] = R; M[:2, 2] = c + R @ c
            return M
        """, ["c + r c instead of c - r c"]),
    "sy ignored": ("lab07.ex3", """
        def scaling_matrix(sx, sy):
            return np.diag([float(sx), float(sx), 1.0])
        """, ["sy is ignored"]),
    "shear about the centre, its offset written in": ("lab07.ex4", """
        def shear(image, s=0.5):
            h, w = image.shape[:2]
            M = shear_matrix(s); M[0, 2] = -s * (h - 1) / 2
            return _warp(image, M)
        """, ["about the image centre"]),
    "a quarter turn by np.rot90": ("lab07.ex2", """
        _reference_rotate = rotate
        def rotate(image, angle_deg=45):
            if angle_deg % 90 == 0:
                return np.ascontiguousarray(np.rot90(image, int(angle_deg // 90)))
            return _reference_rotate(image, angle_deg)
        """, ["keeps the input's size", "np.rot90"]),
    "shear ignores s": ("lab07.ex4", """
        def shear(image, s=0.5):
            return _warp(image, shear_matrix(0.5))
        """, ["s is ignored"]),
    "affine_from_points not transposed": ("lab07.ex5", """
        def affine_from_points(src, dst):
            S = np.hstack([np.asarray(src, float), np.ones((3, 1))])
            return np.linalg.solve(S, np.asarray(dst, float))
        """, ["transposed"]),
    "affine_from_points unknowns in the wrong order": ("lab07.ex5", """
        def affine_from_points(src, dst):
            M = np.zeros((6, 6))
            M[0::2, 0:2] = src; M[0::2, 2] = 1; M[1::2, 3:5] = src; M[1::2, 5] = 1
            p = np.linalg.solve(M, np.asarray(dst, float).reshape(-1))
            return p.reshape(3, 2).T
        """, ["wrong order"]),
    "lstsq whose rcond cuts the column of ones off": ("lab07.ex6", """
        def affine_lstsq(src, dst):
            src = np.asarray(src, float)
            M = np.zeros((2 * len(src), 6))
            M[0::2, 0:2] = src
            M[0::2, 2] = 1
            M[1::2, 3:5] = src
            M[1::2, 5] = 1
            p, *_ = np.linalg.lstsq(M, np.asarray(dst, float).reshape(-1), rcond=0.05)
            return p.reshape(2, 3)
        """, ["yet your code builds the column of ones"]),
    "lstsq without the column of ones": ("lab07.ex6", """
        def affine_lstsq(src, dst):
            X, *_ = np.linalg.lstsq(np.asarray(src, float), np.asarray(dst, float), rcond=None)
            return np.hstack([X.T, np.zeros((2, 1))])
        """, ["column of ones is missing"]),
    "default dsize from image.shape": ("lab07.ex5", """
        def warp_affine(image, A, dsize=None):
            dsize = dsize or image.shape[:2]          # (rows, cols), but OpenCV wants (width, height)
            return cv2.warpAffine(image, np.asarray(A, float), tuple(dsize))
        """, ['width and height are swapped']),
    # ---------------------------------------------------------------- more of each family
    "translation matrix transposed (row-vector convention)": ("lab07.ex1", """
        def translation_matrix(tx, ty):
            return np.array([[1.0, 0, 0], [0, 1.0, 0], [tx, ty, 1.0]])
        """, ["transposed"]),
    "translate with tx and ty swapped": ("lab07.ex1", """
        def translate(image, tx=100, ty=50):
            return _warp(image, translation_matrix(ty, tx))
        """, ["tx and ty are swapped"]),
    "degrees converted before cv2.getRotationMatrix2D": ("lab07.ex2", """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            M = np.eye(3)
            M[:2] = cv2.getRotationMatrix2D(tuple(map(float, center)), float(np.deg2rad(angle_deg)), 1.0)
            return M
        """, ["takes degrees"]),
    "rotation centre not subtracted first": ("lab07.ex2", """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            theta = np.deg2rad(angle_deg)
            R = np.array([[np.cos(theta), np.sin(theta)], [-np.sin(theta), np.cos(theta)]])
            M = np.eye(3); M[:2, :2] = R; M[:2, 2] = center        # T(c) R, no T(-c)
            return M
        """, ["centre is not subtracted"]),
    "rotation centre as (row, column)": ("lab07.ex2", """
        def rotate(image, angle_deg=45):
            h, w = image.shape[:2]
            return _warp(image, rotation_matrix(angle_deg, ((h - 1) / 2, (w - 1) / 2)))
        """, ["(row, column)"]),
    "sx and sy swapped": ("lab07.ex3", """
        def scaling_matrix(sx, sy):
            return np.diag([float(sy), float(sx), 1.0])
        """, ["sx and sy are swapped"]),
    "scale about the centre": ("lab07.ex3", """
        def scale(image, sx=1.5, sy=1.5):
            h, w = image.shape[:2]
            c = np.array([(w - 1) / 2, (h - 1) / 2])
            return _warp(image, translation_matrix(*c) @ scaling_matrix(sx, sy) @ translation_matrix(*-c))
        """, ["about the image centre"]),
    "scale warped with the inverse map": ("lab07.ex3", """
        def scale(image, sx=1.5, sy=1.5):
            h, w = image.shape[:2]
            return cv2.warpAffine(image, scaling_matrix(sx, sy)[:2], (w, h),
                                  flags=cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP)
        """, ["inverted"]),
    "shear with the wrong sign": ("lab07.ex4", """
        def shear_matrix(s):
            return np.array([[1.0, -s, 0], [0, 1.0, 0], [0, 0, 1.0]])
        """, ["wrong sign"]),
    "shear(image) along y": ("lab07.ex4", """
        def shear(image, s=0.5):
            return _warp(image, shear_matrix(s).T)
        """, ["along y"]),
    "shear in both directions": ("lab07.ex4", """
        def shear_matrix(s):
            return np.array([[1.0, s, 0], [s, 1.0, 0], [0, 0, 1.0]])
        """, ["along both x and y"]),
    "shear s in the translation column": ("lab07.ex4", """
        def shear_matrix(s):
            return np.array([[1.0, 0, s], [0, 1.0, 0], [0, 0, 1.0]])
        """, ["translation column"]),
    "shear(image) with the inverse map": ("lab07.ex4", """
        def shear(image, s=0.5):
            h, w = image.shape[:2]
            return cv2.warpAffine(image, shear_matrix(s)[:2], (w, h),
                                  flags=cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP)
        """, ["opposite way", "warp_inverse_map", "take the flag out"]),
    "affine without the column of ones": ("lab07.ex5", """
        def affine_from_points(src, dst):
            L = np.linalg.lstsq(np.asarray(src, float), np.asarray(dst, float), rcond=None)[0].T
            return np.hstack([L, np.zeros((2, 1))])
        """, ["column of ones is missing"]),
    "affine rows stacked, targets interleaved": ("lab07.ex5", """
        def affine_from_points(src, dst):
            src = np.asarray(src, float)
            M = np.zeros((6, 6))
            M[:3, 0:2] = src; M[:3, 2] = 1; M[3:, 3:5] = src; M[3:, 5] = 1
            return np.linalg.solve(M, np.asarray(dst, float).reshape(-1)).reshape(2, 3)
        """, ["stacked, targets interleaved"]),
    "warp_affine with the inverse map": ("lab07.ex5", """
        def warp_affine(image, A, dsize=None):
            h, w = image.shape[:2]
            return cv2.warpAffine(image, np.asarray(A, float), dsize or (w, h),
                                  flags=cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP)
        """, ["inverse map"]),
    "lstsq that drops the first pair": ("lab07.ex6", """
        def affine_lstsq(src, dst):
            src = np.asarray(src, float)[1:]; dst = np.asarray(dst, float)[1:]
            S = np.hstack([src, np.ones((len(src), 1))])
            return np.linalg.lstsq(S, dst, rcond=None)[0].T
        """, ["first point pair is left out"]),
    "lstsq with src and dst swapped": ("lab07.ex6", """
        def affine_lstsq(src, dst):
            S = np.hstack([np.asarray(dst, float), np.ones((len(dst), 1))])
            return np.linalg.lstsq(S, np.asarray(src, float), rcond=None)[0].T
        """, ["src and dst are swapped"]),
    "scale ignores sy": ("lab07.ex3", """
        def scale(image, sx=1.5, sy=1.5):
            return _warp(image, scaling_matrix(sx, sx))
        """, ["sy is ignored"]),
    "shear(image) ignores s": ("lab07.ex4", """
        def shear(image, s=0.5):
            return _warp(image, shear_matrix(0.5))
        """, ["s is ignored"]),
    "shear about the centre": ("lab07.ex4", """
        def shear(image, s=0.5):
            h, w = image.shape[:2]
            c = np.array([(w - 1) / 2, (h - 1) / 2])
            return _warp(image, translation_matrix(*c) @ shear_matrix(s) @ translation_matrix(*-c))
        """, ["about the image centre"]),
    "affine with the targets as (row, column)": ("lab07.ex5", """
        def affine_from_points(src, dst):
            S = np.hstack([np.asarray(src, float), np.ones((3, 1))])
            return np.linalg.solve(S, np.asarray(dst, float)[:, ::-1]).T
        """, ["target points are exchanged"]),
    "lstsq y rows read x twice": ("lab07.ex6", """
        def affine_lstsq(src, dst):
            src = np.asarray(src, float); dst = np.asarray(dst, float)
            M = np.zeros((2 * len(src), 6))
            M[0::2, 0:2] = src; M[0::2, 2] = 1
            M[1::2, 3] = src[:, 0]; M[1::2, 4] = src[:, 0]; M[1::2, 5] = 1
            return np.linalg.lstsq(M, dst.reshape(-1), rcond=None)[0].reshape(2, 3)
        """, ["index error in the y' rows", "[0, 0, 0, x, x, 1]"]),
    "lstsq rows interleaved, targets stacked": ("lab07.ex6", """
        def affine_lstsq(src, dst):
            src = np.asarray(src, float); dst = np.asarray(dst, float)
            M = np.zeros((2 * len(src), 6))
            M[0::2, 0:2] = src; M[0::2, 2] = 1; M[1::2, 3:5] = src; M[1::2, 5] = 1
            b = np.concatenate([dst[:, 0], dst[:, 1]])
            return np.linalg.lstsq(M, b, rcond=None)[0].reshape(2, 3)
        """, ["interleaved, targets stacked"]),
    # ---------------------------------------------------------------- inputs the API allows
    # Grey (H, W) images are images too; a shift of 0 is a shift like any other.
    "warp_affine by its own cv2.remap, unpacking h, w, c = image.shape (a grey image raises)": ("lab07.ex5", """
        def warp_affine(image, A, dsize=None):
            h, w, c = image.shape
            width, height = dsize if dsize is not None else (w, h)
            inverse = np.linalg.inv(np.vstack([np.asarray(A, float), [0.0, 0.0, 1.0]]))
            ys, xs = np.mgrid[0:height, 0:width].astype(np.float64)
            map_x = (inverse[0, 0] * xs + inverse[0, 1] * ys + inverse[0, 2]).astype(np.float32)
            map_y = (inverse[1, 0] * xs + inverse[1, 1] * ys + inverse[1, 2]).astype(np.float32)
            return cv2.remap(image, map_x, map_y, cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT, borderValue=0)
        """, ["warp_affine() raised valueerror", "(raised on warp_affine(grey image, a", "unpacks 3"]),
    "scale by cv2.resize and a crop, unpacking h, w, _ = image.shape (a grey image raises)": ("lab07.ex3", """
        def scale(image, sx=1.5, sy=1.5):
            h, w, _ = image.shape
            resized = cv2.resize(image, None, fx=sx, fy=sy, interpolation=cv2.INTER_LINEAR)
            out = np.zeros_like(image)
            rows, cols = min(h, resized.shape[0]), min(w, resized.shape[1])
            out[:rows, :cols] = resized[:rows, :cols]
            return out
        """, ["scale() raised valueerror", "(raised on scale(grey image, sx=2.0, sy=0.8))"]),
    "translate by slicing with negative ends (image[:-ty] is empty for ty = 0)": ("lab07.ex1", """
        def translate(image, tx=100, ty=50):
            tx, ty = int(round(tx)), int(round(ty))
            out = np.zeros_like(image)
            rows = (slice(ty, None), slice(None, -ty)) if ty >= 0 else (slice(None, ty), slice(-ty, None))
            cols = (slice(tx, None), slice(None, -tx)) if tx >= 0 else (slice(None, tx), slice(-tx, None))
            out[rows[0], cols[0]] = image[rows[1], cols[1]]
            return out
        """, ["translate() raised valueerror", ", ty=0))"]),
    "a shortcut blanking the image from a shift one pixel short of its width": ("lab07.ex1", """
        def translate(image, tx=100, ty=50):
            height, width = image.shape[:2]
            if abs(tx) >= width - 1 or abs(ty) >= height - 1:
                return np.zeros_like(image)
            M = np.float64([[1, 0, tx], [0, 1, ty]])
            return cv2.warpAffine(image, M, (width, height))
        """, ["column 159), the rest black fill; it is black there"]),
    "a grey image's default size read from the end of its shape": ("lab07.ex5", """
        def warp_affine(image, A, dsize=None):
            size = image.shape[-2::-1] if dsize is None else dsize
            return cv2.warpAffine(image, np.asarray(A, np.float64), tuple(int(n) for n in size))
        """, ["warp_affine(grey image, A)", "dsize as 2 numbers"]),

    # (blind set 2026-12-06c)
    "warpAffine's flags joined with | passed positionally, into its dst": ("lab07.ex3", """
        def scale(image, sx=1.5, sy=1.5):
            height, width = image.shape[:2]
            inverse = np.array([[1.0 / sx, 0.0, 0.0], [0.0, 1.0 / sy, 0.0]])
            return cv2.warpAffine(image, inverse, (width, height), cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP)
        """, ["as argument 4 of cv2.warpaffine, which is `dst` there", "flags=cv2.inter_linear | cv2.warp_inverse_map"]),
    "shear_matrix returned as nested Python lists": ("lab07.ex4", """
        def shear_matrix(s):
            return [[1.0, s, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
        """, ["returned a python list of rows, not a numpy array"]),
    "affine_from_points converting with np.asfarray (removed in NumPy 2.0)": ("lab07.ex5", reference_def_with(
        "lab07_transformations", "affine_from_points", "src = np.asarray(src, dtype=np.float64)",
        "src = np.asfarray(src)"), ["uses `np.asfarray` (line", "a name numpy 2.0 removed"]),
    "a whole-pixel shift copying its window without testing it is empty (tx past the width)": ("lab07.ex1", """
        def translate(image, tx=100, ty=50):
            height, width = image.shape[:2]
            if float(tx).is_integer() and float(ty).is_integer():
                dx, dy = int(tx), int(ty)
                out = np.zeros_like(image)
                x0, x1 = max(dx, 0), min(width + dx, width)
                y0, y1 = max(dy, 0), min(height + dy, height)
                out[y0:y1, x0:x1] = image[y0 - dy:y1 - dy, x0 - dx:x1 - dx]
                return out
            M = np.array([[1.0, 0.0, tx], [0.0, 1.0, ty]])
            return cv2.warpAffine(image, M, (width, height))
        """, ["a negative slice bound counts from the end of the axis"]),

    # (blind set 2026-12-06d)
    "np.diag given a dtype it does not take": ("lab07.ex3", reference_def_with(
        "lab07_transformations", "scaling_matrix", "return np.diag([float(sx), float(sy), 1.0])",
        "return np.diag([sx, sy, 1.0], dtype=np.float64)"), ["calls `np.diag` with `dtype=`", "(its parameters: v, k)"]),
    "warp_affine's size picked by a conditional that a comma takes into a tuple": ("lab07.ex5", """
        def warp_affine(image, A, dsize=None):
            height, width = image.shape[:2]
            size = dsize if dsize is not None else width, height
            return cv2.warpAffine(image, np.asarray(A, np.float64), size)
        """, ["a comma binds looser than `if ... else`", "dsize if dsize is not none else (width, height)"]),
}
