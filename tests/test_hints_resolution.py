"""Hint predicates resolve what a called name refers to (autograder/engine/hints.py): a module's
function under any alias or imported from it, never a function of the student's own module that
happens to share its last name (a student's ``recoverPose`` is not ``cv2.recoverPose``)."""

import textwrap

import pytest

from autograder.engine.hints import calls, keyword, mentions, passes_product, read_code
from autograder.labs.lab11 import IN_FRONT_HINT


def found(predicate, source: str, function: str = "f") -> str:
    return predicate.found(read_code(textwrap.dedent(source)).reachable([function]))


@pytest.mark.parametrize("source, refers", [
    ("import cv2\ndef f(E, a, b):\n    return cv2.recoverPose(E, a, b)\n", True),
    ("import cv2 as cv\ndef f(E, a, b):\n    return cv.recoverPose(E, a, b)\n", True),
    ("from cv2 import recoverPose\ndef f(E, a, b):\n    return recoverPose(E, a, b)\n", True),
    ("from cv2 import recoverPose as pose\ndef f(E, a, b):\n    return pose(E, a, b)\n", True),
    ("def f(E, a, b):\n    import cv2 as cv\n    return cv.recoverPose(E, a, b)\n", True),    # imported inside
    ("import cv2\ndef recoverPose(E, a, b):\n    return E\ndef f(E, a, b):\n    return recoverPose(E, a, b)\n", False),
    ("import cv2\ndef f(E, a, b):\n    def recoverPose(E):\n        return E\n    return recoverPose(E)\n", False),
    ("import mytools\ndef f(E, a, b):\n    return mytools.recoverPose(E, a, b)\n", False),   # another module's
    ("def f(E, a, b):\n    return recoverPose(E, a, b)\n", False),                # nothing says it is cv2's
    ("from cv2 import *\ndef f(E, a, b):\n    return recoverPose(E, a, b)\n", True),
])
def test_a_call_is_cv2s_only_when_the_name_refers_to_cv2(source, refers):
    assert bool(found(calls("cv2.recoverPose"), source)) is refers


def test_numpy_under_any_alias_and_its_submodules_and_methods():
    assert found(calls("np.linalg.svd"), "import numpy as xp\ndef f(A):\n    return xp.linalg.svd(A)\n")
    assert found(calls("np.linalg.svd"), "from numpy.linalg import svd\ndef f(A):\n    return svd(A)\n")
    assert found(calls("np.linalg.svd"), "import numpy.linalg as la\ndef f(A):\n    return la.svd(A)\n")
    assert found(calls("np.linalg.svd"), "from scipy import linalg\ndef f(A):\n    return linalg.svd(A)\n")
    assert found(calls("np.argmax"), "def f(a):\n    return a.argmax(0)\n")                 # a method of a value
    assert not found(calls("np.argmax"), "def argmax(a):\n    return 0\ndef f(a):\n    return argmax(a)\n")
    assert not found(calls("np.argmax"), "import torch\ndef f(a):\n    return torch.argmax(a)\n")


def test_the_last_name_alone_still_names_the_students_own_api_function():
    """``calls("transform_points")`` asks for the student's own function: it is found."""
    source = "def transform_points(H, p):\n    return p\ndef f(H, p):\n    return transform_points(H, p)\n"
    assert found(calls("transform_points"), source)
    assert not found(calls(".transform_points"), source)


def test_keywords_attributes_and_products_resolve_too():
    own = """
        def warpPerspective(img, M, size):
            return img
        BORDER_CONSTANT = 0
        def f(img, T, H):
            return warpPerspective(img, T @ H, (4, 4), borderMode=BORDER_CONSTANT)
        """
    assert not found(passes_product("cv2.warpPerspective", 1), own)
    assert not found(keyword("cv2.warpPerspective", "borderMode"), own)
    real = "import cv2 as cv\ndef f(img, T, H):\n    return cv.warpPerspective(img, T @ H, (4, 4), " \
           "borderMode=cv.BORDER_CONSTANT)\n"
    assert found(passes_product("cv2.warpPerspective", 1), real)
    assert found(keyword("cv2.warpPerspective", "borderMode", "cv2.BORDER_CONSTANT"), real)
    assert found(mentions("cv2.BORDER_CONSTANT"), real)


def test_a_students_own_recover_pose_is_told_to_use_cv2s():
    """The issue's case the other way round: a student's own ``recoverPose`` (which does not test
    the points in front) is no reason to take back lab 11's advice to use cv2.recoverPose."""
    source = textwrap.dedent("""
        import numpy as np
        def recoverPose(E, pts1, pts2, K):
            U, _, Vt = np.linalg.svd(E)
            return 0, U @ Vt, U[:, 2:], None
        def two_view_reconstruction(pts1, pts2, K):
            _, R, t, _ = recoverPose(np.eye(3), pts1, pts2, K)
            return R, t
        """)
    code = read_code(source)
    assert not IN_FRONT_HINT.contradicts(code, ["two_view_reconstruction"])
    imported = read_code(source.replace("def recoverPose", "from cv2 import recoverPose\ndef _unused"))
    assert IN_FRONT_HINT.contradicts(imported, ["two_view_reconstruction"])
