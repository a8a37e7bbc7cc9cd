"""The student bundle installs and grades on its own, and gives away no answers."""

import ast
import json
import os
import re
import shutil
import subprocess
import sys
import sysconfig
import tempfile
import zipfile
from pathlib import Path

import pytest

from autograder.instructor.bundle import bundle_requirements, write_student_bundle, write_wheelhouse
from autograder.engine.registry import discover
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

    The environment is made without pip (seeding it costs seconds) and the tests' pip
    installs into it (``pip --python``); the build backend is the pinned setuptools the
    ``.pth`` brings (the old one Python 3.11's venv would seed is too old for the SPDX
    license string).
    """
    venv = open_folder / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    python = venv / "bin" / "python"
    nested_site = subprocess.run([str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                                 check=True, capture_output=True, text=True).stdout.strip()
    ours = dict.fromkeys(sysconfig.get_paths()[key] for key in ("purelib", "platlib"))
    # Plain path lines: the directories join sys.path after the bundle's own
    # site-packages, and their own .pth files (this checkout's editable install of
    # the grader) are not processed, so the bundle's copy of the grader is the one imported.
    (Path(nested_site) / "test-dependencies.pth").write_text("".join(f"{path}\n" for path in ours))
    source = tmp_path_factory.mktemp("install") / "cv-labs"  # a copy: building writes build/
    shutil.copytree(bundle, source)
    subprocess.run([sys.executable, "-m", "pip", "--python", str(python), "install", "--quiet", "--no-index",
                    "--no-build-isolation", str(source)], check=True, capture_output=True, timeout=300)
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
    from autograder.instructor import apidoc

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


# ------------------------------------------------------------------ the wheelhouse (no network here)
def fake_wheel(folder: Path, name: str, version: str, requires=()) -> None:
    """A wheel pip can resolve (metadata only): enough for ``pip download``."""
    info = f"{name}-{version}.dist-info"
    with zipfile.ZipFile(folder / f"{name}-{version}-py3-none-any.whl", "w") as zf:
        zf.writestr(f"{info}/METADATA", f"Metadata-Version: 2.1\nName: {name}\nVersion: {version}\n"
                    + "".join(f"Requires-Dist: {r}\n" for r in requires))
        zf.writestr(f"{info}/WHEEL", "Wheel-Version: 1.0\nGenerator: test\nRoot-Is-Purelib: true\nTag: py3-none-any\n")
        zf.writestr(f"{info}/RECORD", "")


@pytest.fixture
def offline_pip(tmp_path, monkeypatch):
    """pip with no index and no configuration: it finds only what is in the folder returned."""
    links = tmp_path / "links"
    links.mkdir()
    for name, value in (("PIP_NO_INDEX", "1"), ("PIP_FIND_LINKS", str(links)), ("PIP_CONFIG_FILE", os.devnull)):
        monkeypatch.setenv(name, value)
    monkeypatch.delenv("PIP_CONSTRAINT", raising=False)
    return links


def test_the_wheelhouse_holds_the_backend_and_dependencies_at_the_constrained_versions(tmp_path, offline_pip):
    for name, version, requires in (("fakebackend", "1.0", ()), ("fakebackend", "2.0", ()),
                                    ("tinydep", "1.0", ()), ("tinydep", "2.0", ("leafdep",)), ("leafdep", "0.5", ())):
        fake_wheel(offline_pip, name, version, requires)
    out = tmp_path / "bundle"
    out.mkdir()
    (out / "pyproject.toml").write_text('[build-system]\nrequires = ["fakebackend==1.0"]\n'
                                        '[project]\nname = "x"\nversion = "0"\ndependencies = ["tinydep>=1"]\n'
                                        '[project.optional-dependencies]\ntest = ["notthere"]\n')
    (out / "constraints.txt").write_text("tinydep==2.0\nfakebackend==1.0\n")
    (out / "README.md").write_text("# Labs\n\nSet up with a network.\n\n## Grading\n\npython grade.py\n")
    wheels = write_wheelhouse(out)
    assert [w.name for w in wheels] == ["fakebackend-1.0-py3-none-any.whl", "leafdep-0.5-py3-none-any.whl",
                                        "tinydep-2.0-py3-none-any.whl"]
    readme = (out / "README.md").read_text()
    offline = readme.index("## Set up without a network")
    assert readme.index("Set up with a network.") < offline < readme.index("## Grading")
    assert "python -m pip install --no-index --find-links wheels -c constraints.txt -e ." in readme
    assert f"CPython {sys.version_info[0]}.{sys.version_info[1]} on {sysconfig.get_platform()}" in readme
    assert not (out / ".wheels.partial").exists()


def test_bundle_wheels_without_a_network_refuses_cleanly(tmp_path, offline_pip, capsys):
    from autograder.cli import main

    out = tmp_path / "cv-labs"
    assert main(["bundle", "--student", str(out), "--wheels"]) == 1
    err = capsys.readouterr().err
    assert "error: no wheels: pip download failed: ERROR:" in err and "installs with a network only" in err
    assert "Traceback" not in err
    assert not (out / "wheels").exists() and not (out / ".wheels.partial").exists()
    assert (out / "grade.py").is_file() and "--no-index" not in (out / "README.md").read_text()
    assert bundle_requirements(out)[0] == "setuptools==84.2.1"  # what a real wheelhouse starts with
    assert "numpy>=1.24" in bundle_requirements(out)
