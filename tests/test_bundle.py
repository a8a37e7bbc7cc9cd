"""The student bundle installs and grades on its own, and gives away no answers."""

import ast
import json
import re
import shutil
import subprocess
import sys
import sysconfig
import tempfile
from pathlib import Path

import pytest

from autograder.bundle import write_student_bundle
from autograder.registry import discover
from conftest import REFERENCE, ROOT

try:
    import tomllib
except ImportError:  # Python 3.10
    import tomli as tomllib


@pytest.fixture(scope="module")
def bundle(tmp_path_factory):
    out = tmp_path_factory.mktemp("bundle") / "cv-labs"
    write_student_bundle(out)
    return out


@pytest.fixture(scope="module")
def open_folder():
    """A folder others can enter, as a student's home is: when the tests run as
    root the worker runs as an unprivileged user, who must be able to read the
    virtual environment (pytest's own temporary folders are private to root)."""
    folder = Path(tempfile.mkdtemp(prefix="autograder-bundle-test-"))
    folder.chmod(0o755)
    yield folder
    shutil.rmtree(folder, ignore_errors=True)


@pytest.fixture(scope="module")
def bundle_python(bundle, open_folder, tmp_path_factory):
    """A fresh virtual environment with the bundle installed offline.

    Its dependencies are the ones of the interpreter running these tests, made
    visible by a ``.pth`` file: ``--system-site-packages`` would expose the *base*
    interpreter's packages instead, which inside a virtual environment are not
    the ones installed for the tests (and may lack ``wheel``).
    """
    venv = open_folder / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    python = venv / "bin" / "python"
    # Python 3.11's venv seeds an old setuptools that would build the bundle instead of ours
    # (too old for the SPDX license string): the pinned one comes with the .pth below.
    subprocess.run([str(python), "-m", "pip", "uninstall", "--quiet", "--yes", "setuptools"],
                   check=True, capture_output=True)
    nested_site = subprocess.run([str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                                 check=True, capture_output=True, text=True).stdout.strip()
    ours = dict.fromkeys(sysconfig.get_paths()[key] for key in ("purelib", "platlib"))
    # Plain path lines: the directories join sys.path after the bundle's own
    # site-packages, and their own .pth files (this checkout's editable install of
    # the grader) are not processed, so the bundle's copy of the grader is the one imported.
    (Path(nested_site) / "test-dependencies.pth").write_text("".join(f"{path}\n" for path in ours))
    source = tmp_path_factory.mktemp("install") / "cv-labs"  # a copy: building writes build/
    shutil.copytree(bundle, source)
    subprocess.run([str(python), "-m", "pip", "install", "--quiet", "--no-index", "--no-build-isolation",
                    str(source)], check=True, capture_output=True, timeout=300)
    return python


def grade_bundle(python, bundle, *args):
    run = subprocess.run([str(python), "grade.py", "--no-html", *args], cwd=bundle,
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stdout + run.stderr
    return run


def test_bundle_has_the_student_files_and_nothing_else(bundle):
    names = {p.relative_to(bundle).as_posix() for p in bundle.rglob("*") if p.is_file()}
    assert {"grade.py", "pyproject.toml", "README.md", "assignments/lab07_transformations.py"} <= names
    assert not any(n.startswith(("reference_solutions/", "tests/", "autograder/labs/hidden/")) for n in names)
    assert "python grade.py" in (bundle / "README.md").read_text()


def test_skeleton_scores_zero_with_helpful_messages(bundle_python, bundle):
    run = grade_bundle(bundle_python, bundle, "lab07", "--json", "skeleton.json")
    data = json.loads((bundle / "skeleton.json").read_text())
    assert data["total"] == 0 and data["max_total"] > 0
    assert data["hidden_included"] is False
    assert "not implemented yet" in run.stdout and "Traceback" not in run.stdout + run.stderr


def test_reference_placed_in_assignments_gets_full_marks_on_every_public_check(bundle_python, bundle, tmp_path):
    student = tmp_path / "student"
    shutil.copytree(bundle, student)
    for module in REFERENCE.glob("*.py"):
        shutil.copy(module, student / "assignments" / module.name)
    grade_bundle(bundle_python, student, "--json", "full.json")
    data = json.loads((student / "full.json").read_text())
    failed = [(e["id"], c["name"], c["message"]) for e in data["exercises"] for c in e["checks"] if not c["passed"]]
    assert failed == []
    assert data["total"] == data["max_total"] > 0
    assert all(not c["hidden"] for e in data["exercises"] for c in e["checks"])


def _squeezed(text: str) -> str:
    return re.sub(r"\s+", "", text)


def reference_bodies():
    """The body (docstring removed) of every student-facing reference function of two statements or more."""
    for path in sorted(REFERENCE.glob("*.py")):
        source = path.read_text()
        for node in ast.walk(ast.parse(source)):
            if isinstance(node, ast.FunctionDef) and not node.name.startswith("_"):
                body = node.body[1:] if ast.get_docstring(node) else node.body
                if len(body) >= 2:
                    text = "\n".join(ast.get_source_segment(source, stmt) for stmt in body)
                    yield f"{path.name}:{node.name}", _squeezed(text)


def test_no_bundle_file_contains_reference_code_or_hidden_check_data(bundle):
    files = {p: _squeezed(p.read_text(errors="ignore")) for p in bundle.rglob("*") if p.is_file()}
    assert any(p.parts[-3:-1] == ("docs", "api") for p in files), "the scan covers the shipped documentation"
    for name, body in reference_bodies():
        leaks = [str(p.relative_to(bundle)) for p, text in files.items() if body in text]
        assert leaks == [], f"the reference body of {name} appears in {leaks}"
    hidden_names = [c.name for lab in discover().values() for e in lab.exercises.values()
                    for c in e.checks if c.hidden]
    assert hidden_names, "the instructor's copy should have hidden checks"
    raw = {p: p.read_text(errors="ignore") for p in files}
    for name in hidden_names:
        leaks = [str(p.relative_to(bundle)) for p, text in raw.items() if name in text]
        assert leaks == [], f"hidden check {name!r} appears in {leaks}"


def test_bundle_ships_the_contract_and_the_student_guide(bundle):
    """The contract students are judged by, generated for every lab, in the bundle; its
    links and the README's paths stay inside the bundle; no hidden check is named there,
    even in the generated pages' Markdown escaping."""
    from autograder import apidoc

    docs = bundle / "docs"
    labs = sorted(discover())
    assert labs, "no labs registered"
    for lab in labs:
        assert (docs / "api" / f"{lab}.md").is_file() and (docs / "contract" / f"{lab}.md").is_file(), lab
    assert {"assignment-api.md", "labs.md"} <= {p.name for p in (docs / "contract").glob("*.md")}
    assert {"index.md", "grading.md", "notebooks.md", "check.md", "figures.md", "feedback.md"} <= {
        p.name for p in (docs / "students").glob("*.md")}
    for page in docs.rglob("*.md"):
        for target in re.findall(r"\]\(([^)#\s]+\.md)(?:#[^)]*)?\)", page.read_text()):
            if "://" not in target:
                assert (page.parent / target).resolve().is_file(), f"{page.relative_to(bundle)} links to {target}"
    readme = (bundle / "README.md").read_text()
    for words in ("hand in", "notebook", "check(", "--figures", "skip-grading"):
        assert words in readme, words
    for path in re.findall(r"`(docs/[\w/.-]+\.md)`", readme):
        assert (bundle / path).is_file(), f"the README names {path}, which the bundle lacks"
    hidden = {c.name for lab in discover().values() for e in lab.exercises.values() for c in e.checks if c.hidden}
    public = {c.name for lab in discover().values() for e in lab.exercises.values() for c in e.checks
              if not c.hidden}
    for page in docs.rglob("*.md"):
        text = page.read_text()
        leaked = [name for name in hidden - public if name in text or apidoc._plain(name) in text]
        assert leaked == [], f"{page.relative_to(bundle)} names hidden checks {leaked}"


def test_the_build_backend_is_pinned_to_the_constraints_and_the_license_is_an_spdx_expression():
    """pip applies no constraints file to a build's own environment: the pin in pyproject.toml is
    what makes every build (and an offline one from a wheelhouse) use the constrained backend."""
    from packaging.requirements import Requirement
    from packaging.version import Version

    project = tomllib.loads((ROOT / "pyproject.toml").read_text())
    pins = {}
    for line in (ROOT / "constraints.txt").read_text().splitlines():
        if line and not line.startswith("#"):
            name, _, version = line.partition("==")
            pins[name.strip().lower().replace("_", "-")] = version.strip()
    for text in project["build-system"]["requires"]:
        requirement = Requirement(text)
        [spec] = requirement.specifier
        assert spec.operator == "==" and pins[requirement.name.lower()] == spec.version, text
    assert project["project"]["license"] == "MIT"  # an SPDX expression: setuptools 77 or later
    assert Version(pins["setuptools"]) >= Version("77")
