"""The similarity report: disguised copies rank above independent work, which stays below the threshold."""

from __future__ import annotations

import itertools
import json
import zipfile
from pathlib import Path

import pytest

pytest.importorskip("copydetect")

from autograder.instructor.classreport.similarity import (MAX_SOURCE_CHARS, collect_sources, compare_class,  # noqa: E402
                                               compare_module, similarity_html, skeleton_sources)
from autograder.cli import main  # noqa: E402
from autograder.instructor.course import CourseConfig  # noqa: E402
from classreport_disguise import disguise  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
LAB07 = "lab07_transformations"
REFERENCE = (ROOT / "reference_solutions" / f"{LAB07}.py").read_text()
# Written independently of the reference: same answers, a different hand (grades 73/73).
INDEPENDENT = (Path(__file__).parent / "classreport_data" / f"{LAB07}.py").read_text()
SKELETON = (ROOT / "assignments" / f"{LAB07}.py").read_text()
THRESHOLD = CourseConfig().similarity_threshold


@pytest.fixture(scope="module")
def lab07_class():
    """Two independent originals, three disguised copies, and an untouched skeleton."""
    sources = {"ada": REFERENCE, "ben": INDEPENDENT,
               "cleo": disguise(REFERENCE, seed=1), "dan": disguise(REFERENCE, seed=2),
               "eve": disguise(INDEPENDENT, seed=3), "fay": SKELETON}
    origin = {"ada": "reference", "cleo": "reference", "dan": "reference", "ben": "independent", "eve": "independent"}
    return sources, origin, compare_module(LAB07, sources, SKELETON, "lab07")


def test_disguise_really_disguises():
    copy = disguise(REFERENCE, seed=1)
    assert copy != REFERENCE and "_warp" not in copy and "# here is the answer" in copy
    public = lambda code: [line.split("(")[0] for line in code.splitlines()  # noqa: E731
                           if line.startswith("def ") and not line.startswith("def _")]
    assert public(copy) != public(REFERENCE) and sorted(public(copy)) == sorted(public(REFERENCE))


def test_planted_copies_rank_above_every_independent_pair(lab07_class):
    _, origin, result = lab07_class
    copies = [p for p in result.pairs if origin[p.student_a] == origin[p.student_b]]
    independent = [p for p in result.pairs if origin[p.student_a] != origin[p.student_b]]
    assert len(copies) == 3 + 1 and len(independent) == 3 * 2
    assert min(p.score for p in copies) > max(p.score for p in independent)
    assert result.pairs[:len(copies)] == sorted(copies, key=lambda p: -p.score)


def test_copies_cross_the_threshold_and_independent_work_does_not(lab07_class):
    _, origin, result = lab07_class
    for pair in result.pairs:
        same = origin[pair.student_a] == origin[pair.student_b]
        assert (pair.score >= THRESHOLD) == same, (pair.student_a, pair.student_b, pair.score)


def test_the_skeleton_is_boilerplate(lab07_class):
    _, _, result = lab07_class
    assert result.students == 5   # fay handed in the untouched skeleton: nothing of her own
    assert all("fay" not in (p.student_a, p.student_b) for p in result.pairs)
    two_skeletons = compare_module(LAB07, {"x": SKELETON, "y": SKELETON + "\n# mine\n"}, SKELETON)
    assert two_skeletons.pairs == []


def test_page_highlights_and_escapes_student_text(lab07_class):
    sources, _, _ = lab07_class
    hostile = dict(sources, **{"mal</td><script>": INDEPENDENT + "\n# </pre><script>alert(1)</script>\n"})
    results = compare_class({s: {LAB07: code} for s, code in hostile.items()}, {LAB07: SKELETON},
                            {LAB07: "lab07"}, threshold=THRESHOLD)
    html = similarity_html(results, THRESHOLD, course_title="CV <b>")
    assert "<script" not in html and "</td><script>" not in html and "CV <b>" not in html
    assert "leads to read" in html and "Nobody is accused" in html
    # every copy pair; the hostile one is ben's code with a comment: one cluster with ben, listed once
    assert html.count('<details class="pair"') == 4 and "mal&lt;/td&gt;&lt;script&gt;" in html
    assert results[0].clusters == [["ben", "mal</td><script>"]]
    assert "<mark>" in html


def _notebook(code: str) -> str:
    return json.dumps({"cells": [{"cell_type": "code", "source": code.splitlines(True)}], "metadata": {},
                       "nbformat": 4, "nbformat_minor": 5})


def test_sources_from_folders_zips_and_notebooks(tmp_path):
    (tmp_path / "ada").mkdir()
    (tmp_path / "ada" / f"{LAB07}.py").write_text(REFERENCE)
    with zipfile.ZipFile(tmp_path / "ben.zip", "w") as zf:
        zf.writestr(f"ben/{LAB07}.py", INDEPENDENT)
    (tmp_path / "cleo").mkdir()
    (tmp_path / "cleo" / f"{LAB07}.ipynb").write_text(_notebook(disguise(REFERENCE, 1)))
    (tmp_path / "grades.csv").write_text("not a student\n")
    (tmp_path / "dan").mkdir()   # handed in nothing
    (tmp_path / "eve").mkdir()
    (tmp_path / "eve" / f"{LAB07}.py").write_text("x = 1\n" * 250_000)   # 1.5 MB: compared by its start
    sources = collect_sources(tmp_path, [LAB07, "lab08_homographies"])
    assert sorted(sources) == ["ada", "ben", "cleo", "eve"]
    assert len(sources["eve"][LAB07]) == MAX_SOURCE_CHARS
    assert sources["ben"][LAB07] == INDEPENDENT and "def rotation_matrix" in sources["cleo"][LAB07]


def test_cli_writes_the_page_with_the_course_threshold(tmp_path, capsys):
    class_dir = tmp_path / "class"
    for name, code in {"ada": REFERENCE, "ben": INDEPENDENT, "cleo": disguise(REFERENCE, 1)}.items():
        (class_dir / name).mkdir(parents=True)
        (class_dir / name / f"{LAB07}.py").write_text(code)
    course = tmp_path / "course.json"
    course.write_text(json.dumps({"similarity_threshold": 0.8}))  # disguised copies: 0.85-0.98
    out = tmp_path / "similarity.html"
    assert main(["similarity", str(class_dir), "--out", str(out), "--course", str(course)]) == 0
    printed = capsys.readouterr().out
    assert "lab07: 3 students, 1 pairs at or above 80%" in printed
    html = out.read_text()
    assert "ada · cleo" in html and "at least <strong>80%</strong>" in html
    assert main(["similarity", str(tmp_path / "missing")]) == 2


def test_threshold_is_validated(tmp_path):
    from autograder.instructor.course import CourseConfigError

    with pytest.raises(CourseConfigError):
        CourseConfig(similarity_threshold=1.5)
    assert 0 < CourseConfig().similarity_threshold <= 1


def test_skeleton_sources_found_for_every_lab():
    from autograder.instructor.classreport.similarity import lab_modules

    modules = lab_modules()
    assert set(skeleton_sources(modules)) == set(modules)
    assert all(a != b for a, b in itertools.combinations(modules.values(), 2))


def test_aligning_only_candidates_finds_the_same_leads(lab07_class):
    sources, _, quick = lab07_class
    exhaustive = compare_module(LAB07, sources, SKELETON, "lab07", align_above=0.0, aligned_at_least=10**6)
    assert all(p.aligned for p in exhaustive.pairs)
    assert [(p.student_a, p.student_b, p.score) for p in quick.leads(THRESHOLD)] == \
        [(p.student_a, p.student_b, p.score) for p in exhaustive.leads(THRESHOLD)]


def test_sources_from_an_lms_download_use_the_batchs_student_ids(tmp_path):
    ingest = pytest.importorskip("autograder.instructor.batch.ingest")
    (tmp_path / f"smithjohn_12345_67890_{LAB07}.py").write_text(REFERENCE)
    (tmp_path / f"doejane_LATE_23456_78901_{LAB07}-1.py").write_text(disguise(REFERENCE, 4))
    sources = collect_sources(tmp_path, [LAB07])
    ids = sorted(e.student_id for e in ingest.read_class(tmp_path, [LAB07], [LAB07]))
    assert sorted(sources) == ids and len(ids) == 2
    [result] = compare_class(sources, {LAB07: SKELETON}, {LAB07: "lab07"}, threshold=THRESHOLD)
    assert [(p.student_a, p.student_b) for p in result.leads(THRESHOLD)] == [tuple(ids)]


def test_identical_submissions_are_one_cluster_listed_once(lab07_class):
    """A class where many hand in the same file: one line per cluster, not one per pair."""
    sources, _, _ = lab07_class
    same = {f"twin{i:02d}": INDEPENDENT for i in range(23)}            # 253 identical pairs
    same["ada"] = REFERENCE
    result = compare_module(LAB07, same, SKELETON, "lab07")
    assert result.clusters == [[f"twin{i:02d}" for i in range(23)]]
    assert result.students == 24 and len(result.pairs) == 1
    assert result.identical_to("twin00") == [f"twin{i:02d}" for i in range(1, 23)]
    page = similarity_html([result], THRESHOLD)
    assert "23 students:" in page and "twin00 (+22 identical)" in page and "twin05 ·" not in page
