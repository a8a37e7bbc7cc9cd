"""Notebooks are graded as running them from the top defines (issue 27).

Three kinds of tests:

- the rules, one by one, on small notebooks (what is kept, what is left out and
  the words the note gives);
- a property: any notebook drawn from a pool of cells (definitions, derived
  values, helpers, demo code and what depends on it), run top to bottom in this
  process and imported as grading converts it, defines the same values under the
  names grading keeps, and keeps exactly the statements whose needs are kept;
- a corpus of realistic notebooks (data loading, plots, Colab and seaborn
  imports, magics, helpers, cells depending on earlier output, cells that fail),
  each holding the reference solution's functions, graded end to end: each
  scores what the reference module scores.
"""

from __future__ import annotations

import json
import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from autograder.loading.definitions import available_at_grading
from autograder.loading.notebooks import convert
from autograder.engine.runner import grade
from conftest import REFERENCE

MODULE = "lab07_transformations"
SELECTED = ["lab07.ex1", "lab07.ex2"]
REFERENCE_SOURCE = (REFERENCE / f"{MODULE}.py").read_text()


def notebook(*cells, tags=None) -> str:
    """A notebook's JSON with these code cells (a Markdown title first, as students write)."""
    tags = tags or {}
    return json.dumps({"cells": [{"cell_type": "markdown", "metadata": {}, "source": "# Lab"}] + [
        {"cell_type": "code", "metadata": {"tags": tags.get(i, [])}, "source": source, "outputs": [],
         "execution_count": None} for i, source in enumerate(cells)],
        "metadata": {}, "nbformat": 4, "nbformat_minor": 5})


def kept_code(converted) -> list[str]:
    return [line for line in converted.source.splitlines() if line.strip() and not line.startswith("#")]


def module_namespace(converted, guarded: bool = False) -> dict:
    """What importing the converted module defines (it runs here: the tests' own notebooks)."""
    namespace: dict = {"__name__": "graded"}
    source = converted.guarded_source if guarded else converted.source
    exec(compile(source, "graded.py", "exec"), namespace)  # noqa: S102
    return namespace


# ------------------------------------------------------------------ the rules
def test_a_value_needing_demo_code_is_left_out_with_it_and_named():
    """The issue's case: size = img.shape was kept without img, and importing raised NameError."""
    converted = convert(notebook("import numpy as np\nimport skimage",
                                 "img = skimage.data.astronaut()",
                                 "size = img.shape\nh, w = size[:2]",
                                 "def centre():\n    return (w / 2, h / 2)"), "lab.ipynb")
    namespace = module_namespace(converted)
    assert "centre" in namespace and "img" not in namespace and "size" not in namespace
    note = converted.left_out_note("lab.ipynb")
    assert "cell 3 `img = skimage.data.astronaut()` (a call: demo code)" in note
    assert "cell 4 `size = img.shape` (needs img)" in note
    assert "centre() uses h" in note  # a kept function reading a left-out name is named, first
    assert note.index("centre() uses") < note.index("`img = skimage")
    assert "import skimage" in note  # only the left-out statement used it


@pytest.mark.parametrize("k_cell, kept", [
    ("K = np.array([[800, 0, 320], [0, 800, 240], [0, 0, 1]])", True),
    ("K = np.load('camera.npy')", False),
    ("K = calibrate(images)", False),
])
def test_a_derived_value_is_kept_exactly_when_what_it_needs_is(k_cell, kept):
    converted = convert(notebook("import numpy as np", k_cell, "R = np.eye(3)", "H = K @ R\nHinv = np.linalg.inv(H)"))
    namespace = module_namespace(converted)
    assert ("H" in namespace and "Hinv" in namespace) is kept
    assert "R" in namespace
    if kept:
        assert np.array_equal(namespace["H"], namespace["K"] @ np.eye(3))


def test_names_nothing_defines_are_left_out_not_raised():
    converted = convert(notebook("x = undefined + 1\ny = x * 2", "last = _\nprevious = Out[3]"))
    module_namespace(converted)
    reasons = [o.reason for o in converted.omissions]
    assert reasons == ["needs undefined, which no earlier cell defines", "needs x",
                       "needs _, which only Jupyter defines", "needs Out, which only Jupyter defines"]


def test_assigned_callables_are_definitions():
    """to_h = lambda p: ... was left out and a function using it failed with NameError."""
    converted = convert(notebook(
        "import functools\nimport numpy as np\nimport cv2",
        "to_h = lambda p: np.append(p, 1.0)\nscale2 = functools.partial(np.multiply, 2.0)\n"
        "clip = np.vectorize(lambda v: min(max(v, 0), 255))\nsift = cv2.SIFT_create()\n"
        "inv = np.linalg.inv\nfrom collections import namedtuple\nPoint = namedtuple('Point', 'x y')\n"
        "ORIGIN = Point(0.0, 0.0)",
        "def lift(p):\n    return scale2(to_h(p))"))
    namespace = module_namespace(converted)
    assert namespace["lift"]((1.0, 2.0)).tolist() == [2.0, 4.0, 2.0]
    assert converted.omissions == []
    assert namespace["ORIGIN"] == (0.0, 0.0) and namespace["inv"] is np.linalg.inv


def test_calls_that_run_the_notebooks_own_code_are_demo():
    converted = convert(notebook(
        "def f(x):\n    raise NotImplementedError", "y = f(1)", "ys = list(map(f, [1, 2]))",
        "zs = sorted([2, 1], key=f)", "g = lambda v: f(v)", "w = g(3)"))
    namespace = module_namespace(converted)  # no call of f at import: a stub costs nothing
    assert set(namespace) >= {"f", "g"} and not set(namespace) & {"y", "ys", "zs", "w"}
    assert [o.reason for o in converted.omissions][:3] == ["runs f(): demo code", "runs your code: demo code",
                                                            "runs your code: demo code"]


def test_a_lambda_that_only_computes_may_be_handed_to_a_library_call():
    converted = convert(notebook("def f(p):\n    raise NotImplementedError",
                                 "ORDER = sorted([(2, 'b'), (1, 'a')], key=lambda p: p[0])",
                                 "BY_F = sorted([(2, 'b'), (1, 'a')], key=lambda p: f(p))"))
    namespace = module_namespace(converted)
    assert namespace["ORDER"] == [(1, "a"), (2, "b")] and "BY_F" not in namespace


def test_the_notebooks_own_check_calls_are_not_worth_a_note():
    converted = convert(notebook("import numpy as np\nK = np.eye(3)", "from autograder import check",
                                 "report = check('lab07.ex1')\nprint(report.score)\nreport"))
    assert [o.listed for o in converted.omissions] == [False, False, False, False]
    assert converted.left_out_note("n.ipynb") == ""


def test_imports_go_with_the_statements_that_use_them():
    converted = convert(notebook(
        "import numpy as np\nimport matplotlib.pyplot as plt\nimport seaborn as sns\n"
        "from google.colab.patches import cv2_imshow\nfrom google.colab import drive\nimport cv2",
        "drive.mount('/content/drive')\nimg = cv2.imread('/content/drive/MyDrive/lena.png')",
        "sns.set_theme()\nplt.imshow(img)\nplt.show()\ncv2_imshow(img)",
        "def translate(image):\n    return cv2.warpAffine(image, np.eye(3)[:2], image.shape[1::-1])"))
    code = kept_code(converted)
    assert code[:2] == ["import numpy as np", "import cv2"]  # cv2: translate's body reads it
    module_namespace(converted)
    reasons = {o.text: o.reason for o in converted.omissions}
    assert reasons["import matplotlib.pyplot as plt"] == "used only by statements left out"
    assert reasons["import seaborn as sns"] == "seaborn is not available where grading runs"
    assert reasons["from google.colab import drive"] == "google.colab is not available where grading runs"


def test_a_library_grading_lacks_costs_only_the_functions_that_use_it():
    converted = convert(notebook("import numpy as np\nimport seaborn as sns",
                                 "def heat(x):\n    sns.heatmap(x)", "def double(x):\n    return 2 * x"))
    namespace = module_namespace(converted)
    assert namespace["double"](2) == 4 and "sns" not in namespace
    assert "heat() uses sns" in converted.left_out_note("n.ipynb")


def test_a_guarded_import_and_a_misspelt_unused_one_are_kept_as_written():
    converted = convert(notebook("try:\n    import seaborn as sns\nexcept ImportError:\n    sns = None",
                                 "import numpyy"))
    assert kept_code(converted)[-1] == "import numpyy"  # reported at its cell and line when imported
    assert "    import seaborn as sns" in kept_code(converted)


def test_ipython_syntax_is_commented_out_and_python_cell_magics_keep_their_code():
    converted = convert(notebook(
        "%matplotlib inline\n!pip install opencv-python\n%pip install seaborn\nfiles = !ls\n"
        "timing = %timeit -o 1 + 1\nnp.array?\n??np.eye\nimport numpy as np",
        "%%bash\nls -la\necho $HOME",
        "%%writefile helper.py\ndef helper():\n    return 1",
        "%%time\nW = 640\nfor i in range(2):\n    %time y = i\n    !echo hi"))
    namespace = module_namespace(converted)
    assert namespace["W"] == 640 and "helper" not in namespace and "files" not in namespace
    assert kept_code(converted) == ["import numpy as np", "W = 640", "for i in range(2):",
                                    "    pass  # %time y = i", "    pass  # !echo hi"]


def test_ipython_syntax_commented_out_is_named_in_the_note_as_written():
    """`!pip install seaborn` installs nothing where grading runs: the note names each magic left out as the student
    wrote it, a non-Python cell once by its first line, a Python cell magic by its own line (its code is kept) -- the
    guide said so, the note did not (audit of 2026-12-07)."""
    converted = convert(notebook("%matplotlib inline\n!pip install seaborn\nimport numpy as np",
                                 "%%bash\nls -la", "%%time\nW = 640"))
    lines = converted.left_out_lines()   # (cell 1 is the notebook's heading)
    assert "cell 2 `%matplotlib inline` (IPython syntax: commented out)" in lines
    assert "cell 2 `!pip install seaborn` (IPython syntax: commented out)" in lines
    assert "cell 3 `%%bash` (IPython syntax: the whole cell is commented out)" in lines
    assert "cell 4 `%%time` (IPython syntax: commented out)" in lines and not any("W = 640" in line for line in lines)


def test_a_line_holding_kept_and_left_out_statements_keeps_the_kept_ones():
    converted = convert(notebook("import numpy as np", "img = np.load('x.npy'); K = np.eye(3); print(K)"))
    namespace = module_namespace(converted)
    assert "K" in namespace and "img" not in namespace
    assert kept_code(converted)[-1] == "pass; K = np.eye(3); pass"


def test_changes_to_kept_values_are_kept_and_to_left_out_ones_left_out():
    converted = convert(notebook(
        "import numpy as np\nK = np.eye(3)\nK[0, 2] = 320\nK[1, 2] += 240\nPOINTS = []\nPOINTS.append((1, 2))\n"
        "for k in range(2):\n    POINTS.append((k, k))\ncount = 0\ncount += len(POINTS)",
        "img = np.load('x.npy')\nimg[0, 0] = 255\nK[0, 0] = img.mean()\nsize = K.shape"))
    namespace = module_namespace(converted)
    assert namespace["K"].tolist() == [[1, 0, 320], [0, 1, 240], [0, 0, 1]]
    assert namespace["POINTS"] == [(1, 2), (0, 0), (1, 1)] and namespace["count"] == 3
    # K[0, 0] = img.mean() is left out: K is then not what running the notebook gives, nor is size
    assert "size" not in namespace and [o.reason for o in converted.omissions][-1] == "needs K"


def test_a_kept_value_that_raises_is_skipped_at_grading_as_jupyter_goes_on():
    converted = convert(notebook("import numpy as np\nK = np.zeros((3, 3))\nKinv = np.linalg.inv(K); ok = 1",
                                 "ratio = 1 / 0\nlater = ratio * 2", "def f():\n    return ratio",
                                 "POINTS = [1]\nPOINTS.append(POINTS[5])\nd = {}\nd['x'] += 1"))
    with pytest.raises(np.linalg.LinAlgError):
        module_namespace(converted)  # the plain module: as Jupyter shows it, the cell fails
    graded = module_namespace(converted, guarded=True)
    assert "f" in graded and not {"Kinv", "ok", "ratio", "later"} & set(graded)
    assert graded["POINTS"] == [1] and graded["d"] == {}
    assert converted.guarded_source.count("\n") == converted.source.count("\n")  # lines keep their numbers
    assert 'with __import__("contextlib").suppress(Exception): ratio = 1 / 0' in converted.guarded_source
    assert "def f():" in converted.guarded_source.splitlines()  # definitions are not guarded


def test_expressions_nested_too_deep_to_judge_are_read_flat_never_a_grader_crash():
    sums = "+".join(["1"] * 900)
    converted = convert(notebook(f"x = {sums}", "import numpy as np\ny = np.sum(" + "+".join(["np.eye(2)"] * 600) + ")",
                                 "if True:\n" + "".join("    " * (i + 1) + "if True:\n" for i in range(90))
                                 + "    " * 92 + "z = 1"))
    assert kept_code(converted)[0] == f"x = {sums}"
    assert [o.reason for o in converted.omissions][0] == "a call: demo code"


def test_tags_still_decide_where_given():
    converted = convert(notebook("import numpy as np", "K = np.load('K.npy')", "H = K @ np.eye(3)",
                                 tags={1: ["grade"], 2: ["skip-grading"]}))
    assert kept_code(converted) == ["import numpy as np", "K = np.load('K.npy')"]
    assert converted.omissions[0].reason == "the cell is tagged skip-grading"


def test_availability_follows_what_the_sandbox_lets_the_worker_import():
    assert all(available_at_grading(m) for m in ("numpy", "cv2", "matplotlib.pyplot", "skimage.data", "math",
                                                 "collections.abc", "scipy.ndimage"))
    assert not any(available_at_grading(m) for m in ("seaborn", "google.colab", "pandas", "torch", ""))
    assert available_at_grading("helpers", local={"helpers"})


# ------------------------------------------------------------------ the property
# (source, names it defines, names it needs, demo): the pool of cells notebooks are drawn from,
# in an order in which each needs only earlier ones.
POOL = [
    ("import numpy as np", {"np"}, set(), False),
    ("def load():\n    return np.arange(24.0).reshape(4, 6)", {"load"}, {"np"}, False),  # np: when called
    ("K = np.array([[800.0, 0, 320], [0, 800, 240], [0, 0, 1]])", {"K"}, {"np"}, False),
    ("R = np.eye(3)", {"R"}, {"np"}, False),
    ("img = load()", {"img"}, {"load"}, True),
    ("H = K @ R", {"H"}, {"K", "R"}, False),
    ("size = img.shape", {"size"}, {"img"}, False),
    ("h, w = size[:2]", {"h", "w"}, {"size"}, False),
    ("centre = (w / 2, h / 2)", {"centre"}, {"w", "h"}, False),
    ("to_h = lambda p: np.append(p, 1.0)", {"to_h"}, set(), False),
    ("moved = to_h(np.zeros(2))", {"moved"}, {"to_h", "np"}, True),
    ("print(H)", set(), {"H"}, True),
    ("K[0, 2] = 330.0", set(), {"K"}, False),
    ("ANGLE = np.deg2rad(30)\nc, s = np.cos(ANGLE), np.sin(ANGLE)", {"ANGLE", "c", "s"}, {"np"}, False),
    ("Rz = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])", {"Rz"}, {"c", "s", "np"}, False),
    ("PTS = []\nPTS.append((1, 2))", {"PTS"}, set(), False),
    ("brightness = img.mean()\nnormalised = img / brightness", {"brightness", "normalised"}, {"img"}, False),
    ("names = [f'p{i}' for i in range(3)]\nlookup = {n: i for i, n in enumerate(names)}",
     {"names", "lookup"}, set(), False),
    ("scale = float(K[0, 0]) / 2\nKinv = np.linalg.inv(K)", {"scale", "Kinv"}, {"K", "np"}, False),
    ("import functools\nshift = functools.partial(np.add, 1.0)", {"functools", "shift"}, {"np"}, False),
    ("shifted = shift(K)", {"shifted"}, {"shift", "K"}, True),
    ("img", set(), {"img"}, True),
    ("stats = {'mean': float(normalised.mean()), 'scale': scale}", {"stats"}, {"normalised", "scale"}, False),
]


def _closed(chosen: set[int]) -> list[int]:
    """``chosen`` and every cell it needs, transitively (the latest earlier provider of each name)."""
    todo, closed = list(chosen), set(chosen)
    while todo:
        index = todo.pop()
        for name in POOL[index][2]:
            provider = max(i for i in range(index) if name in POOL[i][1])
            if provider not in closed:
                closed.add(provider)
                todo.append(provider)
    return sorted(closed)


def _expected_kept(indices: list[int]) -> set[str]:
    kept, left_out = set(), set()
    for index in indices:
        _, defines, needs, demo = POOL[index]
        if demo or needs & left_out:
            left_out |= defines
        else:
            kept |= defines
    return kept


def _same(a, b) -> bool:
    if callable(a) and callable(b):
        return True
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.array_equal(a, b)
    return a == b


@settings(max_examples=40)
@given(chosen=st.sets(st.integers(0, len(POOL) - 1), max_size=10), joined=st.lists(st.booleans(), max_size=25))
def test_what_grading_keeps_is_what_running_defines(chosen, joined):
    indices = _closed(chosen)
    cells, current = [], []
    for index, join in zip(indices, joined + [False] * len(indices)):
        current.append(POOL[index][0])
        if not join:
            cells.append("\n".join(current))
            current = []
    if current:
        cells.append("\n".join(current))
    ran: dict = {}
    for cell in cells:  # Jupyter's "run all", here
        exec(compile(cell, "cell", "exec"), ran)  # noqa: S102
    converted = convert(notebook(*cells))
    graded = module_namespace(converted)

    defined = {name for name in graded if not name.startswith("__")}
    assert defined == _expected_kept(indices)
    for name in defined:
        assert _same(graded[name], ran[name]), name
    left_out = {name for index in indices for name in POOL[index][1]} - defined
    named = {name for o in converted.omissions for name in re.findall(r"\w+", o.text)}
    assert left_out <= named  # every name left out is in a statement the omissions list


# ------------------------------------------------------------------ the corpus, graded
def reference_cells() -> list[str]:
    """The reference module cut into cells at its top-level definitions, as a student pastes it."""
    return re.split(r"\n(?=def |class )", REFERENCE_SOURCE)


# The reference functions written with helpers a student defines at the top of a notebook.
HELPERS = [
    "import functools\nimport cv2\nimport numpy as np",
    "DEG = np.pi / 180\nBLACK = dict(borderMode=cv2.BORDER_CONSTANT, borderValue=0)\n"
    "warp_affine = functools.partial(cv2.warpAffine, flags=cv2.INTER_LINEAR, **BLACK)\n"
    "as_float = lambda M: np.asarray(M, dtype=np.float64)\nIDENTITY = np.eye(3)\n"
    "from collections import namedtuple\nCentre = namedtuple('Centre', 'x y')\nORIGIN = Centre(0.0, 0.0)",
    "def _warp(image, M, dsize=None):\n    height, width = image.shape[:2]\n"
    "    return warp_affine(image, as_float(M)[:2], dsize or (width, height))",
    "def translation_matrix(tx, ty):\n    M = IDENTITY.copy()\n    M[0, 2], M[1, 2] = tx, ty\n    return M",
    "def translate(image, tx=100, ty=50):\n    return _warp(image, translation_matrix(tx, ty))",
    "def rotation_matrix(angle_deg, center=ORIGIN):\n    theta = np.deg2rad(angle_deg)\n"
    "    cos, sin = np.cos(theta), np.sin(theta)\n    R = np.array([[cos, sin], [-sin, cos]])\n"
    "    c = as_float(center)\n    M = IDENTITY.copy()\n    M[:2, :2] = R\n    M[:2, 2] = c - R @ c\n    return M",
    "def rotate(image, angle_deg=45):\n    height, width = image.shape[:2]\n"
    "    return _warp(image, rotation_matrix(angle_deg, Centre((width - 1) / 2.0, (height - 1) / 2.0)))",
]

CORPUS = {
    # the issue's notebook: a sample image loaded, and values derived from it
    "skimage_demo": ["%matplotlib inline\nimport matplotlib.pyplot as plt\nimport skimage", *reference_cells(),
                     "img = skimage.data.astronaut()\nsize = img.shape\nh, w = size[:2]\ncentre = (w / 2, h / 2)",
                     "fig, axes = plt.subplots(1, 2, figsize=(10, 4))\naxes[0].imshow(img)\n"
                     "axes[1].imshow(rotate(img, 30))\nfor ax in axes:\n    ax.axis('off')\nplt.show()"],
    # written in Colab: Drive, cv2_imshow, seaborn styling, pip
    "colab": ["!pip install opencv-python-headless\nfrom google.colab import drive\n"
              "from google.colab.patches import cv2_imshow\nimport seaborn as sns\nsns.set_theme()",
              "drive.mount('/content/drive')", *reference_cells(),
              "img = cv2.imread('/content/drive/MyDrive/cv/lena.png')\ncv2_imshow(translate(img))\n"
              "cv2_imshow(rotate(img))"],
    # helpers: lambdas, a partial, derived constants, a namedtuple, used by the graded functions
    "helpers": [*HELPERS, "import matplotlib.pyplot as plt\nimg = plt.imread('cat.jpg')\n"
                          "plt.imshow(translate(img)); plt.show()"],
    # cells reading earlier results and outputs, asserts, prints
    "earlier_output": [*reference_cells(), "M = translation_matrix(3, 4)\nM",
                       "pts = np.array([[0, 0], [10, 5]])\nmoved = (M @ np.c_[pts, np.ones(len(pts))].T).T",
                       "last = _\nshown = Out[3]", "err = np.abs(moved[:, :2] - pts - [3, 4]).max()\n"
                       "assert err < 1e-9\nprint(f'max error {err}')"],
    # cells that fail when run: a NameError, a file that is not there, a division by zero, a stop
    "failing_cells": [*reference_cells(), "x = undefined_variable + 1", "K = np.load('calibration.npy')",
                      "ratio = 1 / 0", "raise SystemExit('the demo stops here')", "y = x * 2"],
    # magics of every kind, data loading with libraries grading lacks, a main block
    "magics_and_data": ["%load_ext autoreload\n%autoreload 2\n%matplotlib inline\nimport pandas as pd\nimport os",
                        *reference_cells(), "files = !ls data\ndf = pd.read_csv('points.csv')\ndf.head()",
                        "%%bash\nls -la\nwget https://example.com/lena.png",
                        "%%time\nimages = [cv2.imread(os.path.join('data', f)) for f in os.listdir('data')]",
                        "np.array?\n%timeit translation_matrix(1, 2)",
                        "if __name__ == '__main__':\n    for image in images:\n        rotate(image)"],
    # a demo run before the functions are defined (out of order), and the kernel's own calls
    "out_of_order": ["import cv2\nimport numpy as np\nimg = np.zeros((10, 10), np.uint8)\n"
                     "preview = translate(img)", "get_ipython().run_line_magic('matplotlib', 'inline')",
                     *reference_cells(), "display(preview)"],
}


@pytest.fixture(scope="module")
def reference_verdicts():
    result = grade(REFERENCE, SELECTED, pictures="none")
    assert result.total == result.max_total
    return _verdicts(result)


def _verdicts(result):
    return [(e.id, c.name, c.score, c.status) for e in result.exercises for c in e.checks]


@pytest.mark.parametrize("name", sorted(CORPUS))
def test_a_realistic_notebook_scores_what_its_functions_score_as_a_module(tmp_path, name, reference_verdicts):
    folder = tmp_path / "handin"
    folder.mkdir()
    (folder / f"{MODULE}.ipynb").write_text(notebook(*CORPUS[name]))
    result = grade(folder, SELECTED, pictures="none")
    assert _verdicts(result) == reference_verdicts, [c.message for e in result.exercises for c in e.checks
                                                    if c.score < c.max_score][:2]
    [note] = [n for n in result.notes if n.startswith(f"{MODULE}.ipynb")]
    # one line, then (when it counts more than it names) every statement, one a line, for the page
    first, *listed = note.splitlines()
    assert "left out at grading" in first and (not listed or f"and {len(listed) - 5} more" in first)
    assert len(set(listed)) == len(listed) and all(line.startswith(("cell", "In [")) for line in listed)
