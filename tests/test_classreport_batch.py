"""The class pages from a real batch: ``autograder batch --similarity``, then ``autograder report``."""

from __future__ import annotations

import json
import textwrap

import pytest

from autograder.cli import main
from classreport_disguise import disguise
from conftest import REFERENCE

LAB07 = "lab07_transformations"
SWAPPED = """
def translation_matrix(tx, ty):
    return np.array([[1.0, 0, ty], [0, 1.0, tx], [0, 0, 1.0]])
"""


@pytest.mark.slow
def test_batch_writes_the_overview_and_report_rewrites_it(tmp_path, capsys):
    pytest.importorskip("copydetect")
    reference = (REFERENCE / f"{LAB07}.py").read_text()
    students = {"ada": reference, "ben": reference + textwrap.dedent(SWAPPED), "cleo": disguise(reference, seed=1)}
    submissions = tmp_path / "class"
    for name, code in students.items():
        (submissions / name).mkdir(parents=True)
        (submissions / name / f"{LAB07}.py").write_text(code)
    course = tmp_path / "course.json"
    course.write_text(json.dumps({"select": ["lab07.ex1"], "assignment": "CV lab 7"}))
    results = tmp_path / "results"
    assert main(["batch", str(submissions), "--out", str(results), "--workers", "1", "--pictures", "none",
                 "--course", str(course), "--similarity"]) == 0
    page = (results / "index.html").read_text()
    assert "CV lab 7" in page and "1 of 3: tx and ty are swapped" in page
    assert 'href="ben/feedback.html"' in page and (results / "ben" / "feedback.html").exists()
    similar = (results / "similarity.html").read_text()
    assert "ada · cleo" in similar and "leads to read" in similar

    (results / "index.html").unlink()
    assert main(["report", str(results)]) == 0
    assert "1 of 3: tx and ty are swapped" in (results / "index.html").read_text()
    assert main(["report", str(tmp_path)]) == 2   # no gradebook there
    # RESULTS keeps the sources it graded: the similarity report can be made from it alone.
    assert (results / "ben" / "sources" / f"{LAB07}.py").read_text() == students["ben"]
    (results / "similarity.html").unlink()
    assert main(["similarity", str(results)]) == 0
    assert "ada · cleo" in (results / "similarity.html").read_text()
