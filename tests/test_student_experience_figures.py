"""``--figures DIR``: the lab sheet's expected outputs, made by the student's own functions."""

import cv2
import numpy as np
import pytest

from autograder import cli
from autograder.figures import PRODUCERS, _discover, make_figures
from conftest import REFERENCE, mutant

MODULE = "lab07_transformations"


def test_a_figure_shows_what_the_students_function_returned():
    _discover()
    returned = np.full((240, 320, 3), 77, np.uint8)
    calls = []

    def call(function, *args):
        calls.append(function)
        return returned

    panels = PRODUCERS["lab07.ex1"].make(call)
    assert calls == ["translate"]
    assert any(panel.image is returned for panel in panels)


def test_grade_py_figures_writes_a_png_per_exercise_and_shows_them_on_the_page(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    status = cli.main(["grade", str(REFERENCE), "lab07.ex1", "lab10.ex2", "--figures", "figures"])
    assert status == 0
    for exercise in ("lab07.ex1", "lab10.ex2"):
        image = cv2.imread(str(tmp_path / "figures" / f"{exercise}.png"))
        assert image is not None and image.shape[1] > 600
    printed = capsys.readouterr().out
    assert "figures/lab07.ex1.png" in printed
    page = (tmp_path / "feedback.html").read_text()
    assert page.count('class="lab-figure"') == 2


def test_a_failing_function_names_why_its_figure_is_missing_and_the_others_are_made(tmp_path):
    submission = mutant(tmp_path, MODULE, """
        def rotate(image, angle_deg=45):
            raise NotImplementedError
        """)
    outcomes = {o.exercise_id: o for o in make_figures(submission, ["lab07.ex1", "lab07.ex2"], tmp_path / "f")}
    assert outcomes["lab07.ex1"].path.exists()
    assert outcomes["lab07.ex2"].path is None and "rotate()" in outcomes["lab07.ex2"].reason


def test_a_missing_module_is_the_reason(tmp_path):
    empty = tmp_path / "empty"
    empty.mkdir()
    [outcome] = make_figures(empty, ["lab07.ex1"], tmp_path / "f")
    assert outcome.path is None and f"{MODULE}.py not found" in outcome.reason


@pytest.mark.slow
def test_every_figure_is_made_from_the_reference_solutions(tmp_path):
    outcomes = make_figures(REFERENCE, [], tmp_path)
    assert len(outcomes) == len(_discover()) >= 15
    assert [o.exercise_id for o in outcomes if o.path is None] == []
