"""The shared engine's sentences are held to the student's code, as the labs' are (issue 35).

``tests/test_hints_coverage.py`` holds every lab's strings to the code; the sentences every lab
shares come from the engine: the judges (:mod:`autograder.engine.judges`), the forms named from a
shape or NumPy's error (:mod:`autograder.engine.forms`), the in-place effect
(:mod:`autograder.engine.inplace`), the runner's advice and the explanations of OpenCV and NumPy
exceptions (:mod:`autograder.sandbox.beginner`). Each of their strings that reads like an
instruction or names code is, as in the labs, a guarded sentence or a Hint with ``asks=``, or
marked ``measured()``; the rest are listed below with the reason they are neither:

- ``VersionDifference`` sentences, said only when their Predicate reads the code (from the code);
- sentences addressed to the course's author or the grader's operator, not to a student about
  their code (a lab folder's key, a check registered wrongly, the installed OpenCV);
- the explanations of an OpenCV/NumPy exception, built in the worker from the arguments of the
  call that raised (``yours is int64: convert it with ...``): the fix is about the value measured
  there. The sandbox imports nothing of the engine, so they are listed here, not marked there.

Then, for each sentence guarded here, the code that already does what it asks is not told it,
and the realistic mistake still is.
"""

from __future__ import annotations

import ast
import textwrap
from pathlib import Path

import pytest

from autograder.engine import claims, forms, inplace, judges, runner  # noqa: F401 - register their sentences
from autograder.engine.hints import read_code
from autograder.sandbox import beginner
from test_hints_coverage import unheld

ROOT = Path(__file__).resolve().parents[1]
# claims.py and hints.py define the predicates: their strings are what a predicate says it found.
SHARED = sorted(path for path in (ROOT / "autograder" / "engine").glob("*.py")
                if path.name not in ("claims.py", "hints.py")) + [ROOT / "autograder" / "sandbox" / "beginner.py"]

NOT_TO_A_STUDENT = {
    "labfolders.py": [": give this lab another key (lab13, lab14 ...)"],
    "registry.py": ["{}: check {} needs positive points"],
    "runner.py": ["check returned {}, not a Verdict"],
    "versions.py": ['this course grades with OpenCV {} ("opencv" in its configuration) but OpenCV {} is installed '
                    "here: install the course's pins with `{}` in the grader's folder, or set \"opencv\": \"{}\"."],
    # an input to run again, not code to write
    "checks.py": ["\nSmallest failing input found: {}\n(inputs drawn for this submission: try this one directly, "
                  "your own runs draw others)"],
}
EXCEPTION_EXPLAINED = (   # autograder/sandbox/beginner.py: the value of the call that raised, measured
    "{} needs a whole number for {}; yours is {}: use int(round({}))",
    "{} needs {} as whole numbers, {}; yours is {}: round them, e.g. (int(round(x)), int(round(y)))",
    "{} needs {} as whole numbers within OpenCV's int range (below 2^31 in size); yours is {}: a point that far "
    "away cannot be drawn, clip the end points to the image first (cv2.clipLine)",
    " (did cv2.imread find the file, or a function of yours return nothing?)",
    ": np.asarray(...) makes one",
    "{} needs {} as a float32 or float64 matrix; yours is {}: build it with dtype=float (np.array([[1, 0, tx], "
    "...], dtype=float)) or convert it with {}.astype(np.float64)",
    ": pass its first two rows, {}[:2]",
    ": {} applies {} to every pixel alike, so a weight that changes from pixel to pixel is applied with NumPy "
    "(multiply the arrays by it)",
    ": add the row [0, 0, 1], or warp with cv2.warpAffine",
    "{} needs {} as exactly {} points of {} float32 coordinates, shape ({}, {}); yours is {}: np.float32({})",
    "{} needs points of shape (N, 1, 2) and a 3x3 matrix; yours are {}: pass points.reshape(-1, 1, 2)",
    "{} needs the points in {} as float32 or float64; yours are {}: convert them with {}.astype(np.float64)",
    "{} needs {} as a grey uint8 image (H, W); yours is {}: convert it with {}",
    "{} cannot work on {}, a {} image: OpenCV images are uint8 (or float32); convert it with np.clip(x, 0, "
    "255).astype(np.uint8) or x.astype(np.float32)",
    "{} got None for {}: no image (did cv2.imread find the file, or a function of yours return nothing?)",
    "{} needs grey uint8 images, shape (H, W): convert with cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) and "
    "np.clip(x, 0, 255).astype(np.uint8)",
    "{} needs a float32 or float64 matrix: build it with dtype=float",
    "{} takes {} as {}; yours is {}: convert it with {}",
    ", the size of src itself: either src is a level too large (a pyramid level that was never halved by "
    "cv2.pyrDown) or the dstsize is src's own level's",
    # the measured part around a guarded fix (INDEX_AS_Y_X, BUILD_AS_FLOAT)
    "an image is indexed [row, column], that is [y, x]: index {} fits its {} ({}) but not its {} ({}); ",
    "it holds integers ({}), where the answer has fractions: an array made of whole numbers (np.array([[1, 0, 0], "
    "...]), np.eye(3, dtype=int)) is an integer array, and the fractions written into it are cut off. ",
)
ALLOWED = {**NOT_TO_A_STUDENT, "beginner.py": list(EXCEPTION_EXPLAINED)}


def _from_code_lines(path: Path) -> set[int]:
    """Lines of ``VersionDifference(...)`` calls: their sentences are said only where the code holds
    their Predicate (:func:`autograder.engine.version_differences.with_version_note`)."""
    tree = ast.parse(path.read_text())
    return {line for node in ast.walk(tree) if isinstance(node, ast.Call) and getattr(node.func, "id", "")
            == "VersionDifference" for line in range(node.lineno, node.end_lineno + 1)}


@pytest.mark.parametrize("path", SHARED, ids=lambda path: path.name)
def test_every_shared_sentence_asking_for_code_is_held_to_the_code(path):
    allowed = ALLOWED.get(path.name, [])
    found = [(line, text) for line, text in unheld(path) if line not in _from_code_lines(path)]
    problems = [f"{path.relative_to(ROOT)}:{line}: {text!r}" for line, text in found if text not in allowed]
    assert not problems, "sentences asking for code without a Hint/guard or a measured() mark:\n" + "\n".join(problems)
    stale = set(allowed) - {text for _, text in found}
    assert not stale, f"listed as allowed but no longer found (drop them from the list): {stale}"


# ------------------------------------------------------------------ each guard: told, or not
def told(text: str, source: str, function: str = "f") -> bool:
    """Whether the guarded ``text`` is said as it is to ``source`` (else its ``instead``)."""
    return not claims.GUARDED[text].contradicts(read_code(textwrap.dedent(source)), [function])


def test_points_left_homogeneous_dividing_already_are_told_only_to_keep_the_first_ones():
    sentence = forms.shape_form((10, 3), (None, 2)).sentence
    assert forms.DEHOMOGENISE[2] in sentence   # rewritten finds it in the message
    assert told(forms.DEHOMOGENISE[2], """
        def f(P, X):
            return (P @ np.c_[X, np.ones(len(X))].T).T
        """)
    already = """
        def f(P, X):
            x = (P @ np.c_[X, np.ones(len(X))].T).T
            w = x[:, 2:3]
            return x / w
        """
    assert not told(forms.DEHOMOGENISE[2], already)
    assert "keep only the first 2" in claims.GUARDED[forms.DEHOMOGENISE[2]].neutral()
    assert not told(forms.DEHOMOGENISE[3], "def f(X):\n    return X / X[:, -1:]\n")
    assert told(forms.DEHOMOGENISE[3], "def f(X):\n    return X / X[:, 0:1]\n")   # the wrong one is no fix


def test_the_wrong_coordinate_is_named_a_cause_only_of_code_that_divides():
    sentence = forms.scale_form([1.0, 2.0, 0.5], [2.0, 4.0, 1.0]).sentence
    assert forms.WRONG_COORDINATE in sentence
    assert told(forms.WRONG_COORDINATE, "def f(X):\n    return X[:, :2] / X[:, 1:2]\n")
    assert not told(forms.WRONG_COORDINATE, "def f(X):\n    return X[:, :2] * 2\n")


def test_an_ignored_parameter_is_called_fixed_only_when_the_code_never_reads_it():
    hint = judges.unused_parameter_hint("k")
    fixed = """
        def f(image, k=0.04):
            return cv2.cornerHarris(image, 2, 3, 0.04)
        """
    overwritten = """
        def f(image, k=0.04):
            k = 0.04
            return cv2.cornerHarris(image, 2, 3, k)
        """
    assert not hint.contradicts(read_code(textwrap.dedent(fixed)), ["f"])
    assert hint.contradicts(read_code(textwrap.dedent(overwritten)), ["f"]) == "reads k"
    assert "yet the result does not change" in hint.neutral()


def test_augmented_assignment_is_mentioned_only_to_code_that_writes_one():
    text = ", and write x = x / s rather than x /= s"
    assert inplace.HINT.endswith(text)
    assert told(text, "def f(x):\n    x /= x.max()\n    return x\n")
    assert told(text, "def f(x):\n    x[:, 0] -= x[:, 0].mean()\n    return x\n")
    assert not told(text, "def f(x):\n    x[x < 0] = 0\n    return x\n")   # written in place, no /=
    assert claims.GUARDED[text].neutral() == ""


def test_index_order_is_asked_only_of_code_not_indexing_y_x():
    message = beginner.explain_index_error("index 12 is out of bounds for axis 0 with size 10",
                                           [__import__("numpy").zeros((10, 20), "uint8")])
    assert message.endswith(beginner.INDEX_AS_Y_X)
    swapped = """
        def f(image):
            for x in range(image.shape[1]):
                for y in range(image.shape[0]):
                    image[x, y] = 0
        """
    past_the_end = """
        def f(image):
            h, w = image.shape
            for y in range(h + 2):
                for x in range(w):
                    image[y, x] = 0
        """
    assert told(beginner.INDEX_AS_Y_X, swapped)
    assert not told(beginner.INDEX_AS_Y_X, past_the_end)


def test_float_is_asked_only_of_code_making_no_float_array():
    integer = "def f(R):\n    M = np.eye(3, dtype=int)\n    M[:2, :2] = R\n    return M\n"
    as_int = "def f(R):\n    M = np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.int32)\n    return M\n"
    elsewhere = "def f(R):\n    R = np.asarray(R, dtype=float)\n    M = np.eye(3, dtype=int)\n    M[:2, :2] = R\n" \
                "    return M\n"
    assert told(beginner.BUILD_AS_FLOAT, integer) and told(beginner.BUILD_AS_FLOAT, as_int)
    assert not told(beginner.BUILD_AS_FLOAT, elsewhere)
    assert told(beginner.CONVERT_FIRST, "def f(a, b):\n    return a - b\n")
    assert not told(beginner.CONVERT_FIRST, "def f(a, b):\n    return a.astype(np.float64) - b\n")


def test_rgb_conversion_is_blamed_only_on_code_that_converts():
    assert beginner.RGB_FOR_BGR.endswith(beginner.RGB_ONLY_TO_SHOW)
    assert told(beginner.RGB_ONLY_TO_SHOW, "def f(image):\n    return cv2.cvtColor(image, cv2.COLOR_BGR2RGB)\n")
    assert not told(beginner.RGB_ONLY_TO_SHOW, "def f(b, g, r):\n    return np.dstack([r, g, b])\n")


def test_a_division_by_a_third_coordinate_made_a_column_is_read_as_the_division():
    """`w = x_h[:, 2]` then `x_h / w[:, None]` (or `w.reshape(-1, 1)`) divides by the third coordinate: code that
    does it and returns the undivided array is not told the division is missing, but that what it returns is not
    the divided points; a division by a constant is no such division."""
    from autograder.labs.lab09 import PROJECTION_DIVISION_MISSING
    text = PROJECTION_DIVISION_MISSING   # (guard returns the sentence itself)
    source = """
        def f(P, X):
            x_h = X @ P.T
            w = x_h[:, 2]
            x_n = x_h / w[:, None]
            return x_h[:, :2]
        """
    assert not told(text, source)
    assert not told(text, source.replace("w[:, None]", "w.reshape(-1, 1)"))
    assert told(text, source.replace("x_h / w[:, None]", "x_h / 2.0"))
