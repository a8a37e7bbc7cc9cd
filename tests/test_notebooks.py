"""Notebooks as students write them: definitions graded, demo cells left out, cells named."""

import re

import nbformat
from nbformat.v4 import new_code_cell, new_markdown_cell, new_notebook

from autograder.loading.notebooks import convert
from autograder.engine.runner import grade
from conftest import REFERENCE

MODULE = "lab07_transformations"
EXERCISES = ["lab07.ex1", "lab07.ex2"]
REFERENCE_SOURCE = (REFERENCE / f"{MODULE}.py").read_text()


def reference_cells():
    """The reference module cut into cells at its top-level definitions, as a student types it."""
    return [new_code_cell(chunk) for chunk in re.split(r"\n(?=def |class )", REFERENCE_SOURCE)]


DEMO = [
    new_markdown_cell("## Try it"),
    new_code_cell("%matplotlib inline\nimport matplotlib.pyplot as plt\nimport cv2"),
    new_code_cell("img = cv2.imread('lena.png')  # a file the grader does not have\n"
                  "moved = translate(img)\nplt.imshow(moved)\nplt.show()"),
    new_code_cell("print(translation_matrix(3, 4))\nfor angle in range(0, 360, 45):\n"
                  "    plt.imshow(rotate(img, angle))\n    plt.show()"),
    new_code_cell("raise SystemExit('the demo stops here')"),
]


def write_notebook(tmp_path, cells, name=MODULE):
    folder = tmp_path / "handin"
    folder.mkdir(exist_ok=True)
    nbformat.write(new_notebook(cells=cells), folder / f"{name}.ipynb")
    return folder


def test_a_notebook_with_demo_and_plotting_cells_grades_like_the_module(tmp_path):
    notebook = grade(write_notebook(tmp_path, [new_markdown_cell("# Lab 7"), *reference_cells(), *DEMO]),
                     EXERCISES, pictures="none")
    module = grade(REFERENCE, EXERCISES, pictures="none")
    assert notebook.total == module.total == module.max_total
    verdicts = [[(e.id, c.name, c.score, c.status) for e in r.exercises for c in e.checks]
                for r in (notebook, module)]
    assert verdicts[0] == verdicts[1]
    [note] = notebook.notes
    assert f"{MODULE}.ipynb" in note and "left out" in note and "'grade'" in note


def test_only_definitions_are_taken():
    source = convert(nbformat.writes(new_notebook(cells=[
        new_code_cell("import numpy as np\nANGLE = np.pi / 4\nK = np.array([[1, 0], [0, 1]])\n"
                      "image = load('x.png')\nshow(image)"),
        new_code_cell("@cache\ndef f(x):\n    return x\n\nclass A:\n    pass\nf(2)"),
        new_code_cell("try:\n    import cv2\nexcept ImportError:\n    cv2 = None"),
    ]))).source
    kept = [line for line in source.splitlines() if line and not line.startswith("#")]
    assert kept == ["import numpy as np", "ANGLE = np.pi / 4", "K = np.array([[1, 0], [0, 1]])",
                    "@cache", "def f(x):", "    return x", "class A:", "    pass",
                    "try:", "    import cv2", "except ImportError:", "    cv2 = None"]


def test_cell_tags_control_what_is_graded(tmp_path):
    wrong = new_code_cell("def translation_matrix(tx, ty):\n    return np.eye(3)")
    wrong.metadata["tags"] = ["skip-grading"]
    needed = new_code_cell("OFFSET = int('100')  # a call: left out unless the cell is tagged")
    needed.metadata["tags"] = ["grade"]
    uses = new_code_cell("_reference = translation_matrix\n"
                         "def translation_matrix(tx, ty):\n    return _reference(tx + OFFSET - 100, ty)")
    uses.metadata["tags"] = ["grade"]
    result = grade(write_notebook(tmp_path, [*reference_cells(), wrong, needed, uses]), ["lab07.ex1"],
                   pictures="none")
    assert result.total == result.max_total


def test_a_syntax_error_names_the_cell_and_its_line(tmp_path):
    cells = [*reference_cells(), new_code_cell("def broken(x):\n    return (x +\n")]
    number = len(cells)
    result = grade(write_notebook(tmp_path, cells), ["lab07.ex1"], pictures="none")
    message = result.exercises[0].message
    assert result.total == 0
    assert f"{MODULE}.ipynb, cell {number}, line" in message, message
    assert f"{MODULE}.py" not in message


def test_an_import_error_names_the_cell_and_its_line(tmp_path):
    cells = [*reference_cells(), new_code_cell("import numpy as np\nimport no_such_module_here")]
    number = len(cells)
    result = grade(write_notebook(tmp_path, cells), ["lab07.ex1"], pictures="none")
    message = result.exercises[0].message
    assert "No module named 'no_such_module_here'" in message
    assert f"{MODULE}.ipynb, cell {number}, line 2" in message, message


def test_an_error_in_a_function_points_to_its_cell(tmp_path):
    cells = [*reference_cells(),
             new_code_cell("def translation_matrix(tx, ty):\n    scale = 1\n    return undefined_matrix")]
    number = len(cells)
    result = grade(write_notebook(tmp_path, cells), ["lab07.ex1"], pictures="none")
    tracebacks = [c.traceback for c in result.exercises[0].checks if c.traceback]
    assert tracebacks
    assert f'File "{MODULE}.ipynb", cell {number}, line 3, in translation_matrix' in tracebacks[0]


def test_hand_edited_notebooks_with_odd_metadata_still_give_their_code():
    """Cells without metadata or outputs, metadata that is not an object, junk cells:
    the code is still read, and nothing in them can crash the grader."""
    import json

    from autograder.loading.notebooks import convert

    odd = {"cells": [42, {"cell_type": "code", "source": "def f():\n    return 1\n", "metadata": 42},
                     {"cell_type": "code", "source": ["x = 2\n"], "metadata": {"tags": [1, "grade"]}},
                     {"cell_type": "code", "source": "y = '\x00'\n"}],   # NUL: not parsable on 3.10
           "metadata": [], "nbformat": 4, "nbformat_minor": 5}
    source = convert(json.dumps(odd)).source
    assert "def f():" in source and "x = 2" in source
