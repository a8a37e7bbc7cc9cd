"""Lab 7: single-bug submissions written apart from the tables (see the package docstring)."""

from . import Case

MODULE = "lab07_transformations"

CASES = [
    Case("translation matrix started from an integer identity", "lab07.ex1", """
        def translation_matrix(tx, ty):
            M = np.eye(3, dtype=int)
            M[0, 2] = tx
            M[1, 2] = ty
            return M
        """, "the matrix is an integer array: a fractional tx or ty is cut off",
         ("integer", "int", "fractions", "truncat")),

    Case("translate by slicing (positive whole shifts only)", "lab07.ex1", """
        def translate(image, tx=100, ty=50):
            out = np.zeros_like(image)
            h, w = image.shape[:2]
            tx, ty = int(tx), int(ty)
            out[ty:, tx:] = image[:h - ty, :w - tx]
            return out
        """, "slicing handles only non-negative whole-pixel shifts (a negative tx wraps the slice)",
         ("negative", "slic")),

    Case("rotation about a centre with R transposed in the translation column", "lab07.ex2", """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            theta = np.deg2rad(angle_deg)
            c, s = np.cos(theta), np.sin(theta)
            R = np.array([[c, s], [-s, c]])
            center = np.asarray(center, dtype=float)
            M = np.eye(3)
            M[:2, :2] = R
            M[:2, 2] = center - R.T @ center
            return M
        """, "the translation column uses R^T where (I - R) c needs R: a wrong operand",
         ("r^t c", "r.t @", "uses r^t", "r transposed in the translation")),

    Case("degrees to radians with 360 for 180", "lab07.ex2", """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            theta = angle_deg * np.pi / 360
            c, s = np.cos(theta), np.sin(theta)
            R = np.array([[c, s], [-s, c]])
            cx, cy = center
            M = np.eye(3)
            M[:2, :2] = R
            M[:2, 2] = np.array([cx, cy]) - R @ np.array([cx, cy])
            return M
        """, "theta = angle * pi / 360: the rotation is by half the angle",
         ("half the angle", "360", "half")),

    Case("least-squares parameters reshaped (3, 2) and transposed", "lab07.ex6", """
        def affine_lstsq(src, dst):
            src = np.asarray(src, dtype=float)
            dst = np.asarray(dst, dtype=float)
            rows, b = [], []
            for (x, y), (xp, yp) in zip(src, dst):
                rows.append([x, y, 1, 0, 0, 0])
                rows.append([0, 0, 0, x, y, 1])
                b += [xp, yp]
            params = np.linalg.lstsq(np.array(rows), np.array(b), rcond=None)[0]
            return params.reshape(3, 2).T
        """, "the six parameters (a, b, tx, c, d, ty) are reshaped in the wrong order",
         ("order", "reshape", "unknowns")),

    Case("affine from three points with a column of zeros", "lab07.ex5", """
        def affine_from_points(src, dst):
            src = np.asarray(src, dtype=float)
            dst = np.asarray(dst, dtype=float)
            S = np.hstack([src, np.zeros((3, 1))])
            X = np.linalg.lstsq(S, dst, rcond=None)[0]
            return X.T
        """, "the homogeneous column is zeros instead of ones: no translation can be fitted",
         ("0 instead of 1", "column of ones", "zeros", "translation", "homogeneous")),

    Case("scale keeps the whole scaled image (output enlarged)", "lab07.ex3", """
        def scale(image, sx=1.5, sy=1.5):
            h, w = image.shape[:2]
            M = scaling_matrix(sx, sy)[:2]
            return cv2.warpAffine(image, M, (int(w * sx), int(h * sy)))
        """, "the output is the scaled size, not the input size (the API keeps the size)",
         ("size", "shape", "dsize")),
]
