"""Issue 37: reports in the student's own structure are read.

A Markdown report or notebook with the student's own headings ("## Exercise 2:
Rotation", "Ex. 2", "2. Rotation", "Rotation", "Lab 7 Exercise 2", "Extension 1",
setext, bold lines) gives each exercise the text under its heading; the scaffold's
markers keep precedence; arbitrary text never raises and names only known exercises.
"""

from __future__ import annotations

import json

import pytest
from hypothesis import given
from hypothesis import strategies as st

from autograder.engine.registry import discover
from autograder.instructor.batch.ingest import read_upload
from autograder.loading.headings import ExerciseNames, plain_text_sections
from autograder.loading.report import explanations_in_markdown, read_report
from test_batch import write

LABS = discover()
LAB07 = ExerciseNames.of_labs([LABS["lab07"]])
EVERY = ExerciseNames.of_labs(LABS.values())
LAB08_09 = ExerciseNames.of_labs([LABS["lab08"], LABS["lab09"]])

# (heading text, the lab in force, exercise id or None) -- headings as students write them
HEADINGS = [
    ("Exercise 2: Rotation", None, "lab07.ex2"),
    ("Exercise 2", None, "lab07.ex2"),
    ("EXERCISE 2 - ROTATION", None, "lab07.ex2"),
    ("Ex. 2", None, "lab07.ex2"),
    ("Ex2", None, "lab07.ex2"),
    ("ex 2)", None, "lab07.ex2"),
    ("Exercise no. 2", None, "lab07.ex2"),
    ("2. Rotation", None, "lab07.ex2"),
    ("2) Rotation", None, "lab07.ex2"),
    ("2 Rotation", None, "lab07.ex2"),
    ("2", None, "lab07.ex2"),
    ("Task 2", None, "lab07.ex2"),
    ("Q2", None, "lab07.ex2"),
    ("Question 2(a)", None, "lab07.ex2"),
    ("Part 2", None, "lab07.ex2"),
    ("Problem 2", None, "lab07.ex2"),
    ("Rotation", None, "lab07.ex2"),
    ("rotation:", None, "lab07.ex2"),
    ("*Rotation*", None, "lab07.ex2"),
    ("`Rotation` results", None, "lab07.ex2"),
    ("Exercise 2.1 The rotation matrix", None, "lab07.ex2"),
    ("Affine transformation from three points", None, "lab07.ex5"),
    ("Least-squares affine transformation", None, "lab07.ex6"),
    ("Lab 7 Exercise 2", None, "lab07.ex2"),
    ("Lab 07, Ex. 2", None, "lab07.ex2"),
    ("Lab07 - Ex 2", None, "lab07.ex2"),
    ("lab07.ex2: Rotation", None, "lab07.ex2"),
    ("7.2", None, "lab07.ex2"),
    ("7.2 Rotation", None, "lab07.ex2"),
    ("Lab 7.2", None, "lab07.ex2"),
    # not exercises
    ("3 observations", None, None),
    ("2019 results", None, None),
    ("Lab 7: 2D transformations", None, None),
    ("Introduction", None, None),
    ("Exercise 9", None, None),
    ("Lab 8 Exercise 2", None, None),      # not a lab being graded here
    ("Examples", None, None),
    ("", None, None),
]
EXTENSIONS = [
    ("Extension 1", "lab09", "lab09.ext1"),
    ("ext1", "lab09", "lab09.ext1"),
    ("Ext. 2: panorama", "lab08", "lab08.ext2"),
    ("Extension 2", "lab08", "lab08.ext2"),
    ("Lab 9 Extension 2", None, "lab09.ext2"),
    ("Camera calibration", None, "lab09.ext1"),
    ("Extension: lens distortion", None, "lab09.ext2"),
    ("The pinhole camera", None, "lab09.ex1"),
    ("Pinhole camera", None, "lab09.ex1"),
    ("Multi-band blending", None, "lab08.ext3"),
    ("8.3", None, "lab08.ex3"),
    ("Exercise 3", "lab09", "lab09.ex3"),
    ("Exercise 3", None, None),            # two labs, none in force: no guess
]


@pytest.mark.parametrize("heading, lab, expected", HEADINGS)
def test_headings_as_students_write_them(heading, lab, expected):
    assert LAB07.named(heading, lab).exercise == expected


@pytest.mark.parametrize("heading, lab, expected", EXTENSIONS)
def test_extensions_and_titles_across_labs(heading, lab, expected):
    assert LAB08_09.named(heading, lab).exercise == expected


STUDENT_REPORT = """\
# My report for lab 7
Some introduction that is nobody's exercise.

## Exercise 1: Translation
I moved the image by (100, 50).

### What I noticed
The corner is black.

## Ex. 2 - Rotation
![my rotation](rot.png)
The image turns about its centre.

Scaling
-------
Scaling by two doubles the size.

**Exercise 4**
Shearing slants it.

```python
# Exercise 5
x = 1
```

5. Affine transformation from three points
==========================================
Three points fix an affine map.

Conclusion
==========
That was the lab.
"""


def test_a_markdown_report_in_the_students_own_structure():
    report = read_report({"alice/lab07_report.md": STUDENT_REPORT.encode()}, LAB07)
    texts = {exercise: x.text for exercise, x in report.explanations.items()}
    assert texts == {
        "lab07.ex1": "I moved the image by (100, 50).\n\n### What I noticed\nThe corner is black.",
        "lab07.ex2": "The image turns about its centre.",
        "lab07.ex3": "Scaling by two doubles the size.",
        "lab07.ex4": "Shearing slants it.\n\n```python\n# Exercise 5\nx = 1\n```",
        "lab07.ex5": "Three points fix an affine map.",
    }
    assert report.problems == ()
    assert read_report({"alice/lab07_report.md": STUDENT_REPORT.encode()}).explanations == {}   # no names: not read


def test_the_lab_comes_from_the_path_or_a_heading_or_is_not_guessed():
    body = "## Exercise 2\nIt rotates.\n"
    assert list(read_report({"x/lab07_report.md": body.encode()}, EVERY).explanations) == ["lab07.ex2"]
    assert list(read_report({"x/report.md": ("# Lab 7\n" + body).encode()}, EVERY).explanations) == ["lab07.ex2"]
    assert list(read_report({"x/report.md": ("# 2D transformations\n" + body).encode()}, EVERY).explanations) \
        == ["lab07.ex2"]
    unsure = read_report({"x/report.md": body.encode()}, EVERY)
    assert unsure.explanations == {}
    assert any("names an exercise by number but not its lab" in p for p in unsure.problems)


def test_scaffold_markers_keep_precedence():
    text = ("## lab07.ex2: Rotation\n<!-- explanation lab07.ex2 -->\nFrom the scaffold.\n<!-- end explanation -->\n"
            "## Exercise 2\nMy own words.\n## Exercise 3\nScaled.\n")
    report = read_report({"lab07_report.md": text.encode()}, LAB07)
    assert report.explanations["lab07.ex2"].text == "From the scaffold."
    assert report.explanations["lab07.ex3"].text == "Scaled."
    # across files too: a notebook's tagged cell outranks a Markdown heading of the student's own
    cells = [{"cell_type": "markdown", "metadata": {"tags": ["report:lab07.ex3"]}, "source": "Tagged."}]
    notebook = json.dumps({"cells": cells, "metadata": {}, "nbformat": 4, "nbformat_minor": 5}).encode()
    both = read_report({"lab07_report.md": text.encode(), "lab07_transformations.ipynb": notebook}, LAB07)
    assert both.explanations["lab07.ex3"].text == "Tagged."


def test_an_untouched_scaffold_with_own_headings_elsewhere():
    """The scaffold's placeholder explains nothing: the student's own section counts."""
    text = ("## lab07.ex1: Translation\n<!-- explanation lab07.ex1 -->\n_Explain what you see here._\n"
            "<!-- end explanation -->\n\n# Notes\n## Translation\nWritten under my own heading.\n")
    report = read_report({"lab07_report.md": text.encode()}, LAB07)
    assert report.explanations["lab07.ex1"].text == "Written under my own heading."


def test_notebook_markdown_cells_under_such_headings():
    def cell(kind, source):
        return {"cell_type": kind, "metadata": {}, "source": source, **({"outputs": []} if kind == "code" else {})}

    cells = [cell("markdown", "# Lab 7"), cell("markdown", "## Exercise 1"), cell("code", "translate(img)"),
             cell("markdown", "The picture moved."), cell("markdown", "It moved right."),
             cell("markdown", "## 2. Rotation\nIt turns."), cell("code", "# Exercise 3\nrotate(img)")]
    data = json.dumps({"cells": cells, "metadata": {}, "nbformat": 4, "nbformat_minor": 5}).encode()
    report = read_report({"work.ipynb": data}, EVERY)
    assert {k: (x.text, x.source) for k, x in report.explanations.items()} == {
        "lab07.ex1": ("The picture moved.\n\nIt moved right.", "work.ipynb, cell 2"),
        "lab07.ex2": ("It turns.", "work.ipynb, cell 6"),
    }


def test_the_batch_reads_them(tmp_path):
    folder = tmp_path / "class"
    write(folder / "alice" / "lab07_transformations.py", b"def translate(image, tx, ty):\n    return image\n")
    write(folder / "alice" / "report.md", STUDENT_REPORT.encode())
    [entry] = read_upload(folder, ["lab07_transformations"], names=LAB07).entries
    assert entry.report.explanations["lab07.ex2"].text == "The image turns about its centre."


def test_the_scaffold_writer_still_reads_only_its_own_sections():
    """``explanations_in_markdown`` (what the scaffold carries over) knows no names."""
    assert explanations_in_markdown("## Exercise 2\nText.\n", "r.md") == {}


ALPHABET = st.sampled_from(list("#=-*_`~ \n\t.:)(2713xeEQ") + ["Exercise ", "Ex", "Lab 7", "Rotation", "ext",
                                                              "```", "\n\n", "7.2", "\u00e9", "\r"])


@given(st.lists(ALPHABET, max_size=200).map("".join) | st.text(max_size=300))
def test_arbitrary_text_never_raises_and_names_only_known_exercises(text):
    """Never raises; the student's own headings name only exercises of the labs graded."""
    for names in (LAB07, EVERY, LAB08_09):
        report = read_report({"lab07_report.md": text.encode(),
                              "n.ipynb": json.dumps({"cells": [{"cell_type": "markdown", "source": text}]}).encode()},
                             names)
        # a known exercise, or an id the text spells out (the scaffold's markers and "## ID" headings)
        assert all(exercise in names.exercises or exercise in text.lower() for exercise in report.explanations)
        assert all(explanation.text.strip() for explanation in report.explanations.values())
        assert {section.exercise for section in plain_text_sections(text, names, None, 1_000)} <= set(names.exercises)


# ------------------------------------------------------------------ text extracted from a PDF
PDF_TEXT = """\
Lab 7 - 2D transformations                    Jane Doe
1
Exercise 1: Translation
The picture moves by (100, 50); the corners left behind are black.
2
Lab 7 - 2D transformations                    Jane Doe
2. Rotation
It turns about the centre.
Figure 2.
Ex 3
Scaling doubles the size.
"""


def test_plain_text_of_a_pdf_is_read_per_exercise_strictly():
    """A short line naming an exercise is a heading; page numbers ("2"), running headers and a
    sentence starting with a title are not."""
    sections = plain_text_sections(PDF_TEXT, EVERY, None, 10_000)
    assert [(s.exercise, " ".join(s.body.split())) for s in sections] == [
        ("lab07.ex1", "The picture moves by (100, 50); the corners left behind are black. 2 "
                      "Lab 7 - 2D transformations Jane Doe"),
        ("lab07.ex2", "It turns about the centre. Figure 2."),
        ("lab07.ex3", "Scaling doubles the size."),
    ]
    assert [LAB07.named(line, None, strict=True).exercise for line in ("2", "7.2", "2.", "2. Rotation", "Q2")] \
        == [None, None, None, "lab07.ex2", "lab07.ex2"]


# ------------------------------------------------------------------ linear in what is handed in
@pytest.mark.parametrize("shape", ["many headings", "deep headings under one", "long lines", "spaces in headings",
                                   "many cells"])
def test_reading_own_headings_is_linear(shape):
    """Twice the text, at most RATIO times the CPU time (tests/test_linear_reading.py's measure),
    for the inputs that would make a backtracking or quadratic reader slow."""
    from test_linear_reading import assert_linear

    def make(n):
        # (a file's first MAX_SECTIONS headings are read: below that bound, the text under them grows)
        if shape == "many headings":
            return "".join(f"### Exercise {i % 7}: Rotation\n" + "text " * (n // 50) + "\n" for i in range(900))
        if shape == "deep headings under one":
            return "# Exercise 2\n" + ("###### 2.1 more\n" + "x " * (n // 50) + "\n") * 900
        if shape == "long lines":
            return "## Exercise 2\n" + ("Rotation " * 200 + "\n") * (n // 20)
        if shape == "spaces in headings":
            return ("# Lab 7" + " " * 500 + "Ex" + " " * 500 + ".\n") * (n // 20)
        cells = [{"cell_type": "markdown", "source": f"## Ex {i % 7}\nx"} for i in range(n // 4)]  # < MAX_REPORT_CELLS
        return json.dumps({"cells": cells})

    def run(text):
        read_report({"lab07_report.md" if not text.startswith("{") else "lab07.ipynb": text.encode()}, LAB07)

    assert_linear(run, make, 4_000)
