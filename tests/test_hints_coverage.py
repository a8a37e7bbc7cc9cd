"""Every fixed sentence of the labs' feedback that asks for code, or names an API, is held to the
student's code (issue 35: no hint contradicts the code).

The lab suites (``autograder/labs/labNN.py``, their hidden checks, and the candidate tables of
``fixtures/labNN.py`` whose keys are the mistakes' names) are read with :mod:`ast`. A string that
reads like an instruction (an imperative verb opening a clause: "use", "divide by", "transpose",
"call cv2.Y", "do not ...") or names code (``cv2.X``, ``np.X``, ``order=``, ``.reshape``) must be

- the text or ``instead`` of a :class:`~autograder.engine.hints.Hint` given ``asks=`` (or of a
  factory of such hints: ``nan_behind``), or of :func:`autograder.engine.claims.guard`;
- or marked :func:`~autograder.engine.claims.measured` (a measurement of the student's outputs,
  true of them whatever the code) or :func:`~autograder.engine.claims.from_code` (said only
  after reading the code);
- or, for a fixtures' mistake name, a text the lab module registers with ``guard``/``measured``.

Strings inside a predicate's own arguments (``expr("_ @ K.T")``) are code patterns, not feedback.
Labs another engineer is auditing are listed as pending: strict xfails, which fail once they pass.
"""

from __future__ import annotations

import ast
import importlib
import re
from pathlib import Path

import pytest

from autograder.engine import claims

ROOT = Path(__file__).resolve().parents[1]
LABS = ("lab07", "lab08", "lab09", "lab10", "lab11", "lab12")
PENDING: dict[str, str] = {}   # labs whose audit is under way (strict xfails)

VERBS = ("use|divide|multiply|transpose|reshape|negate|call|convert|take|keep|apply|pass|refine|choose|draw|"
         "build|flip|swap|normalise|normalize|undo|invert|add|subtract|solve|set|enforce|compute|give|return|"
         "work|scale|round|clip|stack|index|treat|check|make|leave|drop|remove|replace|warp|shift|sort|fill|"
         "project|triangulate|match|filter|estimate|decompose|zero|fix|read|write|copy|rotate|compare|look|mask|"
         "start|stop|put|loop|iterate|cast|store|select|pick|average|blend|sum|count|weight|append|ravel|"
         "flatten|concatenate|ensure|avoid|replace|try|do not|don't|never")
# An imperative verb opening a clause (not followed by "(" or "=": a call or keyword in code).
IMPERATIVE = re.compile(rf"(?:^|[:;(]\s*|\bthen\s+|\bor\s+|\band\s+|\.\s+)({VERBS})\b(?!s\b)(?!\s*[(=])", re.I)
CODE = re.compile(r"\b(?:cv2|np)\.\w+|\border\s*=|\bfull_matrices\b|\.reshape\b|\.T\b|\bastype\b")
CALL_SHOWN = re.compile(r"^[\w.]+\(.*\)$")   # "pinhole_project(np.array([1, 1, 2]), f=1)": the call judged

# Calls whose string arguments are held to the code, marked, or code patterns.
HELD = {"Hint", "guard", "nan_behind", "checklist", "look_at"}
MARKED = {"measured", "from_code"}
PATTERNS = {"expr", "calls", "calls_any", "mentions", "keyword", "saying", "divides_by", "matmul_of",
            "passes_product", "passes_argument", "uses_attr", "reshapes", "Predicate"}
NAMES = {"check", "exercise", "advice", "forbid", "hidden_check"}   # a check's or exercise's title


def _called(node) -> str:
    func = node.func
    return func.attr if isinstance(func, ast.Attribute) else func.id if isinstance(func, ast.Name) else ""


def _text(node) -> str | None:
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value
    if isinstance(node, ast.JoinedStr):
        return "".join(v.value if isinstance(v, ast.Constant) else "{}" for v in node.values)
    return None


def asks_code(text: str) -> bool:
    """Whether ``text`` reads like an instruction or names code."""
    return " " in text.strip() and bool(IMPERATIVE.search(text) or CODE.search(text)) \
        and not CALL_SHOWN.match(text)


def unheld(path: Path) -> list[tuple[int, str]]:
    """(line, text) of the strings of ``path`` that ask for code and are not held to it."""
    tree = ast.parse(path.read_text())
    parents = {child: node for node in ast.walk(tree) for child in ast.iter_child_nodes(node)}
    docstrings = {id(n.body[0].value) for n in ast.walk(tree)
                  if isinstance(n, (ast.Module, ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef))
                  and n.body and isinstance(n.body[0], ast.Expr)}

    def held(node) -> bool:
        while node in parents:
            node, child = parents[node], node
            if isinstance(node, ast.Call):
                name = _called(node)
                if name in MARKED or name in PATTERNS:
                    return True
                if name in HELD and (name in ("nan_behind", "checklist", "look_at") or any(k.arg == "asks" for k in node.keywords)
                                     or (name == "guard" and len(node.args) >= 2)):
                    return True
                if name in NAMES and child in node.args[:1]:
                    return True
        return False

    found = []
    for node in ast.walk(tree):
        if isinstance(parents.get(node), ast.JoinedStr) or id(node) in docstrings:
            continue
        text = _text(node)
        if text is None or not asks_code(text) or held(node):
            continue
        if text in claims.GUARDED or text in claims.MEASURED:
            continue
        found.append((node.lineno, text))
    return found


def lab_files(lab: str) -> list[Path]:
    return [path for path in (ROOT / "autograder" / "labs" / f"{lab}.py", ROOT / "autograder" / "labs" / "hidden"
                              / f"{lab}.py", ROOT / "fixtures" / f"{lab}.py") if path.exists()]


@pytest.mark.parametrize("lab", [pytest.param(lab, marks=pytest.mark.xfail(strict=True, reason=PENDING[lab]))
                                 if lab in PENDING else lab for lab in LABS])
def test_every_sentence_asking_for_code_is_held_to_the_code(lab):
    importlib.import_module(f"autograder.labs.{lab}")   # registers its guarded and measured sentences
    importlib.import_module(f"autograder.labs.hidden.{lab}")
    problems = [f"{path.relative_to(ROOT)}:{line}: {text!r}" for path in lab_files(lab) for line, text in unheld(path)]
    assert not problems, "sentences asking for code without a Hint/guard or a measured() mark:\n" + "\n".join(problems)


@pytest.mark.parametrize("text, asks", [
    ("multiply P by -1 first, then decompose", True),
    ("the null vector f was reshaped column by column (order='F')", True),
    ("K[2, 2] is 3, not 1: K is not normalised; divide K by K[2, 2]", True),
    ("do not divide by w", True),
    ("refine corners with cv2.cornerSubPix", True),
    ("the rotation goes the opposite way", False),
    ("rank 2 was not enforced", False),
    ("pinhole_project(np.array([1, 1, 2]), f=1)", False),
])
def test_the_reading_of_an_instruction(text, asks):
    assert asks_code(text) is asks


def test_an_unguarded_instruction_is_found_and_a_held_one_is_not(tmp_path):
    module = tmp_path / "lab99.py"
    module.write_text(
        'def check(t):\n'
        '    t.fail("wrong: use np.linalg.svd", hint="divide by w")\n'
        '    t.fail("wrong", hint=Hint("divide by w", asks=calls("np.divide")).said(t))\n'
        '    t.fail("wrong", hint=Hint("transpose it"))\n'
        '    t.fail(measured("the lines stop short: draw them across the image"))\n')
    assert [line for line, _ in unheld(module)] == [2, 2, 4]


# "check that A, and that B" in a Hint's text or instead, or a guard's: one predicate for the whole
# list, so an item the code already does is said all the same. Such lists are checklist()s, each item
# with the code that does it. Labs still being converted are strict xfails (they fail once they pass).
LISTS = re.compile(r"check (?:that|what|whether|which)\b.*\band that\b", re.S)
PENDING_LISTS: dict[str, str] = {}   # labs whose lists are being converted (issue 35): none left


def listed(path: Path) -> list[tuple[int, str]]:
    """(line, text) of the Hint/guard sentences of ``path`` that list several things to check."""
    found = []
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Call) and _called(node) in ("Hint", "guard"):
            for argument in [*node.args, *(k.value for k in node.keywords if k.arg in ("text", "instead"))]:
                text = _text(argument)
                if text is not None and LISTS.search(text):
                    found.append((argument.lineno, text))
    return found


@pytest.mark.parametrize("lab", [pytest.param(lab, marks=pytest.mark.xfail(strict=True, reason=PENDING_LISTS[lab]))
                                 if lab in PENDING_LISTS else lab for lab in LABS])
def test_lists_of_things_to_check_hold_each_item_to_the_code(lab):
    problems = [f"{path.relative_to(ROOT)}:{line}: {text!r}" for path in lab_files(lab) for line, text in listed(path)]
    assert not problems, "lists of things to check under one predicate (write them as claims.checklist):\n" + \
        "\n".join(problems)
