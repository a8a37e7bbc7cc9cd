"""The documentation: built in strict mode, its code examples run, its contract generated.

- The site builds with ``mkdocs build --strict`` (a broken link or anchor, a page
  missing from the nav, an engine name mkdocstrings cannot find: each is a warning,
  and a warning fails), and every page the nav names exists.
- Every ``python`` block runs (a page's blocks in order, in one namespace), every
  ``json`` block is a course configuration that ``CourseConfig`` accepts.
- The generated pages (``docs/api/*.md`` and the ``apidoc`` blocks of
  ``docs/contract/*.md``) are what ``python -m autograder.instructor.apidoc docs`` writes now.
"""

from __future__ import annotations

import ast
import importlib.util
import json
import os
import re
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from autograder.instructor import apidoc
from autograder.instructor.course import CourseConfig
from autograder.engine.registry import REGISTRY, discover

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
PAGES = sorted(DOCS.rglob("*.md"))
FENCE = re.compile(r"^(?P<indent>[ \t]*)```(?P<lang>[\w-]*)[^\n]*\n(?P<body>.*?)^(?P=indent)```[ \t]*$", re.M | re.S)


def blocks(page: Path, language: str) -> list[str]:
    return [textwrap.dedent(m.group("body")) for m in FENCE.finditer(page.read_text(encoding="utf-8"))
            if m.group("lang") == language]


def nav_pages(entries) -> list[str]:
    """The Markdown files the nav of mkdocs.yml names, however deep."""
    found = []
    for entry in entries:
        values = entry.values() if isinstance(entry, dict) else [entry]
        for value in values:
            found += nav_pages(value) if isinstance(value, list) else [value]
    return found


def mkdocs_config() -> dict:
    import yaml

    return yaml.safe_load((ROOT / "mkdocs.yml").read_text(encoding="utf-8"))


# ------------------------------------------------------------------------------ the site
def test_every_page_in_the_nav_exists_and_every_page_is_in_the_nav():
    named = nav_pages(mkdocs_config()["nav"])
    missing = [page for page in named if not (DOCS / page).is_file()]
    assert missing == [], f"the nav of mkdocs.yml names pages that do not exist: {missing}"
    left_out = sorted(str(p.relative_to(DOCS)) for p in PAGES if str(p.relative_to(DOCS)) not in named)
    assert left_out == [], f"pages no reader can reach from the nav: {left_out}"
    assert len(named) == len(set(named)), "a page is named twice in the nav"


def test_the_site_builds_in_strict_mode(tmp_path):
    if importlib.util.find_spec("mkdocs") is None or importlib.util.find_spec("mkdocstrings") is None:
        pytest.skip("MkDocs is not installed: pip install -c constraints.txt -e '.[docs]'")
    site = tmp_path / "site"
    run = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(site)],
                         cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "WARNING" not in run.stderr, run.stderr
    for page in nav_pages(mkdocs_config()["nav"]):
        built = site / (page[:-3] + "/index.html" if not page.endswith("index.md") else page[:-3] + ".html")
        assert built.is_file(), f"{page} was not built"
    engine = (site / "authors" / "engine-api" / "index.html").read_text(encoding="utf-8")
    assert "autograder.engine.checks.Trial" in engine and "expect_array" in engine, "mkdocstrings rendered no API"


# ------------------------------------------------------------------------------ examples
def test_the_docs_have_the_examples_the_tests_run():
    python_pages = {p.relative_to(DOCS).as_posix() for p in PAGES if blocks(p, "python")}
    assert {"students/check.md", "authors/checks.md"} <= python_pages
    assert sum(len(blocks(p, "json")) for p in PAGES) >= 3


@pytest.fixture
def student_folder(tmp_path, monkeypatch):
    """A student's working folder, as the check() page supposes: the skeletons in
    assignments/ and a notebook of lab 7 beside them."""
    folder = tmp_path / "work"
    shutil.copytree(ROOT / "assignments", folder / "assignments")
    source = (ROOT / "assignments" / "lab07_transformations.py").read_text(encoding="utf-8")
    notebook = {"cells": [{"cell_type": "code", "metadata": {}, "execution_count": None, "outputs": [],
                           "source": source.splitlines(keepends=True)}],
                "metadata": {}, "nbformat": 4, "nbformat_minor": 5}
    (folder / "lab07_transformations.ipynb").write_text(json.dumps(notebook), encoding="utf-8")
    monkeypatch.chdir(folder)
    return folder


@pytest.fixture
def registry_restored():
    """Examples may register a lab of their own; the registry is as it was afterwards."""
    before = dict(discover())
    yield
    REGISTRY.clear()
    REGISTRY.update(before)


@pytest.mark.slow
@pytest.mark.parametrize("page", [p.relative_to(DOCS).as_posix() for p in PAGES if blocks(p, "python")])
def test_python_examples_run(page, student_folder, registry_restored, capsys):
    namespace = {"__name__": "__docs__"}
    for number, code in enumerate(blocks(DOCS / page, "python"), 1):
        try:
            exec(compile(code, f"{page} (python block {number})", "exec"), namespace)  # noqa: S102
        except Exception as exc:  # noqa: BLE001 - named with its page and block
            pytest.fail(f"{page}, python block {number} raised {type(exc).__name__}: {exc}")
    assert "Traceback" not in capsys.readouterr().out


def test_the_check_example_grades_the_skeleton(student_folder):
    """What the check() page promises: the exercise graded, the score of grade.py."""
    from autograder import check

    report = check("lab07.ex2")
    assert report.max_score > 0 and report.score == 0
    assert "not implemented yet" in str(report)


def test_the_writing_a_check_example_stays_out_of_the_registry(registry_restored):
    """The example builds its own lab, lab99, graded in isolation: the project's labs are
    untouched (the fixture puts the registry back), and no built-in lab is lab99."""
    assert "lab99" not in discover()
    code = "\n".join(blocks(DOCS / "authors" / "checks.md", "python")[:1])
    namespace: dict = {}
    exec(compile(code, "authors/checks.md", "exec"), namespace)  # noqa: S102
    lab = namespace["lab"]
    assert REGISTRY["lab99"] is lab and [c.name for c in lab.exercises["ex1"].checks] == [
        "scaling_matrix(1.5, 0.5)", "scaling_matrix keeps the last row [0, 0, 1]", "scaling_matrix for any sx, sy"]


@pytest.mark.parametrize("page", [p.relative_to(DOCS).as_posix() for p in PAGES if blocks(p, "json")])
def test_json_examples_are_course_configurations(page, tmp_path):
    for number, text in enumerate(blocks(DOCS / page, "json"), 1):
        path = tmp_path / f"course{number}.json"
        path.write_text(text, encoding="utf-8")
        config = CourseConfig.load(path)  # raises on unknown keys and bad values
        for key, value in json.loads(text).items():
            assert getattr(config, key) is not None, f"{page} block {number}: {key} = {value!r} was not read"


def test_a_wrong_course_example_would_fail(tmp_path):
    """The check above can fail: a misspelt key is refused."""
    path = tmp_path / "course.json"
    path.write_text('{"selct": ["lab07"]}', encoding="utf-8")
    with pytest.raises(ValueError, match="selct"):
        CourseConfig.load(path)


# ------------------------------------------------------------------------------ the contract
def test_generated_pages_match_the_code():
    out_of_date = apidoc.stale(DOCS)
    assert out_of_date == [], (f"generated pages differ from the skeletons and the registry: "
                               f"{[str(p.relative_to(ROOT)) for p in out_of_date]}; run {apidoc.GENERATOR}")


def test_every_lab_exercise_and_public_check_is_in_the_contract():
    labs = apidoc.lab_facts()
    assert [lab.key for lab in labs] == ["lab07", "lab08", "lab09", "lab10", "lab11", "lab12"]
    for lab in labs:
        api = (DOCS / "api" / f"{lab.key}.md").read_text(encoding="utf-8")
        account = (DOCS / "contract" / f"{lab.key}.md").read_text(encoding="utf-8")
        for exercise in discover()[lab.key].exercises.values():
            assert f"## {exercise.key}: " in api and f"<!-- apidoc:begin {exercise.id} -->" in account
            for check in exercise.checks:
                if not check.hidden:
                    assert apidoc._plain(check.name) in account, (lab.key, check.name)
        for name, function in lab.skeleton.functions.items():
            assert f"def {function.signature}" in api, name


def test_no_hidden_check_in_the_generated_pages():
    hidden = {check.name for lab in discover().values() for exercise in lab.exercises.values()
              for check in exercise.checks if check.hidden}
    public = {check.name for lab in discover().values() for exercise in lab.exercises.values()
              for check in exercise.checks if not check.hidden}
    assert hidden
    for page in [*(DOCS / "api").glob("*.md"), *(DOCS / "contract").glob("*.md")]:
        text = page.read_text(encoding="utf-8")
        leaked = [name for name in hidden - public if name in text or apidoc._plain(name) in text]
        assert leaked == [], f"{page.name} names hidden checks {leaked}"


def test_a_change_to_a_skeleton_makes_the_pages_stale(tmp_path):
    """It cannot drift: a docstring edited, or a parameter the registry names removed,
    shows up (as a stale page, or a refusal naming the function)."""
    skeletons = tmp_path / "assignments"
    shutil.copytree(ROOT / "assignments", skeletons)
    lab07 = skeletons / "lab07_transformations.py"
    text = lab07.read_text(encoding="utf-8")
    lab07.write_text(text.replace("Shift to the right (x) and down (y), in pixels.",
                                  "Shift to the right (x) and down (y), in metres."), encoding="utf-8")
    assert DOCS / "api" / "lab07.md" in apidoc.stale(DOCS, skeletons)
    lab07.write_text(text.replace("def translate(image, tx=100, ty=50):", "def translate(image, dx=100, dy=50):"),
                     encoding="utf-8")
    with pytest.raises(apidoc.ApidocError, match="translate"):
        apidoc.generate(DOCS, skeletons)


def test_a_contract_page_without_an_exercise_is_refused(tmp_path):
    docs = tmp_path / "docs"
    shutil.copytree(DOCS / "contract", docs / "contract")
    page = docs / "contract" / "lab07.md"
    page.write_text(re.sub(r"<!-- apidoc:begin lab07\.ex6 -->.*?<!-- apidoc:end -->", "",
                           page.read_text(encoding="utf-8"), flags=re.S), encoding="utf-8")
    with pytest.raises(apidoc.ApidocError, match="lab07.ex6"):
        apidoc.generate(docs)


def test_the_generator_command_checks_and_writes(tmp_path):
    docs = tmp_path / "docs"
    shutil.copytree(DOCS / "contract", docs / "contract")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    command = [sys.executable, "-m", "autograder.instructor.apidoc", str(docs)]
    assert subprocess.run([*command, "--check"], env=env, capture_output=True).returncode == 1  # no api/ yet
    assert subprocess.run(command, env=env, capture_output=True).returncode == 0
    assert subprocess.run([*command, "--check"], env=env, capture_output=True).returncode == 0
    assert (docs / "api" / "lab12.md").read_text() == (DOCS / "api" / "lab12.md").read_text()


# ------------------------------------------------------------------------------ the converter
def test_docstring_markdown_keeps_every_word_and_code():
    text = textwrap.dedent('''\
        Map points by ``H``, with *the* perspective division.

        Parameters
        ----------
        H : (3, 3) float array
        pts : (N, 2) float array
            Points ``(x, y)``; w**4 and <mistake> print as written,
            ``a
            b`` spans lines.

        Notes
        -----
        Solve::

            A h = 0

        1. first step
           continued
        2. second

        >>> f(1)
        2
        ''')
    out = apidoc.docstring_markdown(text)
    assert "#### Parameters" in out and "#### Notes" in out
    assert "- `H`: (3, 3) float array" in out and "- `pts`: (N, 2) float array" in out
    assert "`H`" in out and "*the*" in out and "w\\*\\*4" in out and "&lt;mistake>" in out
    assert "`a\n    b`" in out
    assert "```text\nA h = 0\n```" in out and "Solve:" in out and "Solve::" not in out
    assert "1. first step\n   continued\n2. second" in out
    assert "```pycon\n>>> f(1)\n2\n```" in out


def test_inline_escapes_markup_but_not_words():
    assert apidoc.inline("translation_matrix(100, 50)") == "translation_matrix(100, 50)"
    assert apidoc.inline("K [R | t] (3 points)") == "K [R | t\\] (3 points)"
    assert apidoc.inline("``x_1`` and _y_") == "`x_1` and \\_y\\_"
    assert apidoc.slug("ex2: Homography from point pairs (DLT)") == "ex2-homography-from-point-pairs-dlt"


def test_signatures_agree_is_checked():
    skeleton = apidoc.read_skeleton(ROOT / "assignments" / "lab08_homographies.py")
    apidoc._agrees("lab08", "ext1", 'match_features(img1, img2, ratio=0.75, method="orb")', skeleton,
                   "match_features")
    with pytest.raises(apidoc.ApidocError, match="no parameter detector"):
        apidoc._agrees("lab08", "ext1", 'match_features(img1, img2, detector="orb")', skeleton, "match_features")
    assert ast.parse("def " + skeleton.functions["match_features"].signature + ": pass")
