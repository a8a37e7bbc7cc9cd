"""Sentences of the labs' feedback that ask for code, or say what the code does, held to the code.

A lab's feedback is made of three kinds of sentence (issue 35, "no hint contradicts the code"):

- **measurements** of the student's outputs ("the lines are right but not scaled so that
  a^2 + b^2 = 1", "returned 12 rows for 14 frames"): true of the student by construction.
  When such a sentence also reads like an instruction or names an API, it is marked with
  :func:`measured` -- an identity function that documents the judgement and lets
  ``tests/test_hints_coverage.py`` tell it from an unguarded instruction (:func:`from_code` marks a
  sentence a check says only after reading the code to do what it names);
- **hints in a check's code**: a :class:`~autograder.engine.hints.Hint` (text, the code it asks
  for, what to say instead), said with ``.said(t)`` where the check builds its message;
- **diagnoses** -- a mistake's name, from the fixtures' candidate tables or a lab's own sentences
  -- that tell the student to do X, or claim the code does Y: registered with :func:`guard`
  (the same predicate and ``instead`` as a Hint). Every failed or partial check's message and
  hint go through :func:`rewritten` (run by :func:`autograder.engine.runner.run_check`), which
  replaces each registered sentence found in them by what its Hint says for this student's
  code: the sentence itself, or its ``instead``.

The predicates are :mod:`autograder.engine.hints`' and the code-reading ones below, which read
the student's module with :mod:`ast`, never executing it:

- :func:`divides_by` -- a division (``a / b``, ``a /= b``, ``np.divide(a, b)``) whose divisor has a
  pattern's shape, directly or through a name assigned it (``w = X[:, 2]; X / w``);
- :func:`negates_on_negative_det` -- a value negated under a test of a determinant's sign
  (``if np.linalg.det(M) < 0: P = -P``), or multiplied by ``np.sign(np.linalg.det(...))``; with an
  argument's position, only that parameter (or a converted copy of it) negated;
- :func:`reshapes` -- a reshape to a given shape in a given order (``f.reshape(3, 3)``: row by
  row; ``order="F"``: column by column);
- :func:`passes_argument` -- a call given an argument at a position or as a keyword, not ``None``
  (``cv2.projectPoints(obj, rvec, tvec, K, dist)``);
- :func:`passes_parameters` -- a call given, at given positions, the function's own parameters as
  they came (``cv2.stereoRectify(K1, d, K2, d, size, np.asarray(R), T.reshape(3, 1))``);
- :func:`takes_last_row_of_vt` -- the last row of an SVD's ``Vt`` (``np.linalg.svd(A)[2][-1]``,
  ``Vt[-1]`` for a ``Vt`` unpacked from an ``svd`` call);
- :func:`zeroes_an_entry` -- an entry of an array set to 0 (``S[2] = 0``, ``s[-1] = 0``) or a
  diagonal built with a literal 0 (``np.diag([s[0], s[1], 0])``).
"""

from __future__ import annotations

import ast
import re
import sys
from dataclasses import replace
from typing import Callable, Iterable

from ..loading.parsing import parse, walk
from .hints import Hint, Predicate, _path, _same, code_of, functions_read, values_bound

# text -> its Hint (or Checklist), for every diagnosis registered with guard() or checklist(); texts marked measured()
GUARDED: dict[str, "Hint | Checklist"] = {}
MEASURED: set[str] = set()


READ_IN_CODE: set[str] = set()   # names said only after reading the code (from_code), made while a module loads


def _remember(text: str, read: bool = False) -> None:
    """Keep a mark made while a module loads (a table's sentence, which the coverage tests then
    find wherever it is used); a mark made in a check holds the student's figures and is never
    said again: kept, a long batch would grow the set without end. Literals written inside
    measured(...)/from_code(...) are recognised by the coverage tests where they stand."""
    if sys._getframe(2).f_code.co_name == "<module>":
        MEASURED.add(text)
        if read:
            READ_IN_CODE.add(text)


def measured(text: str) -> str:
    """``text``, marked as a measurement of the student's outputs: true of every student who
    gets it, whatever their code (the shape returned, a count, an answer matching a mistake's
    on the failing input and a probe). Returns ``text`` unchanged."""
    _remember(text)
    return text


def from_code(text: str) -> str:
    """``text``, marked as said only where the check has read the student's code to do what it
    says (``calls("cv2.getOptimalNewCameraMatrix").found(...)`` before naming it). Returns ``text``."""
    _remember(text, read=True)
    return text


GUESSED: set[str] = set()


def guessed(name: str) -> str:
    """``name``, a mistake's name a check infers about the student's code from what it measured (a
    default too weak for the cost's scale), where other code would measure the same: a change of their
    code confirmed on the check's own inputs (:mod:`autograder.engine.mutants.repair`) that mends the
    failure elsewhere takes its place. Names of what the output shows (the rotation goes the other way)
    stay beside such a change. Returns ``name``."""
    GUESSED.add(name)
    return name


LOOK_FOR: set[str] = set()   # advice on where to look, said beside a measurement where nothing better is known


def where_to_look(text: str) -> str:
    """``text``, a check's advice on where the cause of what it measured usually is ("look for a pixel added or
    lost on the way: a border added and not taken back, ..."): the usual places, none of them read in the
    student's code. Said where nothing better is known; taken out where a change of the student's own code
    is confirmed (:func:`without_where_to_look`): the change says where, and the usual places would send the
    student elsewhere. A fixed sentence (the set stays as small as the labs' code). Returns ``text``."""
    LOOK_FOR.add(text)
    return text


def without_where_to_look(sentence: str) -> str:
    """``sentence`` without the advice :func:`where_to_look` registered."""
    for text in LOOK_FOR:
        if text in sentence:
            sentence = " ".join(sentence.replace(text, " ").split())
            sentence = re.sub(r" ([.,;:])", r"\1", sentence)   # (the advice taken from before a full stop)
    return sentence


def without_guessed_cause(sentence: str, mistake, inferred: bool = False) -> str:
    """``sentence`` without its clause "it looks like <mistake>..." (up to the clause's full stop), the
    punctuation mended; ``sentence`` itself where it holds no such clause. Only a name registered as
    :func:`guessed`, or (``inferred``) any name the check inferred from what the answers look like."""
    if not isinstance(mistake, str) or not (inferred or mistake in GUESSED):
        return sentence
    match = re.search(r"(?:[,;:]?\s*(?:but|so)?\s*)?\bit looks like " + re.escape(mistake) + r"[^.]*", sentence,
                      flags=re.IGNORECASE)
    if match is None:
        return sentence
    kept = (sentence[:match.start()].rstrip(" ,;:") + sentence[match.end():]).strip()
    return kept if kept.endswith((".", "!", "?")) else kept + "."


def guard(text: str, asks: Predicate, instead: str | None = None, functions: tuple = ()) -> str:
    """Register the diagnosis ``text``: wherever a failed check's message or hint holds it, it is
    said only when the student's code does not already do what ``asks`` reads (else ``instead``;
    see :class:`~autograder.engine.hints.Hint`). Returns ``text`` (a plain ``str``: a mistake's
    name stays a dictionary key and a ``mistake=`` label)."""
    if not text:
        raise ValueError("guard: an empty sentence")
    known = GUARDED.get(text)
    if known is not None and known.asks != asks:
        raise ValueError(f"guard: {text!r} is registered twice with different predicates")
    GUARDED[text] = Hint(text, asks=asks, instead=instead, functions=tuple(functions))
    return text


EVIDENCED: dict[str, Predicate] = {}   # a mistake's name -> the code that does that mistake, where visible
ONLY_WHERE_SEEN: set[str] = set()      # names said only where their code is seen


def evidenced(text: str, does: Predicate, only_where_seen: bool = False) -> str:
    """Register what in the student's code shows the mistake ``text`` is theirs (``does``): where
    several mistakes give the same answer and are named together ("A; or, the same answer here, B"),
    the ones whose code is seen are said alone (:func:`seen_in_code`). ``only_where_seen``: the name is
    a reading of one written form (`reshape(3, 3, order='F')`), never said of code that does not show
    it (beside the others, it would tell code reshaping row by row that it reshapes column by column).
    Returns ``text``."""
    known = EVIDENCED.get(text)
    if known is not None and known != does:
        raise ValueError(f"evidenced: {text!r} is registered twice with different predicates")
    EVIDENCED[text] = does
    if only_where_seen:
        ONLY_WHERE_SEEN.add(text)
    return text


def seen_in_code(t, names: list) -> list:
    """Of mistakes that give the same answer, those whose code the student's functions (the check's)
    visibly do; all of them (but those said only where seen) when none is seen, or when the code cannot
    be read."""
    code = code_of(t)
    if len(names) < 2 or not code.functions:
        return names
    read = code.reachable(functions_read(t))
    seen = [name for name in names if name in EVIDENCED and EVIDENCED[name].found(read)]
    return seen or [name for name in names if name not in ONLY_WHERE_SEEN] or names


class LookAt:
    """What a :func:`checklist` points to when none of its items is left: "look at A, and at B", each
    pointer said only where the student's code does not visibly do that step already (a pointer to a
    step the code does sends the student the wrong way, as an item would); ``otherwise`` (a sentence
    naming no step, or nothing) when the code does them all."""

    def __init__(self, pointers: tuple, otherwise: str = ""):
        if not pointers or any(not isinstance(done, Predicate) for _, done in pointers):
            raise ValueError("look_at: every pointer needs the predicate of the code that does its step")
        self.pointers, self.otherwise = pointers, otherwise
        self.text = self._joined([text for text, _ in pointers])

    def _joined(self, texts: list) -> str:
        return "look at " + ", and at ".join(texts) if texts else self.otherwise

    def told(self, read) -> str:
        return self._joined([text for text, done in self.pointers if not done.holds(read)])


def look_at(*pointers: tuple[str, Predicate], otherwise: str = "") -> LookAt:
    """A checklist's ``none_left`` made of pointers, each (what to look at, the code that already does
    that step): "look at which image each map is applied to" is left out for code that visibly warps
    img_l by H1 and img_r by H2. Predicates lean towards "the code does it" where they cannot tell."""
    return LookAt(tuple(pointers), otherwise)


class Checklist:
    """Things to check, each said only where the student's code does not visibly do it already
    (:func:`checklist`): "check that A, and that B" becomes "check that B" for code doing A, and
    ``none_left`` for code doing both (a :class:`LookAt`'s pointers themselves held to the code)."""

    def __init__(self, lead: str, items: tuple, none_left, functions: tuple):
        self.lead, self.items, self.none_left, self.functions = lead, items, none_left, functions
        self.text = _listed(lead, [text for text, _ in items], self._pointer(None))

    def _pointer(self, read) -> str:
        if isinstance(self.none_left, LookAt):
            return self.none_left.text if read is None else self.none_left.told(read)
        return self.none_left

    def said(self, t) -> str:
        code = code_of(t)
        return self.told(code, self.functions or functions_read(t)) if code.functions else self.text

    def told(self, code, functions) -> str:
        """What is said for ``code``'s ``functions`` (and the helpers they call)."""
        if not code.functions:   # nothing to read: every item is said
            return self.text
        read = code.reachable(functions)
        left = [text for text, done in self.items if not done.holds(read)]
        return _listed(self.lead, left, "" if left else self._pointer(read))


def _listed(lead: str, items: list, none_left: str) -> str:
    if not items:
        said = f"{lead}{none_left}".strip()
        # a lead with nothing after it ("your code already calls X:") loses its colon
        return said if none_left else said.rstrip(" :;,")
    return f"{lead}check that {', and that '.join(items)}"


def checklist(lead: str, *items: tuple[str, Predicate], none_left: "str | LookAt" = "the error is elsewhere",
              functions: tuple = ()) -> str:
    """Register a list of things to check: ``lead`` ("your code already calls X: ") then "check that
    A, and that B" of the ``items`` -- (what to check, the code that does it) -- whose code the
    student's functions (those the check calls, or ``functions``) do not already hold; ``none_left``
    after ``lead`` when they hold every one: a sentence naming no step, or :func:`look_at`'s pointers,
    each held to the code as the items are. An item the code does is a hint that contradicts it
    (issue 35); an item no predicate can read is no item (write it as a measurement, or leave it
    out). Returns the full text (a ``str``, said as it is without code to read), registered as
    :func:`guard`'s sentences are: wherever a failed check's message or hint holds it, it is replaced."""
    if not items or any(not isinstance(done, Predicate) for _, done in items):
        raise ValueError("checklist: every item needs the predicate of the code that does it")
    made = Checklist(lead, tuple(items), none_left, tuple(functions))
    GUARDED[made.text] = made
    return made.text


def _replaced(text: str, sentence: str, by: str) -> str:
    """``text`` with ``sentence`` replaced by ``by``; where ``by`` is empty, the separator written before
    it goes too ("your code calls X; " + nothing -> "your code calls X.")."""
    if by:
        return text.replace(sentence, by)
    while sentence in text:
        before, _, after = text.partition(sentence)
        stripped = before.rstrip(" :;,")
        if stripped and (stripped != before.rstrip() or not after.strip()):
            ended = after.lstrip().startswith((".", ")")) or stripped.endswith((".", "!", "?"))
            before = stripped + ("" if ended else ".")
        text = before + after
    return text


def said(t, text: str) -> str:
    """``text`` with every registered diagnosis in it replaced by what it says for ``t``'s code."""
    if not text:
        return text
    for sentence in sorted((s for s in GUARDED if s in text), key=len, reverse=True):
        if sentence in text:   # a longer sentence replaced first may hold a shorter one
            text = _replaced(text, sentence, GUARDED[sentence].said(t))
    return text


def rewritten(verdict, t):
    """``verdict`` (a :class:`~autograder.engine.checks.Verdict`) with its message and hint
    :func:`said` for ``t``'s code. The mistake's label is kept where it is true of the code (class
    reports count it); a label the code contradicts (a guarded diagnosis the code already does
    the opposite of) is dropped: instructors read labels in the overview and the review app too."""
    message, hint = said(t, str(verdict.message)), said(t, str(verdict.hint))
    mistake = verdict.mistake
    # (kept where what replaces it still says it first: a cause the code shows, added to the name; or says its first
    # part, one of the causes it lists left out as not the code's)
    if isinstance(mistake, str) and mistake:
        told = said(t, mistake)
        if not (told.startswith(mistake) or (len(told) >= 40 and mistake.startswith(told))):
            mistake = ""
    if message == verdict.message and hint == verdict.hint and mistake == verdict.mistake:
        return verdict
    return replace(verdict, message=message, hint=hint, mistake=mistake)


# ------------------------------------------------------------------ predicates
def _pattern(text: str) -> ast.AST:
    return parse(text, mode="eval", max_chars=None, max_statements=None).body


def _assigned_names(function, test) -> set[str]:
    """Names the function assigns a value ``test`` holds for (``w = X[:, 2]``)."""
    return {target.id for node in walk(function) if isinstance(node, ast.Assign) and test(node.value)
            for target in node.targets if isinstance(target, ast.Name)}


def divides_by(*patterns: str, says: str = "") -> Predicate:
    """A division whose divisor has one of ``patterns``' shapes (``"_[:, 2]"``, ``"_[2, 2]"``;
    ``_`` matches anything), written there or held by a name the function assigns it to."""
    wanted = [_pattern(p) for p in patterns]

    def shaped(node) -> bool:
        return any(_same(node, p) for p in wanted)

    def test(function) -> bool:
        held = _assigned_names(function, shaped)

        def divisor(node) -> bool:
            node = _axis_added_to(node)
            return shaped(node) or (isinstance(node, ast.Name) and node.id in held)
        for node in walk(function):
            if isinstance(node, (ast.BinOp, ast.AugAssign)) and isinstance(node.op, (ast.Div, ast.FloorDiv)):
                if divisor(node.right if isinstance(node, ast.BinOp) else node.value):
                    return True
            elif isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] in ("divide", "true_divide") \
                    and len(node.args) >= 2 and divisor(node.args[1]):
                return True
        return False
    return Predicate(says or "divides by " + " or ".join(p.replace("_", "...") for p in patterns), test)


def _axis_added_to(node):
    """The name an axis is added to (`w[:, None]`, `w[..., np.newaxis]`, `w.reshape(-1, 1)`: the same values,
    made a column to divide rows by), else ``node``."""
    if isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name) and isinstance(node.slice, ast.Tuple) \
            and len(node.slice.elts) == 2 and any(_new_axis(e) for e in node.slice.elts) \
            and any(isinstance(e, ast.Slice) and e.lower is e.upper is e.step is None
                    or isinstance(e, ast.Constant) and e.value is Ellipsis for e in node.slice.elts):
        return node.value
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "reshape" \
            and isinstance(node.func.value, ast.Name) and [ast.unparse(a) for a in node.args] == ["-1", "1"]:
        return node.func.value
    return node


def _new_axis(node) -> bool:
    return (isinstance(node, ast.Constant) and node.value is None) or _path(node) in ("np.newaxis", "numpy.newaxis")


# The third (last) coordinate of points, however indexed: X[:, 2], X[2], X[..., 2:], X[:, -1:], ...
THIRD_COORDINATE = divides_by("_[:, 2]", "_[2]", "_[..., 2]", "_[:, 2:]", "_[:, 2:3]", "_[..., 2:]",
                              "_[:, 2, None]", "_[:, [2]]", "_[:, -1]", "_[-1]", "_[..., -1]", "_[:, -1:]",
                              "_[..., -1:]", "_[:, -1, None]", "_[2, :]", "_[-1, :]", "_[:, 2][:, None]",
                              "_[:, -1][:, None]", "_[:, 2].reshape(-1, 1)", "_[:, 2:3].copy()",
                              says="divides by a third coordinate")


def _is_det(node) -> bool:
    return isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] == "det"


def _det_sign_test(node, held: set) -> bool:
    """``np.linalg.det(M) < 0`` (or ``> 0``, ``0 > det``, a name ``held`` assigned a determinant)."""
    # (an ordering: `det(R) == -1` tests an exact value a determinant in floating point rarely is -- no sign test)
    return isinstance(node, ast.Compare) and all(isinstance(op, (ast.Lt, ast.Gt, ast.LtE, ast.GtE)) for op in node.ops) \
        and any(_is_det(part) or isinstance(part, ast.Name) and (part.id in held or "det" in part.id.lower())
                for part in [node.left, *node.comparators])


def _negates(statement) -> bool:
    """``x = -x``, ``x = -1 * x``, ``x = x * -1``, ``x *= -1``, ``x = np.negative(x)``, ``x, y = -x, -y``."""
    minus_one = _pattern("-1")
    if isinstance(statement, ast.AugAssign) and isinstance(statement.op, ast.Mult):
        return _same(statement.value, minus_one) or _same(statement.value, _pattern("-1.0"))
    if isinstance(statement, ast.Assign):
        value = statement.value
        if isinstance(value, ast.UnaryOp) and isinstance(value.op, ast.USub):
            return True
        if isinstance(value, ast.Tuple) and value.elts and all(   # `M, p4 = -M, -p4`
                isinstance(item, ast.UnaryOp) and isinstance(item.op, ast.USub) for item in value.elts):
            return True
        if isinstance(value, ast.BinOp) and isinstance(value.op, ast.Mult):
            return any(isinstance(side, ast.UnaryOp) and isinstance(side.op, ast.USub)
                       and isinstance(side.operand, ast.Constant) for side in (value.left, value.right))
        if isinstance(value, ast.Call) and _path(value.func).rsplit(".", 1)[-1] == "negative":
            return True
    return False


def _argument_names(function, index: int) -> set[str]:
    """The names holding the function's parameter at ``index``: the parameter and the names bound
    to a conversion or copy of one of them (``P = np.asarray(P, float)``, ``M = P.copy()``), or to a
    part of one (``M = P[:, :3]``: negating the block is negating P where the block is decomposed)."""
    parameters = function.args.posonlyargs + function.args.args
    if index >= len(parameters):
        return set()
    names = {parameters[index].arg}

    def holds(value) -> bool:
        if isinstance(value, ast.Name):
            return value.id in names
        if isinstance(value, ast.Subscript):
            return holds(value.value)
        if isinstance(value, ast.Call):
            name = _path(value.func).rsplit(".", 1)[-1]
            if name in ("asarray", "array", "asanyarray", "copy", "astype", "float64", "float32"):
                subject = value.func.value if isinstance(value.func, ast.Attribute) and name in (
                    "copy", "astype") else (value.args[0] if value.args else None)
                return holds(subject) if subject is not None else False
        return False
    # in the order written: a copy is made after what it copies (two passes for a loop's order;
    # never a pass per name: a chain of copies stays linear)
    assignments = [node for node in walk(function) if isinstance(node, ast.Assign)]
    assignments.sort(key=lambda node: (node.lineno, node.col_offset))
    for _ in range(2):
        for node in assignments:
            if holds(node.value):
                names.update(t.id for t in node.targets if isinstance(t, ast.Name))
    return names


def _bound_names(statement) -> set[str]:
    """The plain names an assignment binds (``P = ...``, ``P *= -1``, ``M, p = ...``)."""
    targets = statement.targets if isinstance(statement, ast.Assign) else [statement.target] if isinstance(
        statement, ast.AugAssign) else []
    return {n.id for t in targets for n in (t.elts if isinstance(t, ast.Tuple) else [t]) if isinstance(n, ast.Name)}


def negates_on_negative_det(argument: int | None = None, says: str = "") -> Predicate:
    """A value negated in a branch that tests a determinant's sign, or multiplied by the sign
    of a determinant (``np.sign(np.linalg.det(M)) * P``). With ``argument``, only a negation of
    the function's parameter at that position (or a converted copy of it, see
    :func:`_argument_names`): ``P = -P`` counts for ``decompose_camera_matrix(P)``, ``K = -K`` not."""
    sign_of_det = _pattern("np.sign(np.linalg.det(_))")

    def test(function) -> bool:
        held = _assigned_names(function, _is_det)
        aimed_at = None if argument is None else _argument_names(function, argument)

        def aimed(statement) -> bool:
            return aimed_at is None or bool(_bound_names(statement) & aimed_at)
        for node in walk(function):
            if isinstance(node, ast.If) and _det_sign_test(node.test, held):
                if any(_negates(s) and aimed(s) for branch in (node.body, node.orelse) for s in branch
                       for s in walk(s)):
                    return True
            # with an argument, only a value assigned to it counts; without, any expression
            value = node.value if isinstance(node, ast.Assign) and aimed(node) else node if aimed_at is None else None
            if isinstance(value, ast.IfExp) and _det_sign_test(value.test, held) and any(
                    isinstance(b, ast.UnaryOp) and isinstance(b.op, ast.USub) for b in (value.body, value.orelse)):
                return True
            if isinstance(value, ast.BinOp) and isinstance(value.op, ast.Mult) and any(
                    _same(side, sign_of_det) for side in (value.left, value.right)):
                return True
        return False
    return Predicate(says or "negates a matrix when a determinant is negative", test)


def reshapes(*shape: int, order: str = "C") -> Predicate:
    """A reshape to ``shape`` (``x.reshape(3, 3)``, ``x.reshape((3, 3))``, ``np.reshape(x, (3, 3))``)
    in ``order``: "C" (row by row, the default: no ``order`` or ``order="C"``) or "F"."""
    def dims(args) -> tuple | None:
        if len(args) == 1 and isinstance(args[0], (ast.Tuple, ast.List)):
            args = args[0].elts
        if all(isinstance(a, ast.Constant) and isinstance(a.value, int) for a in args):
            return tuple(a.value for a in args)
        return None

    def test(function) -> bool:
        for node in walk(function):
            if not (isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] == "reshape"):
                continue
            method = isinstance(node.func, ast.Attribute) and _path(node.func.value) not in ("np", "numpy")
            if dims(node.args if method else node.args[1:2]) != shape:
                continue
            given = next((k.value for k in node.keywords if k.arg == "order"), None)
            if not method and given is None and len(node.args) > 2:
                given = node.args[2]
            written = given.value if isinstance(given, ast.Constant) else "C" if given is None else None
            if written == order:
                return True
        return False
    where = "row by row" if order == "C" else "column by column (order='F')"
    return Predicate(f"reshapes to {shape[0]} x {shape[1]} {where}", test)


def passes_argument(function: str, position: int, name: str, says: str = "") -> Predicate:
    """A call of ``function`` (matched by its last name: ``"cv2.projectPoints"``, ``projectPoints``
    imported) given an argument at ``position`` or as the keyword ``name``, other than ``None``
    (``cv2.projectPoints(obj, rvec, tvec, K, dist)``, ``distCoeffs=dist``)."""
    last = function.rsplit(".", 1)[-1]

    def given(node) -> bool:
        return not (isinstance(node, ast.Constant) and node.value is None)

    def test(function_node) -> bool:
        for node in walk(function_node):
            if isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] == last:
                if len(node.args) > position and given(node.args[position]):
                    return True
                if any(k.arg == name and given(k.value) for k in node.keywords):
                    return True
        return False
    return Predicate(says or f"passes {name} to {function}", test)


_WRAPPERS = {"np.asarray", "np.array", "np.float64", "np.float32", "numpy.asarray", "numpy.array"}


def passes_parameters(function: str, positions: dict[int, str], says: str = "") -> Predicate:
    """A call of ``function`` given, at each of ``positions``, the enclosing function's own parameter
    of that name as it came (``cv2.stereoRectify(K1, d, K2, d, size, R, T)``): the name itself, read
    directly or through a conversion (``np.asarray(R, np.float64)``, ``T.reshape(3, 1)``), or a local
    assigned once from such a reading."""
    last = function.rsplit(".", 1)[-1]

    def test(function_node) -> bool:
        parameters = {a.arg for a in function_node.args.args + function_node.args.kwonlyargs}
        assigned = values_bound(function_node)

        def reads(node, name: str, depth: int = 0, converted: bool = False) -> bool:
            """Whether ``node`` is the parameter ``name`` as it came (``converted``: inside a conversion
            of it, where the name is the parameter as given, `K1 = np.asarray(K1)`)."""
            if depth > 4:
                return False
            if isinstance(node, ast.Name):
                values = assigned.get(node.id, [])
                if node.id == name and name in parameters:   # unchanged, or only converted in place
                    return converted or all(value is not None and reads(value, name, depth + 1, True)
                                            for value in values)
                return len(values) == 1 and values[0] is not None and reads(values[0], name, depth + 1)
            if isinstance(node, ast.Call) and node.args and _path(node.func) in _WRAPPERS:
                return reads(node.args[0], name, depth + 1, converted)
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) \
                    and node.func.attr in ("reshape", "astype", "copy", "ravel", "flatten"):
                return reads(node.func.value, name, depth + 1, converted)
            return False

        return any(isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] == last
                   and all(len(node.args) > position and reads(node.args[position], name)
                           for position, name in positions.items())
                   for node in walk(function_node))
    return Predicate(says or f"gives {function} its own {', '.join(positions.values())}", test)


def zeroes_an_entry() -> Predicate:
    """An array entry set to 0 (``S[2] = 0``, ``s[-1] = 0.0``) or a diagonal written with a 0
    (``np.diag([s[0], s[1], 0])``, ``np.diag((1, 1, 0))``)."""
    def zero(node) -> bool:
        return isinstance(node, ast.Constant) and node.value == 0 and not isinstance(node.value, bool)

    def one_value(index) -> bool:
        # `s[2]`, `s[-1]`, or a diagonal's `S[2, 2]`: not a row or a column (`Fn[2, :] = 0` is no rank 2)
        if isinstance(index, ast.Tuple):
            return len(index.elts) == 2 and not any(isinstance(e, ast.Slice) for e in index.elts) \
                and ast.dump(index.elts[0]) == ast.dump(index.elts[1])
        return not isinstance(index, ast.Slice)

    def test(function) -> bool:
        for node in walk(function):
            if isinstance(node, ast.Assign) and zero(node.value) and any(
                    isinstance(target, ast.Subscript) and one_value(target.slice) for target in node.targets):
                return True
            if isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] == "diag" and node.args \
                    and isinstance(node.args[0], (ast.List, ast.Tuple)) and any(zero(e) for e in node.args[0].elts):
                return True
        return False
    return Predicate("sets a singular value to 0", test)


def _is_svd(node) -> bool:
    return isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] == "svd"


def _minus_one(index) -> bool:
    return isinstance(index, ast.UnaryOp) and isinstance(index.op, ast.USub) \
        and isinstance(index.operand, ast.Constant) and index.operand.value == 1


def _whole(index) -> bool:
    return isinstance(index, ast.Slice) and index.lower is index.upper is index.step is None


def _vt_indexed(taken: Callable, says: str) -> Predicate:
    """An index of an SVD's V^T that ``taken`` reads (its slice), for a ``Vt`` unpacked from (or indexed out
    of) an ``svd`` call: ``np.linalg.svd(A)[2][...]``, ``Vt[...]``."""
    def vt(node, held) -> bool:
        if isinstance(node, ast.Name):
            return node.id in held
        return isinstance(node, ast.Subscript) and _is_svd(node.value) and isinstance(node.slice, ast.Constant) \
            and node.slice.value == 2

    def test(function) -> bool:
        held = {target.elts[2].id for node in walk(function) if isinstance(node, ast.Assign) and _is_svd(node.value)
                for target in node.targets if isinstance(target, ast.Tuple) and len(target.elts) == 3
                and isinstance(target.elts[2], ast.Name)}
        held |= _assigned_names(function, lambda value: vt(value, set()))
        return any(isinstance(node, ast.Subscript) and vt(node.value, held) and taken(node.slice)
                   for node in walk(function))
    return Predicate(says, test)


def takes_last_row_of_vt() -> Predicate:
    """The last row of an SVD's V^T taken: ``np.linalg.svd(A)[2][-1]``, ``Vt[-1]`` or ``Vt[-1, :]``
    for a ``Vt`` unpacked from (or indexed out of) an ``svd`` call."""
    def last_row(index) -> bool:
        if isinstance(index, ast.Tuple) and index.elts:
            index, rest = index.elts[0], index.elts[1:]
            if not all(_whole(e) for e in rest):
                return False
        return _minus_one(index)
    return _vt_indexed(last_row, "takes the last row of Vt")


def takes_last_column_of_vt() -> Predicate:
    """The last column of an SVD's V^T taken (``Vt[:, -1]``, ``np.linalg.svd(A)[2][:, -1]``): numpy returns V
    transposed, so the right singular vectors are its rows; the column's entries belong to different vectors,
    each of a sign of its own (no number to compare with: only the code shows it)."""
    def last_column(index) -> bool:
        return isinstance(index, ast.Tuple) and len(index.elts) == 2 and _whole(index.elts[0]) \
            and _minus_one(index.elts[1])
    return _vt_indexed(last_column, "takes the last column of Vt")


THRESHOLD_NAMES = ("threshold", "thresh", "thr", "tol", "max_error", "reproj_threshold", "ransac_threshold")


def compares_a_distance_with(names: Iterable[str] = THRESHOLD_NAMES, says: str = "") -> Predicate:
    """A comparison (``<``, ``<=``, ``>``, ``>=``) of a threshold -- a name in ``names`` or starting
    with "thresh" -- with a value computed through a square root (``np.sqrt``, ``np.linalg.norm``,
    ``np.hypot``, ``** 0.5``): followed through the names the function assigns and into the module's
    functions it calls (``errors = _transfer_errors(H, src, dst); errors < threshold``). A square
    root elsewhere in the code (a normalisation's scale) does not count."""
    names = frozenset(names)

    def is_threshold(node) -> bool:
        return any(isinstance(n, ast.Name) and (n.id in names or n.id.startswith("thresh")) for n in walk(node))

    def rooted_in(function, defs, returns_rooted) -> Callable:
        """``rooted(node)`` for ``function``: whether a value is computed through a square root.
        Each name the function assigns, and each module function it calls, is expanded once
        (remembered; a name being expanded counts as not rooted), so the reading stays linear in
        the code's size whatever chains of names a submission writes. A module function's value is
        read from its returns only: its arguments are its inputs (a homography from normalised
        points is not a distance because the normalisation took a square root)."""
        assigned: dict[str, list] = {}
        for statement in walk(function):
            if isinstance(statement, ast.Assign):
                for target in statement.targets:
                    for name in walk(target):
                        if isinstance(name, ast.Name):
                            assigned.setdefault(name.id, []).append(statement.value)
        known: dict[str, bool] = {}

        def rooted(node) -> bool:
            todo = [node]
            while todo:
                part = todo.pop()
                if isinstance(part, ast.Call):
                    called = _path(part.func).rsplit(".", 1)[-1]
                    if called in ("sqrt", "norm", "hypot"):
                        return True
                    if called in defs and defs[called] is not function:
                        if returns_rooted(called):
                            return True
                        continue
                if isinstance(part, ast.BinOp) and isinstance(part.op, ast.Pow) and _same(part.right, _pattern("0.5")):
                    return True
                if isinstance(part, ast.Name) and part.id in assigned:
                    if part.id not in known:
                        known[part.id] = False   # in progress: a cycle adds nothing
                        known[part.id] = any(rooted(value) for value in assigned[part.id])
                    if known[part.id]:
                        return True
                todo.extend(ast.iter_child_nodes(part))
            return False
        return rooted

    def test(functions) -> bool:
        functions = list(functions)
        defs = {f.name: f for f in functions if isinstance(f, (ast.FunctionDef, ast.AsyncFunctionDef))}
        for function in functions:   # (a def inside one: its value is its returns, as a module function's --
            for node in walk(function):   # `errors(H) < threshold` is no distance for H's normalisation)
                if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and node is not function:
                    defs.setdefault(node.name, node)
        readers, returned = {}, {}

        def reader(function):
            if id(function) not in readers:
                readers[id(function)] = rooted_in(function, defs, returns_rooted)
            return readers[id(function)]

        def returns_rooted(name) -> bool:
            if name not in returned:
                returned[name] = False   # in progress: recursion adds nothing
                function = defs[name]
                returned[name] = any(reader(function)(r.value) for r in walk(function)
                                     if isinstance(r, ast.Return) and r.value is not None)
            return returned[name]
        for function in functions:
            rooted = reader(function)
            for node in walk(function):
                if not (isinstance(node, ast.Compare) and all(
                        isinstance(op, (ast.Lt, ast.LtE, ast.Gt, ast.GtE)) for op in node.ops)):
                    continue
                sides = [node.left, *node.comparators]
                if any(is_threshold(side) for side in sides) and any(
                        rooted(side) for side in sides if not is_threshold(side)):
                    return True
        return False
    return Predicate(says or "compares a distance (a square root) with the threshold", test, kind="all")


def calls_any(*names: str, says: str = "") -> Predicate:
    """A call of any of ``names`` (:func:`~autograder.engine.hints.calls`), saying ``says``."""
    from .hints import calls

    found = calls(names[0])
    for name in names[1:]:
        found = found | calls(name)
    return found.saying(says) if says else found


def assigns(*names: str, says: str = "") -> Predicate:
    """A value stored in one of ``names`` (``ratio = 0.8``, ``ratio *= 2``, ``for ratio in ...``): with ``~``,
    a parameter the code never overwrites."""
    def test(function) -> bool:
        for node in walk(function):
            targets = node.targets if isinstance(node, ast.Assign) else \
                [node.target] if isinstance(node, (ast.AugAssign, ast.AnnAssign, ast.For, ast.comprehension)) else []
            if any(isinstance(n, ast.Name) and n.id in names for target in targets for n in walk(target)):
                return True
        return False
    return Predicate(says or f"assigns {' or '.join(names)}", test)


def treats_each_of(first: int = 0, second: int = 1, says: str = "") -> Predicate:
    """One function called on each of two parameters apart (``hartley(src)`` and ``hartley(dst)``,
    ``np.mean(pts1, 0)`` and ``np.mean(pts2, 0)``), or a loop over both (``for pts in (src, dst)``): each
    of the two is given its own (normalising) transform. Read in the function whose parameters they are."""
    def test(function) -> bool:
        parameters = [a.arg for a in function.args.posonlyargs + function.args.args]
        if len(parameters) <= max(first, second):
            return False
        pair = {parameters[first], parameters[second]}
        given: dict[str, set] = {}
        for node in walk(function):
            if isinstance(node, (ast.For, ast.comprehension)) and isinstance(node.iter, (ast.Tuple, ast.List)) \
                    and pair <= {n.id for n in walk(node.iter) if isinstance(n, ast.Name)}:
                return True
            if isinstance(node, ast.Call) and _path(node.func):
                held = {n.id for a in node.args for n in walk(a) if isinstance(n, ast.Name)} & pair
                if len(held) == 1:   # a call given both (build(src, dst)) is no transform of each
                    given.setdefault(_path(node.func), set()).update(held)
        return any(held == pair for held in given.values())
    return Predicate(says or "treats each point set apart", test)


def returns_from(made: Predicate, says: str = "") -> Predicate:
    """A ``return`` holding a value ``made`` reads (``made`` tested on the expression: a division, a product
    with ``np.diag``), written there or stored in a name on the way (``F = U @ np.diag(s) @ Vt; F = T2.T @ F @ T1;
    return F``; ``lines /= norm; return lines``)."""
    def test(function) -> bool:
        held: set[str] = set()
        for _ in range(4):   # names from names, a few steps
            for node in walk(function):
                if isinstance(node, (ast.Assign, ast.AugAssign, ast.AnnAssign)) and node.value is not None:
                    source = node if isinstance(node, ast.AugAssign) else node.value
                    if made.holds([source]) or any(isinstance(n, ast.Name) and n.id in held
                                                   for n in walk(node.value)):
                        targets = node.targets if isinstance(node, ast.Assign) else [node.target]
                        held |= {n.id for target in targets for n in walk(target) if isinstance(n, ast.Name)}
        return any(isinstance(node, ast.Return) and node.value is not None
                   and (made.holds([node.value]) or any(isinstance(n, ast.Name) and n.id in held
                                                        for n in walk(node.value)))
                   for node in walk(function))
    return Predicate(says or f"returns what {made.says}", test)


DIVISION = Predicate("divides", lambda node: any(
    isinstance(n, (ast.BinOp, ast.AugAssign)) and isinstance(n.op, ast.Div)
    or (isinstance(n, ast.Call) and _path(n.func).rsplit(".", 1)[-1] == "divide") for n in walk(node)))


def registered(texts: Iterable[str]) -> list[str]:
    """Of ``texts``, those neither :func:`guard`-ed nor :func:`measured`."""
    return [text for text in texts if text not in GUARDED and text not in MEASURED]


def _is_mean(node) -> bool:
    return isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] in ("mean", "average")


def subtracts_a_mean(says: str = "") -> Predicate:
    """A centroid subtracted: ``pts - pts.mean(axis=0)``, ``x - c[0]`` or ``-s * c[0]`` (a translation's entry) for
    a ``c`` assigned a mean, directly or through one name; read leniently (any mean subtracted or negated)."""
    def test(function) -> bool:
        means = _assigned_names(function, lambda value: any(_is_mean(n) for n in walk(value)))

        def meanish(node) -> bool:
            return any(_is_mean(n) or (isinstance(n, ast.Name) and n.id in means) for n in walk(node))
        for node in walk(function):
            if isinstance(node, (ast.BinOp, ast.AugAssign)) and isinstance(node.op, ast.Sub) \
                    and meanish(node.right if isinstance(node, ast.BinOp) else node.value):
                return True
            if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub) and meanish(node.operand):
                return True
            if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult) and any(
                    isinstance(side, ast.UnaryOp) and isinstance(side.op, ast.USub) for side in (node.left, node.right)) \
                    and meanish(node):
                return True
        return False
    return Predicate(says or "subtracts the centroid", test)


def wherever_written(says: str, test: Callable) -> Predicate:
    """A predicate over the functions read together: ``test(function)`` is True (the step done), False (done
    otherwise than asked) or None (not written in that function); it holds unless a function writes the step
    otherwise than asked (leaning towards "done" where nothing is written: a helper without the step, or code
    this reading cannot follow)."""
    def over(functions) -> bool:
        return all(found for found in (test(f) for f in functions) if found is not None)
    return Predicate(says, over, kind="all")
