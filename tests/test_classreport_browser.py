"""Both class pages in a real browser (headless Chromium) at a phone's and a desktop's width.

Fails on console errors, broken images, sideways scrolling or a missing
viewport tag. Skipped, with the reason, where Chromium is not installed (CI
installs the Debian package ``chromium``). Screenshots are kept in the test's
temporary folder for a person to look at.
"""

from __future__ import annotations

import pytest

from browser import find_chromium, inspect_page

pytestmark = [pytest.mark.browser,
              pytest.mark.skipif(find_chromium() is None,
                                 reason="Chromium is not installed (apt-get install chromium, or set CHROMIUM)")]

WIDTHS = (390, 1280)


def assert_reads_well(page, tmp_path):
    reports = inspect_page(page, WIDTHS)
    assert [r.width for r in reports] == list(WIDTHS)
    for report in reports:
        (tmp_path / f"{page.stem}-{report.width}.png").write_bytes(report.screenshot)
        assert report.screenshot.startswith(b"\x89PNG")
        assert report.problems() == [], f"{page.name} at {report.width} px"


def test_class_overview_reads_well_on_a_phone_and_a_desktop(tmp_path):
    from autograder.instructor.classreport.analysis import StudentRecord
    from autograder.instructor.classreport.overview import render_overview
    from test_classreport import CLASS_SIZE, PLANTED, lab07, lab08

    from autograder.engine.results import GradingResult

    students = []
    for i in range(CLASS_SIZE):
        result = GradingResult(f"s{i}", "h", "v", lab07(i, PLANTED) + lab08(i, PLANTED)).to_dict()
        name = f"Student {i:02d}" if i != 4 else "Maximiliane Wolfeschlegelsteinhausenbergerdorff-Longname"
        students.append(StudentRecord(f"s{i:02d}", name, result=result, feedback_href=f"s{i:02d}/feedback.html"))
    students.append(StudentRecord("broken", status="unreadable",
                                  reason="Traceback: " + "a_very_long_unbroken_identifier_" * 8))
    page = tmp_path / "index.html"
    render_overview(students, page, course_title="Computer vision, spring term")
    assert_reads_well(page, tmp_path)


def test_similarity_page_reads_well_on_a_phone_and_a_desktop(tmp_path):
    pytest.importorskip("copydetect")
    from autograder.instructor.classreport.similarity import compare_class, similarity_html
    from classreport_disguise import disguise
    from test_similarity import INDEPENDENT, LAB07, REFERENCE, SKELETON, THRESHOLD

    sources = {"ada": REFERENCE, "ben": INDEPENDENT, "cleo": disguise(REFERENCE, 1),
               "eve": disguise(INDEPENDENT, 3) + "\nx = '" + "long_line_" * 40 + "'\n"}
    results = compare_class({s: {LAB07: code} for s, code in sources.items()}, {LAB07: SKELETON},
                            {LAB07: "lab07"}, threshold=THRESHOLD)
    page = tmp_path / "similarity.html"
    page.write_text(similarity_html(results, THRESHOLD, course_title="Computer vision"))
    assert_reads_well(page, tmp_path)


def test_the_inspector_catches_what_it_should(tmp_path):
    """The browser check can fail: a wide table, a broken image, a script error."""
    page = tmp_path / "bad.html"
    page.write_text('<!doctype html><html><head><meta charset="utf-8"></head><body>'
                    '<div style="width: 900px">wide</div><img src="missing.png" alt="x">'
                    '<script>throw new Error("boom")</script></body></html>')
    [phone] = inspect_page(page, (390,))
    problems = "\n".join(phone.problems())
    assert "sideways scrolling" in problems and "broken image" in problems
    assert "boom" in problems and "viewport" in problems
