"""``--figures DIR``: the lab sheet's expected outputs, made by the student's own functions."""

import cv2
import numpy as np
import pytest

from autograder import cli
from autograder.engine.registry import select
from autograder.figures import PRODUCERS, SHEET_PICTURES, _discover, figure, make_figures, producers_for
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


# Every figure made from the reference solutions: tests/test_report_scaffold.py (the scaffold
# of every lab makes them all, once).


def test_every_picture_the_lab_sheet_asks_for_has_a_producer_of_a_graded_exercise():
    producers = _discover()
    assert sorted(set(SHEET_PICTURES) - set(producers)) == []
    graded = {exercise.id for exercise in select()}
    assert sorted(p.figure_id for p in producers.values() if p.exercise_id not in graded) == []
    # both experiment extensions have a figure of their own, beside their exercise's
    extensions = [figure_id for figure_id in SHEET_PICTURES if figure_id.endswith("-extension")]
    assert sorted(extensions) == ["lab09.ex3-extension", "lab12.ex4-extension"]
    assert [p.figure_id for p in producers_for("lab12.ex4")] == ["lab12.ex4", "lab12.ex4-extension"]


@pytest.mark.parametrize("bad", ["lab7.ex1", "lab07.ex1:extension", "lab07.ex1-extension.png", "lab07/ex1"])
def test_a_figure_id_that_is_no_file_stem_is_refused(bad):
    with pytest.raises(ValueError, match="figure id"):
        figure(bad, "title")


def test_an_answer_that_cannot_be_drawn_is_the_figures_reason_and_the_others_are_made(tmp_path):
    submission = mutant(tmp_path, "lab09_camera", """
        def pinhole_project(points, f):
            return "not points"

        def intrinsic_matrix(f, px, py):
            return {"K": 1}
        """)
    made = make_figures(submission, ["lab09.ex1", "lab09.ex2", "lab09.ex5"], tmp_path / "f")
    outcomes = {o.figure_id: o for o in made}
    assert outcomes["lab09.ex1"].path is None and "cannot be drawn" in outcomes["lab09.ex1"].reason
    assert outcomes["lab09.ex2"].path is None and outcomes["lab09.ex2"].reason
    assert outcomes["lab09.ex5"].path.is_file()
