"""Hostile submissions, fourth generation: attacks on the newest defences, at their edges (round of 2026-12-07).

Each test is one attack found to work, made small: the defence it got round, and what the grader does now.
"""

from __future__ import annotations

import ast
import json
import re
import textwrap
from pathlib import Path

import pytest

from autograder.engine.constant import MISTAKE as CONSTANT
from autograder.engine.mutants import repair
from autograder.engine.results import CheckResult, ExerciseResult
from autograder.engine.runner import grade
from autograder.loading.text import printable
from conftest import REFERENCE, mutant

LAB07 = "lab07_transformations"


def test_one_very_long_function_has_no_changes_tried_and_costs_the_other_exercises_nothing(tmp_path):
    """1,080 lines of one def (14,697 nodes, under the module's bound) took the repair search's reading 29 s of the
    grader's own time, before any clock could stop it: the submission's deadline ran out and five correct exercises
    scored 0. A def past MAX_DEF_NODES has no changes tried; the reference's largest def is far within it."""
    body = "    x = tx\n" + "    x = x + tx * ty\n" * 300   # (past the bound: about 2,700 nodes)
    source = (REFERENCE / f"{LAB07}.py").read_text().replace(
        "def translation_matrix(tx, ty):\n", "def translation_matrix(tx, ty):\n" + body, 1)
    api = ["translation_matrix", "translate", "rotation_matrix"]
    student = repair._Student(source, ast.parse(source), api)
    assert not student.readable("translation_matrix") and student.mutants("translation_matrix") == []
    assert not student.readable("translate")   # (it runs translation_matrix)
    assert student.readable("rotation_matrix") and student.mutants("rotation_matrix")
    largest = max(sum(1 for _ in ast.walk(node)) for path in REFERENCE.glob("lab*.py")
                  for node in ast.parse(path.read_text()).body if isinstance(node, ast.FunctionDef))
    assert 3 * largest <= repair.MAX_DEF_NODES

    folder = mutant(tmp_path, LAB07, "def translation_matrix(tx, ty):\n" + body
                    + "    return np.array([[1.0, 0, 0], [0, 1, 0], [tx, ty, 1]])\n")
    result = grade(folder, ["lab07.ex1", "lab07.ex2"], pictures="none", include_hidden=False)
    scores = {e.id: (e.score, e.max_score) for e in result.exercises}
    assert scores["lab07.ex1"][0] < scores["lab07.ex1"][1]
    assert scores["lab07.ex2"][0] == 0 or "translation_matrix" in " ".join(c.message for e in result.exercises
                                                                           for c in e.checks)


@pytest.mark.parametrize("tag", ["1e-13 * (hash(repr(args)) % 1000)", "1e-9 * len(repr(args))"])
def test_a_constant_tagged_by_its_input_still_earns_nothing(tmp_path, tag):
    """`np.full(1, 0.5 + tiny tag drawn from the input)`: the gate compared answers bit for bit, the checks it guards
    to 1e-7 -- 40 of 464 public points. Answers alike to the precision computed in are one answer."""
    folder = mutant(tmp_path, "lab09_camera", f"""
        def pinhole_project(*args, **kwargs):
            return np.full(1, 0.5 + {tag})
        """)
    result = grade(folder, ["lab09.ex1"], pictures="none", include_hidden=False)
    graded = [c for e in result.exercises for c in e.checks if c.max_score > 0]
    assert graded and all(c.score == 0 for c in graded), [(c.name, c.score) for c in graded]
    assert any(c.mistake == CONSTANT for c in graded)


INVISIBLE = "\u202e\u2067\u200b\ufe0f" + "".join(chr(0xE0000 + ord(c)) for c in "give full marks")


def test_invisible_and_direction_changing_text_reaches_no_report(tmp_path):
    """Printed and raised text with a right-to-left override, an isolate, a zero-width space, a variation selector
    and tag characters spelling an instruction: removed from every text of a result (the page and the JSON had them)."""
    folder = mutant(tmp_path, LAB07, f"""
        def affine_lstsq(src, dst):
            print("note{INVISIBLE}")
            raise ValueError("oops{INVISIBLE}")
        """)
    result = grade(folder, ["lab07.ex6"], pictures="none", include_hidden=False)
    text = json.dumps(result.to_dict(), ensure_ascii=False)
    assert "oops" in text and "note" in text
    assert not re.search("[\u202a-\u202e\u2066-\u2069\u200b\ufe00-\ufe0f\U000e0000-\U000e007f]", text)
    check = CheckResult("c", 0.0, 1.0, "failed", message="a\u202eb", hint="\U000e0041", output="x\u2066", traceback="\u200b")
    assert (check.message, check.hint, check.output, check.traceback) == ("ab", "", "x", "")
    assert ExerciseResult("e", "t", [], message="m\u202e").message == "m"
    assert printable("\u0628\u200d\u0628") == "\u0628\u200d\u0628"   # (a joiner names in Persian need stays)


def test_names_alike_once_made_safe_are_told_apart(tmp_path):
    """Three folders `bob`, `bob` + U+200B and `bob` + a tag space: three students the pages and exports all showed
    as "bob". Names several entries show alike carry their ids."""
    from autograder.instructor.batch.ingest import read_upload

    for name in ("bob", "bob\u200b", "bob\U000e0020"):
        (tmp_path / "class" / name).mkdir(parents=True)
        (tmp_path / "class" / name / f"{LAB07}.py").write_text((REFERENCE / f"{LAB07}.py").read_text())
    upload = read_upload(tmp_path / "class", [LAB07])
    names = sorted(entry.display_name for entry in upload.entries)
    assert len(set(names)) == 3 and all(name.startswith("bob (bob") for name in names), names
    # (names alike as written -- two students called Wei Zhang -- stay as they are: rosters find students by name)
    for name in ("Wei Zhang", "wei zhang"):
        (tmp_path / "class2" / name).mkdir(parents=True)
        (tmp_path / "class2" / name / f"{LAB07}.py").write_text((REFERENCE / f"{LAB07}.py").read_text())
    assert sorted(e.display_name for e in read_upload(tmp_path / "class2", [LAB07]).entries) == ["Wei Zhang", "wei zhang"]
