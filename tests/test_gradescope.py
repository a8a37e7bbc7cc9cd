"""The Gradescope zip: built once, run against a simulated /autograder tree.

``run_autograder`` honours ``AUTOGRADER_ROOT`` (the tree) and ``AUTOGRADER_PYTHON``
(an interpreter with the dependencies, instead of the venv ``setup.sh`` makes),
so these tests need no root paths and no network.
"""

import base64
import json
import os
import re
import shutil
import stat
import subprocess
import sys
import zipfile
from html.parser import HTMLParser
from pathlib import Path

import cv2
import jsonschema
import numpy as np
import pytest

from autograder.sandbox import confine
from autograder.instructor import gradescope
from autograder.engine import pictures
from autograder.instructor.course import CourseConfig, CourseConfigError
from conftest import REFERENCE, mutant, submission_from_source

SCHEMA = json.loads((Path(__file__).parent / "gradescope_results.schema.json").read_text())
MODULE = "lab07_transformations"
COURSE = CourseConfig(select=["lab07"], call_timeout=2.0)


@pytest.fixture(scope="module")
def autograder_zip(tmp_path_factory):
    return gradescope.build(tmp_path_factory.mktemp("zip") / "autograder.zip", COURSE)


def run_container(zip_path: Path, tmp_path: Path, submission: Path | None) -> dict:
    root = tmp_path / "autograder"
    (root / "source").mkdir(parents=True)
    with zipfile.ZipFile(zip_path) as zf:
        zf.extractall(root / "source")
    for name in ("setup.sh", "run_autograder"):  # zipfile does not restore modes; unzip does
        path = root / "source" / name
        path.chmod(path.stat().st_mode | 0o755)
    if submission is not None:
        shutil.copytree(submission, root / "submission")
    env = {**os.environ, "AUTOGRADER_ROOT": str(root), "AUTOGRADER_PYTHON": sys.executable}
    env.pop("PYTHONPATH", None)
    run = subprocess.run([str(root / "source" / "run_autograder")], cwd=root, env=env,
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    results = json.loads((root / "results" / "results.json").read_text())
    jsonschema.validate(results, SCHEMA)
    return results


def test_zip_layout(autograder_zip):
    with zipfile.ZipFile(autograder_zip) as zf:
        names = set(zf.namelist())
        for script in ("setup.sh", "run_autograder"):
            info = zf.getinfo(script)
            assert stat.S_IMODE(info.external_attr >> 16) & 0o111, f"{script} not executable"
            text = zf.read(script)
            assert text.startswith(b"#!/usr/bin/env bash\n") and b"\r\n" not in text
        assert "autograder/labs/hidden/lab07.py" in names       # the container runs hidden checks
        assert "course.json" in names and "pyproject.toml" in names
        assert f"reference_solutions/{MODULE}.py" in names      # the error model's reference
        assert not any(n.startswith(("tests/", "autograder/labs/mistakes/")) for n in names)


def test_a_course_can_leave_the_reference_out_of_the_zip(tmp_path):
    built = gradescope.build(tmp_path / "autograder.zip", CourseConfig(select=["lab07"], error_model=False))
    with zipfile.ZipFile(built) as zf:
        assert not any(n.startswith("reference_solutions/") for n in zf.namelist())
    with pytest.raises(CourseConfigError, match="error_model"):
        CourseConfig(error_model="yes")


def test_the_error_model_names_a_mistake_in_the_container(autograder_zip, tmp_path):
    """A mistake no check names by hand is named by the error model there too: the container
    holds the reference, read by the grader (never by the student's worker, see below)."""
    from autograder.engine.mutants import naming
    from autograder.engine.mutants.operators import apply_edits
    from autograder.engine.registry import discover

    if not confine.detect().hides_files:
        pytest.skip("student code could read the reference here: the container withholds it (tested below)")
    model = naming.model_for(discover()["lab07"])
    [wrong_index] = [m for m in model.mutants["affine_lstsq"]
                     if m.operator == "axis" and "(0 for 2) is used in the result of `np.zeros`" in m.sentence]
    submission = tmp_path / "submission"
    submission.mkdir()
    (submission / f"{MODULE}.py").write_text(apply_edits(model.source, wrong_index.edits))
    results = run_container(autograder_zip, tmp_path, submission)
    said = "\n".join(t.get("output", "") for t in results["tests"] if t["status"] == "failed")
    # Named by the mutant's sentence, or by the change of the student's code that undoes it (a repair
    # takes a mutant's place: both need the reference the container holds for the grader only).
    assert wrong_index.sentence in said or "makes `affine_lstsq` give the expected answers" in said, said


def test_correct_submission(autograder_zip, tmp_path):
    results = run_container(autograder_zip, tmp_path, REFERENCE)
    assert results["score"] == sum(t["max_score"] for t in results["tests"]) > 0
    assert all(t["status"] == "passed" for t in results["tests"])
    visibilities = {t["visibility"] for t in results["tests"]}
    assert visibilities == {"visible", "after_published"}
    assert results["stdout_visibility"] == "hidden"
    assert isinstance(results["execution_time"], (int, float))


def test_partial_submission(autograder_zip, tmp_path):
    submission = mutant(tmp_path, MODULE, """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            raise NotImplementedError
        """)
    results = run_container(autograder_zip, tmp_path, submission)
    failed = [t for t in results["tests"] if t["status"] == "failed"]
    assert failed and all(t["name"].startswith("lab07.ex2") for t in failed)
    assert 0 < results["score"] < sum(t["max_score"] for t in results["tests"])
    assert "not implemented yet" in failed[0]["output"]


def test_broken_submission_and_missing_submission(autograder_zip, tmp_path):
    broken = submission_from_source(tmp_path, MODULE, "def translation_matrix(:\n")
    results = run_container(autograder_zip, tmp_path / "a", broken)
    assert results["score"] == 0
    assert "SyntaxError in lab07_transformations.py, line 1" in results["tests"][0]["output"]
    results = run_container(autograder_zip, tmp_path / "b", None)  # no submission folder at all
    assert results["score"] == 0 and results["tests"] == []
    assert "could not grade" in results["output"]


def test_hostile_submission_cannot_read_sources_or_forge_results(autograder_zip, tmp_path):
    root = tmp_path / "autograder"
    submission = mutant(tmp_path, MODULE, f"""
        def shear_matrix(s):
            import os
            print("UID", os.getuid())
            for path in ("{root}/source/course.json", "{root}/source/autograder/labs/hidden/lab07.py",
                         "{root}/source/reference_solutions/{MODULE}.py"):
                try:
                    print("READ", open(path).read()[:80])
                except OSError as error:
                    print("DENIED", type(error).__name__)
            try:
                os.makedirs("{root}/results", exist_ok=True)
                with open("{root}/results/results.json", "w") as f:
                    f.write('{{"score": 1000, "tests": []}}')
            except OSError:
                pass
            return None
        """)
    results = run_container(autograder_zip, tmp_path, submission)
    assert results["score"] < 1000
    shear = [t for t in results["tests"] if t["name"].startswith("lab07.ex4")]
    assert shear and all(t["status"] == "failed" for t in shear)
    if confine.detect().hides_files:
        assert "READ" not in shear[0]["output"] and "DENIED" in shear[0]["output"]
    if os.geteuid() == 0 and confine.detect().level == "namespaces+user":
        assert f"UID {confine.detect().uid}" in shear[0]["output"]   # never root


def test_course_config_is_validated(tmp_path):
    bad = tmp_path / "course.json"
    bad.write_text('{"select": ["lab07"], "hidden_visiblity": "hidden"}')
    with pytest.raises(CourseConfigError, match="unknown keys"):
        CourseConfig.load(bad)
    with pytest.raises(CourseConfigError, match="public_visibility"):
        CourseConfig(public_visibility="sometimes")


def test_the_diagnosis_reads_as_text_and_the_matrices_keep_their_layout():
    from autograder.engine.results import CheckResult

    message = ("homography_dlt(src, dst) is wrong: it looks like the rows of the design matrix "
               "have a sign error.\nIt returned\n[[1. 0.]\n [0. 1.]]")
    output = gradescope.check_html(CheckResult("H is right", 0.0, 5.0, "failed", message))
    first, rest = output.split("\n", 1)
    assert first == f"<p>{message.splitlines()[0]}</p>"
    assert rest == "<pre>It returned\n[[1. 0.]\n [0. 1.]]</pre>"


def test_results_are_in_the_course_points_like_every_other_grade():
    """A course that rescales a lab gets the same grade on Gradescope as in the batch's exports."""
    from autograder.instructor.batch.exports import compute_grades
    from autograder.engine.runner import grade

    result = grade(REFERENCE, ["lab07.ex1"])
    course = CourseConfig(select=["lab07.ex1"], points={"lab07": 30}, hidden_points_visible=True)
    data = gradescope.results_json(result, course)
    jsonschema.validate(data, SCHEMA)
    assert data["score"] == sum(t["score"] for t in data["tests"]) == 30
    assert sum(t["max_score"] for t in data["tests"]) == 30 and "Total: 30 / 30" in data["output"]
    row = {"student_id": "s", "display_name": "s", "status": "graded", "result": result.to_dict(), "lms": {}}
    [batch_grade], _ = compute_grades([row], [("lab07.ex1", result.max_total)], course)
    assert batch_grade.total == data["score"]


def test_rescaled_points_add_up_to_the_courses_exactly():
    """20 course points over a lab's 23 raw ones: each check's maximum to a ten-thousandth, the lab's together adding
    up to 20 exactly (audit of 2026-12-07: course.md's example gave 121.9992 of 122 on Gradescope for full marks)."""
    from autograder.engine.runner import grade

    result = grade(REFERENCE, ["lab07.ex1", "lab07.ex2"], pictures="none", include_hidden=False)
    raw = sum(e.max_score for e in result.exercises)
    course = CourseConfig(select=["lab07.ex1", "lab07.ex2"], points={"lab07": 20})
    scaled = result.in_points(course.point_factors([(e.id, e.max_score) for e in result.exercises]))
    maxima = [c.max_score for e in scaled.exercises for c in e.checks]
    assert raw == 23 and round(sum(maxima), 9) == 20 and all(round(m, 4) == m for m in maxima)
    assert round(scaled.total, 9) == 20   # full marks are the course's points, not 19.9992
    data = gradescope.results_json(result, course)
    assert round(sum(t["max_score"] for t in data["tests"]), 9) == 20 == round(data["score"], 9)


def test_gradescope_build_names_the_course_keys_it_does_not_apply(tmp_path, capsys):
    from autograder.cli import main

    course = tmp_path / "course.json"
    course.write_text(json.dumps({"select": ["lab07.ex1"], "late_penalty": {"per_day": 10}}))
    assert main(["gradescope", "build", "--out", str(tmp_path / "a.zip"), "--config", str(course)]) == 0
    assert "late_penalty" in capsys.readouterr().err


# ------------------------------------------------------------------ pictures in results.json
class _Tags(HTMLParser):
    """Every tag and attribute of an HTML fragment, and the text of its <img> sources."""

    def __init__(self, text: str):
        super().__init__(convert_charrefs=True)
        self.tags, self.attributes, self.sources = [], set(), []
        self.feed(text)
        self.close()

    def handle_starttag(self, tag, attrs):
        self.tags.append(tag)
        self.attributes |= {name for name, _ in attrs}
        self.sources += [value for name, value in attrs if tag == "img" and name == "src"]


def pictures_of(output: str) -> list[np.ndarray]:
    """The <img> of a test's output, decoded; each must be a PNG or JPEG data: URI."""
    decoded = []
    for source in _Tags(output).sources:
        match = re.fullmatch(r"data:image/(png|jpeg);base64,([A-Za-z0-9+/]+=*)", source)
        assert match, source[:80]
        image = cv2.imdecode(np.frombuffer(base64.b64decode(match[2]), np.uint8), cv2.IMREAD_UNCHANGED)
        assert image is not None
        decoded.append(image)
    return decoded


def assert_sanitiser_safe(output: str):
    """Only the tags the output promises (those a sanitiser keeps) and no attribute that runs
    anything or styles: student text can add none."""
    parsed = _Tags(output)
    assert set(parsed.tags) <= gradescope.HTML_TAGS, set(parsed.tags) - gradescope.HTML_TAGS
    assert parsed.attributes <= {"src", "alt", "title", "width", "height"}, parsed.attributes


def test_a_failed_public_check_shows_its_pictures_small_and_nothing_student_made_is_markup(
        autograder_zip, tmp_path):
    submission = mutant(tmp_path, MODULE, """
        _translate = translate
        def translate(image, tx=100, ty=50):
            print("<script>alert('printed')</script> & <b>bold</b>")
            return _translate(image, ty, tx)
        """)
    results = run_container(autograder_zip, tmp_path, submission)
    assert all(t["output_format"] == "html" for t in results["tests"])
    for test in results["tests"]:
        assert_sanitiser_safe(test["output"])
        shown = pictures_of(test["output"])
        if test["status"] == "passed" or test["visibility"] != "visible":  # hidden checks: a verdict only
            assert shown == [], test["name"]
        for image in shown:
            assert image.shape[1] <= gradescope.THUMBNAIL[0] and image.shape[0] <= gradescope.THUMBNAIL[1]
    failed = [t for t in results["tests"] if t["status"] == "failed" and t["visibility"] == "visible"]
    assert failed and all(len(pictures_of(t["output"])) >= 3 for t in failed if "translate(image)" in t["name"])
    printed = next(t["output"] for t in failed if "What your code printed" in t["output"])
    assert "&lt;script&gt;alert(&#x27;printed&#x27;)&lt;/script&gt; &amp; &lt;b&gt;bold&lt;/b&gt;" in printed
    assert gradescope.FULL_PAGE in results["output"]


def test_hostile_text_in_every_field_stays_text():
    from autograder.engine.results import Artifact, CheckResult

    hostile = "<img src=x onerror=alert(1)><a href='javascript:x'>\x1b[2J</a>\u202e"
    picture = pictures.picture_item(hostile, np.full((40, 60, 3), 200, np.uint8))
    check = CheckResult(hostile, 0.0, 1.0, "failed", f"{hostile}\n{hostile}", hint=hostile, output=hostile,
                        traceback=hostile, artifacts=[Artifact("images", hostile, [picture, picture], hostile)])
    output = gradescope.check_html(check, gradescope.figures_of(check), left_out=hostile)
    assert_sanitiser_safe(output)
    assert len(pictures_of(output)) == 2 and "\x1b" not in output and "\u202e" not in output
    # Escaped wherever it appears: the message's two lines, hint, traceback, printed output, the
    # figure's title and caption, each picture's alt and title, the labels' line (twice), left_out.
    assert output.count("&lt;img src=x onerror=alert(1)&gt;") == 14


def test_point_plots_become_png_pictures_with_their_points_in_place():
    truth, yours = np.array([[0.0, 0.0], [10.0, 5.0]]), np.array([[10.0, 0.0], [0.0, 5.0]])
    svg = pictures.svg_points({"truth": truth, "yours": yours})
    image = pictures.rasterise_svg(svg)
    assert image.shape == (300, 360, 3)
    yours_drawn = re.findall(r'<circle cx="([\d.]+)" cy="([\d.]+)" r="2"', svg)  # the second series' points
    orange = np.array([2, 95, 217])  # its colour, "#d95f02", in BGR
    assert len(yours_drawn) == 2
    for x, y in ((float(x), float(y)) for x, y in yours_drawn):
        assert np.abs(image[round(y), round(x)].astype(int) - orange).max() < 40, (x, y)
    assert (image == 255).all(axis=2).mean() > 0.9  # a white page with a few marks
    with pytest.raises(ValueError):
        pictures.rasterise_svg("<p>not a plot</p>")
    with pytest.raises(ValueError):
        pictures.rasterise_svg('<svg width="100000" height="10"/>')


def test_the_budget_goes_round_the_exercises_and_says_what_it_left_out(monkeypatch):
    from autograder.engine.results import Artifact, CheckResult, ExerciseResult, GradingResult

    noise = np.random.default_rng(0).integers(0, 255, (120, 160, 3), dtype=np.uint8)

    def failed(name):
        return CheckResult(name, 0.0, 1.0, "failed", "wrong",
                           artifacts=[Artifact("images", name, [pictures.picture_item("yours", noise)])])

    exercises = [ExerciseResult(f"lab07.ex{n}", "T", [], [failed("first"), failed("second")]) for n in (1, 2, 3)]
    result = GradingResult("s", "h", "0", exercises)
    cost = sum(f.size for f in gradescope.figures_of(exercises[0].checks[0]))
    shown, left_out = gradescope.pictures_within_budget(result, budget=3 * cost + cost // 2)
    assert set(shown) == {(f"lab07.ex{n}", 0) for n in (1, 2, 3)}
    assert left_out == {(f"lab07.ex{n}", 1) for n in (1, 2, 3)}
    outputs = [t["output"] for t in gradescope.results_json(result, CourseConfig())["tests"]]
    assert all("<img" in output and "left out" not in output for output in outputs)  # all fit the real budget
    monkeypatch.setattr(gradescope, "PICTURES_BUDGET", 3 * cost + cost // 2)
    outputs = [t["output"] for t in gradescope.results_json(result, CourseConfig())["tests"]]
    assert ["<img" in output for output in outputs] == [True, False] * 3
    assert "python grade.py lab07.ex2 on your own copy shows them" in outputs[3]


# A submission wrong everywhere: every function's array, tuple or float result is off.
WRONG_EVERYWHERE = '''

import functools as _functools, inspect as _inspect
import numpy as _np


def _off(value):
    if isinstance(value, _np.ndarray) and value.dtype.kind == "f":
        return value * 1.07 + 2.5
    if isinstance(value, _np.ndarray) and value.dtype == _np.uint8:
        return _np.ascontiguousarray(255 - value)
    if isinstance(value, _np.ndarray) and value.dtype.kind in "iu":
        return value + 3
    if isinstance(value, tuple):
        return tuple(_off(v) for v in value)
    return value * 1.07 + 2.5 if isinstance(value, float) else value


def _wrong(function):
    @_functools.wraps(function)
    def wrong(*args, **kwargs):
        return _off(function(*args, **kwargs))
    return wrong


for _name, _value in list(globals().items()):
    if _inspect.isfunction(_value) and _value.__module__ == __name__ and not _name.startswith("_"):
        globals()[_name] = _wrong(_value)
'''


@pytest.mark.slow
def test_a_submission_wrong_in_every_lab_stays_within_the_budget(tmp_path, no_naming):
    """(Naming off: the budget is the pictures', which no name changes; 40 s -> 17 s.)"""
    folder = tmp_path / "wrong"
    folder.mkdir()
    for module in REFERENCE.glob("*.py"):
        (folder / module.name).write_text(module.read_text() + WRONG_EVERYWHERE)
    data = gradescope.run(folder, tmp_path / "results.json", CourseConfig())
    jsonschema.validate(data, SCHEMA)
    size = (tmp_path / "results.json").stat().st_size
    pictures_chars = sum(len(source) for t in data["tests"] for source in _Tags(t["output"]).sources)
    with_pictures = [t for t in data["tests"] if "<img" in t["output"]]
    print(f"results.json: {size} bytes, {pictures_chars} of pictures in {len(with_pictures)} tests")
    assert pictures_chars <= gradescope.PICTURES_BUDGET + 40 * len(with_pictures)  # + the "data:...," prefixes
    assert size < 1_000_000
    labs = {t["name"][:5] for t in with_pictures}
    assert len(labs) >= 5 and len(with_pictures) >= 20, labs
    left_out = [t for t in data["tests"] if "Pictures left out here" in t["output"]]
    assert left_out and all(t["status"] == "failed" and t["visibility"] == "visible" for t in left_out)
    assert not any("<img" in t["output"] for t in data["tests"] if t["visibility"] != "visible")


def test_the_reference_is_withheld_where_student_code_could_read_it(tmp_path, monkeypatch):
    """At a level that hides no files (process-group, allowed by the course), the container's
    reference is deleted before any student code runs; where files are hidden it stays."""
    folder = tmp_path / "reference_solutions"
    folder.mkdir()
    (folder / f"{MODULE}.py").write_text("answers")
    monkeypatch.setenv("AUTOGRADER_REFERENCE_SOLUTIONS", str(folder))
    assert not gradescope.withhold_readable_reference(hides_files=True) and folder.is_dir()
    assert gradescope.withhold_readable_reference(hides_files=False) and not folder.exists()
    assert not gradescope.withhold_readable_reference(hides_files=False)     # nothing left to remove
