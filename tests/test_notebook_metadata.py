"""A notebook is data: nothing in its metadata, tags or junk is ever a format string, template
or path, and what it costs the grader is bounded by its size.

Two kinds of tests: a property (any JSON at all as the notebook's or a cell's metadata gives
the module and the messages a clean notebook gives), and hostile notebooks graded end to end
(format strings, huge and deep metadata, tags that are not lists, names that are not
strings, cells that are not objects): each is graded without a traceback, its report stays
small, and reading it costs at most a bounded multiple of its size in memory.
"""

from __future__ import annotations

import io
import json
import tracemalloc

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from rich.console import Console

from autograder.loading.notebooks import GRADE_TAG, SKIP_TAG, NotebookError, convert
from autograder.engine.registry import select
from autograder.reports import html, terminal
from autograder.engine.results import json_text, strip_pictures
from autograder.engine.runner import grade
from conftest import REFERENCE

MODULE = "lab07_transformations"
REFERENCE_CODE = (REFERENCE / f"{MODULE}.py").read_text()
# What str.format, %-formatting and template engines would act on.
TEMPLATES = ["{0.__class__}", "{number}", "{number.__class__.__mro__}", "{number} {number.foo}",
             "{number} {0}", "{number} {number:>99999999}", "%s %d %(x)s", "{{ 7 * 7 }}", "{% for x in y %}",
             "${HOME}", "In [{number}]", "cell {number}", "\\1 \\g<0>", "../../etc/passwd", "/dev/zero"]


def notebook(cells: list, metadata=None, nbformat: bool = True) -> str:
    data = {"cells": cells, "metadata": {} if metadata is None else metadata}
    if nbformat:
        data.update(nbformat=4, nbformat_minor=5)
    return json.dumps(data)


def code_cell(source: str, metadata=None) -> dict:
    return {"cell_type": "code", "metadata": {} if metadata is None else metadata, "source": source,
            "outputs": [], "execution_count": None}


DEMO = ["print(translation_matrix(3, 4))", "image = load('cat.png')\nplt.imshow(translate(image))"]


def cells_with(metadata) -> list:
    """The reference module and two demo cells (left out, so messages name them), each
    with ``metadata``."""
    return [code_cell(REFERENCE_CODE, metadata)] + [code_cell(demo, metadata) for demo in DEMO]


# ------------------------------------------------------------------ metadata never changes the module
def _no_known_words(value) -> bool:
    """Nothing the grader reads on purpose: the two tags, and the kernel-history label."""
    if isinstance(value, str):
        return value not in (GRADE_TAG, SKIP_TAG, "input")
    if isinstance(value, list):
        return all(_no_known_words(v) for v in value)
    if isinstance(value, dict):
        return all(_no_known_words(k) and _no_known_words(v) for k, v in value.items())
    return True


json_values = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats(allow_nan=False, allow_infinity=False)
    | st.text(max_size=20) | st.sampled_from(TEMPLATES),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(
        st.sampled_from(["autograder", "cell_label", "tags", "name", "kernelspec", "number"]) | st.text(max_size=8),
        inner, max_size=4),
    max_leaves=24).filter(_no_known_words)


# Anything, and also anything where the grader looks: the cell label, the tags.
notebook_metadata = json_values | st.builds(lambda label, rest: {**rest, "autograder": {"cell_label": label}},
                                            json_values | st.sampled_from(TEMPLATES), st.dictionaries(
                                                st.text(max_size=8), json_values, max_size=3))
cell_metadata = json_values | st.builds(lambda tags, rest: {**rest, "tags": tags}, json_values, st.dictionaries(
    st.text(max_size=8), json_values, max_size=3))


@settings(max_examples=60)
@given(notebook_metadata=notebook_metadata, cell_metadata=cell_metadata, nbformat=st.booleans())
def test_any_metadata_gives_the_module_a_clean_notebook_gives(notebook_metadata, cell_metadata, nbformat):
    clean = convert(notebook(cells_with({}), {}, nbformat), "clean.ipynb")
    hostile = convert(notebook(cells_with(cell_metadata), notebook_metadata, nbformat), "hostile.ipynb")
    assert hostile.source == clean.source
    assert hostile.left_out == clean.left_out == ["cell 2: print(translation_matrix(3, 4))",
                                                  "cell 3: image = load('cat.png') (+1 lines)"]
    assert [hostile.label(n) for n in (1, 12)] == ["cell 1", "cell 12"]


@pytest.mark.parametrize("label", TEMPLATES + [5, None, ["input"], {"input": 1}])
def test_a_cell_label_from_the_notebook_is_one_of_the_graders_own(label):
    """Only the exact word "input" (the kernel's history, see selfcheck) asks for "In [N]"."""
    converted = convert(notebook(cells_with({}), {"autograder": {"cell_label": label}}))
    assert converted.left_out[0].startswith("cell 2: ")
    history = convert(notebook(cells_with({}), {"autograder": {"cell_label": "input"}}))
    assert history.left_out[0].startswith("In [2]: ") and history.label(7) == "In [7]"


def test_only_the_known_tags_count_and_only_in_a_list():
    def left_out(tags) -> list[str]:
        return convert(notebook([code_cell("x = f(1)\ndef g():\n    pass\n", {"tags": tags})])).left_out
    assert left_out([GRADE_TAG]) == [] and left_out(["junk", GRADE_TAG, 7, None]) == []
    assert left_out([SKIP_TAG]) == ["cell 1: x = f(1) (+2 lines)"]
    for not_a_list in ({GRADE_TAG: True}, GRADE_TAG, 5, [[GRADE_TAG]], [{"grade": 1}]):
        assert left_out(not_a_list) == ["cell 1: x = f(1)"], not_a_list   # definitions only, as untagged


# ------------------------------------------------------------------ hostile notebooks, end to end
def _deep(depth: int):
    value: object = {"leaf": "{0.__class__}"}
    for _ in range(depth):
        value = {"k": value}
    return value


JUNK_CELLS = [42, "cell", [1, 2], None, {}, {"cell_type": 5, "source": 7},
              {"cell_type": "markdown", "metadata": "{0}", "source": {"x": 1}},
              code_cell("y = 2", metadata=[1, 2]), code_cell("z = 3", metadata="{number.foo}"),
              code_cell("w = 4", metadata=None) | {"metadata": None}, code_cell("v = 5", {"tags": "grade"})]

HOSTILE = {
    "format strings": notebook(
        cells_with({"tags": "{0.__class__}", "name": "{number} {number:>99999999}"}),
        {"autograder": {"cell_label": "{number} {number:>99999999}", "title": "{0.__class__}"},
         "kernelspec": {"name": 5, "display_name": ["{0}"]}, "title": "{number.__class__.__mro__}"}),
    "junk cells and metadata that is not an object": notebook(cells_with([1, {"tags": [SKIP_TAG]}]) + JUNK_CELLS,
                                                              metadata=[{"autograder": 1}]),
    "tags that are not lists": notebook(
        [code_cell(REFERENCE_CODE, {"tags": {SKIP_TAG: True}}), code_cell(DEMO[0], {"tags": SKIP_TAG}),
         code_cell(DEMO[1], {"tags": [[SKIP_TAG], f"{SKIP_TAG}x"] + [f"tag{i}" for i in range(50_000)]})]),
    "wide metadata": notebook(cells_with({"x": {f"k{i}": [i, str(i)] for i in range(20_000)}}),
                              {f"key{i}": {"a": [i, "{0}"], "b": None} for i in range(60_000)}),
    "deep metadata": notebook(cells_with({"deep": _deep(400)}), {"deep": _deep(400)}),
    "bare cells, no nbformat": notebook(cells_with({"tags": 5}) + JUNK_CELLS, "{0}", nbformat=False),
}


def _peak_bytes(function, *args):
    tracemalloc.start()
    try:
        function(*args)
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


@pytest.mark.parametrize("case", list(HOSTILE))
def test_a_hostile_notebook_is_graded_and_its_report_is_small(case, tmp_path):
    text = HOSTILE[case]
    # Reading it costs its parsing: a bounded multiple of its size, never what its text asks for.
    assert _peak_bytes(convert, text, "x.ipynb") < 30 * len(text) + 8 * 2**20
    folder = tmp_path / "handin"
    folder.mkdir()
    (folder / f"{MODULE}.ipynb").write_text(text)
    result = grade(folder, ["lab07.ex1"], pictures="none")
    [exercise] = result.exercises
    public = sum(c.points for c in select(["lab07.ex1"])[0].checks if not c.hidden)
    assert exercise.message == "" and sum(c.score for c in exercise.checks if not c.hidden) == public
    view = result.for_students()
    buffer = io.StringIO()
    terminal.render(view, Console(file=buffer, width=120))
    for report in (buffer.getvalue(), html.render(view), json_text(strip_pictures(view.to_dict()))):
        assert len(report) < 200_000 and "<class" not in report and "{0" not in report
    assert all(len(note) < 600 for note in result.notes)


@pytest.mark.parametrize("text, reason", [
    ('{"cells": [' + "[" * 100_000 + "]" * 100_000 + "]}", "nested too deeply"),
    (notebook([code_cell(["def f():\n", 5, "    pass\n"])]), "the code of cell 1 is not text"),
    (notebook([code_cell({"lines": "def f(): pass"})]), "the code of cell 1 is not text"),
    ('{"worksheets": [{"cells": []}], "nbformat": 3}', "no list of cells"),
    ("{0.__class__}", "not valid JSON"),
])
def test_an_unreadable_notebook_is_named_not_a_traceback(text, reason, tmp_path):
    with pytest.raises(NotebookError, match=reason):
        convert(text, f"{MODULE}.ipynb")
    folder = tmp_path / "handin"
    folder.mkdir()
    (folder / f"{MODULE}.ipynb").write_text(text)
    [exercise] = grade(folder, ["lab07.ex1"], pictures="none").exercises
    assert f"{MODULE}.ipynb is not a readable notebook ({reason})" in exercise.message
    assert all(c.score == 0 for c in exercise.checks)


def test_a_notebook_of_more_code_than_grading_reads_is_refused_with_its_reason():
    """The definitions analysis is linear in the code: a notebook of a million generated
    lines is that module's problem, named, never minutes of the grader's time."""
    from autograder.loading.notebooks import MAX_CODE_LINES, NotebookError, convert

    source = "".join(f"a{i} = {i}\n" for i in range(MAX_CODE_LINES + 1))
    notebook = json.dumps({"cells": [{"cell_type": "code", "metadata": {}, "source": source, "outputs": [],
                                      "execution_count": 1}], "metadata": {}, "nbformat": 4, "nbformat_minor": 5})
    with pytest.raises(NotebookError, match="more than 100,000 lines"):
        convert(notebook, "lab07_transformations.ipynb")
