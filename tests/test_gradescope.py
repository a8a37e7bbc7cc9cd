"""The Gradescope zip: built once, run against a simulated /autograder tree.

``run_autograder`` honours ``AUTOGRADER_ROOT`` (the tree) and ``AUTOGRADER_PYTHON``
(an interpreter with the dependencies, instead of the venv ``setup.sh`` makes),
so these tests need no root paths and no network.
"""

import json
import os
import shutil
import stat
import subprocess
import sys
import zipfile
from pathlib import Path

import jsonschema
import pytest

from autograder import confine, gradescope
from autograder.course import CourseConfig, CourseConfigError
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
        assert not any(n.startswith(("reference_solutions/", "tests/")) for n in names)


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
            for path in ("{root}/source/course.json", "{root}/source/autograder/labs/hidden/lab07.py"):
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
    from autograder.results import CheckResult

    message = ("homography_dlt(src, dst) is wrong: it looks like the rows of the design matrix "
               "have a sign error.\nIt returned\n[[1. 0.]\n [0. 1.]]")
    output = gradescope._check_markdown(CheckResult("H is right", 0.0, 5.0, "failed", message))
    first, rest = output.split("\n", 1)
    assert first == message.splitlines()[0]
    assert "```" not in first and "```" in rest and " [0. 1.]]" in rest


def test_results_are_in_the_course_points_like_every_other_grade():
    """A course that rescales a lab gets the same grade on Gradescope as in the batch's exports."""
    from autograder.batch.exports import compute_grades
    from autograder.runner import grade

    result = grade(REFERENCE, ["lab07.ex1"])
    course = CourseConfig(select=["lab07.ex1"], points={"lab07": 30}, hidden_points_visible=True)
    data = gradescope.results_json(result, course)
    jsonschema.validate(data, SCHEMA)
    assert data["score"] == sum(t["score"] for t in data["tests"]) == 30
    assert sum(t["max_score"] for t in data["tests"]) == 30 and "Total: 30 / 30" in data["output"]
    row = {"student_id": "s", "display_name": "s", "status": "graded", "result": result.to_dict(), "lms": {}}
    [batch_grade], _ = compute_grades([row], [("lab07.ex1", result.max_total)], course)
    assert batch_grade.total == data["score"]


def test_gradescope_build_names_the_course_keys_it_does_not_apply(tmp_path, capsys):
    from autograder.cli import main

    course = tmp_path / "course.json"
    course.write_text(json.dumps({"select": ["lab07.ex1"], "late_penalty": {"per_day": 10}}))
    assert main(["gradescope", "build", "--out", str(tmp_path / "a.zip"), "--config", str(course)]) == 0
    assert "late_penalty" in capsys.readouterr().err
