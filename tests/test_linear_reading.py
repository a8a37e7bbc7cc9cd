"""Everything a student hands in is read in linear time and bounded memory (issue 34).

For each reader in the grader's process, inputs of one hostile shape are read at size n
and 2n: a linear reader takes about twice as long, a quadratic one four times. Time is
the process's CPU time (other processes on a shared machine do not count), the best of
a few runs, at sizes where a run takes tens of milliseconds. Then a fuzzer per reader
(derandomised, no files) holds that it raises nothing but its documented errors and
gives bounded output; and ``ast`` is only ever used under the parse lock (CPython
3.11's AST constructor is not thread-safe: gh-106905).

Speed figures are in ``benchmarks/reading.py``.
"""

from __future__ import annotations

import ast
import builtins
import gc
import json
import re
import sys
import threading
import time
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from autograder.engine.properties import grading_settings
from autograder.loading import notebooks, parsing, reading, report
from autograder.loading.notebooks import NotebookError, convert, is_ipython_line
from autograder.loading.report import (MAX_EXPLANATION_CHARS, MAX_EXPLANATIONS, MAX_PLACES, MAX_PROBLEMS,
                                       MAX_REPORT_CELLS, MAX_SECTIONS, explanations_in_markdown, read_report)

PACKAGE = Path(__file__).resolve().parents[1] / "autograder"
RATIO = 2.8     # for twice the input: linear is 2, quadratic 4 (a shared machine's noise, measured: up to x2.8)


# ------------------------------------------------------------------ measuring
def cpu_seconds(run, value) -> float:
    """The CPU time of one run, the garbage collector paused (its passes cost with the test
    process's own heap, not with the input)."""
    gc.collect()
    gc.disable()
    try:
        start = time.process_time()
        run(value)
        return time.process_time() - start
    finally:
        gc.enable()


def assert_linear(run, make, n: int, repeat: int = 3) -> None:
    """``run(make(2n))`` takes at most :data:`RATIO` times as long as ``run(make(n))``: the least
    of ``repeat`` runs of each, taken in turn (so that both sizes share the machine's moods);
    measured up to three times before failing, since a shared machine's noise rarely repeats,
    and a quadratic reader's x4 always does."""
    small, large = make(n), make(2 * n)
    ratios = []
    for _ in range(3):
        base = double = float("inf")
        for _ in range(repeat):
            base = min(base, cpu_seconds(run, small))
            double = min(double, cpu_seconds(run, large))
        ratios.append(f"{base:.3f} s -> {double:.3f} s, x{double / max(base, 1e-9):.2f}")
        if double <= RATIO * max(base, 0.002):
            return
    pytest.fail(f"{len(small):,} -> {len(large):,} characters: " + "; then ".join(ratios))


def _notebook(cells) -> str:
    return json.dumps({"cells": cells, "metadata": {}, "nbformat": 4, "nbformat_minor": 5})


def _code(source: str) -> dict:
    return {"cell_type": "code", "metadata": {}, "source": source, "outputs": [], "execution_count": None}


def _markdown(source: str, tags=()) -> dict:
    return {"cell_type": "markdown", "metadata": {"tags": list(tags)}, "source": source}


FOLDER = "submissions/" + "a-student-s-long-folder-name/" * 5   # each place names it: ~160 characters


def _md_report(text: str):
    return read_report({FOLDER + "lab07_report.md": text.encode("utf-8", "surrogateescape")})


def _nb_reports(data: bytes):
    return read_report({FOLDER + "a/lab07.ipynb": data, FOLDER + "b/lab07.ipynb": data})


def _convert(text: str):
    return convert(text, "lab07_transformations.ipynb")


# ------------------------------------------------------------------ the shapes, at n and 2n
# (reader, shape, make(n), n, repeat); the larger size stays within the caps of a hand-in. The static
# readings of long defs take about 1 ms a statement: a few hundred show a quadratic reader's x4 already.
SHAPES = [
    ("report markdown", "one section repeated", lambda n: "## lab07.ex1\nsome text\n" * n, 20_000),
    ("report markdown", "marked sections, no end markers",
     lambda n: "<!-- explanation lab07.ex1 -->\nsome text\n" * n, 12_000),
    ("report markdown", "a line of spaces after a marker",
     lambda n: "## lab07.ex1\n<!-- explanation" + " " * n + "x\n## lab07.ex2\n_No figure" + " _" * n, 150_000),
    ("report notebook", "thousands of tagged cells (two notebooks)",
     lambda n: _notebook([_markdown(f"text {i}", ["report:lab07.ex1"]) for i in range(n)]).encode(), 3_000),
    ("report notebook", "one cell with thousands of tags",
     lambda n: _notebook([_markdown("text", [f"report:lab07.ex{i}" for i in range(n)])]).encode(), 12_000),
    ("notebook", "a line of spaces", lambda n: _notebook([_code(" " * n + "\n" + " " * n + "x?")]), 1_900_000),
    ("notebook", "one line of statements", lambda n: _notebook([_code("x=1;" * n)]), 1_000),
    ("notebook", "many cells", lambda n: _notebook([_code(f"a{i} = {i}") for i in range(n)]), 400),
    ("notebook", "blocks after names", lambda n: _notebook([_code(
        "".join(f"v{i} = {i}\n" for i in range(n)) + "".join(f"if v{i}:\n    w{i} = v{i}\n" for i in range(n)))]),
     300),
    ("static reading", "one line of statements", lambda n: "a;" * n, 5_000),
    ("static reading", "a // chain", lambda n: "def f(x):\n    return " + "//".join(["1"] * n) + "\n", 800),
    ("static reading", "a * chain", lambda n: "def f(x):\n    return " + "*".join(["x"] * n) + "\n", 800),
    ("static reading", "a lens model's radius taken again and again",
     lambda n: "def f(u, cx, k1):\n    x = u - cx / 1\n" + "    r2 = x * x + x * x\n" * n + "    return k1 * r2\n", 500),
    ("static reading", "writes through an index, many of them",
     lambda n: "def f(M):\n    d = [0, 1]\n" + "    M[0][1] = 1\n" * n + "    M[d][0] = 1\n", 500),
    ("static reading", "loops rebinding a parameter, many of them",
     lambda n: "def f(x, y):\n" + "    for x in y:\n        y = x\n" * n + "    return x\n", 500),
    ("static reading", "a fundamental matrix bound and given again and again",
     lambda n: "def f(a, K):\n" + "    F = fundamental_8point(a, a)\n    cv2.recoverPose(F, a, a, K)\n" * n, 250),
    ("static reading", "a loop variable assigned again and again",
     lambda n: "def f(xs, K):\n    for x, k in ((xs, K), (xs, K)):\n" + "        x = x @ k\n" * n, 400),
    ("static reading", "a chain of helpers",
     lambda n: "".join(f"def f{i}(x):\n    return f{i + 1}(x)\n" for i in range(n)), 200),
]
READERS = {"report markdown": _md_report, "report notebook": _nb_reports, "notebook": _convert,
           "static reading": reading.read_source}


@pytest.mark.parametrize("reader, shape, make, n", SHAPES, ids=[f"{r}: {s}" for r, s, *_ in SHAPES])
def test_reading_time_grows_linearly(reader, shape, make, n):
    assert_linear(READERS[reader], make, n)


def test_the_helpers_a_function_reaches_are_found_in_linear_time():
    def chain(n):
        return reading.Reading({f"f{i}": [] for i in range(n)}, {f"f{i}": {f"f{i + 1}"} for i in range(n)})
    assert_linear(lambda r: r.reachable("f0"), chain, 20_000)
    assert chain(5).reachable("f0") == ["f0", "f1", "f2", "f3", "f4"]


def test_cells_are_found_from_module_lines_in_linear_time():
    def many(n):
        converted = notebooks.ConvertedNotebook("", cells=[(3 * i + 2, i + 1, 2) for i in range(n)])
        return converted, "".join(f'File "lab07_transformations.py", line {3 * i + 2}\n' for i in range(n))

    def point(made):
        converted, text = made
        return notebooks.point_into_notebook(text, "lab07_transformations", "lab07.ipynb", converted)

    assert_linear(point, lambda n: many(n), 4_000)
    converted, text = many(3)
    assert point((converted, text)).splitlines()[2] == 'File "lab07.ipynb", cell 3, line 1'


# ------------------------------------------------------------------ bounds, with a note
def test_an_exercise_explained_in_thousands_of_places_is_bounded_and_said():
    data = _notebook([_markdown(f"text {i}", ["report:lab07.ex1"]) for i in range(MAX_PLACES + 50)]).encode()
    got = read_report({"lab07.ipynb": data})
    explanation = got.explanations["lab07.ex1"]
    assert explanation.text.count("text ") == MAX_PLACES and explanation.source.endswith("; and 50 more places")
    assert any(f"more than {MAX_PLACES} places" in p and f"cell {MAX_PLACES + 1}" in p for p in got.problems)


def test_more_sections_than_read_are_said_and_those_before_are_read():
    text = "".join(f"## lab07.ex{i}: T\nexplained {i}\n" for i in range(1, MAX_SECTIONS + 20))
    got = _md_report(text)
    assert len(got.explanations) == MAX_EXPLANATIONS   # the exercises' own bound comes first here
    assert any(f"more than {MAX_SECTIONS:,} explanation markers or headings" in p for p in got.problems)
    few = "".join(f"## lab07.ex1: T\nexplained {i}\n" for i in range(MAX_SECTIONS + 5))
    [explanation] = explanations_in_markdown(few, "r.md").values()
    assert explanation.text.startswith("explained 0\n\nexplained 1") and explanation.text.count("explained") == MAX_PLACES


def test_more_markdown_cells_than_read_are_said():
    data = _notebook([_markdown("nothing") for _ in range(MAX_REPORT_CELLS)]
                     + [_markdown("late", ["report:lab07.ex1"])]).encode()
    got = read_report({"lab07.ipynb": data})
    assert got.explanations == {}
    assert any(f"more than {MAX_REPORT_CELLS:,} Markdown cells" in p for p in got.problems)


def test_a_notebook_beyond_the_parse_bounds_is_taken_whole_with_a_note():
    source = "x = 1;" * (parsing.MAX_PARSE_STATEMENTS + 1)
    text = _notebook([_code("import numpy as np"), _code(source), _code("plt.show()"),
                      {**_code("secret()"), "metadata": {"tags": ["skip-grading"]}}])
    converted = _convert(text)
    assert converted.omissions == [] and "statements" in converted.whole
    assert "plt.show()" in converted.source.splitlines() and "# (not graded) secret()" in converted.source
    note = converted.left_out_note("lab07.ipynb")
    assert note.startswith("lab07.ipynb: holds more than") and "graded whole" in note and "skip-grading" in note


def test_too_much_code_for_static_reading_is_not_read_and_says_why():
    got = reading.read_source("a;" * parsing.MAX_PARSE_STATEMENTS)
    assert got.findings == {} and "statements" in got.note
    assert reading.read_source("def f(x):\n    return x // 2\n").note == ""


def test_one_line_of_statements_left_out_keeps_each_statement_once():
    line = "; ".join(f"print({i})" for i in range(2000)) + "; K = 3"
    converted = _convert(_notebook([_code(line)]))
    assert converted.source.splitlines()[1] == "; ".join(["pass"] * 2000) + "; K = 3"
    assert len(converted.omissions) == 2000 and converted.omissions[5].text == "print(5)"


@pytest.mark.parametrize("depth", [150, 5_000])
def test_deep_nesting_is_read_or_taken_whole_never_an_error(depth):
    nested = "x = " + "(" * depth + "1" + ")" * depth + "\n"
    listed = "y = " + "[" * depth + "]" * depth + "\n"
    chained = "z = 1" + " + 1" * depth * 2 + "\n"
    source = nested + listed + chained + "def f(a):\n    return a // 2\n"
    got = reading.read_source(source)
    if depth < 200:   # the parser's own bound on parentheses is 200
        assert [finding.function for finding in got.findings["f"]] == ["f"]
    else:
        assert got.findings == {}
    converted = _convert(_notebook([_code(source), _code("print(x)")]))
    assert "def f(a):" in converted.source.splitlines()   # kept (whole, or read), never an error
    deep_json = '{"cells": [' + "[" * depth + "]" * depth + "]}"
    assert read_report({"lab07.ipynb": deep_json.encode()}).explanations == {}
    with pytest.raises(NotebookError):
        convert('{"cells": ' + "[" * 200_000 + "]" * 200_000 + "}", "lab07.ipynb")


# ------------------------------------------------------------------ the IPython line check
_OLD_IPYTHON_LINE = re.compile(r"\s*[%!?]|\s*[\w., ]+=\s*[%!]|[^#'\"]*[\w)\]]\?\??\s*$")  # the regex it replaced
_LINE_PIECES = st.sampled_from([" ", "\t", "x", "é", "_", "1", ".", ",", "=", "%", "!", "?", "??", "#", "'", '"',
                                ")", "]", "(", "==", "a = ", "obj", "np.array", "\u00a0", "\u2003", "٣"])


@grading_settings(max_examples=400)
@given(st.lists(_LINE_PIECES, max_size=12).map("".join))
def test_the_ipython_line_check_is_the_regex_it_replaced(line):
    assert is_ipython_line(line) == bool(_OLD_IPYTHON_LINE.match(line))


@pytest.mark.parametrize("line, magic", [("%matplotlib inline", True), ("  !pip install x", True),
                                         ("files = !ls", True), ("a, b.c = %time f()", True), ("np.array?", True),
                                         ("f(x)??  ", True), ("x = 1", False), ("print('a?')", False),
                                         ("# why?", False), ("x == !y", False), ("a???", False), ("?", True),
                                         (" " * 50_000, False)])
def test_ipython_lines(line, magic):
    assert is_ipython_line(line) is magic


# ------------------------------------------------------------------ fuzzers
_MD_PIECES = st.sampled_from([
    "## ", "# ", "### ", "lab07.ex1", "LAB07.EX2", "lab09.ex3-extension", ": Title", "\n", "\r\n", " ", "\t",
    "<!-- explanation ", "<!-- end explanation -->", " -->", "```", "~~~", "![x](figures/a.png)", "_No figure_",
    "Automatic verdict: 1 / 2", report.PLACEHOLDER, "text", "\x1b[2J", "\u202e", "\udcff", "é", "<", ">"])


def _bounded(got: report.Report) -> None:
    assert len(got.explanations) <= MAX_EXPLANATIONS and len(got.problems) <= MAX_PROBLEMS + 1
    for exercise, explanation in got.explanations.items():
        assert report.exercise_id(exercise) == exercise
        assert 0 < len(explanation.text) <= MAX_EXPLANATION_CHARS
        assert explanation.source.count(";") <= MAX_PLACES


@grading_settings(max_examples=150)
@given(st.lists(_MD_PIECES, max_size=80).map("".join))
def test_fuzz_markdown_reports(text):
    _bounded(_md_report(text))


_JSON = st.recursive(st.none() | st.booleans() | st.integers() | st.text(max_size=20),
                     lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=8), inner, max_size=4),
                     max_leaves=12)
_CELL = st.fixed_dictionaries({"cell_type": st.sampled_from(["markdown", "code", "raw", 3])},
                              optional={"source": st.one_of(st.lists(_MD_PIECES, max_size=20).map("".join),
                                                            st.lists(st.lists(_MD_PIECES, max_size=5).map("".join),
                                                                     max_size=4), _JSON),
                                        "metadata": st.one_of(_JSON, st.fixed_dictionaries({"tags": st.lists(
                                            st.sampled_from(["report:lab07.ex1", "report:LAB07.EX2", "report:x",
                                                             "grade", "skip-grading", 7]), max_size=4)}))})
_NOTEBOOK = st.one_of(st.fixed_dictionaries({"cells": st.lists(_CELL, max_size=8)},
                                            optional={"metadata": _JSON}), _JSON)


@grading_settings(max_examples=60)
@given(_NOTEBOOK, st.booleans())
def test_fuzz_notebook_reports(notebook, broken):
    data = json.dumps(notebook).encode()
    _bounded(read_report({"lab07.ipynb": data[: len(data) // 2] if broken else data, "notes.md": b"## lab07.ex1\nx"}))


_CODE_PIECES = st.sampled_from([
    "x", "y = ", "1", "2.5", "np.array([1, 2])", "import numpy as np\n", "import seaborn\n", "def f(a):\n    ",
    "return a // 2\n", "class C:\n    ", "pass\n", "if x:\n    ", "for i in range(3):\n    ", "print(x)\n",
    "plt.show()\n", "%matplotlib inline\n", "!ls\n", "files = !ls\n", "x?\n", "%%bash\n", "; ", "\n", "    ",
    "(", ")", "[", "]", "lambda p: p", " + ", " @ ", "'s'", "#", "\\", "del x\n", "try:\n    ", "except:\n    "])


@pytest.mark.filterwarnings("ignore::SyntaxWarning")
@grading_settings(max_examples=150)
@given(st.lists(st.tuples(st.lists(_CODE_PIECES, max_size=25).map("".join),
                          st.sampled_from([[], ["grade"], ["skip-grading"], ["report:lab07.ex1"]])), max_size=6),
       st.booleans())
def test_fuzz_notebooks(cells, definitions_only):
    text = _notebook([{**_code(source), "metadata": {"tags": tags}} for source, tags in cells])
    try:
        converted = convert(text, "lab07.ipynb", definitions_only=definitions_only, importable=lambda m: m != "seaborn")
    except NotebookError:
        pytest.fail("a notebook of a few cells is readable")
    lines = converted.source.splitlines() if cells else []   # no cells: the module is "\n"
    assert len(lines) == sum(len(source.splitlines()) + 2 for source, _ in cells)
    for start, number, count in converted.cells:   # every cell line maps back to its cell
        assert all(converted.where(line)[0] == number for line in range(start, start + count))
    assert len(converted.omissions) <= sum(source.count("\n") + source.count(";") + 1 for source, _ in cells)
    assert all(len(o.text) <= 200 for o in converted.omissions)


@grading_settings(max_examples=100)
@given(st.one_of(_JSON.map(json.dumps), st.text(max_size=200)))
def test_fuzz_notebook_files_raise_only_notebook_errors(text):
    try:
        convert(text, "lab07.ipynb")
    except NotebookError as exc:
        assert "lab07.ipynb is not a readable notebook" in str(exc)


@pytest.mark.filterwarnings("ignore::SyntaxWarning")   # "1x": the parser's warning about the text
@grading_settings(max_examples=150)
@given(st.lists(_CODE_PIECES, max_size=60).map("".join))
def test_fuzz_static_reading(source):
    got = reading.read_source(source, api=frozenset({"f"}))
    assert set(got.calls) == set(got.findings)
    for name, findings in got.findings.items():
        assert all(f.function == name and f.line >= 0 for f in findings) and got.calls[name] <= set(got.findings)


# ------------------------------------------------------------------ the parse lock
# Files whose parses run in a process of their own, one thread: no lock is needed there.
SINGLE_THREADED = {"loading/parsing.py": "the lock's own module",
                   "engine/mutants/helper.py": "the mutants' helper process (python -m ...helper)"}


def test_every_parse_and_compile_in_the_package_goes_through_the_lock():
    """No ``ast.parse(...)`` nor ``compile(...)`` call in autograder/ but parsing.py's (and
    those of :data:`SINGLE_THREADED`)."""
    unlocked = []
    for path in PACKAGE.rglob("*.py"):
        if path.relative_to(PACKAGE).as_posix() in SINGLE_THREADED:
            continue
        tree = parsing.parse(path.read_text(encoding="utf-8"), str(path), max_chars=None, max_statements=None)
        for node in ast.walk(tree):
            if not isinstance(node, ast.Call):
                continue
            func = node.func
            bare_compile = isinstance(func, ast.Name) and func.id == "compile"
            ast_parse = (isinstance(func, ast.Attribute) and func.attr == "parse"
                         and isinstance(func.value, ast.Name) and func.value.id == "ast")
            if bare_compile or ast_parse:
                unlocked.append(f"{path.relative_to(PACKAGE.parent)}:{node.lineno}")
    assert unlocked == [], "parse through autograder.loading.parsing.parse / compile_source: " + ", ".join(unlocked)


@pytest.fixture
def lock_checked(monkeypatch):
    """``compile`` (which ``ast.parse`` calls) fails unless the parse lock is held; yields the calls seen."""
    calls, real = [], builtins.compile

    def checked(*args, **kwargs):
        calls.append(threading.current_thread().name)
        assert parsing.PARSE_LOCK._is_owned(), "compile/ast.parse without autograder.loading.parsing.PARSE_LOCK"
        return real(*args, **kwargs)

    monkeypatch.setattr(builtins, "compile", checked)
    return calls


def test_the_readers_parse_only_under_the_lock(lock_checked, tmp_path):
    from autograder.engine.stubs import stub_functions

    reading.read_source("def f(x):\n    return x // 2\n")
    _convert(_notebook([_code("import numpy as np\nK = np.eye(3)\nif K:\n    %time f()\nprint(K)")]))
    module = tmp_path / "m.py"
    module.write_text("def f():\n    raise NotImplementedError\n")
    assert stub_functions(module) == frozenset({"f"})
    assert len(lock_checked) >= 4
    with pytest.raises(AssertionError, match="PARSE_LOCK"):
        ast.parse("x = 1")   # the check itself can fail


class _Cycle:
    """Garbage whose finalizer lets another thread in: a collection inside one thread's AST
    construction is where another thread's parse could interleave with it."""

    def __init__(self):
        self.me = self

    def __del__(self):
        time.sleep(0)


def test_parsing_from_many_threads_never_raises_system_error():
    """Lanes read submissions in threads; unlocked, CPython 3.11's AST constructor shares one
    recursion counter between them (gh-106905). Threads are switched as often as they can
    be, and collections with finalizers happen during parses."""
    deep = "x = " + "(" * 90 + "1" + ")" * 90 + "\ny = " + "[" * 60 + "]" * 60 + "\n"
    source = deep + "def f(a):\n    return a // 2 + " + " + ".join(["a"] * 400) + "\n"
    nb = _notebook([_code(source), _code("%matplotlib inline\nimport numpy as np")])
    errors = []

    def work():
        try:
            for _ in range(4):
                for _ in range(100):
                    _Cycle()
                reading.read_source(source)
                _convert(nb)
                parsing.parse(deep * 5)
        except BaseException as exc:  # noqa: BLE001 - every failure is the test's
            errors.append(repr(exc))

    interval, thresholds = sys.getswitchinterval(), gc.get_threshold()
    sys.setswitchinterval(1e-6)
    gc.set_threshold(50)
    try:
        threads = [threading.Thread(target=work) for _ in range(6)]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
    finally:
        sys.setswitchinterval(interval)
        gc.set_threshold(*thresholds)
    assert errors == []


def test_too_large_text_is_refused_before_parsing(lock_checked):
    with pytest.raises(parsing.TooLarge, match="characters"):
        parsing.parse("x" * (parsing.MAX_PARSE_CHARS + 1))
    with pytest.raises(parsing.TooLarge, match="statements"):
        parsing.parse("a;" * parsing.MAX_PARSE_STATEMENTS)
    assert lock_checked == []   # refused without parsing
    assert isinstance(parsing.TooLarge("x"), ValueError)   # what every reader already catches


@pytest.mark.slow
def test_a_module_too_large_to_read_is_told_to_the_student(tmp_path):
    """The code is still graded (in the sandbox); only the grader's reading of it is skipped,
    and the grading's notes say why (no failure is explained from the code then)."""
    from autograder.engine.runner import grade
    from conftest import REFERENCE

    module = "lab07_transformations"
    folder = tmp_path / "submission"
    folder.mkdir()
    padding = "\n".join(f"_unused_{i} = {i}" for i in range(25_000))   # beyond the statement bound
    (folder / f"{module}.py").write_text((REFERENCE / f"{module}.py").read_text() + "\n" + padding + "\n")
    result = grade(folder, ["lab07.ex1"], pictures="none", include_hidden=False)
    assert result.exercises[0].score == result.exercises[0].max_score
    assert any(note.startswith(f"{module}.py: the code was not read") for note in result.notes), result.notes


def test_a_chain_of_operations_is_read_in_bounded_steps(monkeypatch):
    """`-a / b / b / ...` and `back[x] + back[x] + ...`: the negation reading (lab 12's hint) and the whole-number
    reading (integer arrays) each read a side once -- reading both sides twice per level was 2 ** length steps."""
    import ast

    from autograder.engine import hints
    from autograder.loading import reading

    calls = {"plain": 0, "integral": 0}
    plain, integral = hints._plain_negation, reading._integral_by_making

    def counted_plain(node):
        calls["plain"] += 1
        assert calls["plain"] < 1000, "the chain is read again at each level"
        return plain(node)

    def counted_integral(*args, **kwargs):
        calls["integral"] += 1
        assert calls["integral"] < 1000, "the chain is read again at each level"
        return integral(*args, **kwargs)
    monkeypatch.setattr(hints, "_plain_negation", counted_plain)
    monkeypatch.setattr(reading, "_integral_by_making", counted_integral)
    hints._negation(ast.parse("y = -a" + " / b" * 60).body[0].value)
    reading._integral_by_making(ast.parse("y = " + " + ".join(["back[x]"] * 60)).body[0].value, {"back": None})
    assert calls["plain"] <= 3 and calls["integral"] <= 2 * reading._INTEGRAL_DEPTH + 2, calls
