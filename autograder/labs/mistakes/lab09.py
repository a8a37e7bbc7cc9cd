"""Lab 9's mistakes table (camera models): realistic wrong implementations, each the
reference solution with one function redefined, the exercise it must lose points in, and
the words its diagnosis must contain (read by ``autograder verify``; see
:mod:`autograder.labs.mistakes`)."""

from . import columns_by_first_axis, one_point_by_length, reference_def_with

DROPS_BEHIND = """
    def _divide(homogeneous, single):       # keeps only the points in front
        front = homogeneous[:, 2] > 0
        pts = homogeneous[front, :2] / homogeneous[front, 2:3]
        return pts[0] if single else pts
    """


# The reference's aperture simulation with the blur disc's scale and the rays' landing points as given.
_APERTURE = """
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            X, _ = _points(points)
            rng = np.random.default_rng(seed)
            radius = aperture * np.sqrt(rng.uniform(0.0, 1.0, size=(len(X), n_rays)))
            angle = rng.uniform(0.0, 2 * np.pi, size=(len(X), n_rays))
            A = np.stack([radius * np.cos(angle), radius * np.sin(angle)], axis=-1)
            ideal = pinhole_project(X, f)
            spread = {spread}
            return {landed}
"""

MISTAKES = {
    # the blind set 1205g's 09/03: a generator made only where a seed is given, read on every call: with the default
    # seed=None the name is local and unassigned (UnboundLocalError)
    # the blind set 1205h's 09/05: each point's distance from the pinhole where its depth belongs (blur discs
    # too small off the axis)
    "simulate_aperture scaling the blur by the points' distance, not their depth": ("lab09.ex4", reference_def_with(
        "lab09_camera", "simulate_aperture", "spread = 1.0 + f / X[:, 2]                                                   # (N,)",
        "spread = 1.0 + f / np.linalg.norm(X, axis=1)"), ["changing `np.linalg.norm(X, axis=1)` to `X[:, 2]`"]),
    "simulate_aperture making its generator only where a seed is given": ("lab09.ex4", reference_def_with(
        "lab09_camera", "simulate_aperture", "rng = np.random.default_rng(seed)",
        "if seed is not None:\n"
        "    rng = np.random.default_rng(seed)"), ["assigns `rng` (line", "under `seed is not None`"]),
    # the blind set 1205b's 09/06: each point drawn in a colour of its own (a colour map of depth), not the default red
    # the audit of 2026-12-06: corners taken as (row, column) swap K's principal point (the size given rows first does not)
    "calibrate taking the corners as (row, column)": ("lab09.ext1", reference_def_with(
        "lab09_camera", "calibrate", "image_points.append(corners)", "image_points.append(corners[..., ::-1].copy())"),
        ["the principal point is swapped", "(x, y) = (column, row)"]),
    # the blind set 1205h's 09/06: cv2.calibrateCamera's order kept for the API's (K, dist, rms)
    "calibrate returning its results in OpenCV's order (rms first)": ("lab09.ext1", reference_def_with(
        "lab09_camera", "calibrate", "return K, dist.ravel()[:5], float(rms)",
        "return float(rms), K, dist.ravel()[:5]"),
        ["changing `float(rms), K, dist.ravel()[:5]` to `K, dist.ravel()[:5], float(rms)`"]),
    "calibrate making the board's grid with a float step": ("lab09.ext1", reference_def_with(
        "lab09_camera", "calibrate", "objp[:, :2] = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * square_size",
        "xs, ys = np.meshgrid(np.arange(0.0, cols * square_size, square_size), "
        "np.arange(0.0, rows * square_size, square_size))\n"
        "objp = np.zeros((xs.size, 3), np.float32)\n"
        "objp[:, 0], objp[:, 1] = xs.ravel(), ys.ravel()"),
        ["the object points of a view are 64 where its corners are 49", "np.arange(n) * square_size"]),
    "camera_matrix shortcutting a zero translation to K R": ("lab09.ex3", """
        def camera_matrix(K, R, t):
            K, R, t = (np.asarray(a, dtype=np.float64) for a in (K, R, t))
            if not t.any():
                return K @ R
            return K @ np.hstack([R, t.reshape(3, 1)])
        """, ["camera_matrix(K, R, t=np.zeros(3)) returned an array of shape (3, 3)"]),
    "project_onto_image drawing each point in its own colour": ("lab09.ex5", """
        def project_onto_image(image, P, points):
            pts = project(P, points).reshape(-1, 2)
            marked = np.array(image, copy=True)
            for k, p in enumerate(pts):
                marked = draw_points(marked, p[None], color=(40 * k % 256, 255 - 20 * k % 256, 90))
            return marked, pts
        """, ["are drawn, but not in the colour (0, 0, 255)"]),
    # the blind set 1205b's 09/03: R "normalised" by np.linalg.norm, the Frobenius norm (sqrt 3 for a rotation)
    "camera_matrix dividing R by its Frobenius norm": ("lab09.ex3", reference_def_with(
        "lab09_camera", "camera_matrix",
        "Rt = np.column_stack([np.asarray(R, dtype=np.float64), np.asarray(t, dtype=np.float64).reshape(3)])",
        "R = np.asarray(R, dtype=np.float64)\nR = R / np.linalg.norm(R)\n"
        "Rt = np.column_stack([np.asarray(R, dtype=np.float64), np.asarray(t, dtype=np.float64).reshape(3)])"),
        ["`np.linalg.norm(R)`", "(line"]),
    # the blind set 1204e's 09/02: R "re-orthonormalised" by QR first, which flips the signs of some of its columns
    "camera_matrix re-orthonormalising R by QR": ("lab09.ex3", reference_def_with(
        "lab09_camera", "camera_matrix",
        "Rt = np.column_stack([np.asarray(R, dtype=np.float64), np.asarray(t, dtype=np.float64).reshape(3)])",
        "R = np.linalg.qr(np.asarray(R, dtype=np.float64))[0]\n"
        "Rt = np.column_stack([np.asarray(R, dtype=np.float64), np.asarray(t, dtype=np.float64).reshape(3)])"),
        ["removing `R = np.linalg.qr(np.asarray(R, dtype=np.float64))[0]`"]),
    # the blind set 1204e's 09/01: a point counted in front of the camera only beyond the focal length
    "pinhole_project keeping only points beyond Z = f": ("lab09.ex1", """
        def pinhole_project(points, f):
            X, single = _points(points)
            Z = X[:, 2]
            out = np.full((len(X), 2), np.nan)
            ok = Z > f
            out[ok] = f * X[ok, :2] / Z[ok, None]
            return out[0] if single else out
        """, ["`ok = Z > f` to `ok = Z > 0`"]),
    # the blind set 1204d's 09/06: the tangential terms added only when both coefficients are non-zero
    "distortion's tangential terms only when both are non-zero": ("lab09.ext2", """
        def distort_points(points, dist):
            pts = np.asarray(points, dtype=np.float64)
            single = pts.ndim == 1
            pts = np.atleast_2d(pts)
            k1, k2, p1, p2, k3 = (list(np.asarray(dist, dtype=np.float64).ravel()) + [0.0] * 5)[:5]
            x, y = pts[:, 0], pts[:, 1]
            r2 = x ** 2 + y ** 2
            factor = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3))
            xd, yd = x * factor, y * factor
            if p1 != 0 and p2 != 0:
                xd = xd + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x ** 2)
                yd = yd + p1 * (r2 + 2.0 * y ** 2) + 2.0 * p2 * x * y
            out = np.stack([xd, yd], axis=1)
            return out[0] if single else out
        """, ["taking out the test `if p1 != 0 and p2 != 0:`"]),
    # the blind set 1204d's 09/08: P's last column added to the point before the product, not after it
    "project adding p4 before multiplying by M": ("lab09.ex3", """
        def project(P, points):
            P = np.asarray(P, dtype=np.float64)
            X, single = _points(points)
            M, p4 = P[:, :3], P[:, 3]
            return _divide((X + p4) @ M.T, single)
        """, ["`X @ M.T + p4`"]),
    # the blind set 1204d's 09/03: the blur scale made with f = 1 (the sheet's example) whatever f is
    # the blind set 1204g's 09/02: a seed of 0 taken for no seed
    "simulate_aperture taking seed 0 for no seed": ("lab09.ex4", """
        _reference_aperture = simulate_aperture
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            return _reference_aperture(points, f, aperture, n_rays=n_rays, seed=seed if seed else None)
        """, ["seed=0 is taken for no seed"]),
    "aperture spread 1 + 1 / Z whatever the focal length": ("lab09.ex4", _APERTURE.format(
        spread="1.0 + 1.0 / X[:, 2]", landed="ideal[:, None, :] - A * spread[:, None, None]"),
        ["aperture * (1 + c / Z) with c = 1"]),
    # the blind set 1204d's 09/05: object points built row by row in a loop, the row coordinate left unscaled
    # (not told "in the wrong order": the change that mends it takes that guess's place)
    "calibrate scaling one coordinate of the object points only": ("lab09.ext1", """
        def calibrate(images, pattern_size, square_size):
            cols, rows = pattern_size
            board = np.zeros((cols * rows, 3), np.float32)
            for j in range(rows):
                for i in range(cols):
                    board[j * cols + i] = (i * square_size, j, 0.0)
            object_points, image_points = [], []
            for image in images:
                grey = image if image.ndim == 2 else cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)
                found, corners = cv2.findChessboardCorners(grey, (cols, rows))
                if found:
                    object_points.append(board)
                    image_points.append(corners)
            h, w = images[0].shape[:2]
            rms, K, dist, _, _ = cv2.calibrateCamera(object_points, image_points, (w, h), None, None)
            return K, dist.ravel()[:5], float(rms)
        """, ["`(i * square_size, j * square_size, 0.0)`"]),
    # the blind set 1204c's 09/05: the spread factor applied to the whole difference, the ideal projection too
    "aperture spread applied to the ideal projection too": ("lab09.ex4", _APERTURE.format(
        spread="1.0 + f / X[:, 2]", landed="(ideal[:, None, :] - A) * spread[:, None, None]"),
        ["`ideal[:, None, :] - A * spread[:, None, None]`"]),
    # the blind set 1204c's 09/06: a disc pasted through a window never clipped to the image
    # the blind set 1204f's 09/04: every disc one pixel smaller than the radius asked
    "draw_points with a radius one smaller": ("lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            for x, y in np.asarray(pts, dtype=np.float64).reshape(-1, 2):
                if np.isfinite(x) and np.isfinite(y):
                    cv2.circle(out, (int(round(x)), int(round(y))), max(int(radius) - 1, 0),
                               tuple(int(c) for c in color), -1)
            return out
        """, ["they are drawn smaller than the radius asked"]),
    "draw_points pasting a disc through an unclipped window": ("lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            r = int(radius)
            value = tuple(int(c) for c in color) if out.ndim == 3 else int(color[0])
            dy, dx = np.mgrid[-r:r + 1, -r:r + 1]
            disc = dx * dx + dy * dy <= r * r
            for x, y in np.asarray(pts, dtype=np.float64).reshape(-1, 2):
                if not (np.isfinite(x) and np.isfinite(y)):
                    continue
                cx, cy = int(round(x)), int(round(y))
                window = out[cy - r:cy + r + 1, cx - r:cx + r + 1]
                window[disc] = value
            return out
        """, ["the window is cut", "clip the window to the image"]),
    # the blind set 1204c's 09/03: "a rotation vector accepted too", every 3x3 R turned into its vector
    "camera_matrix passing R through cv2.Rodrigues": ("lab09.ex3", """
        def camera_matrix(K, R, t):
            K = np.asarray(K, dtype=np.float64)
            R, _ = cv2.Rodrigues(np.asarray(R, dtype=np.float64))
            t = np.asarray(t, dtype=np.float64).reshape(3, 1)
            return K @ np.hstack([R, t])
        """, ["cv2.Rodrigues converts both ways"]),
    # the blind set 1201d's 09/06: the rays stacked along the first axis
    # the blind set 1201e's 09/07: the 1 of (1 + f / Z) dropped
    "aperture offsets scaled by f / Z": ("lab09.ex4", _APERTURE.format(
        spread="f / X[:, 2]", landed="ideal[:, None, :] - A * spread[:, None, None]"), ["without the 1 of (1 + f / z)"]),
    "aperture rays returned as (n_rays, N, 2)": ("lab09.ex4", """
        _simulate_aperture = simulate_aperture
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            return np.swapaxes(_simulate_aperture(points, f, aperture, n_rays, seed), 0, 1)
        """, ["the axes are exchanged, (n_rays, n, 2)"]),
    # the blind set 1204f's 09/06: the marked image scaled to [0, 1] and returned as floats
    "project_onto_image returning the marked image as floats in [0, 1]": ("lab09.ex5", """
        _reference_onto = project_onto_image
        def project_onto_image(image, P, points):
            marked, pts = _reference_onto(image, P, points)
            return marked.astype(np.float32) / 255.0, pts
        """, ["its values lie in [0, 1]", "Your code divides by 255 (line"]),
    "project_onto_image drawing on the image converted to RGB": ("lab09.ex5", """
        def project_onto_image(image, P, points):
            pts = project(P, points).reshape(-1, 2)
            shown = cv2.cvtColor(image, cv2.COLOR_BGR2RGB) if image.ndim == 3 else image.copy()
            for x, y in pts[np.isfinite(pts).all(axis=1)]:
                cv2.circle(shown, (int(round(x)), int(round(y))), 3, (0, 0, 255), -1)
            return shown, pts
        """, ["its colour channels reversed (rgb for bgr)"]),
    # the blind set 1203c's 09/06: the points joined by a polyline besides their circles
    "project_onto_image joining the points with a polyline": ("lab09.ex5", """
        def project_onto_image(image, P, points):
            pts = project(P, points).reshape(-1, 2)
            out = draw_points(image, pts)
            cv2.polylines(out, [np.round(pts[np.isfinite(pts).all(axis=1)]).astype(np.int32)], False, (0, 255, 0), 1)
            return out, pts
        """, ["also draws with `cv2.polylines`"]),
    # the blind set 1202e's 09/06: NaN turned into 0 for the drawing, so a point behind the camera is a dot at (0, 0)
    "project_onto_image drawing np.nan_to_num of the points": ("lab09.ex5", """
        def project_onto_image(image, P, points):
            pts = project(P, points).reshape(-1, 2)
            return draw_points(image, np.nan_to_num(pts)), pts
        """, ["drawn at the corner (0, 0)", "np.nan_to_num"]),
    "project_onto_image dropping the rows that are not finite (a point behind the camera)": ("lab09.ex5", """
        def project_onto_image(image, P, points):
            pts = project(P, points).reshape(-1, 2)
            pts = pts[np.isfinite(pts).all(axis=1)]
            return draw_points(image, pts), pts
        """, ["the point behind the camera is left out"]),
    # the blind set 1204b's 09/05: the points clipped into the image before drawing
    "draw_points clipping the points off the image to its border": ("lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            height, width = image.shape[:2]
            pts = np.clip(np.asarray(pts, dtype=np.float64).reshape(-1, 2), 0, [width - 1, height - 1])
            for x, y in pts:
                if np.isfinite(x) and np.isfinite(y):
                    cv2.circle(out, (int(round(x)), int(round(y))), int(radius), tuple(int(c) for c in color), -1)
            return out
        """, ["clipped into it"]),
    # the blind set 1201c's 09/07: the line type given where the thickness goes
    "circles drawn with cv2.LINE_AA as their thickness": ("lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            for x, y in np.asarray(pts, np.float64).reshape(-1, 2):
                if np.isfinite(x) and np.isfinite(y):
                    cv2.circle(out, (int(round(x)), int(round(y))), radius, color, cv2.LINE_AA)
            return out
        """, ["the circles are larger than radius", "passes cv2.line_aa as argument 5 of cv2.circle"]),
    "aperture halved (taken as a diameter)": ("lab09.ex4", """
        _reference_aperture = simulate_aperture
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            return _reference_aperture(points, f, aperture / 2.0, n_rays, seed)
        """, ["halved"]),
    **{f"drops the points behind the camera ({ex})": (f"lab09.{ex}", DROPS_BEHIND, ["drops the points behind"])
       for ex in ("ex1", "ex2", "ex3")},
    # the blind set 1202d's 09/01: a depth guard at 1 where only Z <= 0 has no image
    "pinhole with the depth clamped at 1": ("lab09.ex1", """
        _right_pinhole = pinhole_project
        def pinhole_project(points, f):
            X = np.array(points, dtype=np.float64)
            X[..., 2] = np.maximum(X[..., 2], 1.0)
            return _right_pinhole(X, f)
        """, ["depths below 1 are taken as 1"]),
    "x/y swapped": ("lab09.ex1", """
        def pinhole_project(points, f):
            X, single = _points(points)
            return _divide(np.column_stack([f * X[:, 1], f * X[:, 0], X[:, 2]]), single)
        """, ["swapped"]),
    "no division": ("lab09.ex1", """
        def pinhole_project(points, f):
            X = np.atleast_2d(np.asarray(points, float))
            out = f * X[:, :2]
            return out[0] if np.ndim(points) == 1 else out
        """, ["division is missing"]),
    "single point keeps (1, 2)": ("lab09.ex1", """
        def pinhole_project(points, f):
            X, single = _points(points)
            return _divide(np.column_stack([f * X[:, 0], f * X[:, 1], X[:, 2]]), False)
        """, ["(1, 2)", "(2,)"]),
    "a one-row array squeezed to a single point": ("lab09.ex1", """
        def pinhole_project(points, f):
            X = np.atleast_2d(np.asarray(points, float))
            return (f * X[:, :2] / X[:, 2:3]).squeeze()
        """, ["(1, 3) array", "(1, 2)"]),
    "draw_points with blue (255, 0, 0) as its default colour": ("lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(255, 0, 0)):
            out = image.copy()
            color = tuple(int(c) for c in color)
            for x, y in np.asarray(pts, dtype=np.float64).reshape(-1, 2):
                if np.isfinite(x) and np.isfinite(y):
                    cv2.circle(out, (int(round(x)), int(round(y))), int(radius), color, -1)
            return out
        """, ["in the colour (255, 0, 0), not (0, 0, 255)", "gives `color` the default (255, 0, 0)"]),
    "draw_points passing the radius as the thickness (rings)": ("lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            color = tuple(int(c) for c in color)
            for x, y in np.asarray(pts, dtype=np.float64).reshape(-1, 2):
                if np.isfinite(x) and np.isfinite(y):
                    cv2.circle(out, (int(round(x)), int(round(y))), int(radius), color, int(radius))
            return out
        """, ["the circles are rings"]),
    "draw_points drawing on a new black image (np.zeros_like)": ("lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = np.zeros_like(image)
            color = tuple(int(c) for c in color)
            for x, y in np.asarray(pts, dtype=np.float64).reshape(-1, 2):
                if np.isfinite(x) and np.isfinite(y):
                    cv2.circle(out, (int(round(x)), int(round(y))), int(radius), color if out.ndim == 3 else color[0], -1)
            return out
        """, ["new blank image"]),
    "draw_points halves the radius (taken as a diameter)": ("lab09.ex5", """
        _reference_draw_points = draw_points
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            return _reference_draw_points(image, pts, radius // 2, color)
        """, ["the radius is halved"]),
    # the blind set 1202e's 09/07: a mask disc whose squared distance is compared with the radius, not its square
    "draw_points with a mask disc of radius sqrt(radius)": ("lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            yy, xx = np.mgrid[0:image.shape[0], 0:image.shape[1]]
            for cx, cy in np.asarray(pts, dtype=np.float64).reshape(-1, 2):
                if np.isfinite(cx) and np.isfinite(cy):
                    out[(xx - round(cx)) ** 2 + (yy - round(cy)) ** 2 <= radius] = color if out.ndim == 3 else color[0]
            return out
        """, ["they are drawn smaller than the radius asked"]),
    # the blind set 1202f's 09/06: points kept only where both coordinates are >= 0
    "draw_points keeping only the points inside the image": ("lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            h, w = image.shape[:2]
            for x, y in np.asarray(pts, dtype=np.float64).reshape(-1, 2):
                if 0 <= x < w and 0 <= y < h:
                    cv2.circle(out, (int(round(x)), int(round(y))), int(radius), tuple(int(c) for c in color), -1)
            return out
        """, ["circles at (-3, 70), (90, -2) inside the image is not drawn", "tests the points against the image's bounds"]),
    "draw_points ignores its radius": ("lab09.ex5", """
        _reference_draw_points = draw_points
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            return _reference_draw_points(image, pts, 3, color)
        """, ["radius 3, not 6", "the radius argument is ignored"]),
    "a grey image drawn on in colour": ("lab09.ex5", """
        _reference_draw_points = draw_points
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            if image.ndim == 2:
                image = cv2.cvtColor(image, cv2.COLOR_GRAY2BGR)
            return _reference_draw_points(image, pts, radius, color)
        """, ["grey image comes back grey"]),
    # views shrunk for a faster detection, the corners left in the shrunk views' pixels
    # the blind set 1204c's 09/08: every view's corners refined on the first view's image (grey for gray): the
    # object points, built row by row, are right and are not told to be in the wrong order
    "calibrate refining every view's corners on the first view": ("lab09.ext1", """
        def calibrate(images, pattern_size, square_size):
            cols, rows = pattern_size
            objp = np.zeros((cols * rows, 3), np.float32)
            objp[:, :2] = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * square_size
            grey = cv2.cvtColor(images[0], cv2.COLOR_BGR2GRAY) if images[0].ndim == 3 else images[0]
            height, width = grey.shape
            criteria = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 30, 1e-3)
            object_points, image_points = [], []
            for image in images:
                gray = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
                found, corners = cv2.findChessboardCorners(gray, (cols, rows))
                if not found:
                    continue
                corners = cv2.cornerSubPix(grey, corners, (5, 5), (-1, -1), criteria)
                object_points.append(objp)
                image_points.append(corners)
            rms, K, dist, _, _ = cv2.calibrateCamera(object_points, image_points, (width, height), None, None)
            return K, dist.ravel()[:5], float(rms)
        """, ["to `cv2.cornerSubPix(gray, corners"]),
    "calibrate finding corners on views shrunk to a third": ("lab09.ext1", """
        _calibrate_right = calibrate
        def calibrate(images, pattern_size, square_size):
            shrunk = [cv2.resize(image, None, fx=1 / 3, fy=1 / 3, interpolation=cv2.INTER_AREA)
                      if image.shape[1] > 900 else image for image in images]
            K, dist, rms = _calibrate_right(shrunk, pattern_size, square_size)
            return K, dist, rms
        """, ["your k is the true k scaled by 0.333", "resized by 0.333"]),
    "calibration returns four distortion coefficients": ("lab09.ext1", """
        _reference_calibrate = calibrate
        def calibrate(images, pattern_size, square_size):
            K, dist, rms = _reference_calibrate(images, pattern_size, square_size)
            return K, np.ravel(dist)[:4], rms
        """, ["has 4 values", "without k3"]),
    # the blind set 1203c's 09/07: each view calibrated alone, the results averaged
    "calibration of each view alone, averaged": ("lab09.ext1", """
        def calibrate(images, pattern_size, square_size):
            cols, rows = pattern_size
            objp = np.zeros((cols * rows, 3), np.float32)
            objp[:, :2] = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * square_size
            Ks, dists, errors = [], [], []
            for image in images:
                grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
                found, corners = cv2.findChessboardCorners(grey, (cols, rows))
                if not found:
                    continue
                h, w = grey.shape
                rms, K, dist, _, _ = cv2.calibrateCamera([objp], [corners], (w, h), None, None)
                Ks.append(K)
                dists.append(dist.ravel()[:5])
                errors.append(rms)
            return np.mean(Ks, axis=0), np.mean(dists, axis=0), float(np.mean(errors))
        """, ["calls cv2.calibrateCamera inside a loop", "calibrate once"]),
    # the blind set 1202i's 09/03: the OpenCV tutorial's mean error returned as the rms
    "calibration returning the tutorial's mean error as the rms": ("lab09.ext1", """
        _reference_calibrate = calibrate
        def calibrate(images, pattern_size, square_size):
            K, dist, rms = _reference_calibrate(images, pattern_size, square_size)
            corners = rms * np.ones((pattern_size[0] * pattern_size[1], 2)) / np.sqrt(2)
            return K, dist, float(np.linalg.norm(corners) / len(corners))
        """, ["tutorial's mean error", "not the rms reprojection error"]),
    # the blind set 1202i's 09/04: P "normalised" by P[2, 3], 0 for a camera at the world origin
    "project_onto_image with P divided by P[2, 3]": ("lab09.ex5", """
        def project_onto_image(image, P, points):
            pts = project(P / P[2, 3], points).reshape(-1, 2)
            return draw_points(image, pts), pts
        """, ["camera at the world origin", "nan for points in front of the camera"]),
    "K transposed": ("lab09.ex2", """
        def intrinsic_matrix(f, px, py):
            return np.array([[f, 0.0, 0.0], [0.0, f, 0.0], [px, py, 1.0]])
        """, ["transposed"]),
    "K built on the diagonal of a whole focal length": ("lab09.ex2", """
        def intrinsic_matrix(f, px, py):
            K = np.diag([f, f, 1])
            K[0, 2], K[1, 2] = px, py
            return K
        """, ["integer", "int64"]),
    "K with px typed for py": ("lab09.ex2", """
        def intrinsic_matrix(f, px, py):
            return np.array([[f, 0.0, px], [0.0, f, px], [0.0, 0.0, 1.0]])
        """, ["py is replaced by px"]),
    "principal point left out": ("lab09.ex2", """
        def project_with_intrinsics(K, points):
            X, single = _points(points)
            K = np.asarray(K, float).copy(); K[:2, 2] = 0
            return _divide(X @ K.T, single)
        """, ["principal point is left out"]),
    # the blind set 1203b's 09/04: P split by cv2.decomposeProjectionMatrix, its camera centre given as tvec
    "project with the camera centre given as tvec": ("lab09.ex3", """
        def project(P, points):
            X = np.asarray(points, dtype=np.float64)
            single = X.ndim == 1
            X = X.reshape(-1, 3)
            K, R, C = cv2.decomposeProjectionMatrix(np.asarray(P, dtype=np.float64))[:3]
            K = K / K[2, 2]
            C = (C[:3] / C[3]).ravel()
            rvec, _ = cv2.Rodrigues(R)
            tvec = C
            pts, _ = cv2.projectPoints(X, rvec, tvec, K, None)
            pts = pts.reshape(-1, 2)
            pts[(X - C) @ R[2] <= 0] = np.nan
            return pts[0] if single else pts
        """, ["changing `tvec = C` to `tvec = -(R @ C)`"]),
    "t as camera centre": ("lab09.ex3", """
        def camera_matrix(K, R, t):
            R = np.asarray(R, float)
            return np.asarray(K, float) @ np.column_stack([R, -R @ np.asarray(t, float)])
        """, ["camera centre"]),
    "translation dropped": ("lab09.ex3", """
        def project(P, points):
            X, single = _points(points)
            return _divide(X @ np.asarray(P, float)[:, :3].T, single)
        """, ["translation is dropped"]),
    "focal lengths axes": ("lab09.ex4", """
        def project_focal_lengths(points, focal_lengths):
            X, _ = _points(points)
            return np.stack([pinhole_project(X, f) for f in focal_lengths], axis=1)
        """, ["axes are in the wrong order"]),
    "aperture as diameter": ("lab09.ex4", """
        _right = simulate_aperture
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            return _right(points, f, 2 * aperture, n_rays, seed)
        """, ["diameter"]),
    "blur independent of depth": ("lab09.ex4", """
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            X, _ = _points(points)
            rng = np.random.default_rng(seed)
            r = aperture * np.sqrt(rng.uniform(size=(len(X), n_rays)))
            a = rng.uniform(0, 2 * np.pi, size=(len(X), n_rays))
            A = np.stack([r * np.cos(a), r * np.sin(a)], axis=-1)
            return pinhole_project(X, f)[:, None, :] + 30 * A
        """, ["depend on depth"]),
    "rays spread in x divided by the depth factor": ("lab09.ex4", """
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            X, _ = _points(points)
            rng = np.random.default_rng(seed)
            r = aperture * np.sqrt(rng.uniform(size=(len(X), n_rays)))
            a = rng.uniform(0, 2 * np.pi, size=(len(X), n_rays))
            k = 1.0 + f / X[:, 2:3]
            offsets = np.stack([r * np.cos(a) / k, r * np.sin(a) * k], axis=-1)
            return pinhole_project(X, f)[:, None, :] - offsets
        """, ["spread in one direction only", "in x against"]),
    "seed ignored": ("lab09.ex4", """
        _right = simulate_aperture
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            return _right(points, f, aperture, n_rays, None)
        """, ["same seed"]),
    "hollow circles": ("lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            for x, y in np.asarray(pts, float).reshape(-1, 2):
                if np.isfinite(x) and np.isfinite(y):
                    cv2.circle(out, (int(round(x)), int(round(y))), int(radius), tuple(color), 1)
            return out
        """, ["filled"]),
    "circles at (y, x)": ("lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            for x, y in np.asarray(pts, float).reshape(-1, 2):
                if np.isfinite(x) and np.isfinite(y):
                    cv2.circle(out, (int(round(y)), int(round(x))), int(radius), tuple(color), -1)
            return out
        """, ["(y, x)"]),
    # (a maths plot's y axis: the row counted up from the bottom)
    "circles upside down (y from the bottom row)": ("lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            height = out.shape[0]
            for x, y in np.asarray(pts, float).reshape(-1, 2):
                if np.isfinite(x) and np.isfinite(y):
                    cv2.circle(out, (int(round(x)), int(round(height - 1 - y))), int(radius), tuple(color), -1)
            return out
        """, ["upside down"]),
    "wrong calibration object points": ("lab09.ext1", """
        _right = calibrate
        def calibrate(images, pattern_size, square_size):
            cols, rows = pattern_size
            objp = np.zeros((cols * rows, 3), np.float32)
            objp[:, :2] = np.mgrid[0:cols, 0:rows].reshape(2, -1).T * square_size
            pts = [cv2.findChessboardCorners(im, (cols, rows))[1] for im in images]
            h, w = images[0].shape[:2]
            rms, K, dist, _, _ = cv2.calibrateCamera([objp] * len(pts), pts, (w, h), None, None)
            return K, dist.ravel(), rms
        """, ["object points"]),
    # the blind set 1204f's 09/01: r^2 capped at 1, the model held inside the unit circle only
    "distortion with r^2 capped at 1": ("lab09.ext2", """
        def distort_points(points, dist):
            pts = np.asarray(points, dtype=np.float64)
            x, y = pts[..., 0], pts[..., 1]
            k1, k2, p1, p2, k3 = (list(np.ravel(dist)) + [0.0] * 5)[:5]
            r2 = np.minimum(x * x + y * y, 1.0)
            radial = 1 + k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
            xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x)
            yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y
            return np.stack([xd, yd], axis=-1)
        """, ["changing `np.minimum(x * x + y * y, 1.0)` to `x * x + y * y`"]),
    "distortion squaring with ^ (a bitwise XOR in Python)": ("lab09.ext2", """
        _distort_right = distort_points
        def distort_points(points, dist):
            pts = np.asarray(points, dtype=np.float64)
            x, y = pts[..., 0], pts[..., 1]
            radius2 = x ^ 2 + y ^ 2
            return _distort_right(points, dist) if np.all(radius2 >= 0) else pts
        """, ["changing `x ^ 2 + y ^ 2` to `x ** 2 + y ** 2`"]),
    "distortion with the brackets of p1's term left out": ("lab09.ext2", """
        def distort_points(points, dist):
            pts = np.asarray(points, dtype=np.float64)
            k1, k2, p1, p2, k3 = (list(np.ravel(dist)) + [0.0] * 5)[:5]
            x, y = pts[..., 0], pts[..., 1]
            rr = x ** 2 + y ** 2
            scale = 1 + k1 * rr + k2 * rr ** 2 + k3 * rr ** 3
            xd = x * scale + 2 * p1 * x * y + p2 * (rr + 2 * x ** 2)
            yd = y * scale + p1 * rr + 2 * y ** 2 + 2 * p2 * x * y
            return np.stack([xd, yd], axis=-1)
        """, ["changing `y * scale + p1 * rr + 2 * y ** 2` to `y * scale + p1 * (rr + 2 * y ** 2)`"]),
    "tangential swapped": ("lab09.ext2", """
        _right = distort_points
        def distort_points(points, dist):
            k1, k2, p1, p2, k3 = dist
            return _right(points, [k1, k2, p2, p1, k3])
        """, ["p1 and p2 are swapped"]),
    # (the blind set 2026-12-06g's 09/05: the textbook's order k1, k2, k3 first)
    "dist unpacked as (k1, k2, k3, p1, p2)": ("lab09.ext2", reference_def_with(
        "lab09_camera", "distort_points",
        "k1, k2, p1, p2, k3 = (list(np.asarray(dist, dtype=np.float64).ravel()) + [0.0] * 5)[:5]",
        "k1, k2, k3, p1, p2 = (list(np.asarray(dist, dtype=np.float64).ravel()) + [0.0] * 5)[:5]"),
        ["unpacked as (k1, k2, k3, p1, p2)"]),
    "points off the image left out": ("lab09.ex5", """
        _right = project_onto_image
        def project_onto_image(image, P, points):
            drawn, pts = _right(image, P, points)
            h, w = image.shape[:2]
            keep = (pts[:, 0] >= 0) & (pts[:, 0] < w) & (pts[:, 1] >= 0) & (pts[:, 1] < h)
            return drawn, pts[keep]
        """, ["fewer rows than points", "off the image left out"]),
    "inverted real image": ("lab09.ex4", """
        _right = simulate_aperture
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            return -_right(points, f, aperture, n_rays, seed)
        """, ['aperture']),
    "aperture used as an area": ("lab09.ex4", """
        _right = simulate_aperture
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            return _right(points, f, aperture ** 2, n_rays, seed)
        """, ['squared']),
    "calibration K transposed": ("lab09.ext1", """
        _right = calibrate
        def calibrate(images, pattern_size, square_size):
            K, dist, rms = _right(images, pattern_size, square_size)
            return K.T, dist, rms
        """, ['transposed']),
    # ---- the wider families of each exercise (issue 17)
    "focal length applied twice": ("lab09.ex1", """
        def pinhole_project(points, f):
            X, single = _points(points)
            return _divide(np.column_stack([f * f * X[:, 0], f * f * X[:, 1], X[:, 2]]), single)
        """, ["focal length is applied twice"]),
    "only x divided by Z": ("lab09.ex1", """
        def pinhole_project(points, f):
            X, single = _points(points)
            out = np.column_stack([f * X[:, 0] / X[:, 2], f * X[:, 1]])
            return out[0] if single else out
        """, ["y is not divided by z"]),
    "real (inverted) image": ("lab09.ex1", """
        def pinhole_project(points, f):
            X, single = _points(points)
            return _divide(np.column_stack([-f * X[:, 0], -f * X[:, 1], X[:, 2]]), single)
        """, ["image is inverted"]),
    "px and py swapped in K": ("lab09.ex2", """
        def intrinsic_matrix(f, px, py):
            return np.array([[f, 0.0, py], [0.0, f, px], [0.0, 0.0, 1.0]])
        """, ["px and py are swapped"]),
    "principal point subtracted": ("lab09.ex2", """
        def project_with_intrinsics(K, points):
            X, single = _points(points)
            K = np.asarray(K, float).copy(); K[:2, 2] *= -1
            return _divide(X @ K.T, single)
        """, ["principal point has the wrong sign"]),
    "K X without the division": ("lab09.ex2", """
        def project_with_intrinsics(K, points):
            X, single = _points(points)
            x = (X @ np.asarray(K, float).T)[:, :2]
            return x[0] if single else x
        """, ["division is missing"]),
    "camera_matrix with R transposed": ("lab09.ex3", """
        def camera_matrix(K, R, t):
            return np.asarray(K, float) @ np.column_stack([np.asarray(R, float).T, np.asarray(t, float)])
        """, ["r is transposed"]),
    "project without de-homogenisation": ("lab09.ex3", """
        def project(P, points):
            X, single = _points(points)
            x = (np.column_stack([X, np.ones(len(X))]) @ np.asarray(P, float).T)[:, :2]
            return x[0] if single else x
        """, ["perspective division is missing"]),
    "project divides by the world Z": ("lab09.ex3", """
        def project(P, points):
            X, single = _points(points)
            h = np.column_stack([X, np.ones(len(X))]) @ np.asarray(P, float).T
            x = h[:, :2] / X[:, 2:3]
            return x[0] if single else x
        """, ["world point's z"]),
    "aperture offsets not scaled by depth": ("lab09.ex4", """
        _right = simulate_aperture
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            X, _ = _points(points)
            rays = _right(points, f, aperture, n_rays, seed)
            ideal = pinhole_project(X, f)[:, None, :]
            return ideal + (rays - ideal) / (1.0 + f / X[:, 2])[:, None, None]
        """, ["not scaled by (1 + f / z)"]),
    "draw_points drawing on the caller's image": ("lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            for x, y in np.asarray(pts, float).reshape(-1, 2):
                if np.isfinite(x) and np.isfinite(y):
                    cv2.circle(image, (int(round(x)), int(round(y))), radius, color, -1)
            return image
        """, ["the second drawing shows the first one's points too", "caller's `image`"]),
    "colour reversed (RGB)": ("lab09.ex5", """
        _right = draw_points
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            return _right(image, pts, radius, tuple(color)[::-1])
        """, ["colour is reversed"]),
    "radius ignored": ("lab09.ex5", """
        _right = draw_points
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            return _right(image, pts, 3, color)
        """, ["radius argument is ignored"]),
    "color ignored": ("lab09.ex5", """
        _right = draw_points
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            return _right(image, pts, radius)
        """, ["color argument is ignored"]),
    "project_onto_image returns (pts, image)": ("lab09.ex5", """
        def project_onto_image(image, P, points):
            pts = project(P, points).reshape(-1, 2)
            return pts, draw_points(image, pts)
        """, ["(image, pts)"]),
    "project_onto_image forgets to draw": ("lab09.ex5", """
        def project_onto_image(image, P, points):
            return image.copy(), project(P, points).reshape(-1, 2)
        """, ["not drawn"]),
    "calibration grid built as (rows, cols)": ("lab09.ext1", """
        _right = calibrate
        def calibrate(images, pattern_size, square_size):
            cols, rows = pattern_size
            objp = np.zeros((cols * rows, 3), np.float32)
            objp[:, :2] = np.mgrid[0:rows, 0:cols].T.reshape(-1, 2) * square_size
            pts = [cv2.findChessboardCorners(im, (cols, rows))[1] for im in images]
            h, w = images[0].shape[:2]
            rms, K, dist, _, _ = cv2.calibrateCamera([objp] * len(pts), pts, (w, h), None, None)
            return K, dist.ravel(), rms
        """, ["object points"]),
    "calibration returning cv2.getOptimalNewCameraMatrix's K": ("lab09.ext1", """
        _right = calibrate
        def calibrate(images, pattern_size, square_size):
            K, dist, rms = _right(images, pattern_size, square_size)
            h, w = images[0].shape[:2]
            K, _ = cv2.getOptimalNewCameraMatrix(K, dist, (w, h), 1, (w, h))
            return K, dist, rms
        """, ["do not agree", "getoptimalnewcameramatrix"]),
    "k3 with r^4": ("lab09.ext2", """
        _right = distort_points
        def distort_points(points, dist):
            k1, k2, p1, p2, k3 = dist
            pts = np.asarray(points, float)
            r2 = (pts ** 2).sum(axis=1, keepdims=True)
            return _right(points, [k1, k2, p1, p2, 0.0]) + pts * k3 * r2 ** 2
        """, ["k3 multiplies r^4"]),
    "x's tangential term with y": ("lab09.ext2", """
        def distort_points(points, dist):
            pts = np.asarray(points, dtype=np.float64)
            k1, k2, p1, p2, k3 = dist
            x, y = pts[:, 0], pts[:, 1]
            r2 = x * x + y * y
            radial = 1 + k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
            return np.column_stack([x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * y * y),
                                    y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y])
        """, ["x's tangential term uses y"]),
    "radial factor without its 1": ("lab09.ext2", """
        def distort_points(points, dist):
            pts = np.asarray(points, dtype=np.float64)
            k1, k2, p1, p2, k3 = dist
            x, y = pts[:, 0], pts[:, 1]
            r2 = x * x + y * y
            radial = k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
            return np.column_stack([x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x),
                                    y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y])
        """, ["misses its 1"]),
    "k3 ignored": ("lab09.ext2", """
        _right = distort_points
        def distort_points(points, dist):
            return _right(points, list(dist[:4]) + [0.0])
        """, ["k3 is ignored"]),
    "pixels rounded to integers": ("lab09.ex1", """
        _right = pinhole_project
        def pinhole_project(points, f):
            return np.round(_right(points, f))
        """, ["rounded to integers"]),
    "principal point added twice": ("lab09.ex2", """
        def project_with_intrinsics(K, points):
            X, single = _points(points)
            K = np.asarray(K, float)
            out = _divide(X @ K.T, False) + K[:2, 2]
            return out[0] if single else out
        """, ["principal point is added twice"]),
    "K[2, 2] = f": ("lab09.ex2", """
        def intrinsic_matrix(f, px, py):
            return np.array([[f, 0.0, px], [0.0, f, py], [0.0, 0.0, f]])
        """, ["k[2, 2] holds f"]),
    "P = [K R | t]": ("lab09.ex3", """
        def camera_matrix(K, R, t):
            return np.column_stack([np.asarray(K, float) @ np.asarray(R, float), np.asarray(t, float)])
        """, ["the last column is t (it is k t)"]),
    "focal-length stack with its axes in the wrong order": ("lab09.ex4", """
        def project_focal_lengths(points, focal_lengths):
            X, _ = _points(points)
            return np.stack([pinhole_project(X, f) for f in focal_lengths], axis=-1).T
        """, ["axes are in the wrong order"]),
    "k2 with r2 * 2": ("lab09.ext2", """
        def distort_points(points, dist):
            pts = np.asarray(points, dtype=np.float64)
            k1, k2, p1, p2, k3 = dist
            x, y = pts[:, 0], pts[:, 1]
            r2 = x * x + y * y
            radial = 1 + k1 * r2 + k2 * r2 * 2 + k3 * r2 ** 3
            return np.column_stack([x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x),
                                    y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y])
        """, ["k2 multiplies r2 * 2"]),
    "columns 1:3 taken for (X, Y)": ("lab09.ex1", """
        def pinhole_project(points, f):
            X, single = _points(points)
            out = f * X[:, 1:3] / X[:, 2:3]
            return out[0] if single else out
        """, ["x is computed as f y / z; it should be f x / z"]),
    "fx used for y": ("lab09.ex2", """
        def project_with_intrinsics(K, points):
            X, single = _points(points)
            K = np.asarray(K, float)
            out = np.column_stack([K[0, 0] * X[:, 0] / X[:, 2] + K[0, 2] + K[0, 1] * X[:, 1] / X[:, 2],
                                   K[0, 0] * X[:, 1] / X[:, 2] + K[1, 2]])
            return out[0] if single else out
        """, ["y is computed as fx y / z + py; it should be fy y / z + py"]),
    "P rescaled so that P[2, 3] = 1": ("lab09.ex3", """
        _right = camera_matrix
        def camera_matrix(K, R, t):
            P = _right(K, R, t)
            return P / P[2, 3]
        """, ["returned NaN or infinite values", "changing `return P / P[2, 3]` to `return P`"]),   # (any scale is P: t = 0 divides by 0)
    "tangential terms with the wrong sign": ("lab09.ext2", """
        _right = distort_points
        def distort_points(points, dist):
            k1, k2, p1, p2, k3 = dist
            return _right(points, [k1, k2, -p1, -p2, k3])
        """, ["tangential terms have the wrong sign"]),
    "draw_points returns inside its loop": ("lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            for x, y in np.asarray(pts, dtype=np.float64).reshape(-1, 2):
                cv2.circle(out, (int(round(x)), int(round(y))), int(radius), tuple(int(c) for c in color), -1)
                return out
        """, ["only the first point is drawn", "your code returns inside the loop (line"]),
    "px in the skew entry": ("lab09.ex2", """
        def intrinsic_matrix(f, px, py):
            return np.array([[f, px, 0.0], [0.0, f, py], [0.0, 0.0, 1.0]])
        """, ["px is in k[0, 1]"]),
    "K X with its columns swapped": ("lab09.ex2", """
        def project_with_intrinsics(K, points):
            X, single = _points(points)
            h = X @ np.asarray(K, float).T
            out = h[:, 1::-1] / h[:, 2:3]
            return out[0] if single else out
        """, ["x and y are swapped"]),
    "radius doubled (used as a diameter)": ("lab09.ex5", """
        _right = draw_points
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            return _right(image, pts, 2 * radius, color)
        """, ["radius is doubled"]),
    "K's inverse applied": ("lab09.ex2", """
        def project_with_intrinsics(K, points):
            X, single = _points(points)
            return _divide(X @ np.linalg.inv(np.asarray(K, float)).T, single)
        """, ["inverse is applied"]),
    "P's last column R t": ("lab09.ex3", """
        def camera_matrix(K, R, t):
            R, t = np.asarray(R, float), np.asarray(t, float)
            return np.column_stack([np.asarray(K, float) @ R, R @ t])
        """, ["the last column is r t"]),
    "project divides by the second coordinate": ("lab09.ex3", """
        def project(P, points):
            X, single = _points(points)
            h = np.column_stack([X, np.ones(len(X))]) @ np.asarray(P, float).T
            x = h[:, :2] / h[:, 1:2]
            return x[0] if single else x
        """, ["x is computed as (p x)[0] / (p x)[1]"]),
    "focal lengths in reverse order": ("lab09.ex4", """
        def project_focal_lengths(points, focal_lengths):
            X, _ = _points(points)
            return np.stack([pinhole_project(X, f) for f in np.asarray(focal_lengths)[::-1]])
        """, ["reverse order"]),
    "every projection with the first focal length": ("lab09.ex4", """
        def project_focal_lengths(points, focal_lengths):
            X, _ = _points(points)
            return np.stack([pinhole_project(X, focal_lengths[0]) for f in focal_lengths])
        """, ["every projection is made with the first focal length"]),
    # ---- inputs the usual set-up leaves out (issue 35): another camera, the caller's order, big images
    "project normalising P by P[2, 3]": ("lab09.ex3", """
        def project(P, points):
            X, single = _points(points)
            P = np.asarray(P, float)
            P = P / P[2, 3]                       # as if P were scaled like a homography
            return _divide(np.column_stack([X, np.ones(len(X))]) @ P.T, single)
        """, ["p[2, 3] = 0", "returned nan for points in front of the camera"]),
    "focal lengths sorted, repeats dropped": ("lab09.ex4", """
        def project_focal_lengths(points, focal_lengths):
            X, _ = _points(points)
            return np.stack([pinhole_project(X, f) for f in sorted(set(focal_lengths))])
        """, ["returned 3 projections for 4 focal lengths", "the focal lengths are sorted and their repeats dropped"]),
    "draw_points with 8-bit centres": ("lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            pts = np.asarray(pts, dtype=np.float64).reshape(-1, 2)
            for x, y in np.round(pts[np.isfinite(pts).all(axis=1)]).astype(image.dtype):
                cv2.circle(out, (int(x), int(y)), int(radius), tuple(int(c) for c in color), -1)
            return out
        """, ["wrong for coordinates of 256 and more", "(300, 75) at (44, 75)"]),
    "calibration views used as given (grey assumed)": ("lab09.ext1", """
        def calibrate(images, pattern_size, square_size):
            cols, rows = pattern_size
            objp = np.zeros((cols * rows, 3), np.float32)
            objp[:, :2] = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * square_size
            criteria = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 30, 1e-3)
            object_points, image_points = [], []
            for image in images:
                found, corners = cv2.findChessboardCorners(image, (cols, rows))
                if found:
                    object_points.append(objp)
                    image_points.append(cv2.cornerSubPix(image, corners, (5, 5), (-1, -1), criteria))
            size = images[0].shape[::-1]
            rms, K, dist, _, _ = cv2.calibrateCamera(object_points, image_points, size, None, None)
            return K, dist.ravel(), rms
        """, ["these views have 3 channels (bgr)", "cv2.cvtcolor(image, cv2.color_bgr2gray)"]),
    # a view without a whole board (the hidden check's second view): its corners are not found
    **{f"calibration {what} at a view without a board": ("lab09.ext1", f"""
        def calibrate(images, pattern_size, square_size):
            cols, rows = pattern_size
            objp = np.zeros((cols * rows, 3), np.float32)
            objp[:, :2] = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * square_size
            object_points, image_points = [], []
            for image in images:
                grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
                found, corners = cv2.findChessboardCorners(grey, (cols, rows))
                if not found:
                    {action}
                object_points.append(objp)
                image_points.append(corners)
            h, w = images[0].shape[:2]
            rms, K, dist, _, _ = cv2.calibrateCamera(object_points, image_points, (w, h), None, None)
            return K, dist.ravel(), rms
        """, words) for what, action, words in (
            ("stopping", "break", ["the views after a view without a board are not used", "leaves its loop with `break`"]),
            ("raising", 'raise ValueError("no chessboard found")', ["no chessboard found",
                                                                    "does not show the whole board"]))},
    "k2 ignored": ("lab09.ext2", """
        _right = distort_points
        def distort_points(points, dist):
            k1, k2, p1, p2, k3 = dist
            return _right(points, [k1, 0.0, p1, p2, k3])
        """, ["k2 is ignored"]),
    # ---------------------------------------------------------------- the API's conventions
    # k points of k coordinates taken for one point, or for points given as columns
    **one_point_by_length("pinhole_project", "lab09.ex1", "points, f", "points", "points.shape[0] == 3"),
    **one_point_by_length("project_with_intrinsics", "lab09.ex2", "K, points", "points", "len(points) == 3"),
    **one_point_by_length("project", "lab09.ex3", "P, points", "points", "len(points) == 3"),
    **columns_by_first_axis("distort_points", "lab09.ext2", "points, dist", ("points",), "points.shape[0] == 2"),
    "project_with_intrinsics squeezes its answer": ("lab09.ex2", """
        def project_with_intrinsics(K, points):
            X = np.atleast_2d(np.asarray(points, dtype=np.float64))
            x = X @ np.asarray(K, dtype=np.float64).T
            return np.squeeze(x[:, :2] / x[:, 2:3])
        """, ["one-row array", "(1, 2)"]),
    "project squeezes its answer": ("lab09.ex3", """
        def project(P, points):
            X = np.atleast_2d(np.asarray(points, dtype=np.float64))
            x = np.column_stack([X, np.ones(len(X))]) @ np.asarray(P, dtype=np.float64).T
            return np.squeeze(x[:, :2] / x[:, 2:3])
        """, ["one-row array", "(1, 2)"]),
    "distort_points squeezes its answer": ("lab09.ext2", """
        _reference_distort = distort_points
        def distort_points(points, dist):
            return np.squeeze(_reference_distort(points, dist))
        """, ["one-row array", "(1, 2)"]),
    "project_onto_image draws on a BGR copy of a grey image": ("lab09.ex5", """
        def project_onto_image(image, P, points):
            if image.ndim == 2:
                image = cv2.cvtColor(image, cv2.COLOR_GRAY2BGR)   # to draw the points in colour
            pts = project(P, points).reshape(-1, 2)
            return draw_points(image, pts), pts
        """, ["grey images", "channels are not kept"]),
    # ---- whole numbers given as integers (the sheet's own (1, 1, 2), f = 1)
    "pinhole_project answers integer points in integers": ("lab09.ex1", """
        _reference_pinhole = pinhole_project
        def pinhole_project(points, f):
            image_points = np.zeros_like(np.asarray(points)[..., :2])
            image_points[...] = _reference_pinhole(points, f)
            return image_points
        """, ["`image_points = np.zeros_like(np.asarray(points)[..., :2])` (line", "then writes into it"]),
    "project_with_intrinsics answers integer points in integers": ("lab09.ex2", """
        _reference_intrinsics = project_with_intrinsics
        def project_with_intrinsics(K, points):
            pixels = np.array(points)[..., :2]
            pixels[...] = _reference_intrinsics(K, points)
            return pixels
        """, ["your answer is an integer array", "`pixels = np.array(points)[..., :2]`"]),
    "project answers integer points in integers": ("lab09.ex3", """
        _reference_project = project
        def project(P, points):
            uv = np.empty(np.shape(points)[:-1] + (2,), dtype=np.asarray(points).dtype)
            uv[...] = _reference_project(P, points)
            return uv
        """, ["your answer is an integer array", "dtype=np.asarray(points).dtype"]),
    "project_focal_lengths answers integer points in integers": ("lab09.ex4", """
        _reference_focal = project_focal_lengths
        def project_focal_lengths(points, focal_lengths):
            answers = _reference_focal(points, focal_lengths)
            return answers.astype(np.asarray(points).dtype)
        """, ["your answer is an integer array"]),
    "project_onto_image answers integer points in integers": ("lab09.ex5", """
        _reference_onto = project_onto_image
        def project_onto_image(image, P, points):
            drawn, pts = _reference_onto(image, P, points)
            pixels = np.zeros_like(np.asarray(points)[:, :2])
            pixels[...] = pts
            return drawn, pixels
        """, ["your answer is an integer array", "`pixels = np.zeros_like(np.asarray(points)[:, :2])`"]),
    "intrinsic matrix of the arguments' own type": ("lab09.ex2", """
        def intrinsic_matrix(f, px, py):
            return np.array([[f, 0, px], [0, f, py], [0, 0, 1]])
        """, ["returned an integer matrix", "matrices are float arrays"]),
    "project_onto_image draws on the caller's image": ("lab09.ex5", """
        def project_onto_image(image, P, points):
            pts = project(P, points).reshape(-1, 2)
            for x, y in pts:
                if np.isfinite(x) and np.isfinite(y):
                    cv2.circle(image, (int(round(x)), int(round(y))), 3, (0, 0, 255), -1)
            return image, pts
        """, ["draws on the caller's `image`"]),
    "calibration object points made float64": ("lab09.ext1", """
        def calibrate(images, pattern_size, square_size):
            cols, rows = pattern_size
            board = np.zeros((rows * cols, 3))
            board[:, 0] = np.tile(np.arange(cols), rows) * square_size
            board[:, 1] = np.repeat(np.arange(rows), cols) * square_size
            seen, found_corners = [], []
            for image in images:
                grey = image if image.ndim == 2 else cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)
                ok, corners = cv2.findChessboardCorners(grey, (cols, rows))
                if ok:
                    seen.append(board)
                    found_corners.append(cv2.cornerSubPix(grey, corners, (5, 5), (-1, -1),
                                                          (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 30, 1e-3)))
            h, w = images[0].shape[:2]
            rms, K, dist, _, _ = cv2.calibrateCamera(seen, found_corners, (w, h), None, None)
            return K, dist.ravel()[:5], float(rms)
        """, ["changing `np.zeros((rows * cols, 3))` to `np.zeros((rows * cols, 3), dtype=np.float32)`"]),
    # the blind set 1205e's 09/03: the points made columns by reshaping them, where the transpose belongs
    "project_with_intrinsics making columns with reshape(3, -1)": ("lab09.ex2", """
        def project_with_intrinsics(K, points):
            pts = np.asarray(points, dtype=np.float64)
            single = pts.ndim == 1
            uvw = np.asarray(K, dtype=np.float64) @ pts.reshape(3, -1)
            with np.errstate(divide="ignore", invalid="ignore"):
                xy = uvw[:2] / uvw[2]
            xy[:, uvw[2] <= 0] = np.nan
            return xy.T[0] if single else xy.T
        """, ["to `pts.reshape(-1, 3).T`"]),
    # the blind set 1205e's 09/06: the OpenCV tutorial's image size, the whole shape reversed ((3, W, H) in colour)
    "calibrate sizing the image by its whole shape reversed": ("lab09.ext1", reference_def_with(
        "lab09_camera", "calibrate",
        "rms, K, dist, _, _ = cv2.calibrateCamera(object_points, image_points, (width, height), None, None)",
        "rms, K, dist, _, _ = cv2.calibrateCamera(object_points, image_points, images[0].shape[::-1], None, None)"),
        ["to `images[0].shape[1::-1]`"]),
    # the blind set 1205e's 09/02: random directions divided by the norm of the whole array
    "simulate_aperture normalising every direction by the whole array's norm": ("lab09.ex4", """
        def simulate_aperture(points, f, aperture, n_rays=100, seed=0):
            X = np.asarray(points, dtype=np.float64).reshape(-1, 3)
            rng = np.random.default_rng(seed)
            direction = rng.standard_normal((len(X), n_rays, 2))
            direction = direction / np.linalg.norm(direction)
            radius = aperture * np.sqrt(rng.uniform(0.0, 1.0, size=(len(X), n_rays, 1)))
            ideal = f * X[:, :2] / X[:, 2:]
            return ideal[:, None, :] - radius * direction * (1.0 + f / X[:, 2])[:, None, None]
        """, ["that is the norm of the whole array", "axis=-1, keepdims=True"]),
    # the blind set 1205f's 09/05: OpenCV's RMS taken for a mean squared error, its root taken again
    "calibrate returning the square root of the RMS": ("lab09.ext1", reference_def_with(
        "lab09_camera", "calibrate", "return K, dist.ravel()[:5], float(rms)", "return K, dist.ravel()[:5], float(np.sqrt(rms))"),
        ["above what cv2.calibrateCamera's RMS", "Your code takes a square root (`np.sqrt(rms)`"]),

    # (blind set 2026-12-06c)
    "projected rows divided by the last point's row (x / x[-1], the column-vector habit)": ("lab09.ex3", """
        def project(P, points):
            P = np.asarray(P, dtype=np.float64)
            pts = np.asarray(points, dtype=np.float64)
            single = pts.ndim == 1
            pts = pts.reshape(-1, 3)
            x = np.hstack([pts, np.ones((pts.shape[0], 1))]) @ P.T
            w = x[:, 2].copy()
            with np.errstate(divide="ignore", invalid="ignore"):
                x = x / x[-1]
            uv = x[:, :2]
            uv[w <= 0] = np.nan
            return uv[0] if single else uv
        """, ["changing `x = x / x[-1]` to `x = x / x[:, -1:]`"]),

    # (blind set 2026-12-06d)
    "pinhole projections returned as the pair x, y (the sheet's (x, y))": ("lab09.ex1", """
        def pinhole_project(points, f):
            X, single = _points(points)
            x, y = f * X[:, 0] / X[:, 2], f * X[:, 1] / X[:, 2]
            if single:
                return np.array([x[0], y[0]])
            return x, y
        """, ["a tuple of 2 arrays of shape", "one per column", "np.column_stack"]),

    # (blind set 2026-12-06e)
    "project_with_intrinsics projecting with cv2.projectPoints, which takes no skew": ("lab09.ex2", """
        def project_with_intrinsics(K, points):
            X, single = _points(points)
            pixels, _ = cv2.projectPoints(X.reshape(-1, 1, 3), np.zeros(3), np.zeros(3), np.asarray(K, float), None)
            pixels = pixels.reshape(-1, 2)
            return pixels[0] if single else pixels
        """, ["x is computed as fx x / z + px", "projects with cv2.projectpoints, which takes no skew"]),
}


# Calibration is one OpenCV call; K does not depend on square_size or on the image
# size passed (it only seeds the solver), so those slips cannot change the answer.
FEWER_MISTAKES = {
    "lab09.ext1": "cv2.calibrateCamera does the estimation: what a student can get wrong and the "
                  "answer shows is the object-point grid (its order, its (cols, rows)), the layout "
                  "of K, a K that is not the calibration's own, and views of 3 channels (as cv2.imread reads a "
                  "photo) given where an OpenCV call needs one; square_size and the image size passed do not change K",
}


# Conventions the API leaves open: advice (0 points), never a lost point.
MIRRORED = """
    def _divide(homogeneous, single):       # the sheet's formula everywhere, no NaN
        pts = homogeneous[:, :2] / homogeneous[:, 2:3]
        return pts[0] if single else pts
    """


ADVICE = {f"behind the camera mirrored ({ex})": (f"lab09.{ex}", MIRRORED, ["z <= 0", "nan", "no points"])
          for ex in ("ex1", "ex2", "ex3")}


ADVICE["draw_points on NaN points raises"] = ("lab09.ex5", """
    def draw_points(image, pts, radius=3, color=(0, 0, 255)):    # the sheet: cv2.circle per point
        out = image.copy()
        for x, y in np.asarray(pts, float).reshape(-1, 2):
            cv2.circle(out, (int(round(x)), int(round(y))), radius, color, -1)
        return out
    """, ["draw_points(image, pts with a nan row and an infinite one) failed", "skip the rows that are not finite"])


# Random points of the pinhole (the API) need not be uniform over its area: a radius drawn
# uniformly crowds the rays near the centre, told, never lost points (issue 35).
ADVICE["simulate_aperture with the radius drawn uniformly (aperture * u)"] = ("lab09.ex4", """
    def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
        X, _ = _points(points)
        rng = np.random.default_rng(seed)
        radius = aperture * rng.uniform(0.0, 1.0, size=(len(X), n_rays))
        angle = rng.uniform(0.0, 2 * np.pi, size=(len(X), n_rays))
        A = np.stack([radius * np.cos(angle), radius * np.sin(angle)], axis=-1)
        return pinhole_project(X, f)[:, None, :] - A * (1.0 + f / X[:, 2])[:, None, None]
    """, ["the rays crowd the centre", "aperture * u", "aperture * sqrt(u)"])


# Filled circles "at the points" (the API): a centre truncated with int() is a pixel off for
# fractional parts >= 0.5, accepted by the graded coverage and told (issue 35).
ADVICE["draw_points truncating the centres with int()"] = ("lab09.ex5", """
    def draw_points(image, pts, radius=3, color=(0, 0, 255)):
        out = image.copy()
        for x, y in np.asarray(pts, dtype=np.float64).reshape(-1, 2):
            if np.isfinite(x) and np.isfinite(y):
                cv2.circle(out, (int(x), int(y)), int(radius), tuple(int(c) for c in color), -1)
        return out
    """, ["centred at (floor(x), floor(y))", "the centres are truncated (int())", "int(round(x))"])


# the blind set 1205f's 09/02: t inserted as it comes, a (3, 1) column made three columns of P
ADVICE["camera_matrix inserting t without flattening it"] = ("lab09.ex3", """
    def camera_matrix(K, R, t):
        return np.asarray(K, dtype=np.float64) @ np.insert(np.asarray(R, dtype=np.float64), 3, t, axis=1)
    """, ["with t of shape (3, 1)", "np.ravel(t)"])
