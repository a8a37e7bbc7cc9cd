"""``check("lab07.ex2")`` inside a real Jupyter kernel (nbclient) and from a plain shell."""

import re
import subprocess
import sys

import nbformat
import pytest
from nbclient import NotebookClient
from nbformat.v4 import new_code_cell, new_notebook

from autograder.engine.registry import select
from autograder.engine.runner import grade
from conftest import REFERENCE

MODULE = "lab07_transformations"
SELECTED = ["lab07.ex1", "lab07.ex2"]
WRONG_ROTATION = """\
def rotation_matrix(angle_deg, center=(0.0, 0.0)):
    # a classic slip: degrees used as radians
    c, s = np.cos(angle_deg), np.sin(angle_deg)
    cx, cy = center
    return np.array([[c, s, (1 - c) * cx - s * cy], [-s, c, s * cx + (1 - c) * cy]])"""


def student_notebook() -> nbformat.NotebookNode:
    source = (REFERENCE / f"{MODULE}.py").read_text()
    cells = [new_code_cell(chunk) for chunk in re.split(r"\n(?=def |class )", source)]
    cells += [
        new_code_cell(WRONG_ROTATION),
        new_code_cell("%matplotlib inline\nimport matplotlib.pyplot as plt\n"
                      "image = np.zeros((120, 160, 3), np.uint8)\nimage[40:80, 60:100] = 255\n"
                      "plt.imshow(translate(image))\nplt.show()\nprint(translation_matrix(3, 4))"),
        new_code_cell("from autograder import check\n"
                      f"report = check({', '.join(repr(s) for s in SELECTED)})\n"
                      "print('SCORE', report.score, report.max_score)\nreport"),
    ]
    return new_notebook(cells=cells, metadata={"kernelspec": {"name": "python3", "display_name": "Python 3",
                                                               "language": "python"}})


@pytest.mark.slow
def test_check_in_a_kernel_gives_the_score_grade_py_gives(tmp_path):
    notebook = student_notebook()
    NotebookClient(notebook, timeout=300, kernel_name="python3",
                   resources={"metadata": {"path": str(tmp_path)}}).execute()
    outputs = notebook.cells[-1].outputs
    printed = "".join(o.get("text", "") for o in outputs if o.output_type == "stream")
    score, maximum = map(float, re.search(r"SCORE (\S+) (\S+)", printed).groups())
    [shown] = [o for o in outputs if o.output_type == "execute_result"]
    page = shown.data["text/html"]

    path = tmp_path / f"{MODULE}.ipynb"
    nbformat.write(notebook, path)
    by_grade_py = grade(path, SELECTED).for_students()  # what grade.py shows: hidden points withheld
    assert (score, maximum) == (by_grade_py.total, by_grade_py.max_total)
    assert 0 < score < maximum  # the wrong rotation loses points, translation keeps them
    assert 'class="ag-check"' in page and "lab07.ex2" in page
    assert "data:image/png;base64," in page, "a failed check shows its pictures"
    failed = [c for e in by_grade_py.exercises for c in e.checks if not c.passed]
    assert failed[0].message.splitlines()[0].replace("'", "&#39;")[:40] in page
    assert "text/plain" in shown.data and "lab07.ex2" in shown.data["text/plain"]


def test_check_from_a_plain_shell_grades_the_module_in_the_folder(tmp_path):
    (tmp_path / "assignments").mkdir()
    (tmp_path / "assignments" / f"{MODULE}.py").write_text((REFERENCE / f"{MODULE}.py").read_text())
    run = subprocess.run([sys.executable, "-c", "from autograder import check; print(check('lab07.ex1'))"],
                         cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    public = sum(c.points for c in select(["lab07.ex1"])[0].checks if not c.hidden)  # hidden points withheld
    assert "lab07.ex1" in run.stdout and f"{public:g} / {public:g}" in run.stdout


def test_check_names_what_to_grade_when_it_finds_nothing(tmp_path):
    run = subprocess.run([sys.executable, "-c", "from autograder import check; check('lab07.ex1')"],
                         cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert run.returncode != 0
    assert f"no {MODULE}.py in" in run.stderr and "submission=" in run.stderr


def test_check_points_to_the_kernels_input_numbers(monkeypatch):
    from autograder.student import selfcheck

    source = (REFERENCE / f"{MODULE}.py").read_text()
    history = [source, "def rotation_matrix(angle_deg:\n    pass",  # a typo, mended in In [3]
               "def rotation_matrix(angle_deg, center=(0.0, 0.0)):\n    offset = 1\n    return undefined_name",
               "translate(image)  # a demo: never run at grading"]
    monkeypatch.setattr(selfcheck, "_kernel_history", lambda: history)
    report = selfcheck.check("lab07.ex1", "lab07.ex2")
    tracebacks = [c.traceback for e in report.result.exercises for c in e.checks if c.traceback]
    assert tracebacks and "In [3], line 3, in rotation_matrix" in tracebacks[0]
    assert 0 < report.score < report.max_score  # translation still passes
    assert "In [4]" in " ".join(report.result.notes)
