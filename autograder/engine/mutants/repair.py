"""Naming a failure by repairing the student's own code: one small change that makes it right.

The error model (:mod:`.naming`) explains a student's answers by a mutant of the reference. When
the student's code is built otherwise -- other steps, other names, a helper of their own -- no
mutant of the reference gives their answers, even when their mistake is one slip. Here the same
operators (:mod:`.operators`) change the *student's* function instead (and the module functions it
runs), one change at a time, and each variant is called in a companion sandbox
(:meth:`~autograder.sandbox.supervisor.Sandbox.companion`: the student's code never runs in the
grader's process, and a variant that hangs costs the student's own worker nothing) on the inputs
where their answers were wrong. A change is told only when the variant gives the reference's
answers there, on the trial's other calls of that function, and on confirmation inputs derived
from the failing ones. The sentence shows the student's own code before and after the change
("changing `std_l * std_l` to `std_l * std_r` (line 23) makes `ncc_disparity` give the expected
answers on all 9 inputs tried"), never the reference's.

When no single change mends the answers, pairs are tried (one slip made at two places first).
What it cannot name: a step that is missing (beyond a few insertions: an inversion, a division by
the last coordinate, a conversion to radians), more than two slips, a mistake in another graded
function (told as inherited), and a function whose right answers are random (RANSAC with its own
samples). Time is bounded per failed check, and per grading together with the error model's
naming (:data:`.naming.GRADING_SECONDS`).
"""

from __future__ import annotations

import ast
import difflib
import functools
import hashlib
import itertools
import os
import re
import threading
from collections import Counter, OrderedDict
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from ...loading.parsing import copy_tree, parse, walk
from ...loading.reading import MAX_SOURCE_BYTES
from ...sandbox.supervisor import array_bytes
from ..checks import Trial, Verdict, fingerprint
from ..hints import RANDOM_DRAWS, SIZE_ARGUMENTS
from ..inherited import SHARED_FAILING
from . import anchors, naming
from .aligned import aligned_mutants
from .helper import HelperFailed
from .operators import (DRAWING_COLOUR_AT, OPERATORS, _MAKE, _MOVES, _defs, _derived_names, _dotted, _entry_of_literal, _parents, _replace, mutants_of,
                        mutated_defs, runs, twin_names, unpacked_items)

CHECK_SECONDS = 3.0       # the repairs' time for one failed check (the grading's is the error model's)
CALLS_PER_FUNCTION = 6    # the trial's last calls of the function that are compared
VARIANTS = 4              # confirmation inputs derived from the failing calls
VARIANT_TIMEOUT = 1.0     # seconds for one variant on its inputs (one request), at least
MISTAKE = "repair:"       # + the operator: a mistake named by a change of the student's code
_SHOWN = 70               # the longest code shown before and after a change
# The operators' reading is not linear in a function's size (each name against every local before
# it): a module larger than a few times the largest lab's (3.4k nodes) is not changed at all, and a
# function running a def larger than three times the largest measured in students' and course code
# (628 nodes; 1,080 lines of one def took 29 s to read, the grader's own time, before any clock could
# stop it) has no changes tried, so reading it never outlasts the time the repairs are given.
MAX_NODES = 15_000
MAX_DEF_NODES = 2_000
_EXCHANGES = {"swap_operands", "swap_args", "stack_order"}   # operators that exchange two things
_IN_WORDS = _MOVES | {"grey", "guard", "branch", "keep_parameter", "add_step"}   # changes told in words (their code would be too long to show)


@dataclass(frozen=True)
class Fix:
    """One change (or two, one slip made twice) of the student's code that makes a function right.

    changes : ``((line, before, after), ...)``: each changed line of the student's module, the code
        there and the same code changed (``ast.unparse`` forms).
    where : the ``def`` changed (the graded function or a module function it runs).
    operator : the operator that made the (first) change.
    edits : the change, as :func:`.operators.apply_edits` takes it.
    skips : ``(line, name, source, module names)`` where the change reads ``source`` in the place of
        ``name``, which ``line`` computes from ``source`` (:meth:`_Student.skipped_step`): the answers come
        right by skipping that step, so the step is where to look; ``()`` otherwise.
    """

    changes: tuple
    where: str
    operator: str
    edits: tuple
    skips: tuple = ()
    needed: bool = False   # a centring taken out that a right solution makes too (see _Variants.repair)
    why: str = ""          # why the change mends, where its code says it (" (numpy's svd returns V transposed ...)")

    @property
    def size(self) -> int:
        """How many characters the change adds and removes (a statement removed: its own; two
        things exchanged, however long: as a few characters, one slip)."""
        if all(edit[2] in _EXCHANGES for edit in self.edits) or self.operator in _IN_WORDS:
            return 3 * len(self.edits)   # (a statement moved, however long: one slip)
        changed = [(before, "" if after == "pass" else after) for _, before, after in self.changes]
        kept = sum(sum(block.size for block in difflib.SequenceMatcher(None, before, after, autojunk=False)
                       .get_matching_blocks()) for before, after in changed)
        return sum(len(before) + len(after) for before, after in changed) - 2 * kept

    @property
    def written(self) -> int:
        """How long the changed code is: of two changes of one size, the shorter result is the slip
        undone (`len(frames)`), the longer one compensates for it (`len(frames) - 1 + 1`)."""
        return sum(len(after) for _, _, after in self.changes)

    def told(self, function: str) -> str:
        inside = "" if self.where == function else f", in `{self.where}`"
        if self.operator in _IN_WORDS:   # (told in words: see _Student._moved)
            return self.changes[0][2].replace("{inside}", inside)
        merged = _nested_merged(self.changes)
        # (one change made alike on several lines -- `size` to `(width, height)` in both warps -- told once)
        lines_of: dict = {}
        for line, before, after in merged:
            lines_of.setdefault((before, after), []).append(line)
        if all(len(set(lines)) == len(lines) for lines in lines_of.values()):   # (twice on one line: told twice)
            merged = [(lines[0], before, after) for (before, after), lines in lines_of.items()]
        else:
            lines_of = {(before, after): [line] for line, before, after in merged}
        at = {(before, after): (f"line {lines[0]}" if len(lines) == 1 else
                                f"lines {', '.join(map(str, lines[:-1]))} and {lines[-1]}")
              for (before, after), lines in lines_of.items()}
        # (a block taken out whole is shown by its first line, `if test: ...`, and told by its lines)
        blocks = [_BLOCK_SHOWN.match(before) if after == "pass" else None for _, before, after in merged]
        said = [f"`{block[1]}` (lines {block[2]}{inside})" if block else
                f"`{before}`" + ("" if after == "pass" else f" to `{after}`") + f" ({at[before, after]}{inside})"
                for (line, before, after), block in zip(merged, blocks)]
        verbs = ["removing " if after == "pass" else "changing " for _, _, after in merged]
        # (one verb for changes of one kind; each its own where a step is taken out and a line changed)
        told = verbs[0] + " and ".join(said) if len(set(verbs)) == 1 else \
            " and ".join(verb + part for verb, part in zip(verbs, said))
        told += self.why
        if self.skips:
            line, name, source, constants = self.skips
            reads = " and ".join(f"`{c}`" for c in constants)
            told += (f", which skips the step of line {line} that computes `{name}` from `{source}`"
                     + (f" (and reads {reads}, defined outside the function)" if reads else "") + ",")
        return told

    @property
    def likely(self) -> str:
        """Where the mistake likely is, after a sentence telling this change alone."""
        if self.skips:
            return f"so the mistake is likely in that step (line {self.skips[0]}), or the step does not belong there"
        if self.needed:
            return "but a right solution centres there too: the mistake is more likely where the centring is undone"
        return "so the mistake is likely there"


_BLOCK_SHOWN = re.compile(r"^(.*: \.\.\.) \(lines (\d+-\d+)\)$")


def _drawn_otherwise(values, students) -> bool:
    """Whether a change's answers are colour images (uint8, 3 channels) the student's own answers are
    too, shaped alike, and differ from them: a drawing redrawn."""
    return bool(values) and all(
        isinstance(v, np.ndarray) and isinstance(s, np.ndarray) and v.dtype == s.dtype == np.uint8
        and v.ndim == 3 and v.shape == s.shape and not np.array_equal(v, s) for v, s in zip(values, students))


def _nested_merged(changes) -> tuple:
    """Two changes of one line, one inside the code the other shows (`homographies[1:]` in
    `zip(images[1:], homographies[1:])`), shown as one change of the outer code with both made: told
    apart, the outer one shows the inner one's code unchanged."""
    if len(changes) != 2 or changes[0][0] != changes[1][0] or "pass" in (changes[0][2], changes[1][2]):
        return changes
    for (line, inner, inner_after), (_, outer, outer_after) in (changes, changes[::-1]):
        if inner != outer and outer.count(inner) == 1 and outer_after.count(inner) == 1:
            return ((line, outer, outer_after.replace(inner, inner_after)),)
    return changes


@dataclass(frozen=True)
class Repair:
    """The confirmed fixes of a graded function: each makes its answers right on ``inputs`` inputs
    (the failing ones, the trial's other calls, confirmation inputs). Several when several places
    can be changed to the same effect (a swapped call, or the result transposed later): one of them
    is the mistake."""

    function: str
    fixes: tuple
    inputs: int
    complete: bool = True   # every single change was tried (else another place might mend it too)
    checked: str = ""       # judged by the failed check itself: confirmed by its "checks" or answers "nearer"

    @property
    def mistake(self) -> str:
        return MISTAKE + self.fixes[0].operator

    @property
    def sentence(self) -> str:
        head = HEAD
        said = f"the expected answers on all {self.inputs} inputs tried"
        makes = f"makes `{self.function}` give {said}"
        if self.checked:   # (the student's own recipe, or a function with many right answers)
            makes = f"makes `{self.function}` pass this check, " + (
                "and the grading's other checks of it" if self.checked == "checks" else
                f"and its answers on the {self.inputs} inputs tried are no farther from the expected ones")
        # (two operators may make the same change: it is told once)
        told = list(dict.fromkeys(fix.told(self.function) for fix in self.fixes))
        if len(told) == 1:
            return f"{head}: {told[0]} {makes}, " \
                   + (self.fixes[0].likely if self.complete
                      else "so the mistake may be there (other changes were not all tried in the time)")
        listed = "; ".join(told)
        return f"{head}: each of these {makes}, so the mistake is likely at one " \
               f"of them: {listed}"


# ------------------------------------------------------------------ the student's code
def _live(fn) -> set[str]:
    """The local names whose values reach what ``fn`` returns (flow-insensitive: a name is live when a
    return, a condition, or the value of an assignment to a live name reads it; a method call on a
    live name, `rows.append(...)`, reads its arguments into it)."""
    live: set[str] = set()
    reads = lambda node: {n.id for n in walk(node) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}  # noqa: E731
    flows = []   # (the names a statement sets, the names it reads)
    for node in walk(fn):
        if isinstance(node, ast.Return) and node.value is not None:
            live |= reads(node.value)
        elif isinstance(node, (ast.If, ast.While)):
            live |= reads(node.test)
        elif isinstance(node, (ast.Assign, ast.AugAssign, ast.AnnAssign)) and node.value is not None:
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            flows.append(({n.id for t in targets for n in walk(t) if isinstance(n, ast.Name)},
                          reads(node.value) | {n.id for t in targets for n in walk(t) if isinstance(n, ast.Name)
                                               and isinstance(n.ctx, ast.Load)}))
        elif isinstance(node, ast.For):
            flows.append(({n.id for n in walk(node.target) if isinstance(n, ast.Name)}, reads(node.iter)))
        elif isinstance(node, ast.Expr) and isinstance(node.value, ast.Call) \
                and isinstance(node.value.func, ast.Attribute) and isinstance(node.value.func.value, ast.Name):
            flows.append(({node.value.func.value.id}, reads(node.value)))
    grown = True
    while grown:
        grown = False
        for sets, read in flows:
            if sets & live and not read <= live:
                live |= read
                grown = True
    return live


def _left_out(fn) -> tuple[set, set]:
    """The names whose values ``fn`` computes and never uses (`x_norm = T @ ...`, no read of x_norm),
    and the names and helpers those values read (T, _normalising_transform through `T = ...(x)`)."""
    loaded = {n.id for n in walk(fn) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}
    assignments = [node for node in walk(fn) if isinstance(node, ast.Assign) and len(node.targets) == 1
                   and isinstance(node.targets[0], ast.Name)]
    left = {a.targets[0].id for a in assignments if a.targets[0].id not in loaded and not isinstance(a.value, ast.Constant)
            and not a.targets[0].id.startswith("_")}
    feeding = {n.id for a in assignments if a.targets[0].id in left
               for n in walk(a.value) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}
    # A step made of one call's results unpacked (`n1, T1 = normalise(p1)`): the unused result is left out,
    # its siblings are the same step's (T1 is n1's transform: dropping T1 downstream works round n1 unused).
    for a in walk(fn):
        if isinstance(a, ast.Assign) and len(a.targets) == 1 and isinstance(a.targets[0], (ast.Tuple, ast.List)) \
                and all(isinstance(e, ast.Name) for e in a.targets[0].elts) and isinstance(a.value, ast.Call):
            names = [e.id for e in a.targets[0].elts]
            unused = {n for n in names if n not in loaded and not n.startswith("_")}
            if unused and len(unused) < len(names):
                left |= unused
                feeding |= set(names) - unused
                feeding |= {n.id for n in walk(a.value) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}
    helpers = {_dotted_call(c) for a in assignments if a.targets[0].id in feeding | left
               for c in walk(a.value) if isinstance(c, ast.Call)}
    return left, feeding | helpers


def _own_results(fn, own: frozenset) -> set[str]:
    """The names ``fn`` assigns from a call of the student's own defs (the module's, or one nested in
    ``fn``): `U = _normalising_transform(X)`, `T1, T2 = conditioner(a), conditioner(b)`."""
    own = own | {n.name for n in walk(fn) if isinstance(n, ast.FunctionDef) and n is not fn}
    results = set()
    for node in walk(fn):
        if isinstance(node, ast.Assign) and any(isinstance(c, ast.Call) and isinstance(c.func, ast.Name)
                                                and c.func.id in own for c in walk(node.value)):
            results |= {n.id for t in node.targets for n in walk(t) if isinstance(n, ast.Name)}
    return results


def _disconnects(before, after, helpers_changed=frozenset(), own=frozenset()) -> bool:
    """Whether a change (``after``: the def ``before`` changed; ``helpers_changed``: the other defs it
    changes) works around a step the student left out: ``before`` computes a value it never uses
    (`x_norm`, the rows built from `x`), the change leaves it unused, and either takes out of what the
    function returns a name that value reads (`inv(T) @ P` -> `P`: T then reaches nothing) or changes a
    helper that computes one (T made the identity). The answers come right; the step is still missing.
    So does a change after which a parameter the function used no longer reaches its answers, or a
    value it computed with a def of the student's own (``own``: the module's defs), an image it drew on
    (:func:`_drawn_on`: `return out` -> `return canvas` throws away the circles drawn on `out`), or a size it
    computed for a value whose size it goes on to read (:func:`_size_step_emptied`)."""
    # A parameter whose value reached the answers and no longer does: the change makes the caller's
    # argument irrelevant (a penalty `s` replaced by `block_size`, which happens to suit the inputs).
    # A helper of the student's whose result no longer does: the student wrote it for that step, and
    # the change throws the step away (`inv(T) @ P @ U` -> `inv(T) @ P` where the points were never
    # normalised by U; the raw points in the rows where the cameras were never conditioned).
    parameters = {a.arg for a in (*before.args.posonlyargs, *before.args.args, *before.args.kwonlyargs)}
    dropped = _live(before) - _live(after)
    if dropped & (parameters | _own_results(before, frozenset(own)) | _drawn_on(before)) \
            or _size_step_emptied(before, dropped):
        return True
    left, feeding = _left_out(before)
    if not left:
        return False
    if left & {n.id for n in walk(after) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}:
        return False   # (the change puts the value to use: the step taken up)
    if feeding & set(helpers_changed):
        return True
    assigned = {n.id for n in walk(before) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)}
    return bool((feeding & assigned & _live(before)) - _live(after))


# (NumPy's float types and dtype names; not the builtin float() of one number, whose fix is no image's dtype)
_FLOAT_DTYPES = {"np.float32", "np.float64", "numpy.float32", "numpy.float64", "np.double", "np.single", "float",
                 "'float32'", "'float64'", "'float'", "cv2.CV_32F", "cv2.CV_64F"}
_FLOAT_MAKERS = _FLOAT_DTYPES - {"float", "'float32'", "'float64'", "'float'", "cv2.CV_32F", "cv2.CV_64F"}
# (why a conversion mends: told where the step added makes float arrays -- uint8 images subtracted, squared, averaged)
_FLOAT_WHY = (" (it makes the arrays float: arithmetic on uint8 images wraps around, 10 - 20 gives 246, and "
              "rounds every result to a whole number)")


# (the subscripted value is an expression, never a statement's text: `h = Vt` is no base)
_COLUMN_TO_ROW = re.compile(r"(?P<base>[^=]+?)\[\s*:\s*,\s*(?P<i>-?\d+)\s*\]")
_ROW = re.compile(r"(?P<base>[^=]+?)\[\s*(?P<i>-?\d+)\s*(?:,\s*:\s*)?\]")


_AXIS = re.compile(r"\baxis\s*=\s*(-?\d+)")


def _why_it_mends(shown, fn) -> str:
    """Why a change between a column and a row mends, in NumPy's terms, when it is one: of np.linalg.svd's
    answer, its third output is V transposed (a singular vector is a row of it), its first U (a vector is a
    column); of any other array, `a[i]` is its row i and `a[:, i]` its column i; a reduction's axis=0 gives one
    value per column, axis=1 one per row. "" for any other change."""
    if fn is None or len(shown) != 1 or shown[0] is None:
        return ""
    _, before, after = shown[0]
    before, after = _changed_subscripts(before, after) or (before, after)
    for column, row, factor in ((before, after, "Vt"), (after, before, "U")):
        c, r = _COLUMN_TO_ROW.fullmatch(column), _ROW.fullmatch(row)
        if c and r and c["base"] == r["base"] and c["i"] == r["i"]:
            made = _svd_output(c["base"], fn)
            if made == factor:
                return (" (numpy's svd returns V transposed: a singular vector of V is a row of its third output)"
                        if factor == "Vt" else " (a singular vector of U is a column of it, U[:, k])")
            if not made and len(c["base"]) <= 40:
                return f" (`{c['base']}[{c['i']}]` is row {c['i']} of `{c['base']}`, `{c['base']}[:, {c['i']}]` its column)"
    opencv = _opencv_order_why(shown[0][1], shown[0][2], fn)
    if opencv:
        return opencv
    axes = [_AXIS.findall(text) for text in (before, after)]
    if len(axes[0]) == len(axes[1]) == 1 and {axes[0][0], axes[1][0]} == {"0", "1"} \
            and _AXIS.sub("", before) == _AXIS.sub("", after):
        return " (along axis=0 a 2-D array gives one value per column, along axis=1 one per row)"
    return ""


# (what an OpenCV call reads a pair of numbers as, where a change reversing or swapping the pair mends)
_PATTERN_CALLS = {"findChessboardCorners", "findChessboardCornersSB", "drawChessboardCorners", "findCirclesGrid"}


def _opencv_order_why(before: str, after: str, fn) -> str:
    """Why a change that reverses a pair (`[::-1]` taken out or put in, two items exchanged) mends, where the pair
    is what an OpenCV call of ``fn`` reads as a size (width, height) or a board's pattern (columns, rows); ""
    otherwise. A whole statement shown (`h, w = image.shape[:2]` for `w, h = ...`, `size = (w, h)` for
    `size = (h, w)`): the pair its names make, or the name it binds, is what the call reads."""
    b, a = _parsed(before, ("eval",)), _parsed(after, ("eval",))
    if b is not None and a is not None:
        return _opencv_reader(fn, lambda arg: ast.unparse(arg) == before) if _reverses(b.body, a.body) else ""
    b, a = _parsed(before, ("exec",)), _parsed(after, ("exec",))
    if b is None or a is None or len(b.body) != 1 or len(a.body) != 1 \
            or not all(isinstance(s, ast.Assign) and len(s.targets) == 1 for s in (b.body[0], a.body[0])):
        return ""
    (target_b,), (target_a,) = b.body[0].targets, a.body[0].targets
    value_b, value_a = b.body[0].value, a.body[0].value
    if ast.dump(value_b) == ast.dump(value_a) and _reverses(target_b, target_a) \
            and all(isinstance(e, ast.Name) for e in target_b.elts):
        names = {e.id for e in target_b.elts}   # (the pair bound in another order: a call reads the two names)
        return _opencv_reader(fn, lambda arg: isinstance(arg, ast.Tuple) and len(arg.elts) == 2
                              and {ast.unparse(e) for e in arg.elts} == names)
    if ast.dump(target_b) == ast.dump(target_a) and isinstance(target_b, ast.Name) and _reverses(value_b, value_a):
        return _opencv_reader(fn, lambda arg: isinstance(arg, ast.Name) and arg.id == target_b.id)
    return ""


def _reverses(b, a) -> bool:
    """Whether the node ``a`` is ``b`` with its pair in the other order: two items exchanged, or `[::-1]`
    taken out or put in."""
    reversal = lambda n: isinstance(n, ast.Subscript) and ast.unparse(n.slice) == "::-1"  # noqa: E731
    swapped = isinstance(b, ast.Tuple) and isinstance(a, ast.Tuple) and len(b.elts) == len(a.elts) == 2 \
        and ast.unparse(b.elts[0]) == ast.unparse(a.elts[1]) and ast.unparse(b.elts[1]) == ast.unparse(a.elts[0]) \
        and ast.unparse(b.elts[0]) != ast.unparse(b.elts[1])
    return swapped or (reversal(b) and ast.dump(b.value) == ast.dump(a)) or (reversal(a) and ast.dump(a.value) == ast.dump(b))


def _opencv_reader(fn, reads) -> str:
    """What the first OpenCV call of ``fn`` given an argument ``reads`` accepts reads it as: a board's pattern
    or a size, said in its own order; "" where no such call reads it."""
    for call in (n for n in walk(fn) if isinstance(n, ast.Call)):
        name = ast.unparse(call.func).rsplit(".", 1)[-1]
        if not any(reads(arg) for arg in list(call.args) + [k.value for k in call.keywords]):
            continue
        if name in _PATTERN_CALLS:
            return f" (cv2.{name} reads a pattern as (columns, rows) of inner corners: the API's pattern_size as given)"
        if name in SIZE_ARGUMENTS:
            return f" (cv2.{name} reads a size as (width, height), where a shape is (rows, columns))"
    return ""


def _parsed(text: str, modes: tuple):
    """``text`` parsed in the first of ``modes`` ("eval", "exec") that reads it; None when none does."""
    for mode in modes:
        try:
            return parse(text, mode=mode)
        except (SyntaxError, ValueError, RecursionError):
            continue
    return None


def _changed_subscripts(before: str, after: str) -> tuple | None:
    """The one subscript ``before`` writes that ``after`` does not, and the one in its place (`pts[2]` and
    `pts[:, 2]` of `np.mean(pts[2])` and `np.mean(pts[:, 2])`); None when not exactly one each."""
    def subscripts(text) -> set:
        tree = _parsed(text, ("eval", "exec"))   # (an expression, or a statement: `h = Vt[:, -1]`)
        return set() if tree is None else {ast.unparse(n) for n in walk(tree) if isinstance(n, ast.Subscript)}
    gone, made = subscripts(before), subscripts(after)
    gone, made = gone - made, made - gone
    return (gone.pop(), made.pop()) if len(gone) == len(made) == 1 else None


def _svd_output(text: str, fn) -> str:
    """"Vt" or "U" when ``text`` (an expression of ``fn``) is np.linalg.svd's third or first output: `...svd(A)[2]`,
    or a name unpacked from an svd call (`U, S, Vt = np.linalg.svd(A)`); "" otherwise."""
    def svd_call(node) -> bool:
        return isinstance(node, ast.Call) and ast.unparse(node.func).rsplit(".", 1)[-1] == "svd"
    try:
        node = parse(text, mode="eval").body
    except (SyntaxError, ValueError, RecursionError):
        return ""
    if isinstance(node, ast.Subscript) and svd_call(node.value) and isinstance(node.slice, ast.Constant):
        return {2: "Vt", 0: "U"}.get(node.slice.value, "")
    if isinstance(node, ast.Name):
        for assign in (n for n in walk(fn) if isinstance(n, ast.Assign) and svd_call(n.value)):
            target = assign.targets[0]
            if isinstance(target, ast.Tuple) and len(target.elts) == 3:
                names = [e.id if isinstance(e, ast.Name) else None for e in target.elts]
                if node.id == names[2]:
                    return "Vt"
                if node.id == names[0]:
                    return "U"
    return ""


def _makes_float(text: str, defs: dict) -> bool:
    """Whether the statement ``text`` converts to float: an ``astype``, ``np.float32(...)`` and the like, or a call
    of a def of the student's (``defs``) whose returns do (one call deep)."""
    try:
        statement = parse(text)
    except (SyntaxError, ValueError, RecursionError):
        return False

    def converts(node) -> bool:
        for call in (n for n in walk(node) if isinstance(n, ast.Call)):
            name = ast.unparse(call.func)
            if name in _FLOAT_MAKERS:   # (np.float32(image): a call of the type itself)
                return True
            if name.endswith(".astype") and call.args and ast.unparse(call.args[0]) in _FLOAT_DTYPES:
                return True
            if any(k.arg == "dtype" and ast.unparse(k.value) in _FLOAT_DTYPES for k in call.keywords):
                return True
        return False

    if converts(statement):
        return True
    called = {ast.unparse(n.func) for n in walk(statement) if isinstance(n, ast.Call)}
    return any(converts(r.value) for name in called if name in defs
               for r in walk(defs[name]) if isinstance(r, ast.Return) and r.value is not None)


class _Student:
    """The student's module read once: its tree, the operators' changes per API function, and each
    change shown (made lazily, for the functions that fail: showing every change of a long module
    takes seconds)."""

    def __init__(self, text: str, tree: ast.Module, api):
        self.text, self.tree = text, tree
        self._defs = _defs(tree)
        self.api = frozenset(api) & set(self._defs)   # the graded functions it defines
        self._mutants: dict = {}     # API function -> the operators' changes of the code it runs
        self.fixes: dict = {}        # mutant key -> its Fix, or None when it cannot be shown
        self._ordered: dict = {}     # function -> its mutants that can be shown, smallest change first
        self._novel: dict = {}       # function -> the places of its statements the reference writes nowhere
        self._extra: dict = {}       # (def, ordinal) -> whether taking that statement out removes a step of the student's own
        self._statements: dict = {}   # def -> line -> the first line of the statement holding it
        self._blocks: dict = {}       # def -> a body statement's first line -> the first line of its if or loop
        self._walked: dict = {}      # def name -> (its nodes in ast.walk order, their parents)
        self._own_sized: dict = {}   # def name -> its comparisons of a value with its own size (as written)
        self._shapes: dict = {}      # id of a statement (kept alive in _walked) -> its code with names masked
        self._places: dict = {}      # id of a node (kept alive in _walked) -> (its statement, its position there)
        self._zipped: dict = {}      # def name -> the (name, name) pairs of its loops over zip
        self._resolved: dict = {}    # def name -> {(raw, resolved): line} of names made from a parameter or constant
        self._unpacking: dict | None = None   # line -> the loops and assignments with several targets there
        self._sizes: dict = {}       # def name -> the names it computes from an array's size
        self._lock = threading.Lock()
        self.reference_parts: frozenset = frozenset()   # (name, its parts' names) the reference unpacks
        self.reference_source = ""    # the lab's reference module (see follows_reference)
        self._anchored: dict = {}    # def name -> ids of its statements anchored in the reference's
        self._differ: frozenset | None = None   # module-level names bound otherwise than the reference's

    def mutants(self, function: str) -> list:
        """The operators' changes of the code ``function`` runs (made at its first failure: a long
        module's every function would take seconds)."""
        if function not in self._mutants and not self.readable(function):
            self._mutants[function] = []
        if function not in self._mutants:
            made = mutants_of(self.text, self.api, phrased=False, functions={function}) if function in self.api else {}
            # (and the statements written as the reference's but for a slip, made its again: see aligned.py)
            try:
                aligned = aligned_mutants(self.tree, _reference_tree(self.reference_source), function) \
                    if function in self.api and self.reference_source else []
            except RecursionError:   # (code nested past what comparing it statement by statement can follow)
                aligned = []
            self._mutants[function] = aligned + made.get(function, [])
        return self._mutants[function]

    def readable(self, function: str) -> bool:
        """Whether every def ``function`` runs is within :data:`MAX_DEF_NODES` (changes of it are read in time)."""
        return all(sum(1 for _ in walk(self._defs[name])) <= MAX_DEF_NODES for name in runs(self._defs, function))

    def shared(self, where: str, function: str) -> bool:
        """Whether the def ``where`` (not ``function`` itself) is run by another graded function too."""
        return bool(self.sharing(where, function))

    def sharing(self, where: str, function: str) -> set:
        """The graded functions other than ``function`` that run the def ``where`` (none for ``function``'s own)."""
        if where == function:
            return set()
        return {other for other in self.api if other != function and where in runs(self._defs, other)}

    def ordered(self, function: str) -> list:
        """``function``'s changes that can be shown: its own code's first, then its private helpers'
        (another graded function it calls has checks of its own, and a mistake there is told as
        inherited), each the smallest change of the text first: the student's slip is a few
        characters, where a change compensating for it rewrites more."""
        with self._lock:
            if function not in self._ordered:
                shown = [m for m in self.mutants(function)
                         if (m.where == function or m.where not in self.api) and self.fix(m) is not None
                         and not self.reorders_api_results(m) and not self.follows_reference(m)]
                # (a name swapped for its twin -- R1 for R2, left for right -- first of its kind: the
                # likeliest slip among a function's many names that might be another's)
                # (and of each kind, a change of code the reference writes word for word after the others:
                # mending there likely compensates -- `np.cross(e1, e2)` exchanged beside `C2 = R.T @ T`
                # whose minus is missing -- and a search bounded in time may end at the first it finds)
                # (and a parameter or constant read after the function made its resolved form, `s` of `smoothness`)
                # (of those, a name read for the one unpacked beside it first -- `kp2[n.trainIdx]` in a loop over
                # `m, n` pairs: the pair is the code's own, where `kp1`/`kp2` twins are many; a slow function's
                # search in its time may reach only the first few of a kind)
                smallest = sorted(shown, key=lambda m: (
                    m.where != function, not (_twin_swap(self.fixes[m.key]) or self.twin_items(m) or self.zipped_swap(m)
                                              or self.twin_sibling(m) or self.resolved_name(m)), not self.zipped_swap(m),
                    m.operator not in ADDITIONS and self.departs_from_reference(m),
                    self.fixes[m.key].size,
                    self.fixes[m.key].written, m.line))
                # Each kind of slip has its turn: the k-th smallest change of every operator before the
                # (k+1)-th of any (a function's 150 names that might be another's would otherwise come
                # before its one loop over a fixed count).
                turn, taken = {}, Counter()
                for m in smallest:
                    turn[m.key] = taken[(m.where != function, m.operator)]
                    taken[(m.where != function, m.operator)] += 1
                    # (a line made its twin line's again, where the two differ at one place but their
                    # names: the slip the code itself shows, first of all)
                    turn[m.key] -= m.operator in SHOWN_BY_THE_CODE or self.filters_a_stack(m)
                # Code written as the reference's but for a statement or two: those of a private helper
                # first (a helper's `xy = mapped[..., :2]` before the 300 changes of the function's own
                # lines, all the reference's); the function's own keep their turns (a reshape's order
                # changed on its own line, not compensated on the line before).
                novel = self._novel[function] = self._novel_statements(function, shown)
                # A statement written as the reference's but at a place or two, made its counterpart's, before all:
                # the slip the code shows beside the statement it stands for (aligned.py); and beside them, a
                # call given whole arrays the code selects by a mask elsewhere, selected by the mask bound last
                # above it (a refit after a RANSAC loop given every point: a slow loop's search tries few changes).
                selections = {}
                for m in shown:   # (in the order made: the mask bound last above the call first)
                    if m.operator == "select_mask":
                        selections.setdefault(m.edits[0][:2], m.key)
                first_selections = set(selections.values())
                self._ordered[function] = sorted(smallest, key=lambda m: (
                    m.operator not in ALIGNED and m.key not in first_selections,
                    not (m.where != function and self._place_of(m) in novel),
                    m.where != function, turn[m.key]))
            return self._ordered[function]

    def _place_of(self, mutant):
        """(def, line) of the statement the mutant's first change is in."""
        where, ordinal = mutant.edits[0][0], mutant.edits[0][1]
        nodes, parents = self._walk(where)
        if not 0 <= ordinal < len(nodes):
            return None
        statement = nodes[ordinal]
        while not isinstance(statement, ast.stmt) and id(statement) in parents:
            statement = parents[id(statement)][0]
        return (where, getattr(statement, "lineno", None)) if isinstance(statement, ast.stmt) else None

    def _novel_statements(self, function: str, shown) -> set:
        """The simple statements holding ``shown``'s changes that the reference writes nowhere (by their
        text), when they are few (at most :data:`NOVEL_STATEMENTS`): the student's edits of code otherwise
        the reference's. Empty for code of their own (many such statements)."""
        if not self.reference_source:
            return set()
        written = set().union(*_reference_texts(self.reference_source).values())
        novel, seen = set(), set()
        for m in shown:
            place = self._place_of(m)
            if place is None or place in seen:   # (each statement read once, however many changes it holds)
                continue
            seen.add(place)
            nodes, parents = self._walk(place[0])
            statement = nodes[m.edits[0][1]] if 0 <= m.edits[0][1] < len(nodes) else None
            while statement is not None and not isinstance(statement, ast.stmt) and id(statement) in parents:
                statement = parents[id(statement)][0]
            if isinstance(statement, (ast.Assign, ast.AugAssign, ast.Expr, ast.Return)) \
                    and ast.unparse(statement) not in written:
                novel.add(place)
                if len(novel) > NOVEL_STATEMENTS:
                    return set()
        return novel

    def own_steps(self, function: str) -> list[tuple]:
        """Pairs of places ((def, line), (def, line)) of two statements the reference writes nowhere
        (:meth:`_novel_statements`), one right after the other in one block, the second reading a name
        the first binds: a step of the student's own and the line written for it (`s = np.sort(s)`,
        then `s[0] = 0.0`), where one slip is mended at both lines at once and at neither alone."""
        self.ordered(function)
        novel = self._novel.get(function, set())
        steps = []
        for where in {place[0] for place in novel}:
            fn = self._defs.get(where)
            blocks = [getattr(node, field) for node in walk(fn) if fn is not None
                      for field in ("body", "orelse") if isinstance(getattr(node, field, None), list)]
            for block in blocks:
                for first, second in zip(block, block[1:]):
                    places = (where, first.lineno), (where, second.lineno)
                    if places[0] in novel and places[1] in novel and isinstance(first, (ast.Assign, ast.AugAssign)) \
                            and _bound_names(first) & _read(second):
                        steps.append(places)
        return steps

    def extra_block(self, mutant) -> bool:
        """Whether the mutant takes out a whole `if` block every simple statement of which is one the reference
        writes nowhere, in a def otherwise the reference's but for a few statements (:data:`NOVEL_STATEMENTS`): a
        step of the student's own (a gain applied after a warp), whose removal is the fix -- the changes that make
        it do nothing (its gain 1, its test never true) only work round it. (In code of their own, every statement
        is new: a special case's block there holds a slip a change inside it mends.)"""
        where, ordinal, operator, _ = mutant.edits[0]
        if operator != "drop_statement" or len(mutant.edits) != 1 or not self.reference_source:
            return False
        key = (where, ordinal)   # (asked for every pair of every sort: read once per statement)
        if key not in self._extra:
            self._extra[key] = self._extra_block(where, ordinal)
        return self._extra[key]

    def _extra_block(self, where: str, ordinal: int) -> bool:
        nodes, _ = self._walk(where)
        block = nodes[ordinal] if 0 <= ordinal < len(nodes) else None
        # (an early return or raise makes the block a special case, a path of its own: a change inside it mends it)
        if not isinstance(block, ast.If) or any(isinstance(node, (ast.Return, ast.Raise)) for node in walk(block)):
            return False
        written = set().union(*_reference_texts(self.reference_source).values())
        simple = lambda root: [node for node in walk(root) if isinstance(node, (ast.Assign, ast.AugAssign, ast.Return))  # noqa: E731
                               or isinstance(node, ast.Expr) and not isinstance(node.value, ast.Constant)]
        inside = simple(block)
        lines = {node.lineno for node in inside}
        outside = [node for node in simple(self._defs[where]) if node.lineno not in lines
                   and ast.unparse(node) not in written]
        return bool(inside) and all(ast.unparse(node) not in written for node in inside) \
            and len(outside) <= NOVEL_STATEMENTS

    def inside_block(self, block_mutant, fix: Fix) -> bool:
        """Whether every line ``fix`` changes lies in the body of the `if` block ``block_mutant`` takes out."""
        where, ordinal, _, _ = block_mutant.edits[0]
        nodes, _ = self._walk(where)
        block = nodes[ordinal] if 0 <= ordinal < len(nodes) else None
        return isinstance(block, ast.If) and fix.where == where and all(
            block.body[0].lineno <= line <= (block.end_lineno or block.lineno) for line, _, _ in fix.changes)

    def follows_reference(self, mutant) -> bool:
        """Whether the change rewrites a statement that is the reference's own, with all it reads
        (:mod:`.anchors`): mending the answers there compensates for a slip elsewhere. (A statement
        moved is not rewritten: `best = np.inf` inside the loop is the reference's line misplaced.)"""
        if not self.reference_source:
            return False
        for where, ordinal, operator, _ in mutant.edits:
            nodes, parents = self._walk(where)
            if operator in _IN_WORDS or not 0 <= ordinal < len(nodes):
                continue
            statement = nodes[ordinal]
            while not isinstance(statement, ast.stmt) and id(statement) in parents:
                statement = parents[id(statement)][0]
            if isinstance(statement, ast.stmt) and id(statement) in self._anchored_in(where) \
                    and not (operator in ADDITIONS and self._updated_further_in_reference(where, statement)):
                return True
        return False

    def _updated_further_in_reference(self, where: str, statement: ast.stmt) -> bool:
        """Whether the name ``statement`` assigns is assigned more often in the reference's def than in the
        student's: the reference's line, right at that point, is followed there by a step the student
        left out (`e2 /= np.linalg.norm(e2)` after `e2 = np.cross(axis, e1)`), which a step added to
        the line itself supplies."""
        if not (isinstance(statement, ast.Assign) and len(statement.targets) == 1
                and isinstance(statement.targets[0], ast.Name)):
            return False
        name = statement.targets[0].id
        reference = _defs(_reference_tree(self.reference_source)).get(where)
        fn = self._defs.get(where)

        def assignments(def_) -> int:
            return sum(1 for node in walk(def_) if isinstance(node, (ast.Assign, ast.AugAssign))
                       and any(isinstance(t, ast.Name) and t.id == name
                               for t in (node.targets if isinstance(node, ast.Assign) else [node.target])))
        return reference is not None and fn is not None and assignments(reference) > assignments(fn)

    def departs_from_reference(self, mutant) -> bool:
        """Whether the change rewrites code the reference's def of that name writes word for word
        (`k ^ k >> 1`, the Gray code): of two changes that mend alike, the one elsewhere is the
        slip (`g >> n_bits - i`, a bit read one place off), this one compensates for it. Only code
        with an operation in it counts (a lone name or number is written everywhere)."""
        fix = self.fixes.get(mutant.key)
        return fix is not None and _departs(fix, self.reference_source)

    def around_a_branch(self, fix: Fix, ran: set | None = None) -> Fix | None:
        """``fix`` told as the branch it makes the code skip, when it changes a value that only the tests
        of branches ending in a return read (`angle = float(angle_deg) % 360` -> `float(width) % 360`
        beside `if height == width and angle in quarter: return cv2.rotate(...)`): it mends by not taking
        the shortcut, so the slip is inside that branch, not on the changed line (``ran``: the lines the
        student's code ran on the failing inputs, to tell the branch it took). None otherwise."""
        if len(fix.edits) != 1 or fix.operator in _IN_WORDS or fix.operator == "twin_test":
            return None
        where, ordinal, _, _ = fix.edits[0]
        nodes, parents = self._walk(where)
        fn = self._defs.get(where)
        if fn is None or not 0 <= ordinal < len(nodes):
            return None
        statement = nodes[ordinal]
        while not isinstance(statement, ast.stmt) and id(statement) in parents:
            statement = parents[id(statement)][0]
        if not isinstance(statement, ast.Assign):
            return None
        # (the changed value no longer reads a parameter it read -- `float(angle_deg)` made `float(width)`:
        # a value made unrelated to its input, not a value's slip mended, `n // 2` -> `n // 3`)
        parameters = {a.arg for a in fn.args.args + fn.args.kwonlyargs}
        line, before, after = fix.changes[0]
        try:
            read_before, read_after = ({n.id for n in walk(parse(text)) if isinstance(n, ast.Name)} & parameters
                                       for text in (before, after))
        except SyntaxError:
            return None
        if read_before <= read_after:
            return None
        made = {n.id for t in statement.targets for n in walk(t) if isinstance(n, ast.Name)}
        tests = {id(node.test): node for node in walk(fn) if isinstance(node, ast.If)}
        branches, reads = [], 0
        for node in walk(fn):
            if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load) and node.id in made \
                    and node.lineno > statement.lineno:
                reads += 1
                holder, branch = node, None
                while id(holder) in parents:   # (a read in a test, or in the body of a branch testing it)
                    parent = parents[id(holder)][0]
                    if id(holder) in tests:
                        branch = tests[id(holder)]
                        break
                    if isinstance(parent, ast.If) and holder in parent.body and \
                            made & {n.id for n in walk(parent.test) if isinstance(n, ast.Name)}:
                        branch = parent
                        break
                    holder = parent
                if branch is None:
                    return None   # (the value is used, not only tested)
                if branch not in branches:
                    branches.append(branch)
        exits = [b for b in branches if any(isinstance(n, ast.Return) for s in b.body for n in walk(s))]
        if not reads or not exits:
            return None
        exits.sort(key=lambda b: (not (ran and b.body[0].lineno in ran), b.lineno))   # (the one taken first)
        branch = exits[0]
        test = " ".join(ast.unparse(branch.test).split())
        if len(test) > 60:
            return None
        last = max(getattr(s, "end_lineno", None) or s.lineno for s in branch.body)
        # (the change that skipped it is how it was tried, no fix: it makes a value unrelated to its input)
        told = (f"skipping the branch `if {test}:` (lines {branch.lineno}-{last}{{inside}}; tried by changing "
                f"`{before}` to `{after}` on line {line}, which only steers round it)")
        return Fix(((line, before, told),), where, "branch", fix.edits)

    def _anchored_in(self, where: str) -> set:
        if where not in self._anchored:
            reference = _defs(_reference_tree(self.reference_source)).get(where)
            fn = self._defs.get(where)
            if self._differ is None:
                self._differ = anchors.differing_names(self.tree, _reference_tree(self.reference_source))
            self._anchored[where] = anchors.anchored(fn, reference, self._differ) \
                if fn is not None and reference is not None else set()
        return self._anchored[where]

    def reorders_api_results(self, mutant) -> bool:
        """Whether the change exchanges the names a graded function's results are unpacked into
        (`K, R, t = decompose_camera_matrix(P)` -> `K, t, R = ...`): the API fixes the order of what
        it returns, so taking its results in another order is never the fix, whatever it mends
        (`-R @ t` with the two exchanged is `-t @ R`, R^T t)."""
        names = lambda text: re.findall(r"\w+", text.split("=", 1)[0])  # noqa: E731  (the targets, in order)
        for line, before, after in self.fix(mutant).changes:
            for node in self.unpacking_at(line):
                if isinstance(node, ast.For):
                    # (a loop's names exchanged -- `for x, y in pts` -> `for y, x in pts`, `for i, (X, Y, Z) in
                    # enumerate(pts)` -> `(Y, X, Z)` -- named as the reference names them, or in their axes'
                    # order: the names would lie)
                    for part in (n for n in walk(node.target) if isinstance(n, ast.Tuple)):
                        told = [t.id for t in part.elts if isinstance(t, ast.Name)]
                        if mutant.edits[0][2] == "swap_items" and _names_as_written(told, self.reference_parts,
                                                                                    node.iter):
                            return True
                    continue
                targets = [t.id for t in getattr(node.targets[0], "elts", ()) if isinstance(t, ast.Name)]
                if not (names(before) != names(after) and sorted(names(before)) == sorted(names(after))) \
                        or names(before) != targets[:len(names(before))]:
                    # (or the value's items exchanged under names that say their order: `x, y = (Y, X)` for a
                    # right `x, y = (X, Y)` compensates as a relabelling does)
                    if isinstance(node, ast.Assign) and isinstance(node.value, ast.Tuple) \
                            and _in_known_order(targets, node.value) and mutant.edits[0][2] in _EXCHANGES | {"swap_items"}:
                        return True
                    continue
                if isinstance(node.value, ast.Call) and _call_name(node.value) in self.api:
                    return True
                # (a value's parts named as the reference names them -- `cols, rows = pattern_size`,
                # `k1, k2, p1, p2, k3 = d` -- are right: naming them the other way mends a later swap by
                # making the names lie)
                if isinstance(node.value, ast.Name) and (node.value.id, tuple(names(before))) in self.reference_parts:
                    return True
                if _names_as_written(names(before), self.reference_parts, node.value):
                    return True
                # (and names in the order the value is known to hold its parts -- `b, g, r = cv2.split(image)`,
                # `h, w = image.shape[:2]`, `k1, k2, p1, p2, k3 = dist` -- are right whatever the reference calls
                # them: relabelling them mends a later swap by making the names lie)
                if _in_known_order(names(before), node.value):
                    return True
        return False

    def unpacking_at(self, line: int) -> list:
        """The loops over tuples (`for x, y in pts`) and the assignments to several names
        (`K, R, t = ...`) that start at ``line``: the module walked once, not once per change."""
        if self._unpacking is None:
            found: dict = {}
            for node in walk(self.tree):
                if (isinstance(node, ast.For) and isinstance(node.target, ast.Tuple)) or (
                        isinstance(node, ast.Assign) and len(node.targets) == 1
                        and isinstance(node.targets[0], (ast.Tuple, ast.List))):
                    found.setdefault(node.lineno, []).append(node)
            self._unpacking = found
        return self._unpacking.get(line, [])

    def quoted_first(self, mutants, said: str, named: str = "") -> list:
        """``mutants``, those on a line holding a call the text ``said`` quotes (`np.sign`, `cv2.remap`)
        first (in their order), and before them those of the kinds the check's name of the mistake (``named``)
        speaks of."""
        quoted = set(re.findall(r"\b(?:np|numpy|cv2|cv|math)\.[A-Za-z_][\w.]*\w", said or ""))
        # (the changes of the kinds the check's name speaks of -- "the squared error is compared with the
        # threshold": a squared bound -- before the others; the name, not the message, whose measures use every word)
        # (of those, the kinds whose word comes first in the name first: "squared" before "compared")
        at = {operator: _agreement_at(operator, named) for operator in {m.operator for m in mutants}} if named else {}
        first = sorted((m for m in mutants if at.get(m.operator) is not None), key=lambda m: at[m.operator])
        mutants = first + [m for m in mutants if at.get(m.operator) is None]
        if not quoted:
            return mutants
        lines = self.text.splitlines()
        fix = {m.key: self.fix(m) for m in mutants}
        near = {m.key for m in mutants if fix[m.key] is not None and all(
            0 < change[0] <= len(lines) and any(name in lines[change[0] - 1] for name in quoted)
            for change in fix[m.key].changes)}
        return [m for m in mutants if m.key in near] + [m for m in mutants if m.key not in near]

    def vouched_last(self, mutants, function: str, passing) -> list:
        """``mutants`` of ``function``, those in a private helper that one of the ``passing`` graded
        functions runs too moved last (in their order)."""
        vouched = {m.key for m in mutants if m.where != function and any(
            other in passing and other != function and m.where in runs(self._defs, other) for other in self.api)}
        return [m for m in mutants if m.key not in vouched] + [m for m in mutants if m.key in vouched]

    def runs(self, mutant, lines) -> bool:
        """Whether code the ``lines`` ran holds each of the mutant's changes (True when nothing is
        known: ``lines`` None). A change is run when the statement around it is; a def's header (a
        default value) always is."""
        if lines is None:
            return True
        fix = self.fix(mutant)
        return fix is None or all((self._block_of(edit[0], change[0]) if edit[2] == "dedent" else
                                   self._statement_of(edit[0], change[0])) in lines
                                  for edit, change in zip(mutant.edits, fix.changes))

    def _block_of(self, where: str, line: int) -> int:
        """The first line of the `if` or loop whose body holds the statement at ``line``: a statement moved out of
        it runs where the block does (a conversion written in the colour branch only, which the grey input that
        failed never enters), else the statement's own."""
        if where not in self._blocks:   # (read once per def: a long function's many moves stay linear)
            fn = self._defs.get(where)
            self._blocks[where] = {s.lineno: block.lineno for block in (walk(fn) if fn is not None else ())
                                   if isinstance(block, (ast.If, ast.For, ast.While)) for s in block.body}
        return self._statement_of(where, self._blocks[where].get(line, line))

    def ran_here(self, function: str, lines) -> set | None:
        """``lines`` when they hold the first statement of ``function`` (the file the sandbox ran
        is the text read here), else None (nothing is known)."""
        fn = self._defs.get(function)
        return lines if lines is not None and fn is not None and _first_run(fn) in lines else None

    def _statement_of(self, where: str, line: int) -> int:
        """The first line of the innermost statement of ``where`` holding ``line`` (a def's header
        lines: the first line of its body, which every call runs)."""
        if where not in self._statements:
            fn, starts = self._defs.get(where), {}
            if fn is not None and fn.body:
                for statement in walk(fn):   # outer statements first: inner ones overwrite
                    if isinstance(statement, ast.stmt) and statement is not fn:
                        for held in range(statement.lineno, (statement.end_lineno or statement.lineno) + 1):
                            starts[held] = statement.lineno
                for held in range(fn.lineno, fn.body[0].lineno):
                    starts[held] = _first_run(fn)
            self._statements[where] = starts
        return self._statements[where].get(line, line)

    def raising_guard(self, mutant, raised_lines) -> bool:
        """Whether ``mutant`` changes the test of an `if` whose own `raise` the student's call raised at
        (``raised_lines``): `if len(pts1) <= 8: raise ValueError(...)` refusing the 8 points it was given."""
        fix = self.fix(mutant)
        lines = {line for line, _, _ in fix.changes} if fix is not None else set()
        if not raised_lines or not lines:
            return False
        return any(isinstance(node, ast.If) and node.test.lineno in lines
                   and any(isinstance(statement, ast.Raise) and statement.lineno in raised_lines
                           for statement in node.body)
                   for node in walk(self.tree))

    def guards(self, mutant) -> list:
        """The mutant's code with a condition it changes made constant instead, True then False
        (each condition of an ``if``, a conditional expression or a comprehension's filter that holds
        one of its changes): the guard removed, taken or never."""
        made = []
        for where, ordinal, _, _ in mutant.edits:
            nodes, parents = self._walk(where)
            node = nodes[ordinal] if 0 <= ordinal < len(nodes) else None
            while node is not None and id(node) in parents:
                parent, field, _ = parents[id(node)]
                if (isinstance(parent, (ast.If, ast.IfExp)) and field == "test") \
                        or (isinstance(parent, ast.comprehension) and field == "ifs"):
                    test = next(i for i, each in enumerate(nodes) if each is node)
                    made += [replace(mutant, edits=((where, test, "constant", value),)) for value in (True, False)]
                    break
                node = None if isinstance(parent, ast.stmt) else parent
        return made

    def block_never_run(self, mutant):
        """For a statement taken out that is the whole block of an ``if`` without ``else`` (`if xl - xr <= 0:`
        then `X = np.full(3, np.nan)`), the same change as that test made always false (None otherwise): told
        so, it points at the test, where the slip is likelier than in the one line the block holds."""
        if len(mutant.edits) != 1 or mutant.edits[0][2] != "drop_statement":
            return None
        where, ordinal, _, _ = mutant.edits[0]
        nodes, parents = self._walk(where)
        node = nodes[ordinal] if 0 <= ordinal < len(nodes) else None
        holder, field, _ = parents.get(id(node), (None, None, None)) if node is not None else (None, None, None)
        if not (isinstance(holder, ast.If) and field == "body" and len(holder.body) == 1 and not holder.orelse):
            return None
        test = next((i for i, each in enumerate(nodes) if each is holder.test), None)
        return None if test is None else replace(mutant, edits=((where, test, "constant", False),))

    def test_taken_out(self, guard) -> Fix | None:
        """A guard of :meth:`guards` (its test made True or False) told as the test taken out: its block
        always run, or never (None when the test is not an ``if``'s)."""
        where, ordinal, _, value = guard.edits[0]
        nodes, parents = self._walk(where)
        node = nodes[ordinal] if 0 <= ordinal < len(nodes) else None
        holder = parents.get(id(node), (None,))[0] if node is not None else None
        if not isinstance(holder, ast.If):
            return None
        test = " ".join(ast.unparse(holder.test).split())
        if len(test) > _SHOWN:
            return None
        last = max(getattr(s, "end_lineno", None) or s.lineno for s in holder.body)
        said = (f"taking out the test `if {test}:` (line {holder.lineno}{{inside}}) so that its block always runs"
                if value else f"taking out the block under `if {test}:` (lines {holder.lineno}-{last}{{inside}}), "
                              "which runs where it should not")
        return Fix(((holder.lineno, f"if {test}:", said),), where, "guard", guard.edits)

    def reads_size(self, mutant) -> bool:
        """Whether one of the mutant's changes is in a statement that reads an array's size: its
        ``.shape`` or ``.size``, ``len(...)``, or a name computed from them in the same def (`h, w =
        image.shape[:2]`, then `cx = (w - 1) / 2`)."""
        for where, ordinal, _, _ in mutant.edits:
            nodes, parents = self._walk(where)
            node = nodes[ordinal] if 0 <= ordinal < len(nodes) else None
            while node is not None and not isinstance(node, ast.stmt):
                node = parents.get(id(node), (None,))[0]
            if node is not None and _reads_size(node, self._size_names(where)):
                return True
        return False

    def _size_names(self, where: str) -> set:
        """The names the def ``where`` computes from an array's size (directly or through one another)."""
        if where not in self._sizes:
            self._sizes[where] = self._sized(where)
        return self._sizes[where]

    def _sized(self, where: str) -> set:
        return _sized_names(self._walk(where)[0])

    def colours_with_a_size(self, mutant) -> bool:
        """Whether the mutant gives an OpenCV drawing call, as its colour, a name computed from an image's
        size (`cv2.line(canvas, p, q, width, 1)` for `colour`): a grey line of the value 60 passes "a line is
        drawn", and is no account of a colour chosen wrongly."""
        where, ordinal, operator, payload = mutant.edits[0]
        if operator != "other_name" or len(mutant.edits) != 1 or payload not in self._size_names(where):
            return False
        nodes, parents = self._walk(where)
        node = nodes[ordinal] if 0 <= ordinal < len(nodes) else None
        parent, field, index = parents.get(id(node), (None, None, None))
        if isinstance(parent, ast.keyword):
            return parent.arg == "color"
        return isinstance(parent, ast.Call) and field == "args" \
            and _COLOUR_AT.get(_call_name(parent)) == index and _dotted(parent.func).startswith(("cv2.", "cv."))

    def chooses(self, mutant) -> bool:
        """Whether one of the mutant's changes is in what an argmin, argmax or argsort reads (an index
        chosen, as a branch is)."""
        for where, ordinal, _, _ in mutant.edits:
            nodes, parents = self._walk(where)
            node = nodes[ordinal] if 0 <= ordinal < len(nodes) else None
            for _ in range(4):
                node = parents.get(id(node), (None,))[0] if node is not None else None
                if isinstance(node, ast.Call) and _call_name(node).startswith(("argmin", "argmax", "argsort",
                                                                               "nanargmin", "nanargmax")):
                    return True
        return False

    def renormalises(self, mutant) -> bool:
        """Whether the mutant changes which of an array's own entries divides it (``F / F[2, 2]``: the
        index, or the entry, of the divisor ``F[...]`` of a division of ``F``), in any of its edits (a
        pair: both indices of `P[2, 3]` made 0). A divisor made a column (`x / x[-1]` -> `x / x[:, -1:]`, each
        row divided by its own entry) changes more than the scale: not this."""
        return any(self._renormalises(where, ordinal) for where, ordinal, operator, _ in mutant.edits
                   if operator != "keep_axis")

    def _renormalises(self, where: str, ordinal: int) -> bool:
        nodes, parents = self._walk(where)
        node = nodes[ordinal] if 0 <= ordinal < len(nodes) else None
        while node is not None:
            parent = parents.get(id(node), (None,))[0]
            if isinstance(parent, ast.BinOp) and isinstance(parent.op, ast.Div) and parent.right is node:
                divided = parent.left
            elif isinstance(parent, ast.AugAssign) and isinstance(parent.op, ast.Div) and parent.value is node:
                divided = parent.target
            else:
                if not isinstance(parent, (ast.Subscript, ast.Tuple, ast.Constant, ast.UnaryOp, ast.Slice)):
                    return False
                node = parent
                continue
            return isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name) \
                and isinstance(divided, ast.Name) and divided.id == node.value.id
        return False

    def compares_with_its_own_size(self, mutant) -> bool:
        """Whether the mutant makes a comparison of a value with its own length or shape (`depth < len(depth)`,
        from `column < len(patterns)` by two names changed): values against the count of those values mean
        nothing, and such a change mends only by being true on the inputs tried (a bound that never binds)."""
        def own_sized(fn) -> set:
            found = set()
            for node in walk(fn):
                if not isinstance(node, ast.Compare):
                    continue
                sides = [node.left, *node.comparators]
                bare = {side.id for side in sides if isinstance(side, ast.Name)}
                sized = {part.args[0].id for side in sides for part in walk(side)
                         if isinstance(part, ast.Call) and _call_name(part) == "len" and part.args
                         and isinstance(part.args[0], ast.Name)}
                sized |= {part.value.id for side in sides for part in walk(side)
                          if isinstance(part, ast.Attribute) and part.attr in ("shape", "size")
                          and isinstance(part.value, ast.Name)}
                if bare & sized:
                    found.add(ast.unparse(node))
            return found
        where = mutant.edits[0][0]
        try:
            mutated = _defs(mutated_defs(self.tree, mutant.edits, self.text)).get(where)
        except (ValueError, SyntaxError):
            return False
        if mutated is None or where not in self._defs:
            return False
        if where not in self._own_sized:   # (the student's def is the same for each of its hundreds of changes)
            self._own_sized[where] = own_sized(self._defs[where])
        return bool(own_sized(mutated) - self._own_sized[where])

    def bypasses(self, mutant) -> bool:
        """Whether the mutant puts another name where the only reading of a value the def computes was
        (`normalised @ K.T` -> `X @ K.T`, `normalised` read nowhere else): it mends by skipping a step, which
        leaves the step's own slip in place, where a change inside the step mends it."""
        where, ordinal, operator, _ = mutant.edits[0]
        if operator != "other_name" or len(mutant.edits) != 1:
            return False
        nodes, _ = self._walk(where)
        node = nodes[ordinal] if 0 <= ordinal < len(nodes) else None
        if not isinstance(node, ast.Name):
            return False
        stored = any(isinstance(n, ast.Name) and n.id == node.id and isinstance(n.ctx, ast.Store) for n in nodes)
        readings = sum(isinstance(n, ast.Name) and n.id == node.id and isinstance(n.ctx, ast.Load) for n in nodes)
        return stored and readings == 1

    def filter_all_feed(self, fixes) -> object | None:
        """The student's mutant taking out a filter that every one of ``fixes`` (in one def) feeds: a statement
        keeping the entries of a mask (`rows, cols = rows[front], cols[front]`), the changes all at lines the
        mask is computed from -- its test turned round, a value made another, what it is compared with
        replaced. Where taking the filter out mends too (the caller confirms it), such changes mend by letting
        it keep everything: the filter is the slip. (How many of them the search confirms in its time
        varies; one is enough.) None where there is no such filter, or no change taking it out."""
        wheres = {fix.where for _, fix in fixes}
        if not fixes or len(wheres) != 1:
            return None
        where = wheres.pop()
        nodes, _ = self._walk(where)
        changed = {line for _, fix in fixes for line, _, _ in fix.changes}
        for statement in nodes:
            mask = _kept_by_mask(statement)
            if mask is None or statement.lineno in changed or not changed <= _feeding(nodes, statement, mask):
                continue
            for mutant in self.ordered(where):
                where_, ordinal, operator, _ = mutant.edits[0]
                if len(mutant.edits) == 1 and operator == "drop_statement" and where_ == where \
                        and 0 <= ordinal < len(nodes) and nodes[ordinal] is statement:
                    return mutant
        return None

    def removes_a_mask_guard(self, mutant) -> bool:
        """Whether the mutant takes out whole an `if` that raises when a mask is not all (or any) true, the
        mask read again after it (`valid = d > 0`, `if not valid.all(): raise`, then `np.divide(...,
        where=valid)`): the function goes on to treat the entries the guard refuses, so the guard is the slip."""
        if len(mutant.edits) != 1 or mutant.edits[0][2] != "drop_statement":
            return False
        where, ordinal, _, _ = mutant.edits[0]
        nodes, _ = self._walk(where)
        return 0 <= ordinal < len(nodes) and id(nodes[ordinal]) in self._mask_guards(where)

    def narrows_a_mask_guard(self, mutant) -> bool:
        """Whether the mutant changes the test of such a guard (`.all()` -> `.any()`, the mask for another
        name): that only narrows what it refuses -- an all-invalid map still raises --, where the guard
        taken out is the fix."""
        for where, ordinal, _, _ in mutant.edits:
            guards = self._mask_guards(where)
            nodes, parents = self._walk(where)
            node = nodes[ordinal] if 0 <= ordinal < len(nodes) else None
            while node is not None and id(node) in parents:
                parent, field, _ = parents[id(node)]
                if id(parent) in guards and field == "test":
                    return True
                node = parent
        return False

    def _mask_guards(self, where: str) -> dict:
        """The def's `if`s that raise when a mask is not all (any) true and whose mask is read after them
        (id -> node). Memoised per def."""
        cache = self.__dict__.setdefault("_mask_guard_cache", {})
        if where in cache:
            return cache[where]
        nodes, _ = self._walk(where)
        loads: dict = {}
        for n in nodes:
            if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load):
                loads[n.id] = max(loads.get(n.id, 0), getattr(n, "lineno", 0))
        found = {}
        for guard in nodes:
            if not (isinstance(guard, ast.If) and len(guard.body) == 1 and isinstance(guard.body[0], ast.Raise)):
                continue
            test = guard.test.operand if isinstance(guard.test, ast.UnaryOp) else guard.test
            mask = None
            if isinstance(test, ast.Call) and isinstance(test.func, ast.Attribute) and test.func.attr in ("all", "any"):
                if not test.args and isinstance(test.func.value, ast.Name):
                    mask = test.func.value.id              # valid.all()
                elif len(test.args) == 1 and isinstance(test.args[0], ast.Name):
                    mask = test.args[0].id                 # np.all(valid)
            if mask is not None and loads.get(mask, 0) > (guard.end_lineno or guard.lineno):
                found[id(guard)] = guard
        cache[where] = found
        return found

    def steers_round_a_guard(self, mutant) -> bool:
        """Whether the mutant changes a value the def reads only in the tests of guards that raise (`area =
        e1[0] * e2[1] - ...` read only by `if area <= 0: raise`): any value the guard lets through mends
        the answers alike, so such a change steers round the guard -- the guard itself is the place to
        look, not the value."""
        return all(self._read_by_guards_only(where, ordinal) for where, ordinal, _, _ in mutant.edits)

    def steers_a_branch(self, mutant) -> bool:
        """Whether the mutant changes a value computed from the inputs that the def reads only in the tests
        of its branches (`e1, e2 = src[1] - src[0], src[2] - src[0]` read only by `if e1[0] * e2[1] - ... > 0:`,
        whose body reorders `src`): the change mends by making the code take the other way, so the slip is
        in a branch, where a change inside it mends it too (`src, dst = src[order], dst[order]`)."""
        return all(self._read_by_guards_only(where, ordinal, raising=False, computed=True)
                   or self._in_a_branch_test(where, ordinal) for where, ordinal, _, _ in mutant.edits)

    def _in_a_branch_test(self, where: str, ordinal: int) -> bool:
        """Whether the node changed is inside the test of an ``if`` (`img1.shape[1]` in `if cx2 < img1.shape[1] / 2:`)
        whose branch does more than raise: a change there mends by taking the other way."""
        nodes, parents = self._walk(where)
        node = nodes[ordinal] if 0 <= ordinal < len(nodes) else None
        while node is not None and id(node) in parents:
            parent, field, _ = parents[id(node)]
            if isinstance(parent, ast.If) and field == "test":
                return not (len(parent.body) == 1 and isinstance(parent.body[0], ast.Raise))
            if isinstance(parent, ast.stmt):
                return False
            node = parent
        return False

    def _read_by_guards_only(self, where: str, ordinal: int, raising: bool = True, computed: bool = False) -> bool:
        nodes, parents = self._walk(where)
        statement = nodes[ordinal] if 0 <= ordinal < len(nodes) else None
        while statement is not None and not isinstance(statement, ast.stmt):
            statement = parents.get(id(statement), (None,))[0]
        if not (isinstance(statement, ast.Assign) and len(statement.targets) == 1):
            return False
        if computed and not any(isinstance(n, ast.Name) for n in walk(statement.value)):
            return False   # (a threshold written as a number, read by a test: the number may be the slip)
        made = [n for n in walk(statement.targets[0]) if isinstance(n, ast.Name)]
        guarded = self._guard_only_names(where, raising)
        return bool(made) and all(n.id in guarded for n in made)

    def _guard_only_names(self, where: str, raising: bool = True) -> set:
        """The def's names read only in the tests of guards that raise (``raising``; else of any branch),
        directly or through names made of them (`e1` read only to make `area`, `area` only in `if area <= 0:
        raise`). Memoised per def."""
        cache = self.__dict__.setdefault("_guarded", {})
        if (where, raising) in cache:
            return cache[(where, raising)]
        nodes, parents = self._walk(where)
        in_tests = {id(n) for guard in nodes if isinstance(guard, ast.If) and (
                        not raising or any(isinstance(b, ast.Raise) for b in guard.body))
                    for n in walk(guard.test)}
        reads: dict = {}   # name -> [(read in a guard's test, the names the statement reading it makes)]
        for node in nodes:
            if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load):
                statement = node
                while statement is not None and not isinstance(statement, ast.stmt):
                    statement = parents.get(id(statement), (None,))[0]
                makes = frozenset(n.id for target in getattr(statement, "targets", ())
                                  for n in walk(target) if isinstance(n, ast.Name)) \
                    if isinstance(statement, ast.Assign) else frozenset()
                reads.setdefault(node.id, []).append((id(node) in in_tests, makes))
        # A name joins once every reading is a guard's or makes guarded names only: a worklist over the
        # names each one waits for (linear in the readings, however long a chain of names).
        waits = {name: set().union(*(makes for test, makes in found if not test)) - {name}
                 for name, found in reads.items()
                 if all(test or makes for test, makes in found)}   # (a reading that makes nothing: never)
        waited_by: dict = {}
        for name, needed in waits.items():
            for other in needed:
                waited_by.setdefault(other, []).append(name)
        ready = [name for name, needed in waits.items() if not needed]
        guarded: set = set()
        while ready:
            name = ready.pop()
            if name in guarded:
                continue
            guarded.add(name)
            for waiting in waited_by.get(name, ()):
                waits[waiting].discard(name)
                if not waits[waiting]:
                    ready.append(waiting)
        cache[(where, raising)] = guarded
        return guarded

    def reduces_a_number(self, mutant, numbers: set) -> bool:
        """Whether the mutant puts a parameter that is a single number on every call (``numbers``) where an
        array is reduced (`np.nanmin(d)` -> `np.nanmin(baseline)`): the minimum of one number is the number,
        a threshold nobody writes so -- right by coincidence where the data never falls below it."""
        where, ordinal, operator, payload = mutant.edits[0]
        if operator != "other_name" or len(mutant.edits) != 1 or payload not in numbers:
            return False
        nodes, parents = self._walk(where)
        node = nodes[ordinal] if 0 <= ordinal < len(nodes) else None
        parent, field, index = parents.get(id(node), (None, None, None))
        return isinstance(parent, ast.Call) and field == "args" and index == 0 \
            and _dotted(parent.func).rsplit(".", 1)[-1] in _REDUCTIONS

    def leaves_a_step_unused(self, mutant) -> bool:
        """Whether a statement moved leaves another's result unread (`extrinsic = np.hstack([R, t])` moved above
        `R = R / np.linalg.norm(R)`: the division is never used): a step skipped, its slip left in place."""
        defs = self._def_changed(mutant) if mutant.edits[0][2] == "move" else None
        return defs is not None and bool(_unread_steps(defs[1]) - _unread_steps(defs[0]))

    def _def_changed(self, mutant) -> tuple | None:
        """(the def the mutant's first change is in, that def changed), or None where it cannot be made."""
        where = mutant.edits[0][0]
        own = _defs(self.tree).get(where)
        try:
            mutated = _defs(mutated_defs(self.tree, mutant.edits, self.text)).get(where)
        except (ValueError, SyntaxError):
            return None
        return None if own is None or mutated is None else (own, mutated)

    def negates_a_size(self, mutant) -> bool:
        """Whether the mutant exchanges the two sides of a difference that is an output size OpenCV is given
        (`size = (int(x1 - x0) + 1, h)` -> `int(x0 - x1) + 1`, then `cv2.warpPerspective(img, H, size)`), or
        negates a part of one (`(new_w, new_h)` -> `(-new_h, new_w)`): a
        canvas's extent made negative is no size -- OpenCV takes the input's in its place, which mends a
        canvas sized otherwise by coincidence, not by the slip."""
        defs = self._def_changed(mutant) if len(mutant.edits) == 1 else None
        if defs is None:
            return False
        own, mutated = defs
        sizes = _output_size_names(own)
        for before, after in zip(_statements_of(own), _statements_of(mutated)):
            if ast.dump(before) == ast.dump(after):
                continue
            assigns = isinstance(before, (ast.Assign, ast.AugAssign, ast.AnnAssign))
            sized = (assigns and bool(_bound_names(before) & sizes)) or any(
                id(arg) in {id(n) for n in walk(before)} for arg in _output_size_arguments(before))
            negated = lambda statement: sum(isinstance(n, ast.UnaryOp) and isinstance(n.op, ast.USub)  # noqa: E731
                                            for n in walk(statement))
            return sized and (negated(after) > negated(before) or any(
                isinstance(a, ast.BinOp) and isinstance(a.op, ast.Sub) and isinstance(b, ast.BinOp)
                and isinstance(b.op, ast.Sub) and ast.dump(a.left) == ast.dump(b.right)
                and ast.dump(a.right) == ast.dump(b.left) and ast.dump(a.left) != ast.dump(a.right)
                for a, b in zip(walk(before), walk(after))))
        return False

    def skips_a_right_step(self, mutant) -> bool:
        """Whether the mutant reads, in place of a name, its earlier form that its last assignment above was
        made from, by a step the reference writes too, names aside (`F / norm(F)` -> `Fn / norm(F)` after `F = T2.T @ Fn
        @ T1`, the denormalisation): it mends by skipping a right step, which leaves the slip before it."""
        where, ordinal, operator, payload = mutant.edits[0]
        if operator != "other_name" or len(mutant.edits) != 1 or not self.reference_source:
            return False
        nodes, _ = self._walk(where)
        node = nodes[ordinal] if 0 <= ordinal < len(nodes) else None
        if not isinstance(node, ast.Name):
            return False
        made = [n for n in nodes if isinstance(n, ast.Assign) and n.lineno < node.lineno
                and any(isinstance(t, ast.Name) and t.id == node.id for t in n.targets)]
        if not made:
            return False
        step = max(made, key=lambda n: n.lineno).value
        if not (_derived_names(node.id, payload) and any(isinstance(n, ast.Name) and n.id == payload
                                                         for n in walk(step))):
            return False   # (the name's own earlier form, `Fn` for `F`, not any name the step reads)
        return naming._alike(step) in _reference_shapes(self.reference_source)

    def copies_an_item(self, mutant) -> bool:
        """Whether the mutant puts a name in place of another item of the same tuple, list or call that
        holds it already (`(0, 0, height, width)` -> `(0, 0, width, width)`): where a size or a pair is
        given in the wrong order, such a copy is right on the inputs whose larger side it happens to
        keep, and the exchange of the two items is the fix."""
        where, ordinal, operator, payload = mutant.edits[0]
        if operator != "other_name" or len(mutant.edits) != 1:
            return False
        nodes, parents = self._walk(where)
        node = nodes[ordinal] if 0 <= ordinal < len(nodes) else None
        holder = parents.get(id(node), (None,))[0] if node is not None else None
        items = holder.elts if isinstance(holder, (ast.Tuple, ast.List)) else \
            holder.args if isinstance(holder, ast.Call) else []
        return any(isinstance(item, ast.Name) and item.id == payload for item in items if item is not node)

    def twin_items(self, mutant) -> bool:
        """Whether the mutant exchanges two items (or a call's two arguments) that are each other's twins
        (`(int(y_max - y_min) + 1, int(x_max - x_min) + 1)`: the same code with x for y, a size given rows first)."""
        where, ordinal, operator, payload = mutant.edits[0]
        if operator not in ("swap_items", "swap_args") or len(mutant.edits) != 1 or payload[0] == "moved":
            return False
        nodes, _ = self._walk(where)
        node = nodes[ordinal] if 0 <= ordinal < len(nodes) else None
        # (a call's two arguments alike: `np.meshgrid(np.arange(h), np.arange(w))`, a grid made rows first)
        items = node.args if operator == "swap_args" and isinstance(node, ast.Call) else \
            node.elts if operator == "swap_items" and isinstance(node, (ast.Tuple, ast.List)) else None
        if items is None or max(payload) >= len(items):
            return False
        first, second = (re.findall(r"\w+", ast.unparse(items[k])) for k in payload)
        pairs = [(a, b) for a, b in zip(first, second) if a != b]
        return len(first) == len(second) and bool(pairs) and all(twin_names(a, b) for a, b in pairs)

    def filters_a_stack(self, mutant) -> bool:
        """Whether the mutant gives a filter's window per image of an array the def stacks itself (`np.stack`,
        `np.dstack`, `np.array([...])`, or made with a shape of three sizes): one number as the window runs across
        the stack too, the slip the code shows."""
        where, ordinal, operator, _ = mutant.edits[0]
        if operator != "stack_window" or len(mutant.edits) != 1:
            return False
        nodes, _ = self._walk(where)
        call = nodes[ordinal] if 0 <= ordinal < len(nodes) else None
        if not (isinstance(call, ast.Call) and call.args and isinstance(call.args[0], ast.Name)):
            return False
        name = call.args[0].id
        for node in nodes:
            if isinstance(node, ast.Assign) and any(isinstance(t, ast.Name) and t.id == name for t in node.targets) \
                    and isinstance(node.value, ast.Call):
                made = _call_name(node.value)
                shape = node.value.args[0] if node.value.args else None
                if made in ("stack", "dstack", "array") or (made in ("zeros", "empty", "full", "ones")
                                                            and isinstance(shape, ast.Tuple) and len(shape.elts) == 3):
                    return True
        return False

    def twin_sibling(self, mutant) -> bool:
        """Whether the mutant does a step done to one name to its twin too (`pts1 = pts1[inliers]` ->
        `pts1, pts2 = pts1[inliers], pts2[inliers]`)."""
        where, _, operator, payload = mutant.edits[0]
        if operator != "sibling_step" or len(mutant.edits) != 1 or not isinstance(payload, str):
            return False
        fix = self.fix(mutant)
        return fix is not None and any(twin_names(name, payload) for name in re.findall(r"\w+", fix.changes[0][1]))

    def zipped_swap(self, mutant) -> bool:
        """Whether the mutant reads, for a name, the one looped over beside it (`p[1]` -> `q[1]` in
        `for p, q in zip(pts1, pts2)`): a line written for one of the pair with the other's name left."""
        where, _, operator, payload = mutant.edits[0]
        if operator not in ("other_name", "swap_names", "exchange") or len(mutant.edits) != 1:
            return False
        fn = self._defs.get(where)
        if fn is None:
            return False
        if where not in self._zipped:
            # (and names a loop unpacks together, `for m, n in pairs`: a ratio test written
            # `n.distance < 0.75 * m.distance` has the two exchanged)
            pairs = set()
            for loop in walk(fn):
                if isinstance(loop, (ast.For, ast.comprehension)) and isinstance(loop.target, ast.Tuple):
                    names = [n.id for n in loop.target.elts if isinstance(n, ast.Name)]
                    pairs |= {(a, b) for a in names for b in names if a != b}
            for names in unpacked_items(fn):   # (or unpacked in the loop: `m, n = pair`)
                pairs |= {(a, b) for a in names for b in names if a != b}
            self._zipped[where] = pairs
        fix = self.fix(mutant)
        if fix is None or len(fix.changes) != 1:
            return False
        before, after = (re.findall(r"\w+", text) for text in fix.changes[0][1:])
        changed = {(a, b) for a, b in zip(before, after) if a != b}
        if len(before) != len(after) or not changed <= self._zipped[where]:
            return False
        return len(changed) == 1 if operator == "other_name" else len(changed) == 2

    def resolved_name(self, mutant) -> bool:
        """Whether the mutant reads, for a parameter or a module constant, the local the function made of
        it before that line (`DEFAULT_SMOOTHNESS` -> `s` after `s = DEFAULT_SMOOTHNESS if smoothness is None
        else smoothness`; `pts` -> `pts_n` after `pts_n = normalise(pts)`): the raw value read where its
        resolved form belongs."""
        where, _, operator, _ = mutant.edits[0]
        fn = self._defs.get(where)
        if operator != "other_name" or len(mutant.edits) != 1 or fn is None:
            return False
        if where not in self._resolved:
            self._resolved[where] = self._resolving(fn)
        fix = self.fix(mutant)
        if fix is None or len(fix.changes) != 1:
            return False
        line, before, after = fix.changes[0]
        before, after = re.findall(r"\w+", before), re.findall(r"\w+", after)
        changed = [(a, b) for a, b in zip(before, after) if a != b]
        return len(before) == len(after) and len(changed) == 1 and \
            self._resolved[where].get(changed[0], line) < line

    def _resolving(self, fn) -> dict:
        """{(raw, resolved): line} of ``fn``'s assignments that make one value stand for a parameter or
        a module constant: a choice between it and another (`s = DEFAULT if smoothness is None else
        smoothness`, `k = k or 3`), or a step of it alone (`pts_n = pts - pts.mean(axis=0)`, `grey =
        cv2.cvtColor(image, ...)`; modules and constants aside)."""
        modules = {alias.asname or alias.name.split(".")[0] for node in walk(self.tree)
                   if isinstance(node, (ast.Import, ast.ImportFrom)) for alias in node.names}
        raw = {a.arg for a in fn.args.args + fn.args.kwonlyargs}
        constants = {node.id for node in walk(fn) if isinstance(node, ast.Name) and node.id.isupper()}
        made = {}
        for node in walk(fn):
            if not (isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name)):
                continue
            target, value = node.targets[0].id, node.value
            if isinstance(value, (ast.IfExp, ast.BoolOp)):
                branches = [value.body, value.orelse] if isinstance(value, ast.IfExp) else value.values
                sources = {b.id for b in branches if isinstance(b, ast.Name)} & (raw | constants)
            else:
                read = {n.id for n in walk(value) if isinstance(n, ast.Name)} - modules - constants
                sources = read if len(read) == 1 and read <= raw else set()
            for source in sources - {target}:
                made.setdefault((source, target), node.lineno)
        return made

    def neighbours(self, first, second) -> bool:
        """Whether two changes are of items side by side: the same list's, tuple's or call's (`[..., x2,
        y2, 1]`), or a matrix literal's entries one above the other (its translation column, `s * c[0]`
        over `s * c[1]`)."""
        edited = self._edited(first, second)
        if edited is None:
            return False
        (node_a, node_b), parents = edited
        a, b = (parents.get(id(node), (None, None, None)) for node in (node_a, node_b))
        if a[0] is not None and a[0] is b[0] and a[1] == b[1] and a[2] is not None and b[2] is not None \
                and abs(a[2] - b[2]) == 1:
            return True
        entries = [_entry_of_literal(node, parents) for node in (node_a, node_b)]
        if None in entries or entries[0][1] != entries[1][1] or abs(entries[0][0] - entries[1][0]) != 1:
            return False
        matrices = [_matrix_of(node, parents) for node in (node_a, node_b)]
        return matrices[0] is not None and matrices[0] is matrices[1]

    def twins_given(self, first, second) -> bool:
        """Whether two changes each give one name's use in one of two neighbouring items of a tuple or list
        a twin name of its own, at the same place of each (`((side - 1) / 2, (side - 1) / 2)` -> `width` in
        the first, `height` in the second): a pair (x, y) written with one name for both halves."""
        if not all(len(m.edits) == 1 and m.edits[0][2] == "other_name" and isinstance(m.edits[0][3], str)
                   for m in (first, second)) or not twin_names(first.edits[0][3], second.edits[0][3]):
            return False
        edited = self._edited(first, second)
        if edited is None:
            return False
        (one, other), parents = edited
        if not (isinstance(one, ast.Name) and isinstance(other, ast.Name) and one.id == other.id):
            return False
        items = [_item_of_pair(node, parents) for node in (one, other)]
        return None not in items and items[0][0] is items[1][0] and abs(items[0][1] - items[1][1]) == 1 \
            and items[0][2] == items[1][2]

    def feeds(self, first, second) -> bool:
        """Whether the statement ``first`` changes assigns a name the statement ``second`` changes reads
        (both in one def, ``first`` above): ``second`` works on what ``first`` makes."""
        edited = self._edited(first, second) if len(first.edits) == len(second.edits) == 1 else None
        if edited is None:
            return False
        made, using = (self._statement_node(node, edited[1]) for node in edited[0])
        if made is using or not isinstance(made, (ast.Assign, ast.AugAssign)) or made.lineno >= using.lineno:
            return False
        targets = made.targets if isinstance(made, ast.Assign) else [made.target]
        assigned = {n.id for t in targets for n in walk(t) if isinstance(n, ast.Name)}
        return any(isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load) and n.id in assigned for n in walk(using))

    def _edited(self, first, second):
        """((the node the first change edits, the second's), the def's parents), both in one def; or None."""
        (where_a, ordinal_a, _, _), (where_b, ordinal_b, _, _) = first.edits[0], second.edits[0]
        if where_a != where_b:
            return None
        nodes, parents = self._walk(where_a)
        if not (0 <= ordinal_a < len(nodes) and 0 <= ordinal_b < len(nodes)):
            return None
        return (nodes[ordinal_a], nodes[ordinal_b]), parents

    @staticmethod
    def _statement_node(node, parents):
        while not isinstance(node, ast.stmt) and id(node) in parents:
            node = parents[id(node)][0]
        return node

    def mirrored(self, first, second) -> bool:
        """Whether two changes are the same change of two statements written alike but for their names
        (`a = np.pad(a, ((h - a.shape[0], 0), ...))` beside `b = np.pad(b, ...)`: one image's line
        copied for the other's, the slip with it), at the same place of each."""
        edited = self._edited(first, second)
        if edited is None:
            return False
        (one, at_one), (other, at_other) = (self._place_in_statement(node, edited[1]) for node in edited[0])
        return one is not other and at_one == at_other and self._shape(one) == self._shape(other)

    def _place_in_statement(self, node, parents) -> tuple:
        """(the statement holding ``node``, its position among the statement's nodes), found once per node."""
        if id(node) not in self._places:
            statement = self._statement_node(node, parents)
            self._places[id(node)] = statement, next((i for i, held in enumerate(walk(statement)) if held is node), None)
        return self._places[id(node)]

    def _shape(self, statement) -> str:
        """:func:`_shape_of` ``statement``, made once per statement (asked for many pairs of changes)."""
        key = id(statement)
        if key not in self._shapes:
            self._shapes[key] = _shape_of(statement)
        return self._shapes[key]

    def slip(self, mutant) -> str:
        """What the mutant's (first) change does, alike for the same slip at two places: its payload,
        or for a name used in another's place the part of the name changed (`x2` -> `x1` and `y2` ->
        `y1` are both "2 -> 1": a line copied from image 2's with image 1's names half changed)."""
        where, ordinal, operator, payload = mutant.edits[0]
        nodes, _ = self._walk(where)
        old = nodes[ordinal] if 0 <= ordinal < len(nodes) else None
        if operator in ("summary", "divided_by_w", "true_division", "by_last", "ufunc_out", "empty_slice", "keep_axis",
                        "column_order", "grey", "whole_shape", "move_factor", "convert_first",
                        "precedence", "drop_term", "python_numbers", "middle_axis", "widen", "bracket",
                        "perspective_warp", "size_given", "x_difference", "colour_axis", "drop_w",
                        "power_xor", "half_pixel", "swap_axes", "stack_last", "own_values", "scale_inverse",
                        "zero_based", "focal_left_out", "key_order"):
            # (each array's own mean: `dst[0]` -> `dst_mean`, `src[0]` -> `src_mean`; each row divided
            # by the third: the change is written out whole, alike in kind only)
            return repr(operator)
        if operator == "one_of_two" and isinstance(old, ast.Call):
            # (the same side kept at two places: `max(h1, h2)` -> `h1` and `max(w1, w2)` -> `w1`)
            return repr((operator, _dotted(old.func), [ast.unparse(a) for a in old.args].index(payload)
                         if payload in [ast.unparse(a) for a in old.args] else payload))
        if operator == "drop_statement" and old is not None:
            # (a statement taken out at two places is one slip only where the two are written alike, names
            # apart: `x /= 2` and `y /= 2`; the two halves of a normalisation -- `T[:-1, :-1] *= s` and
            # `T[:-1, -1] = -s * c` -- are a step disabled, no slip made twice)
            return repr(("removed", _shape_of(old)))
        if operator == "axis" and isinstance(payload, list):
            # (an index moved to another axis, alike wherever it is: `pts[0]` and `pts[1]` both to columns)
            return repr(("axis", tuple(isinstance(part, str) and part == ":" for part in payload)))
        if operator != "other_name" or not isinstance(old, ast.Name) or not isinstance(payload, str):
            return repr(payload)
        a, b = old.id, payload
        head = len(os.path.commonprefix([a, b]))
        tail = len(os.path.commonprefix([a[head:][::-1], b[head:][::-1]]))
        return repr((a[head:len(a) - tail], b[head:len(b) - tail])) if head or tail else repr(payload)

    def _walk(self, where: str) -> tuple[list, dict]:
        """The def ``where``'s nodes in ast.walk order and their parents (empty when no such def)."""
        fn = self._defs.get(where)
        if fn is None:
            return [], {}
        if where not in self._walked:
            self._walked[where] = (list(walk(fn)), _parents(fn))
        return self._walked[where]

    def fix(self, mutant) -> Fix | None:
        """The mutant's changes shown in the student's code (None when one cannot be shown briefly)."""
        if mutant.key not in self.fixes and mutant.edits[0][2] in _IN_WORDS:
            self.fixes[mutant.key] = self._moved(mutant)
        if mutant.key not in self.fixes:
            try:
                shown = _together([self.shown(edit) for edit in mutant.edits])
            except (SyntaxError, ValueError, RecursionError):   # (a change that cannot be written is none)
                shown = [None]
            self.fixes[mutant.key] = None if any(each is None for each in shown) else \
                Fix(tuple(shown), mutant.where, mutant.operator, mutant.edits,
                    why=_why_it_mends(shown, self._defs.get(mutant.where)))
        return self.fixes[mutant.key]

    def skipped_step(self, mutant) -> tuple:
        """``(line, name, source, module names)`` where the mutant reads ``source`` in the place of ``name``,
        the value the def's last assignment of ``name`` before that place computes from ``source``
        (`homogeneous[:, :2]` -> `X[:, :2]` below `homogeneous = ... X ... @ M.T`): the step between them
        is skipped, and the module's own names that step reads (a constant matrix `M`); ``()`` otherwise."""
        where, ordinal, operator, payload = mutant.edits[0]
        if operator != "other_name" or len(mutant.edits) != 1 or not isinstance(payload, str):
            return ()
        nodes, parents = self._walk(where)
        node = nodes[ordinal] if 0 <= ordinal < len(nodes) else None
        if not isinstance(node, ast.Name):
            return ()
        above = parents.get(id(node), (None,))[0]
        while above is not None and not isinstance(above, ast.stmt):
            if isinstance(above, (ast.Compare, ast.BoolOp)) or (isinstance(above, ast.UnaryOp)
                                                                 and isinstance(above.op, (ast.Not, ast.Invert))):
                return ()   # (a name read in a test -- `depth[~(depth > 0)] = 0` -- selects; it skips no step)
            above = parents.get(id(above), (None,))[0]
        made = [n for n in nodes if isinstance(n, ast.Assign) and n.lineno < node.lineno
                and any(isinstance(t, ast.Name) and t.id == node.id for t in n.targets)]
        if not made:
            return ()
        step = max(made, key=lambda n: n.lineno)
        read = {n.id for n in walk(step.value) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}
        if payload not in read:
            return ()
        statement = node
        while statement is not None and not isinstance(statement, ast.stmt):
            statement = parents.get(id(statement), (None,))[0]
        if any(isinstance(n, ast.Name) and n.id == node.id and isinstance(n.ctx, ast.Load) and n.lineno > step.lineno
               and not (statement is not None and statement.lineno <= n.lineno <= (statement.end_lineno or statement.lineno))
               for n in nodes):
            return ()   # (the value is read elsewhere too -- `shift` moving the points and making a focal length --:
            # the step is needed there, and the change is of this one use of it)
        if _stacks(step.value, payload):
            return ()   # (a name made by stacking a column onto the other -- `Xh = [pts | 1]` -- holds it: its
            # column read from the other, `pts[:, -1]` for `Xh[:, -1]`, is another column, no step skipped)
        local = {n.id for n in nodes if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)} \
            | {a.arg for a in walk(self._defs[where].args) if isinstance(a, ast.arg)}
        module = {t.id for statement in self.tree.body if isinstance(statement, ast.Assign)
                  for t in statement.targets if isinstance(t, ast.Name)}
        constants = tuple(sorted(n for n in read if n in module and n not in local))
        return (step.lineno, node.id, payload, constants)

    def _moved(self, mutant) -> Fix | None:
        """A change of where statements are, told in words (the statements whole would be too long to
        show): the change's line is the moved statement's, its "after" the sentence."""
        where, ordinal, operator, payload = mutant.edits[0]
        nodes = self._walk(where)[0]
        if not 0 <= ordinal < len(nodes):
            return None
        edited = nodes[ordinal]
        if operator == "grey":
            image = " ".join(ast.unparse(edited.args[payload]).split())
            call = _dotted_call(edited)
            return Fix(((edited.lineno, f"{call}({image}, ...)", f"giving `{call}` the grey view of `{image}` "
                         f"(`cv2.cvtColor({image}, cv2.COLOR_BGR2GRAY)` where it has 3 channels, line {edited.lineno}"
                         "{inside})"),), where, operator, mutant.edits)
        if operator == "guard":
            divisor = " ".join(ast.unparse(edited.right).split())
            if len(divisor) > 40:
                return None
            return Fix(((edited.lineno, f"... / {divisor}", f"dividing by `{divisor}` only where it is > 0 (line "
                         f"{edited.lineno}{{inside}}; {'0' if payload == '0.0' else 'NaN'} elsewhere: "
                         f"`np.where({divisor} > 0, ..., {payload})`)"),), where, operator, mutant.edits)
        if operator == "keep_parameter":
            k, name, fresh = payload
            line = edited.body[k].lineno
            return Fix(((line, f"{name} = ...", f"giving each turn's value a name of its own (`{fresh} = ...` at line "
                         f"{line}{{inside}}, `{fresh}` read below it in the loop; the parameter `{name}`, overwritten "
                         f"at each turn, makes every turn after the first start from the turn before's value)"),),
                       where, operator, mutant.edits)
        if operator == "simultaneous":
            first, second = ast.unparse(edited.targets[0]), payload[1]
            together = f"{first}, {second} = ..., ..."
            return Fix(((edited.lineno, f"{first} = ...; {second} = ...",
                         f"assigning `{first}` and `{second}` together (`{together}`, line {edited.lineno}{{inside}}: "
                         f"`{second}` from the `{first}` of before that line, not the one it sets)"),),
                       where, operator, mutant.edits)
        _, text, line, side = payload
        shown = " ".join(text.split())
        if len(shown) > _SHOWN:
            shown = shown[:_SHOWN - 4].rsplit(" ", 1)[0] + " ..."
        block = {ast.For: "`for` loop", ast.While: "`while` loop", ast.If: "`if` block"}.get(type(edited), "block")
        said = {"move": f"moving `{shown}` (line {line}{{inside}}) {side} the {block} of line {edited.lineno}"
                        if isinstance(edited, (ast.For, ast.While, ast.If)) else
                        f"moving `{shown}` (line {line}{{inside}}) {side} line {edited.lineno}",
                "indent": f"moving `{shown}` (line {line}{{inside}}) into the {block} below it (line {edited.lineno}), "
                          "as its first statement: a new one for each turn" if side == "first" else
                          f"moving `{shown}` (line {line}{{inside}}) into the {block} above it (line {edited.lineno}), "
                          "as its last statement",
                "dedent": f"moving `{shown}` (line {line}{{inside}}) out of the {block} of line {edited.lineno}, "
                          "to just after it",
                "hoist": f"moving `{shown}` (line {line}{{inside}}) out of the {block} of line {edited.lineno}, to "
                         "just before it (made at each turn, the array keeps only the last turn's item)",
                "add_step": f"adding the step `{shown}` right after line {line}{{inside}}"
                            + (_FLOAT_WHY if _makes_float(text, self._defs) else "")}[operator]
        return Fix(((line, text, said),), where, operator, mutant.edits)

    def shown(self, edit) -> tuple[int, str, str] | None:
        """(line, before, after): the smallest expression or statement around the change that shows
        it (a name alone is ambiguous: `sl * sl`, not `sl`), before and after; None when the change
        cannot be shown in a short line."""
        where, ordinal, operator, payload = edit
        fn = self._defs.get(where)
        if fn is None:
            return None
        nodes, parents = self._walk(where)
        if not 0 <= ordinal < len(nodes):
            return None
        edited = nodes[ordinal]
        if operator == "drop_statement" and isinstance(edited, ast.If) and len(edited.body) == 1 \
                and isinstance(edited.body[0], ast.Raise):
            # (a test of the student's own that raises, taken out whole: "removing `if ...: raise ...`")
            test = " ".join(ast.unparse(edited.test).split())
            return (edited.lineno, f"if {test}: raise ...", "pass") if len(test) <= _SHOWN else None
        if operator == "drop_statement" and isinstance(edited, ast.If):
            # (a special case of the student's own taken out whole: "removing `if ...: ...`", its lines said)
            test = " ".join(ast.unparse(edited.test).split())
            last = max(getattr(s, "end_lineno", None) or s.lineno for s in edited.body)
            return (edited.lineno, f"if {test}: ... (lines {edited.lineno}-{last})", "pass") \
                if len(test) <= _SHOWN else None
        context = edited
        while isinstance(context, (ast.Name, ast.Constant, ast.Attribute, ast.keyword, ast.Slice)) \
                or (isinstance(context, ast.expr) and _width(context) < 12):
            parent = parents.get(id(context), (None,))[0]
            if parent is None or isinstance(parent, (ast.FunctionDef, ast.AsyncFunctionDef)) \
                    or (_width(parent) > _SHOWN and not isinstance(context, ast.Constant)):
                break   # (a number alone says nothing: its call is shown, long arguments as `...`)
            context = parent
        # (a subscript's tuple of slices is shown with what it indexes: `np.mgrid[0:rows, 0:cols]`, not `(0:rows, 0:cols)`)
        holder = parents.get(id(context), (None, None))
        if isinstance(context, ast.Tuple) and isinstance(holder[0], ast.Subscript) and holder[1] == "slice" \
                and _width(holder[0]) <= _SHOWN:
            context = holder[0]
        # (the same code twice in the statement -- `[r * np.cos(a), r * np.cos(a)]` -- is shown with
        # enough around it to say which one)
        statement = context
        while not isinstance(statement, ast.stmt) and id(statement) in parents:
            statement = parents[id(statement)][0]
        whole = ast.unparse(statement)
        while whole.count(ast.unparse(context)) > 1:
            parent = parents.get(id(context), (None,))[0]
            if parent is None or isinstance(parent, (ast.stmt, ast.FunctionDef)) or _width(parent) > _SHOWN:
                break
            context = parent
        before = ast.unparse(context)
        copied = copy_tree(context)
        position = next(i for i, node in enumerate(walk(context)) if node is edited)
        target = list(walk(copied))[position]
        made = _MAKE[operator](target, payload)
        if target is copied:
            copied = made
        else:
            _replace(_parents(copied), target, made)
        after = ast.unparse(ast.fix_missing_locations(copied))
        before, after = (" ".join(text.split()) for text in (before, after))
        # (a tuple written without brackets -- `height, width = dsize` -- is shown without them, as it is written)
        if isinstance(context, ast.Tuple) and before[:1] == after[:1] == "(" and before[-1:] == after[-1:] == ")":
            segment = ast.get_source_segment(self.text, context)
            if segment is not None and not segment.lstrip().startswith("("):
                before, after = before[1:-1], after[1:-1]
        # (a minus put on a term is shown as the student would write it: `z0 + -c` is `z0 - c`)
        after = re.sub(r" - -(?=[\w(])", " + ", re.sub(r" \+ -(?=[\w(])", " - ", after))
        if before == after:
            return None
        # (a long line: its calls with the unchanged arguments as `...` where that fits whole, so the
        # function called stays in sight; else cut to the change and a few characters around it)
        if operator == "chain_order" and payload == "outer" and max(len(before), len(after)) > _SHOWN:
            # (the outer factors exchanged: the middle one, where it stays, as "...")
            context, copied = (ast.BinOp(ast.BinOp(n.left.left, ast.MatMult(), _ELLIPSIS), ast.MatMult(), n.right)
                               if isinstance(n, ast.BinOp) and isinstance(n.left, ast.BinOp) else n
                               for n in (context, copied))
            before, after = (" ".join(ast.unparse(n).split()) for n in (context, copied))
            if max(len(before), len(after)) <= 2 * _SHOWN:   # (two whole factors: no shorter way to show it)
                return (getattr(edited, "lineno", None) or getattr(context, "lineno", fn.lineno), before, after)
        if operator in ADDITIONS | {"measure_first", "sibling_line"} and len(before) <= 2 * _SHOWN \
                and len(after) <= 2 * _SHOWN:
            # (the twin's step added beside the line doubles it, a measure moved inside a filter rewrites both
            # operands, a line written as its siblings are rewrites it: shown whole, as the student would write it)
            return (getattr(edited, "lineno", None) or getattr(context, "lineno", fn.lineno), before, after)
        whole = _abbreviated(context, copied) if max(len(before), len(after)) > _SHOWN else None
        shortened = (whole if whole is not None and max(map(len, whole)) <= _SHOWN else None) \
            or _elided(before, after) or _elided(*_abbreviated(context, copied))
        if shortened is None:
            return None
        return (getattr(edited, "lineno", None) or getattr(context, "lineno", fn.lineno), *shortened)


REFUTED = "repair refuted"   # the shared key of (a change as told, whether a hidden check refuted it)
HEAD = "Trying small changes to your code"


def _kept_by_mask(statement) -> str | None:
    """The mask a statement filters by -- `a = a[m]`, `a, b = a[m], b[m]` (each value the entries of the mask
    ``m``, a name) -- or None."""
    if not isinstance(statement, ast.Assign) or len(statement.targets) != 1:
        return None
    values = statement.value.elts if isinstance(statement.value, ast.Tuple) else [statement.value]
    masks = {v.slice.id for v in values if isinstance(v, ast.Subscript) and isinstance(v.slice, ast.Name)}
    return masks.pop() if len(masks) == 1 and all(isinstance(v, ast.Subscript) for v in values) else None


def _feeding(nodes, statement, name: str) -> set[int]:
    """The lines, before ``statement``, of the statements ``name``'s value there is computed from: those
    assigning it, or writing into it in place (`np.minimum.at(nearest, ...)`), followed back through every
    name they read (one pass, from the statement back: linear in the def)."""
    before = sorted((n for n in nodes if isinstance(n, (ast.Assign, ast.AugAssign, ast.Expr))
                     and n.lineno < statement.lineno), key=lambda n: n.lineno, reverse=True)
    wanted, lines = {name}, set()
    for step in before:
        if isinstance(step, ast.Expr):
            call = step.value
            written = {call.args[0].id} if isinstance(call, ast.Call) and call.args \
                and isinstance(call.args[0], ast.Name) else set()
        else:
            targets = step.targets if isinstance(step, ast.Assign) else [step.target]
            written = {n.id for t in targets for n in walk(t) if isinstance(n, ast.Name)}
        if written & wanted:
            lines.add(step.lineno)
            wanted |= {n.id for n in walk(step) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}
    return lines


def _refuted(trial, fix, function: str) -> None:
    """Keep, for the grading's end, that a change told on an earlier check of ``function`` does not mend
    this one (the student's code is the same in every check: the change is no account of it)."""
    if fix is not None:
        trial.sandbox.shared.setdefault(REFUTED, []).append(
            (fix.told(function), bool(getattr(getattr(trial, "check", None), "hidden", False))))


def take_back_refuted(results, refuted) -> None:
    """One account per function: a repair told on a check (``results``: check results) that a later check
    of the same function refuted (``refuted``: (the change as told, by a hidden check) pairs) is taken
    back, with its sentence; a hidden check's refutation changes no public check's words. In place."""
    def told(result) -> str:
        first = result.message.partition("\n")[0]
        return first.split(f" {HEAD}", 1)[1] if f" {HEAD}" in first else ""

    def refuted_for(result, text: str) -> bool:
        return any(change in text for change, by_hidden in refuted if result.hidden or not by_hidden)

    taken = [result for result in results if told(result) and refuted_for(result, told(result))]
    kept = [result for result in results if told(result) and not refuted_for(result, told(result))]
    for result in taken:
        first, newline, rest = result.message.partition("\n")
        sentence = told(result)
        result.message = first.split(f" {HEAD}", 1)[0] + newline + rest
        result.mistake = "" if result.mistake.startswith(MISTAKE) else result.mistake
        # (the change another check of the function confirmed, where one is, takes its place: one
        # mistake, one repair told -- a public check's from a public check only)
        function = re.search(r"makes `(\w+)`", sentence)
        other = next((k for k in kept if function and f"makes `{function.group(1)}`" in told(k)
                      and (result.hidden or not k.hidden) and not refuted_for(result, told(k))), None)
        if other is not None:
            lead, _, tail = result.message.partition("\n")
            result.message = f"{lead} {HEAD}{told(other)}" + ("\n" + tail if tail or newline else "")
            result.mistake = other.mistake if not result.mistake else result.mistake


def student_steers(trial, repair: Repair) -> bool:
    """Whether every fix of ``repair`` mends by making a step of the student's code do nothing
    (:func:`_undoes_a_step`)."""
    student = _student_code(trial)
    if student is None:
        return False
    return all(_undoes_a_step(student, _as_mutant(fix), fix) for fix in repair.fixes)


def _as_mutant(fix: Fix):
    """A stand-in mutant for a fix (its edits), for the readings of the student's code that take one."""
    from types import SimpleNamespace

    return SimpleNamespace(edits=fix.edits)


def _undoes_a_step(student, mutant, fix: Fix) -> bool:
    """Whether a change mends by making a step of the code do nothing: steering round a branch
    (:meth:`_Student.steers_a_branch`) or writing a permutation as the identity (`order = [0, 2, 1]` ->
    `[0, 1, 2]`): the step's own slip stays, where a change inside it mends it."""
    # (and a special case's whole block taken out -- `if ...: ...` -- which a change inside it mends too)
    # (a test given its twin's half steers round the branch only where the twin says it must: the test is the slip)
    if fix.operator == "twin_test":
        return False
    return student.steers_a_branch(mutant) or _neutralises_a_pair(student, mutant) \
        or any(_identity_order(after) and not _identity_order(before)
               or _assigns_itself(after) for _, before, after in fix.changes) \
        or (fix.operator == "drop_statement" and fix.changes[0][1].startswith("if ") and " ... (lines " in fix.changes[0][1]
            and not student.extra_block(mutant))


def _neutralises_a_pair(student, mutant) -> bool:
    """Whether a change makes a value neutral (1, 0) that the def reads at two places or more -- a scale applied,
    then undone (`norms = np.linalg.norm(A, axis=0)` dividing A's columns and multiplying the solution): both steps
    then do nothing, the slip in one of them stays (`z * norms` where `z / norms` undoes the scaling)."""
    if len(mutant.edits) != 1 or mutant.edits[0][2] != "neutral":
        return False
    where, ordinal = mutant.edits[0][:2]
    fn = student._defs.get(where)
    nodes, parents = student._walk(where)
    node = nodes[ordinal] if fn is not None and 0 <= ordinal < len(nodes) else None
    statement = parents.get(id(node), (None,))[0] if node is not None else None
    if not (isinstance(statement, ast.Assign) and statement.value is node and len(statement.targets) == 1
            and isinstance(statement.targets[0], ast.Name)):
        return False
    name = statement.targets[0].id
    return sum(isinstance(n, ast.Name) and n.id == name and isinstance(n.ctx, ast.Load) for n in walk(fn)) >= 2


def _one_argument_twice(fix: Fix) -> bool:
    """Whether a name given in another's place makes a call take one name at two of its positions where it took
    two (`cv2.addWeighted(overlay, 0.6, image, 0.4, 0)` -> `(overlay, 0.6, overlay, ...)`: a blend of the drawing
    with itself, which works round the blend)."""
    if fix.operator != "other_name":
        return False

    def repeated(text: str) -> int:
        try:
            tree = parse(text)
        except (SyntaxError, ValueError, RecursionError, MemoryError):
            return 0
        return sum(len(names) - len(set(names)) for call in walk(tree) if isinstance(call, ast.Call)
                   for names in [[a.id for a in call.args if isinstance(a, ast.Name)]])
    return any(repeated(after) > repeated(before) for _, before, after in fix.changes)


def _lines_changed(student, mutant) -> set:
    """The (def, line) pairs whose code a change rewrites (a statement moved: its own line)."""
    fix = student.fix(mutant)
    return {(fix.where, line) for line, _, _ in fix.changes} if fix is not None else set()


def _agreement_at(operator: str, name: str) -> int | None:
    """Where in a name of a mistake the first of the words an operator's sentences use stands, as a word or a
    word's start ("squared" for "square"; not "pointing" for "int", nor a letter or a digit alone); None where the
    name uses none."""
    said = name.lower()
    found = [match.start() for word in OPERATORS.get(operator, ()) if len(word) >= 3
             for match in [re.search(rf"(?<![a-z0-9_]){re.escape(word)}", said)] if match]
    return min(found) if found else None


def _agrees_with(operator: str, name: str) -> bool:
    """Whether a name of a mistake uses one of the words an operator's sentences use (:func:`_agreement_at`)."""
    return _agreement_at(operator, name) is not None


_NEUTRAL_RIGHT = {ast.FloorDiv: 1, ast.Div: 1, ast.Mult: 1, ast.Pow: 1, ast.Add: 0, ast.Sub: 0}
_NEUTRAL_LEFT = {ast.Mult: 1, ast.Add: 0}


def _neutral_operands(text: str) -> int:
    """How many operations in ``text`` take a written neutral operand (`x / 1.0`, `n - 0`, `1 * x`)."""
    try:
        tree = parse(text.strip().rstrip(":"))
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return 0

    def neutral(operand, table, op) -> bool:
        return isinstance(operand, ast.Constant) and type(operand.value) in (int, float) \
            and type(op) in table and operand.value == table[type(op)]
    return sum(isinstance(node, ast.BinOp) and (neutral(node.right, _NEUTRAL_RIGHT, node.op)
                                                or neutral(node.left, _NEUTRAL_LEFT, node.op))
               for node in walk(tree))


def _neutral_operand_written(fix: Fix) -> bool:
    """Whether a change writes an operation with a neutral operand (`total / 2.0` -> `total / 1.0`): code nobody
    writes, that mends by accident where it mends (a sum of two images left undivided passes the checks of the
    geometry, and saturates the overlap); a change taking the operation out says the same in the student's terms."""
    return any(_neutral_operands(after) > _neutral_operands(before) for _, before, after in fix.changes)


def _floor_kept(fix: Fix, floors: set) -> bool:
    """Whether a change keeps a floor division on a line where making it a true division mends too."""
    return fix.operator != "true_division" and fix.changes[0][0] in floors and "//" in fix.changes[0][2]


def _assigns_itself(text: str) -> bool:
    """Whether ``text`` is an assignment of names to themselves (`P2, P1 = (P2, P1)`): a statement doing nothing."""
    try:
        tree = parse(text)
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return False
    statement = tree.body[0] if len(tree.body) == 1 else None
    if not (isinstance(statement, ast.Assign) and len(statement.targets) == 1):
        return False
    target, value = statement.targets[0], statement.value
    names = lambda node: [getattr(e, "id", None) for e in (node.elts if isinstance(node, ast.Tuple) else [node])]  # noqa: E731
    return None not in names(target) and names(target) == names(value)


def _identity_order(text: str) -> bool:
    """Whether ``text`` holds a literal list or tuple 0, 1, ..., n - 1 (n >= 2) of integers in order."""
    try:
        tree = parse(text.strip().rstrip(":"))
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return False
    return any(isinstance(node, (ast.List, ast.Tuple)) and len(node.elts) >= 2
               and [getattr(e, "value", None) for e in node.elts] == list(range(len(node.elts)))
               for node in walk(tree))


def _read(statement) -> set:
    """The names a statement reads (a subscript assignment's `s` in `s[0] = 0` included)."""
    return {node.id for node in walk(statement) if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load)}


def _item_of_pair(node, parents) -> tuple | None:
    """(the tuple or list ``node`` lies in, the index of its item there, (that item's code with names masked,
    ``node``'s position in it)), or None where no tuple or list holds it within its statement."""
    item = node
    while id(item) in parents:
        parent, _, index = parents[id(item)]
        if isinstance(parent, (ast.Tuple, ast.List)) and index is not None:
            return parent, index, (_shape_of(item), next(i for i, held in enumerate(walk(item)) if held is node))
        if isinstance(parent, ast.stmt):
            return None
        item = parent
    return None


def _dotted_call(call: ast.Call) -> str:
    """`cv2.cornerSubPix`, `matcher.compute`: the function a call calls, as written."""
    return ast.unparse(call.func) if len(ast.unparse(call.func)) <= 40 else "the call"


def _call_name(call: ast.Call) -> str:
    """The called function's own name (`np.argmin` -> `argmin`, `x.argmin` -> `argmin`)."""
    func = call.func
    return func.attr if isinstance(func, ast.Attribute) else func.id if isinstance(func, ast.Name) else ""


def _shape_of(statement) -> str:
    """A statement's code with every name the same: two lines written alike for two images compare equal."""
    masked = copy_tree(statement)
    for node in walk(masked):
        if isinstance(node, ast.Name):
            node.id = "_"
    return ast.dump(masked)


def _matrix_of(node, parents):
    """The nested list literal an entry (or its minus) belongs to."""
    for _ in range(3):
        node = parents.get(id(node), (None,))[0]
        if isinstance(node, ast.List) and node.elts and all(isinstance(row, ast.List) for row in node.elts):
            return node
    return None


def _twin_swap(fix: "Fix") -> bool:
    """Whether the fix's one change puts a name for its twin (:func:`.operators.twin_names`)."""
    if fix.operator not in ("other_name", "swap_names", "other_name_line") or len(fix.changes) != 1:
        return False
    before, after = (re.findall(r"\w+", text) for text in fix.changes[0][1:])
    pairs = [(a, b) for a, b in zip(before, after) if a != b]
    return len(before) == len(after) and len(pairs) == 1 and twin_names(*pairs[0])


def _together(shown: list) -> list:
    """Changes shown in the same code of the same line told as one (`[..., x2, y2, 1]` to `[..., x1, y1,
    1]`), where they change different characters of it."""
    if len(shown) != 2 or any(each is None for each in shown) or shown[0][:2] != shown[1][:2]:
        return shown
    (line, before, first), (_, _, second) = shown
    edits = []
    for after in (first, second):
        matcher = difflib.SequenceMatcher(None, before, after, autojunk=False)
        edits += [(i1, i2, after[j1:j2]) for tag, i1, i2, j1, j2 in matcher.get_opcodes() if tag != "equal"]
    edits.sort()
    if any(a[1] > b[0] or (a[0] == a[1] == b[0]) for a, b in zip(edits, edits[1:])):
        return shown   # (they overlap: told apart)
    merged, at = [], 0
    for start, end, text in edits:
        merged += [before[at:start], text]
        at = end
    return [(line, before, "".join(merged) + before[at:])]


def _first_run(fn) -> int:
    """The line of the first statement a call of ``fn`` runs (a docstring is not run)."""
    body = fn.body[1:] if len(fn.body) > 1 and isinstance(fn.body[0], ast.Expr) \
        and isinstance(fn.body[0].value, ast.Constant) and isinstance(fn.body[0].value.value, str) else fn.body
    return body[0].lineno


def _width(node) -> int:
    """How many characters ``node`` takes in the source (a node over several lines: many)."""
    if getattr(node, "end_lineno", None) is None or node.lineno != node.end_lineno:
        return 10**6 if getattr(node, "end_lineno", None) is not None else len(ast.unparse(node))
    return node.end_col_offset - node.col_offset


_READ: OrderedDict = OrderedDict()   # digest of (text, api) -> _Student (a class's copies of one file)
_READ_LOCK = threading.Lock()


def _student_code(trial) -> _Student | None:
    """The student's module the trial's sandbox holds, parsed within the reading bounds, and the
    changes the operators make to its API functions; None when there is none or it is too large."""
    folder = getattr(getattr(trial, "sandbox", None), "submission_dir", None)
    if folder is None:
        return None
    try:
        path = Path(folder) / f"{trial.lab.module}.py"
        if path.stat().st_size > MAX_SOURCE_BYTES:
            return None
        text = path.read_bytes().decode("utf-8", errors="replace")
    except (OSError, TypeError, ValueError):
        return None
    api = sorted(name for exercise in trial.lab.exercises.values() for name in exercise.signatures)
    key = hashlib.sha256("\0".join([text, *api]).encode()).digest()
    with _READ_LOCK:
        if key in _READ:
            _READ.move_to_end(key)
            return _READ[key]
    read = None
    try:
        tree = parse(text)   # the student's text: within the bounds, under the parse lock
        if sum(1 for _ in walk(tree)) <= MAX_NODES:
            read = _Student(text, tree, api)
            model = naming.model_for(trial.lab)
            read.reference_parts = _named_parts(model.source) if model is not None else frozenset()
            read.reference_source = model.source if model is not None else ""
    except Exception:  # noqa: BLE001 - code the operators cannot read has no repairs (said once, not per check)
        read = None
    with _READ_LOCK:
        _READ[key] = read
        while len(_READ) > 8:
            _READ.popitem(last=False)
    return read


@functools.lru_cache(maxsize=8)
def _reference_tree(source: str) -> ast.Module:
    return parse(source)   # (the reference: trusted, the grader's own; parsed under the lock all parses take)


def _departs(fix: Fix, reference_source: str) -> bool:
    """Whether ``fix`` rewrites code the reference's def of that name writes word for word
    (:meth:`_Student.departs_from_reference`)."""
    if not reference_source or fix.operator in _IN_WORDS:
        return False
    written = _reference_texts(reference_source).get(fix.where, frozenset())
    return any(before in written and after not in written for _, before, after in fix.changes)


def _extra_step(fix: Fix, reference_source: str, function: str) -> bool:
    """Whether a removal takes out an operation of a kind that the reference's ``function``, and every def
    it runs, never does (`T @ H` -> `H` where the reference warps by H as given): the step taken out is one
    the student added, so its removal is the fix -- not a compensation, as taking out a division the
    reference makes too would be (a division by a w the student made Z)."""
    if fix.operator == "extra_step":
        return True   # (a rebinding the reference's def has no counterpart of: aligned.py)
    if not reference_source or fix.operator not in REMOVALS:
        return False
    removed = Counter()
    for _, before, after in fix.changes:
        try:
            removed.update(_operations(before))
            removed.subtract(_operations(after))
        except (SyntaxError, ValueError, RecursionError):
            return False
    kinds = {kind for kind, count in removed.items() if count > 0}
    return bool(kinds) and not kinds & _reference_operations(reference_source, function)


def _operations(text: str) -> Counter:
    """The kinds of arithmetic in a piece of code (`@`, `/`, `*`, `+`, `-`), counted."""
    return Counter(type(node.op).__name__ for node in walk(parse(text)) if isinstance(node, (ast.BinOp, ast.AugAssign)))


@functools.lru_cache(maxsize=64)
def _reference_operations(source: str, function: str) -> frozenset:
    """The kinds of arithmetic the reference's ``function`` and the defs it runs do."""
    defs = _defs(_reference_tree(source))
    return frozenset(type(node.op).__name__ for name in runs(defs, function) for node in walk(defs[name])
                     if isinstance(node, (ast.BinOp, ast.AugAssign)))


@functools.lru_cache(maxsize=8)
def _reference_shapes(source: str) -> frozenset:
    """The reference's expressions with an operation in them, names aside (:func:`naming._alike`)."""
    return frozenset(naming._alike(node) for fn in _defs(_reference_tree(source)).values() for node in walk(fn)
                     if isinstance(node, (ast.BinOp, ast.Call, ast.Compare, ast.Subscript)))


# a point array divided by its own last coordinate (`x[:, :2] / x[:, 2:3]`, `p[:2] / p[2]`): the step that
# leaves homogeneous coordinates, right wherever it is written
_DEHOMOGENISED = re.compile(r"^\(?\s*(\w+)\[[^\]]*:\s*(\d)\s*\]\s*\)?\s*/\s*\(?\s*\1\[[^\]]*\b\2\b")


def _dehomogenisation_dropped(fix: "Fix") -> bool:
    """Whether the fix takes out the division of points by their last (homogeneous) coordinate: where
    that mends, the matrix or the points' last coordinate is wrong (a camera whose last row reads Z),
    and the division compensates nothing -- it is the recipe."""
    return fix.operator == "drop_division" and len(fix.changes) == 1 \
        and _DEHOMOGENISED.match(fix.changes[0][1].strip()) is not None


@functools.lru_cache(maxsize=8)
def _reference_texts(source: str) -> dict[str, frozenset]:
    """def name -> the code of each of its statements and expressions with an operation in it
    (``ast.unparse`` forms, as :class:`Fix` shows the student's)."""
    texts = {}
    for name, fn in _defs(_reference_tree(source)).items():
        texts[name] = frozenset(ast.unparse(node) for node in walk(fn)
                                if isinstance(node, (ast.stmt, ast.expr)) and node is not fn
                                and not isinstance(node, (ast.Name, ast.Constant, ast.Attribute)))
    return texts


@functools.lru_cache(maxsize=8)
def _named_parts(source: str) -> frozenset:
    """``(name, (part, ...))`` of each name the reference unpacks into named parts (``cols, rows =
    pattern_size``); ``("", (part, ...))`` for the names it unpacks anything else into, a loop's too
    (``k1, k2, p1, p2, k3 = ...``, ``for x, y in pts``)."""
    try:
        tree = parse(source)
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return frozenset()
    named = set()
    for node in walk(tree):
        target, value = (node.targets[0], node.value) if isinstance(node, ast.Assign) and len(node.targets) == 1 \
            else (node.target, None) if isinstance(node, ast.For) else (None, None)
        if isinstance(target, (ast.Tuple, ast.List)) and all(isinstance(t, ast.Name) for t in target.elts):
            parts = tuple(t.id for t in target.elts)
            named.add((_value_key(value), parts))
            if isinstance(value, ast.Name):
                named.add((value.id, parts))
    return frozenset(named)


_ROWS_FIRST = {"nonzero", "argwhere", "where", "indices", "mgrid", "unravel_index"}


def _value_key(value) -> str:
    """What kind of value is unpacked, for comparing namings: "shape" for an array's shape or indices
    (rows first: the slip `w, h = image.shape[:2]`, `for x, y in np.argwhere(mask)` makes), "" for
    anything else."""
    rows_first = lambda n: (isinstance(n, ast.Attribute) and n.attr == "shape") or (  # noqa: E731
        isinstance(n, ast.Call) and _call_name(n).rsplit(".", 1)[-1] in _ROWS_FIRST)
    return "shape" if value is not None and any(rows_first(n) for n in walk(value)) else ""


_AXIS_ORDER = (("x", "y"), ("u", "v"), ("x", "z"), ("y", "z"))
# A shape's two sides by their own words, rows first (`h, w = image.shape[:2]`, `rows, cols`,
# `height1, width1`): unpacked so, the names are right whatever the reference calls them.
_ROWS_THEN_COLUMNS = (("height", "width"), ("rows", "cols"), ("rows", "columns"), ("nrows", "ncols"),
                      ("n_rows", "n_cols"), ("ny", "nx"), ("h", "w"), ("H", "W"))


def _names_as_written(names, reference_parts, value=None) -> bool:
    """Whether names a value is unpacked into are right by their own words: as the reference writes
    them for a value of the same kind (in that order), or two of them an axis pair in its order (`x,
    y`, `x1, y1`, `u, v`). (An array's shape is another kind: `w, h = image.shape[:2]` is the slip,
    wherever the reference writes `w, h = dsize`.)"""
    if _value_key(value) == "shape":
        return (_value_key(value), tuple(names)) in reference_parts or _rows_then_columns(names)
    if len(names) >= 2 and ("", tuple(names)) in reference_parts:
        return True
    # (every axis pair among them in its order, one at least: `X, Y, Z` as `x, y`, a point's coordinates
    # in capitals; `Y, X, Z` holds X before Z, and Y before X)
    def in_order(a, b) -> bool:
        a, b = (a.lower(), b.lower()) if a.isupper() and b.isupper() else (a, b)
        return len(a) == len(b) and any(a.replace(first, "\0", 1) == b.replace(second, "\0", 1)
                                        and a.count(first) == 1 for first, second in _AXIS_ORDER)
    pairs = list(itertools.combinations(names, 2))
    return any(in_order(a, b) for a, b in pairs) and not any(in_order(b, a) for a, b in pairs)


# Parts of a value in the order it holds them, by the start of their names: OpenCV's channels, a shape's
# axes, OpenCV's distortion coefficients.
_CHANNELS = (("b", "g", "r"), ("b", "g", "r", "a"))
_AXES = (("h", "w"), ("h", "w", "c"), ("height", "width"), ("height", "width", "c"), ("rows", "cols"),
         ("rows", "cols", "c"), ("n_rows", "n_cols"), ("nrows", "ncols"), ("r", "c"))
_DISTORTION = (("k1", "k2", "p1", "p2"), ("k1", "k2", "p1", "p2", "k3"))
_X_NAMES = {"x", "u", "col", "column", "xs", "us", "cols", "x_img", "px"}
_Y_NAMES = {"y", "v", "row", "ys", "vs", "rows", "y_img", "py"}
_X_WORDS = {"width", "cols", "columns", "ncols"}   # words that say an axis within a longer name (`missing_cols`)
_Y_WORDS = {"height", "rows", "nrows"}


def _on_axis(name: str, axis: set) -> bool:
    """Whether ``name`` (lowered) is one of ``axis``'s names, or has one of its words between underscores."""
    return name in axis or any(word in (_X_WORDS | _Y_WORDS) & axis for word in re.split(r"[_\d]+", name))


def _in_known_order(names, value) -> bool:
    """Whether ``names`` unpack ``value`` in the order it is known to hold its parts: `b, g, r` (or `blue,
    green, red`) from cv2.split, `h, w` (`rows, cols`, `height, width`) from a shape, `k1, k2, p1, p2, k3`
    from anything."""
    lowered = [n.lower().strip("_") for n in names]
    if any(tuple(n[:len(k)] for n, k in zip(lowered, known)) == known and len(known) == len(lowered)
           for known in _DISTORTION):
        return True
    if isinstance(value, ast.Call) and _dotted(value.func).rsplit(".", 1)[-1] == "split" \
            and _dotted(value.func).startswith(("cv2.", "cv.")):
        return any(len(known) == len(lowered) and all(n.startswith(k) for n, k in zip(lowered, known))
                   for known in _CHANNELS)
    if isinstance(value, ast.Tuple) and len(value.elts) == len(lowered) == 2:
        # (`col, row = u / w, v / w`: each name says the axis of the value it takes -- x, u, col; y, v, row)
        read = [next((n.id.lower() for n in walk(e) if isinstance(n, ast.Name)), "") for e in value.elts]
        if all(name in axis and given in axis for name, given, axis in zip(lowered, read, (_X_NAMES, _Y_NAMES))):
            return True
        # (or by a word of each, in either order: `missing_rows, missing_cols = height - ..., width - ...`)
        axes = (_X_NAMES | _X_WORDS, _Y_NAMES | _Y_WORDS)
        if all(any(_on_axis(name, axis) and _on_axis(given, axis) for axis in axes) for name, given in zip(lowered, read)):
            return True
    text = ast.unparse(value)
    if re.search(r"\.shape\b|\bnp\.shape\(", text):
        return any(len(known) == len(lowered) and all(n == k or (len(k) == 1 and n.startswith(k) and len(n) <= 3)
                                                     for n, k in zip(lowered, known)) for known in _AXES)
    return False


def _arctan2_ordered(fix: "Fix") -> bool:
    """Whether the change exchanges arctan2's two arguments into its order by their names: `arctan2(x, y)`
    -> `arctan2(y, x)` (NumPy's and math's arctan2 take y first)."""
    def pair(text):
        found = re.search(r"\b(?:arctan2|atan2)\(\s*(\w+)[^,()]*,\s*(\w+)", text)
        return found.groups() if found else None
    if fix.operator not in _EXCHANGES or len(fix.changes) != 1:
        return False
    before, after = pair(fix.changes[0][1]), pair(fix.changes[0][2])
    return before is not None and after is not None and after == before[::-1] \
        and after[0].lower() in _Y_NAMES and after[1].lower() in _X_NAMES


def _rows_then_columns(names) -> bool:
    """Whether the first two names are a shape's sides in its order by their own words (`h, w`,
    `height_left, width_left`, `rows, cols`), the rest of each name alike."""
    if len(names) < 2:
        return False
    a, b = names[0], names[1]
    for rows, columns in _ROWS_THEN_COLUMNS:
        for case in (str, str.lower):
            if case(a).startswith(rows) and case(b).startswith(columns) \
                    and case(a)[len(rows):] == case(b)[len(columns):] and not case(a)[len(rows):].isalpha():
                return True
    return False


_AROUND = 30   # characters kept on each side of a change shown in a long line


def _abbreviated(before, after) -> tuple[str, str]:
    """``before`` and ``after`` (nodes) written with the long arguments the change leaves as they were
    as "...": `cv2.blur(diff, ..., borderType=...) ** 2` -> `cv2.blur(diff ** 2, ..., borderType=...)`."""
    kept = _arguments(before) & _arguments(after)   # (the same call's same argument, on both sides)

    def cut(node) -> str:
        node = copy_tree(node)
        for call, function in _calls_counted(node):
            call.args = [_ELLIPSIS if (function, i, ast.dump(a)) in kept and len(ast.unparse(a)) > 8 else a
                         for i, a in enumerate(call.args)]
            unchanged = [(function, k.arg, ast.dump(k.value)) in kept for k in call.keywords]
            if call.keywords and all(unchanged):   # keywords as they were, and the arguments' tail: one "..."
                call.keywords = []
                while call.args and call.args[-1] is _ELLIPSIS:
                    call.args.pop()
                call.args.append(_ELLIPSIS)
            for keyword in call.keywords:
                if (function, keyword.arg, ast.dump(keyword.value)) in kept and len(ast.unparse(keyword.value)) > 8:
                    keyword.value = _ELLIPSIS
        return " ".join(ast.unparse(ast.fix_missing_locations(node)).split())

    return cut(before), cut(after)


_ELLIPSIS = ast.Constant(...)


def _calls_counted(node) -> list:
    """(call, its function with the how-many-th call of that function it is) of every call in ``node``:
    two calls of one function moved to each other's place (`T(-c) @ R @ T(c)` -> `T(c) @ R @ T(-c)`)
    keep their arguments apart."""
    seen: Counter = Counter()
    counted = []
    for call in walk(node):
        if isinstance(call, ast.Call):
            function = ast.dump(call.func)
            counted.append((call, (function, seen[function])))
            seen[function] += 1
    return counted


def _arguments(node) -> set:
    """(function and its count, position or keyword, argument) of every call in ``node`` (dumped)."""
    return {(function, i, ast.dump(a)) for call, function in _calls_counted(node) for i, a in enumerate(call.args)} | \
        {(function, k.arg, ast.dump(k.value)) for call, function in _calls_counted(node) for k in call.keywords}


def _elided(before: str, after: str) -> tuple[str, str] | None:
    """``before`` and ``after`` shortened to the change and :data:`_AROUND` characters on each side
    ("..." for what is left out) when either is longer than :data:`_SHOWN`; None when even that is."""
    if len(before) <= _SHOWN and len(after) <= _SHOWN:
        return before, after
    prefix = len(os.path.commonprefix([before, after]))
    suffix = len(os.path.commonprefix([before[prefix:][::-1], after[prefix:][::-1]]))
    start = max(0, prefix - _AROUND)
    if start:   # at a word's start, not inside a name
        space = before.find(" ", start, prefix)
        start = space + 1 if space != -1 else start
    cut = max(0, suffix - _AROUND)
    if cut:
        space = before.rfind(" ", len(before) - suffix, len(before) - cut)
        cut = len(before) - space if space != -1 else cut
    shortened = [("... " if start else "") + text[start:len(text) - cut] + (" ..." if cut else "")
                 for text in (before, after)]
    return None if max(map(len, shortened)) > _SHOWN else (shortened[0], shortened[1])


# ------------------------------------------------------------------ right answers
def right(value, reference, student=None, confirming: bool = False, projective: bool = True) -> bool:
    """Whether a variant's answer is the reference's.

    Exactly, up to rounding: images within a grey level on average and nowhere drawn otherwise;
    numbers entry by entry within 1e-4 of their size (1e-6 of the answer's largest), small matrices
    up to scale and sign too (unless ``projective`` is False: where the student's answer is the
    reference's up to scale, scale is their mistake). Or closely -- images within 3 grey levels, numbers within 1% -- where
    the student's code differs from the reference's legitimately (another normalisation, their own
    interpolation): on a failing input, when the variant is also far nearer the reference than the
    student's own answer (``student``: 100 times for numbers, 30 for images); on a confirmation
    input (``confirming``), alone (the failing inputs showed the change is what mends the answers).
    An error is never right."""
    if naming.error_kind(value) is not None or naming.error_kind(reference) is not None:
        return False
    if naming.has_image(reference) and _kinds(value) != _kinds(reference):
        return False   # (an image of floats where 8 bits are asked is not right however near its values)
    if _within(value, reference, rtol=1e-4, grey=1.0, projective=projective):
        return True
    if student is None and not confirming:
        return False
    if not _within(value, reference, rtol=1e-2, grey=3.0, projective=projective):
        return False
    if confirming:
        return True
    nearer = 30 if naming.has_image(reference) else 100
    return naming.distance(value, reference, projective=projective) * nearer \
        <= naming.distance(student, reference, projective=projective)


def _within(value, reference, rtol: float, grey: float, projective: bool = True) -> bool:
    if naming.has_image(reference):
        return naming.distance(value, reference) <= grey and not naming.drawn_elsewhere(value, reference)
    pairs = naming.numeric_pairs(value, reference)
    if pairs is None:
        return False
    floor = rtol / 100 * max(naming.largest_entry(reference), 1e-12)
    for got, want in pairs:
        kind = np.complex128 if "c" in got.dtype.kind + want.dtype.kind else np.float64
        got, want = got.astype(kind), want.astype(kind)
        if np.isfinite(got).tolist() != np.isfinite(want).tolist():
            return False
        if np.allclose(got, want, rtol=rtol, atol=floor, equal_nan=True):
            continue
        small = projective and got.ndim == 2 and got.size <= 16 and np.isfinite(got).all()
        scale = np.vdot(got, want) / np.vdot(got, got) if small and np.vdot(got, got) != 0 else 0
        # (a unit vector -- an epipole, a singular vector -- has no sign of its own: up to sign only)
        unit = projective and got.ndim == 1 and got.shape == want.shape and got.size <= 4 and np.isfinite(got).all() \
            and all(abs(np.linalg.norm(v) - 1) < 1e-6 for v in (got, want))
        if unit and np.allclose(-got, want, rtol=rtol, atol=floor):
            continue
        if not (small and scale != 0 and np.allclose(got * scale, want, rtol=rtol, atol=floor)):
            return False
    return True


# ------------------------------------------------------------------ the search
def name_by_repair(trial, seconds: float = CHECK_SECONDS, tries: int | None = None, said: str = "",
                   named: str = "") -> Repair | None:
    """A change of the student's code that makes the failed trial's answers right, confirmed; or None.
    ``tries``: at most this many single changes, no pairs (a search whose outcome does not depend on
    the machine's speed, within ``seconds``).

    Never raises for the student's sake: a variant that fails is no repair; without a reference
    module, a reading of the student's code or time left, nothing is named."""
    model = naming.model_for(trial.lab)
    if model is None or not (trial.calls or getattr(trial, "served", None) or getattr(trial, "raised", None)):
        return None
    raised = naming.raised_answer(trial.raised[3]) if getattr(trial, "raised", None) else None
    if raised is not None and naming.error_kind(raised)[0] in naming.NO_MUTANT_RAISES:
        return None   # a name undefined (a notebook cell that raised), an import: no change of a value mends it
    # One time per grading for naming by mutants and by repairs (naming.GRADING_SECONDS): what
    # failing everything costs stays bounded by what passing costs.
    spent = trial.sandbox.shared.setdefault(naming.SPENT, [0.0])
    # A slow function (a pipeline on photographs) needs more than the check's time for the confirmation of a
    # change found (its reference and the change run on every confirmation input): that time is added to the
    # check's, as measured on this machine's own calls (a slower machine's calls take longer, its names alike).
    seconds += min(seconds, max(0.0, _confirming_seconds(trial) - RESERVE))
    seconds = min(seconds, naming.GRADING_SECONDS - spent[0])
    if seconds <= 0.2:
        return None
    clock = naming.work_clock(trial, seconds)
    # (the search stays within the check's time; the confirmation of a change it found may take the
    # grading's time left too, and more for a slow submission -- a Python loop's variants run as slowly as the
    # student's own calls)
    clock.spare = max(0.0, naming.GRADING_SECONDS - spent[0] - seconds) + naming.confirming_extra(trial)
    try:
        student = _student_code(trial)
        if student is None:
            return None
        return _search(trial, model, student, clock, tries, said, named)
    except HelperFailed:
        return None
    finally:
        spent[0] += clock.used()
        naming.forget_measures()
        naming.release_helper()


def _confirming_seconds(trial) -> float:
    """The time kept for confirming a change once one is found: the reference and the change each run on
    about :data:`CONFIRMATION_INPUTS` inputs, at the student's own time per call (with the helpers' and the
    grader's own work beside them, measured: half as much again), or :data:`RESERVE` if longer."""
    per_call = getattr(trial, "student_seconds", 0.0) / max(1, len(getattr(trial, "calls", ()) or ()))
    return max(RESERVE, 3 * CONFIRMATION_INPUTS * per_call / naming.machine_pace())


def _recorded(trial) -> dict:
    """function -> [(function, args, kwargs, the student's outcome)] of the trial, raised last: those it made
    and those behind a value another check's ``t.shared`` served it (a panorama judged by several checks)."""
    recorded = {}
    for function, args, kwargs, value in list(getattr(trial, "served", ())) + list(trial.calls):
        recorded.setdefault(function, []).append((function, tuple(args), dict(kwargs), value))
    if getattr(trial, "raised", None):
        function, args, kwargs, message = trial.raised
        theirs = naming.raised_answer(message)
        if theirs is not None:
            recorded.setdefault(function, []).append((function, tuple(args), dict(kwargs), theirs))
    return recorded


def _search(trial, model, student: _Student, clock, tries=None, said: str = "", named: str = "") -> Repair | None:
    runner = naming.helper()
    for function, calls in _recorded(trial).items():
        if function not in model.mutants or not student.ordered(function):
            continue
        calls = calls[-CALLS_PER_FUNCTION:]
        inputs = [call[:3] for call in calls]
        runner.prepare(model.source, model.module, inputs, max(1.0, clock.wall_left()))
        references = runner.run((), range(len(inputs)), max(0.5, clock.wall_left()))
        failing = [i for i, (call, reference) in enumerate(zip(calls, references))
                   if naming.error_kind(reference) is None and _wrong(call[3], reference)]
        subtle = not failing   # the check failed on answers near the reference's (a line missing
        if subtle and _replayable(trial):   # of five): only the check itself tells a change right
            failing = [i for i, (call, reference) in enumerate(zip(calls, references))
                       if naming.error_kind(reference) is None and _differs(call[3], reference)]
        # (a check that raised failed at that call: the calls before it it had taken -- a drawing of its
        # own colours, far from the reference's and accepted -- are no failing inputs of the change)
        raised = getattr(trial, "raised", None)
        if raised and raised[0] == function and len(inputs) - 1 in failing:
            failing = [len(inputs) - 1]
        if not failing:
            continue
        found = _repaired(trial, model, student, function, inputs, references, failing, clock, subtle, tries, said, named)
        seen = trial.sandbox.shared.setdefault("repair seen", {}).setdefault(function, [])
        known = {_key(call) for call in seen}
        seen += [call for call in inputs if _key(call) not in known][:max(0, SEEN - len(seen))]
        if found is not None:
            return found
    return None


_DRAWN = {"seed", "rng", "random_state"}   # parameters that fix a random draw (the API's `seed=None`)
SEEN = 8                 # a function's calls kept from a grading's checks for confirming later repairs
SEEN_CONFIRMATIONS = 3   # of which a repair is confirmed on at most this many


def found_on_earlier_checks(trial, function: str) -> bool:
    """Whether a change of ``function``'s code was confirmed on an earlier check of this grading: a check's own
    guess at a cause (a rule read from the answers) then yields to it -- the change is tried on this check too."""
    shared = getattr(getattr(trial, "sandbox", None), "shared", None)
    return bool(shared is not None and shared.get("repair found", {}).get(function))


def passing_functions(trial) -> set:
    """The graded functions every check of which, run so far in this grading, passed (one at least)."""
    shared = trial.sandbox.shared
    failing = shared.get((SHARED_FAILING, trial.lab.module), set())
    return {key[1] for key, kept in list(shared.items())
            if isinstance(key, tuple) and key[0] == "checks calling" and kept} - failing


def _widened(call, defaults=(), factors=(4.0,)) -> list:
    """The call made unlike the check's own inputs, when it can be: every float argument given alone (a
    factor, an angle, a threshold; a numeric default it left out, given) four times larger (each of
    ``factors``), every small whole number (1 to 4) two larger, and every image a few rows and columns
    smaller. A change right by coincidence on the
    check's inputs -- `s * s` truncated to 0 where `s * height` belongs for small factors, an angle taken
    from the width of a 360-pixel image, a comparison turned round that sends enlargements the way of
    shrinks (`w >= width` -> `w <= width`: the floats half as large) -- is wrong there. [] when nothing
    changes."""
    function, args, kwargs = call
    kwargs = {**{name: float(value) for name, position, value in defaults
                 if position >= len(args) and name not in kwargs and isinstance(value, float)}, **kwargs}

    def widen(value, factor):
        if isinstance(value, float) and value != 0:
            return value * factor
        # (a small whole number two larger, its parity kept -- an odd window stays odd: at the smallest
        # values a search shrinks to, `2 ** n // width` and `width // 2 ** n` agree at n = width = 1)
        if factor > 1 and isinstance(value, int) and not isinstance(value, bool) and 1 <= value <= 4:
            return value + 2
        if factor > 1 and isinstance(value, np.ndarray) and value.dtype == np.uint8 and value.ndim >= 2 \
                and min(value.shape[:2]) > 20:
            return np.ascontiguousarray(value[:-3, :-5])
        return value

    made = []
    for factor in factors:
        call = (function, tuple(widen(a, factor) for a in args), {k: widen(v, factor) for k, v in kwargs.items()})
        if any(a is not b for a, b in zip(call[1], args)) or any(call[2][k] is not kwargs[k] for k in kwargs):
            made.append(call)
    return made


def _one_enlarged(call, factor: int = 4, largest: int = 16) -> list:
    """The call with each of its small whole numbers (1 to ``largest``) alone made ``factor`` times larger,
    the others as they were: a change right by a coincidence between two of them -- `max(2 ** n, width)`
    for `min(2 ** n, width)` where the check's widths are all below 2 ** n -- is wrong where their order
    turns round. ([] when the call has none.)"""
    function, args, kwargs = call
    small = lambda value: isinstance(value, int) and not isinstance(value, bool) and 1 <= value <= largest  # noqa: E731
    made = [(function, args[:k] + (value * factor,) + args[k + 1:], kwargs) for k, value in enumerate(args) if small(value)]
    made += [(function, args, {**kwargs, name: value * factor}) for name, value in kwargs.items() if small(value)]
    return made


# the colour's position among an OpenCV drawing function's arguments
_COLOUR_AT = DRAWING_COLOUR_AT


def _bound_names(node) -> set:
    """The names an assignment binds whole (`w`, `h, w`; not `M` of `M[0, 2] = cx`)."""
    targets = node.targets if isinstance(node, ast.Assign) else [node.target]
    return {t.id for target in targets for t in (target.elts if isinstance(target, (ast.Tuple, ast.List)) else [target])
            if isinstance(t, ast.Name)}


def _sized_names(nodes) -> set:
    """The names the assignments among ``nodes`` compute from an array's size (directly or through one another)."""
    assigned = [n for n in nodes if isinstance(n, (ast.Assign, ast.AugAssign, ast.AnnAssign)) and n.value is not None]
    names: set = set()
    for _ in range(4):   # (a few rounds: `h, w = shape[:2]`, `cx = w / 2`, `tx = cx - s * cx`)
        before = len(names)
        for node in assigned:
            if _reads_size(node.value, names):
                names |= _bound_names(node)
        if len(names) == before:
            break
    return names


def _unread_steps(fn) -> set[str]:
    """The assignments of a def's own top-level statements (by their code) whose names no later statement reads
    before they are bound again (a return reads; a compound statement reads every name it holds)."""
    def flat(statements):   # (a change's `if True:` holding statements moved together, and its `pass`, read inline)
        for node in statements:
            if isinstance(node, ast.If) and isinstance(node.test, ast.Constant) and node.test.value is True \
                    and not node.orelse:
                yield from flat(node.body)
            elif not isinstance(node, ast.Pass) \
                    and not (isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant)):
                yield node
    body = list(flat(fn.body))
    reads = lambda node: {n.id for n in walk(node) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}  # noqa: E731
    unread = set()
    for k, node in enumerate(body):
        if not (isinstance(node, ast.Assign) and all(isinstance(t, ast.Name) for t in node.targets)):
            continue
        names = {t.id for t in node.targets}
        for later in body[k + 1:]:
            if reads(later) & names:
                break
            if isinstance(later, ast.Assign) and names <= _bound_names(later):
                unread.add(ast.unparse(node))
                break
        else:
            unread.add(ast.unparse(node))
    return unread


_OUTPUT_SIZE_AT = {"warpPerspective": 2, "warpAffine": 2, "resize": 1}   # OpenCV's `dsize` argument


def _output_size_arguments(tree) -> list:
    """The expressions ``tree`` passes to OpenCV as an output size (`dsize`)."""
    found = []
    for node in walk(tree):
        if isinstance(node, ast.Call) and _dotted(node.func).startswith(("cv2.", "cv.")):
            at = _OUTPUT_SIZE_AT.get(_dotted(node.func).rsplit(".", 1)[-1])
            found += [node.args[at]] if at is not None and len(node.args) > at else []
            found += [k.value for k in node.keywords if k.arg == "dsize"]
    return found


def _output_size_names(fn) -> set:
    """The names a def passes to OpenCV as an output size (`size`, or `w` and `h` of `(w, h)`)."""
    return {n.id for arg in _output_size_arguments(fn) for n in walk(arg) if isinstance(n, ast.Name)}


def _statements_of(fn) -> list:
    """A def's statements in walking order (two copies of one def, changed at one place, pair up)."""
    return [node for node in walk(fn) if isinstance(node, ast.stmt) and node is not fn]


def _drawn_on(fn) -> set[str]:
    """The names ``fn`` draws on with OpenCV (the image a cv2.line, cv2.circle, ... is given first)."""
    return {node.args[0].id for node in walk(fn) if isinstance(node, ast.Call) and node.args
            and isinstance(node.args[0], ast.Name) and _dotted(node.func).startswith(("cv2.", "cv."))
            and _dotted(node.func).rsplit(".", 1)[-1] in _COLOUR_AT}


def _size_step_emptied(before, dropped: set) -> bool:
    """Whether ``dropped`` (names a change leaves unused) holds a size ``before`` computes for a value it
    makes (`scaled = cv2.warpAffine(image, M, (new_w, new_h))`) and then reads the size of that value
    or of one made from it (`part = scaled[:h, :w]`, `part.shape[0]`): the student's own steps fit
    the value to the size they chose, so a change that lets the value take another size (`dsize` ->
    None, the input's) leaves those steps nothing to do -- a compensation, not the slip. (A size
    computed for what is returned at once, `return cv2.warpAffine(image, M, (out_w, h))`, is the
    slip itself when the answer must keep the input's size.)"""
    nodes = list(walk(before))
    sizes = dropped & _sized_names(nodes)
    if not sizes:
        return False
    assignments = sorted((n for n in nodes if isinstance(n, (ast.Assign, ast.AnnAssign)) and n.value is not None),
                         key=lambda n: n.lineno)
    reads = lambda node: {n.id for n in walk(node) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}  # noqa: E731
    made = set()   # the values made with those sizes, and those made from them
    for node in assignments:
        if reads(node.value) & (sizes | made):
            made |= _bound_names(node) - _sized_names([node])
    made -= sizes
    return any((isinstance(n, ast.Attribute) and n.attr in ("shape", "size") and isinstance(n.value, ast.Name)
                and n.value.id in made)
               or (isinstance(n, ast.Call) and isinstance(n.func, ast.Name) and n.func.id == "len" and n.args
                   and isinstance(n.args[0], ast.Name) and n.args[0].id in made) for n in nodes)


def _reads_size(node, names) -> bool:
    """Whether the code ``node`` reads an array's size (``.shape``, ``.size``, ``len``) or one of ``names``."""
    for n in walk(node):
        if (isinstance(n, ast.Attribute) and n.attr in ("shape", "size")) or (isinstance(n, ast.Name) and n.id in names) \
                or (isinstance(n, ast.Call) and isinstance(n.func, ast.Name) and n.func.id == "len"):
            return True
    return False


SMALL_IMAGE = (7, 9)   # rows, columns of the images of a change's small-image confirmation input


# parameters that are homogeneous matrices, defined up to scale (a homography, a camera, F, E)
_UP_TO_SCALE = frozenset({"H", "H1", "H2", "P", "P1", "P2", "F", "E"})


@functools.lru_cache(maxsize=16)
def _up_to_scale(source: str) -> dict:
    """function -> [(position, name)] of its parameters that are defined up to scale (by their names)."""
    tree = parse(source, max_chars=None, max_statements=None)   # (the reference's text: trusted)
    return {fn.name: [(i, a.arg) for i, a in enumerate(fn.args.args) if a.arg in _UP_TO_SCALE]
            for fn in tree.body if isinstance(fn, ast.FunctionDef)}


def _matrices_replaced(call, positions, replacement) -> list:
    """[the call with each matrix parameter at ``positions`` ((position, name): given by position or by
    name) replaced by ``replacement(name, value)``], or [] when it replaces none (None: kept)."""
    function, args, kwargs = call
    args, kwargs, replaced = list(args), dict(kwargs), False
    for position, name in positions:
        value = args[position] if position < len(args) else kwargs.get(name)
        new = replacement(name, value) if isinstance(value, np.ndarray) and value.dtype.kind == "f" else None
        if new is not None:
            if position < len(args):
                args[position] = new
            else:
                kwargs[name] = new
            replaced = True
    return [(function, tuple(args), kwargs)] if replaced else []


def _rescaled(call, positions) -> list:
    """The call with each matrix defined up to scale given twice as large ([] when it has none): a change
    right only at the check's scale -- a division by `H[2, 2]` kept beside the one by w, exact where
    H[2, 2] = 1 -- is wrong there, where the reference answers alike."""
    return _matrices_replaced(call, positions, lambda name, value: value * 2.0 if value.shape in ((3, 3), (3, 4))
                              and np.all(np.isfinite(value)) else None)


# homographies among them: a translation is one too, whatever the function does with it
_HOMOGRAPHIES = frozenset({"H", "H1", "H2"})
SHIFTS = ((7.0, 3.0), (-7.0, -3.0))   # a few pixels right and down, then left and up; unequal: x and y apart


def _translated(call, positions) -> list:
    """The call with each homography it is given replaced by a pure translation, one call per shift of
    :data:`SHIFTS` ([] when it has none): a change right only where the check's homography sends the
    image up and left -- a shift added "to keep it visible" made 0 by a sign turned round, `max(0, y)` for
    `max(0, -y)` -- is wrong where it sends it down and right, and a name used for its twin (dx for dy)
    where both are not 0."""
    def shifted(tx, ty):
        return lambda name, value: np.array([[1.0, 0.0, tx], [0.0, 1.0, ty], [0.0, 0.0, 1.0]], dtype=value.dtype) \
            if name in _HOMOGRAPHIES and value.shape == (3, 3) else None
    return [made for tx, ty in SHIFTS for made in _matrices_replaced(call, positions, shifted(tx, ty))]


def _points_changed(call, accepts, change) -> list:
    """The call with each of its point arrays (float arrays ``accepts`` takes, all of one length) changed by
    ``change``, every array alike: ``[call]``, or [] when it has none or arrays of several lengths."""
    function, args, kwargs = call
    points = lambda v: isinstance(v, np.ndarray) and v.dtype.kind == "f" and v.ndim == 2 and accepts(v)  # noqa: E731
    counts = {len(v) for v in list(args) + list(kwargs.values()) if points(v)}
    if len(counts) != 1:
        return []
    made = lambda v: change(v) if points(v) else v  # noqa: E731
    return [(function, tuple(made(a) for a in args), {k: made(v) for k, v in kwargs.items()})]


def _single_point(call) -> list:
    """The call with its point arrays ((N, 2) or (N, 3) floats, N >= 2, all of one N) given their first point
    alone, as a (2,) or (3,) vector ([] when it has none): the API's single point, which a change mending the
    batch only -- `return result.T` where `result[0]` is taken for one point -- gets wrong. Where the reference
    does not take a single point, the input is no confirmation (it raises there)."""
    return _points_changed(call, lambda v: v.shape[1] in (2, 3) and v.shape[0] >= 2,
                           lambda v: np.ascontiguousarray(v[0]))


def _one_point(answer):
    """An answer to a single point with a leading axis of length 1 dropped ((1, 3) -> (3,)): where the API
    does not say what one point gives (a triangulated pair), the reference's (1, 3) or (3,) is no truth of
    the student's convention -- either is compared as the one point it is (a change giving the points
    transposed, (3, 1), is not that)."""
    if isinstance(answer, np.ndarray) and answer.ndim >= 2 and answer.shape[0] == 1:
        return answer[0]
    return answer


def _reordered(call) -> list:
    """The call with its point arrays ((N, 2) or (N, 3) floats, N >= 3, all of one N; no square matrix)
    given in the reverse order, every array alike ([] when it has none): a correspondence set's order is
    the caller's, and a change right for one order only -- a sign flipped in an orientation test that
    rejects the triangles listed the other way round -- is wrong there."""
    return _points_changed(call, lambda v: v.shape[1] in (2, 3) and v.shape[0] >= 3 and v.shape[0] != v.shape[1],
                           lambda v: np.ascontiguousarray(v[::-1]))


# Offsets of 2-D points: far, each with its opposite and a perpendicular pair, so that whatever the direction
# of a difference d of the points, one offset c turns the cross product d x c against what it was (by at
# least 0.7 |d| |c|): a point read where a difference belongs is right by chance on at most three of them.
MOVES = ((1500.0, -1300.0), (-1500.0, 1300.0), (1300.0, 1500.0), (-1300.0, -1500.0))


def _points_moved(call) -> list:
    """The call with its 2-D point arrays ((N, 2) floats, N >= 3, all of one N) moved by each of
    :data:`MOVES`, every array alike ([] when it has none): what a set of points means does not hang on where the
    origin is, and a change reading a point where a difference of two belongs (`src[2]` for
    `src[2] - src[0]`) is right only by where the points happen to lie."""
    return [made for move in MOVES
            for made in _points_changed(call, lambda v: v.shape[1] == 2 and v.shape[0] >= 3,
                                        lambda v, move=move: v + np.asarray(move, v.dtype))]


def _branch_values(call, fn) -> list:
    """The call with a number it gives (or leaves to its default) set to each other whole number the student's
    def ``fn`` compares that parameter with, or takes it modulo (`if angle_deg % 180 == 0:` -> 180), one value
    at a time: the inputs that take the branch the failing one took, or the other way, without being it. A
    change of what the branch does, right for the failing input alone (a half-turn shortcut taken at 0 degrees:
    its flip dropped, and 180 degrees is no longer turned), is wrong there. [] without such a test."""
    if not isinstance(fn, ast.FunctionDef):
        return []
    function, args, kwargs = call
    params = [a.arg for a in fn.args.posonlyargs + fn.args.args]
    defaults = dict(zip(params[len(params) - len(fn.args.defaults):], fn.args.defaults))
    made = []
    for position, name in enumerate(params):
        given = args[position] if position < len(args) else kwargs.get(name, _literal(defaults.get(name)))
        if type(given) not in (int, float):
            continue
        values = []
        for test in (n for n in walk(fn) if isinstance(n, ast.Compare)):
            if not any(isinstance(n, ast.Name) and n.id == name for n in walk(test.left)):
                continue
            moduli = [n.right for n in walk(test.left) if isinstance(n, ast.BinOp) and isinstance(n.op, ast.Mod)]
            for node in moduli + list(test.comparators):
                value = _literal(node)
                if type(value) is int and value != given and value not in values:
                    values.append(value)
        for value in values[:2]:
            value = type(given)(value)
            made.append((function, args[:position] + (value,) + args[position + 1:], dict(kwargs))
                        if position < len(args) else (function, tuple(args), {**kwargs, name: value}))
    return made


def _literal(node):
    """The number a literal node writes (`180`, `-1`); None otherwise."""
    try:
        return ast.literal_eval(node) if node is not None else None
    except (ValueError, SyntaxError, TypeError):
        return None


def _fewer(call) -> list:
    """The call with each list of three or more arrays it is given (the images of a panorama, the views of
    a calibration) one item shorter ([] when it has none): a count written where the list's length belongs
    (`range(3)` -> `range(4)` for four images) is wrong there."""
    function, args, kwargs = call
    made = []
    for position, value in enumerate(args):
        if isinstance(value, (list, tuple)) and len(value) >= 3 and all(isinstance(v, np.ndarray) for v in value):
            shorter = type(value)(value[:-1])
            made.append((function, args[:position] + (shorter,) + args[position + 1:], dict(kwargs)))
    return made


def _small(call) -> list:
    """The call with every 8-bit image (both sides above 20 pixels) cut to a window of
    :data:`SMALL_IMAGE` at its centre -- images of one shape alike: a stereo pair stays a pair --
    ([] when it has none). A change in what is computed from an image's size must hold at every size:
    `2 / (w - 1)` where `(w - 1) / 2` was is almost 0 on a 320-pixel image, as a translation of 0 would
    be, and a quarter pixel on a 9-pixel one."""
    function, args, kwargs = call

    def cut(value):
        if isinstance(value, np.ndarray) and value.dtype == np.uint8 and value.ndim >= 2 and min(value.shape[:2]) > 20:
            top, left = (value.shape[0] - SMALL_IMAGE[0]) // 2, (value.shape[1] - SMALL_IMAGE[1]) // 2
            return np.ascontiguousarray(value[top:top + SMALL_IMAGE[0], left:left + SMALL_IMAGE[1]])
        return value

    made = (function, tuple(cut(a) for a in args), {k: cut(v) for k, v in kwargs.items()})
    changed = any(a is not b for a, b in zip(made[1], args)) or any(made[2][k] is not kwargs[k] for k in kwargs)
    return [made] if changed else []


def _greyed(call) -> list:
    """The call with every 8-bit BGR image (H, W, 3) made grey (as cv2.cvtColor does), in a list of images too ([] when
    it has none): the API takes grey images wherever it takes colour ones, and a change that mends a colour
    call by reading past the channels -- `image[0].shape[::-1]` for `images[0].shape[::-1]`, a row's shape --
    fails on grey ones."""
    function, args, kwargs = call

    def grey(value, depth=0):
        if isinstance(value, np.ndarray) and value.dtype == np.uint8 and value.ndim == 3 and value.shape[2] == 3 \
                and min(value.shape[:2]) > 8:
            # (cv2.COLOR_BGR2GRAY's weights)
            return np.round(value.astype(np.float64) @ np.array([0.114, 0.587, 0.299])).astype(np.uint8)
        if isinstance(value, (list, tuple)) and depth == 0 and value:
            made = [grey(v, 1) for v in value]
            return type(value)(made) if any(m is not v for m, v in zip(made, value)) else value
        return value

    made = (function, tuple(grey(a) for a in args), {k: grey(v) for k, v in kwargs.items()})
    changed = any(a is not b for a, b in zip(made[1], args)) or any(made[2][k] is not kwargs[k] for k in kwargs)
    return [made] if changed else []


def _turned(call) -> list:
    """The call with every 8-bit image that is not square (both sides above 20 pixels) turned a quarter
    (np.rot90: a landscape image made portrait), images of one shape alike ([] when it has none)."""
    function, args, kwargs = call

    def turn(value):
        if isinstance(value, np.ndarray) and value.dtype == np.uint8 and value.ndim >= 2 \
                and min(value.shape[:2]) > 20 and value.shape[0] != value.shape[1]:
            return np.ascontiguousarray(np.rot90(value))
        return value

    made = (function, tuple(turn(a) for a in args), {k: turn(v) for k, v in kwargs.items()})
    changed = any(a is not b for a, b in zip(made[1], args)) or any(made[2][k] is not kwargs[k] for k in kwargs)
    return [made] if changed else []


def _beyond(call, defaults=()) -> list:
    """The call with the values its check chose given as the contract's other values of the same kind:
    whole numbers (an int argument: a shift of 100 px) made fractional, a number given with the other
    sign, a float mask of 0s and 1s made soft, one value at a time. A change right only on the check's
    choice -- nearest-neighbour interpolation where the shifts are whole, a clip bound moved by 2 where
    the shear is negative, a mask multiplied by 255 and clipped, exact on 0 and 1 -- is wrong there. [] when the
    call holds neither. (Where the student's own code does not take such a value, the input says
    nothing of a change: :meth:`_Variants.confirmed` leaves it out.)"""
    import cv2

    function, args, kwargs = call
    # (a numeric default left out, given: `scale(image)`'s sx=1.5 with the other sign too -- a size made
    # negative by a changed sign falls back to the input's in OpenCV, right by that alone)
    kwargs = {**{name: value for name, position, value in defaults
                 if position >= len(args) and name not in kwargs and type(value) in (int, float)}, **kwargs}

    def other(value):
        if isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_)) and value != 0:
            return float(value) + 0.5
        if isinstance(value, float) and value != 0 and np.isfinite(value):
            return -value
        if isinstance(value, np.ndarray) and value.dtype.kind == "f" and value.ndim == 2 and min(value.shape) >= 8 \
                and np.isin(value, (0.0, 1.0)).all() and 0 < value.mean() < 1:
            return cv2.GaussianBlur(value, (0, 0), max(2.0, min(value.shape) / 16))
        return value

    # one value at a time: a count given a fraction (levels=5.5) makes the call no input at all
    made = [(function, args[:i] + (other(a),) + args[i + 1:], dict(kwargs))
            for i, a in enumerate(args) if other(a) is not a]
    return made + [(function, tuple(args), {**kwargs, k: other(v)}) for k, v in kwargs.items() if other(v) is not v]


def _given(call, resolved) -> list:
    """The call with each optional argument it leaves out (or gives as None) that the reference resolves
    to a number (``resolved``: [(parameter, position, number)]) given as four times that number, one
    argument at a time: a change right only with the default's own number -- `s` -> `block_size`, 5 beside
    a default smoothness of 6 -- is wrong where the caller chooses it."""
    function, args, kwargs = call
    made = []
    for name, position, number in resolved:
        if position < len(args):
            if args[position] is None:
                made.append((function, args[:position] + (4.0 * number,) + args[position + 1:], dict(kwargs)))
        elif kwargs.get(name) is None:
            made.append((function, tuple(args), {**kwargs, name: 4.0 * number}))
    return made


def _redraws(fix) -> bool:
    """Whether ``fix`` changes only how a random draw is made -- a keyword of the draw (`replace=False` ->
    `replace=True`): the samples drawn are then others, and a check judged on a few seeds may pass by luck
    (a RANSAC stopping too early passed five seeds with its samples drawn with replacement). Such a change is
    told only where it gives the reference's very answers, never on the check's word."""
    if fix is None:
        return False

    def draws(code):
        try:
            tree = parse(code)
        except (SyntaxError, ValueError, RecursionError, MemoryError):
            return {}
        return {ast.dump(n.func) + "|" + "|".join(ast.dump(a) for a in n.args): {ast.dump(k) for k in n.keywords}
                for n in walk(tree) if isinstance(n, ast.Call) and isinstance(n.func, ast.Attribute)
                and n.func.attr in RANDOM_DRAWS and _dotted(n.func).split(".")[0] not in ("cv2", "cv")}

    for _, before, after in fix.changes:
        old, new = draws(before), draws(after)
        if any(key in new and new[key] != kept for key, kept in old.items()):
            return True
    return False


def _holed(call) -> list:
    """The call with the last row of a float point array ((N, 2) or (N, 3), N >= 2) given as NaN, one
    array at a time ([] when the call has none)."""
    function, args, kwargs = call

    def holed(value):
        if isinstance(value, np.ndarray) and value.dtype.kind == "f" and value.ndim == 2 \
                and value.shape[1] in (2, 3) and value.shape[0] >= 2:
            value = value.copy()
            value[-1] = np.nan
            return value
        return None

    made = [(function, args[:i] + (holed(a),) + args[i + 1:], dict(kwargs))
            for i, a in enumerate(args) if holed(a) is not None]
    made += [(function, tuple(args), {**kwargs, k: holed(v)}) for k, v in kwargs.items() if holed(v) is not None]
    return made[:2]


def _close(value, reference) -> bool:
    """Whether an answer is near the reference's as legitimate recipes are: images within 3 grey levels
    on average (their own interpolation may differ at edges), numbers within 1%."""
    if naming.has_image(reference):
        return naming.distance(value, reference) <= 3.0
    return _within(value, reference, rtol=1e-2, grey=3.0)


def _differs(answer, reference) -> bool:
    """Whether an answer differs from the reference's at all: in a value, or in its arrays' kind (the
    right values as float64 where uint8 is asked for)."""
    return naming.distance(answer, reference) > 0 or _kinds(answer) != _kinds(reference)


def _kinds(value) -> list:
    """The kinds of the arrays of an answer (``"u"`` for an 8-bit image, ``"f"``...)."""
    return [v.dtype.kind for v in (value if isinstance(value, (tuple, list)) else [value]) if isinstance(v, np.ndarray)]


def _weight(call) -> int:
    """How large a call's array arguments are (bytes): what a slow function's time grows with."""
    function, args, kwargs = call[:3]
    return sum(value.nbytes for value in (*args, *kwargs.values()) if isinstance(value, np.ndarray))


def _key(call) -> str:
    return fingerprint(call[0], call[1], call[2])


def _answers_key(values) -> str:
    """A key of a variant's answers (equal answers, equal keys; never raises)."""
    try:
        return fingerprint(*values)
    except Exception:  # noqa: BLE001 - answers it cannot read are nobody's twins
        return repr(id(values))


def _wrong(answer, reference) -> bool:
    return naming.error_kind(answer) is not None or naming.wrong(answer, reference)


def _repaired(trial, model, student, function, inputs, references, failing, clock, subtle=False,
              tries=None, said="", named="") -> Repair | None:
    """The confirmed single changes of ``function``'s code (or of a helper it runs) whose answers on
    the ``failing`` inputs are the reference's (up to :data:`FIXES`, one per line), or with which the
    failed check itself passes (:meth:`_Variants.passes_check`; only that where the student's answers
    are ``subtle``-ly off); else the first confirmed pair of changes among those that each bring the
    answers nearer (one slip made twice: a row copied twice with the wrong camera's name)."""
    shared = trial.sandbox.shared
    ruled_out = shared.setdefault("repair ruled out", {}).setdefault(function, set())
    kept_near = shared.setdefault("repair near", {}).setdefault(function, [])
    earlier = shared.setdefault("repair found", {}).get(function, [])
    variant = _Variants(trial, model, student, function, inputs, references, clock)
    off = sum(variant.distance(references[i], variant.students[i]) for i in failing)
    # A slow function's variants are tried on its smallest failing input first (a matcher's crop
    # offered to the error model): only those right or nearer there run on the others.
    screen = min(failing, key=lambda i: _weight(inputs[i]))
    candidates, near, slightly, near_answers = [], [], [], {}
    restyled = []   # changes of a drawing in a style of the student's own (see _drawn_otherwise)
    exactly = set()   # the candidates giving the reference's answers on every failing input
    partly = []       # changes told on an earlier check, here right on some inputs only (failing or confirming)
    to_the_bit = set()   # of which those giving its very numbers (its computation, not one within rounding)
    known = {m.key for m in earlier}
    complete = True   # every change tried (or ruled out in an earlier check)
    # A change in code the smallest failing input does not run leaves the student's wrong answer
    # there as it is: only changes of the lines it runs are tried (a cost="ncc" branch, unused helpers).
    ran = student.ran_here(function, variant.ran(screen))
    runnable = [m for m in student.ordered(function) if student.runs(m, ran)]
    # A private helper another graded function runs, whose checks all passed, is likelier right than
    # this function's own code: its changes are tried last (a panorama's compositing before the
    # normalisation its homography estimate shares with a DLT that passed).
    runnable = student.vouched_last(runnable, function, passing_functions(trial))
    # The check's own name of the mistake, where it quotes the student's code ("your code fixes signs
    # with np.sign"), says where to look first.
    runnable = student.quoted_first(runnable, said, named)
    if all(_sized_otherwise(variant.students[i], references[i]) for i in failing):
        # An answer of another size (an image shrunk, a map cropped): only code that makes or reads a size can
        # mend it -- those changes first (a resize for wide images, taken out whole, is far down the list).
        sized = [m for m in runnable if _SIZE_CODE.search(str(student.fix(m).changes if student.fix(m) else ""))]
        runnable = sized + [m for m in runnable if m not in sized]
    if any(_rows_for_columns(variant.students[i], references[i]) for i in failing):
        # An answer with rows and columns exchanged (a canvas sized (height, width)): the exchanges
        # of twins first, wherever they are (`(y_max - y_min, x_max - x_min)`, `w, h = shape[:2]`).
        twins = [m for m in runnable if _twin_swap(student.fix(m)) or student.twin_items(m)]
        # (of those, the twins that are sizes first: only they change a shape -- `x`/`y`, `fx`/`fy` of a lens
        # model are many, and each is a variant run)
        sized = [m for m in twins if _SIZE_TWINS.search(str(student.fix(m).changes))]
        runnable = sized + [m for m in twins if m not in sized] + [m for m in runnable if m not in twins]
    # (time kept for confirming a change found: a slow function's -- features matched on photographs --
    # confirmation calls take as long as its own calls, a few of them)
    reserve = min(max(RESERVE, CONFIRMATION_CALLS * variant.seconds_per_call / clock.pace), clock.left() / 2)
    # (and once a change is found, the time its confirmation takes: the reference and the change each
    # run on every confirmation input -- a whole pipeline each for a slow function)
    confirming = max(reserve, _confirming_seconds(trial))
    queue = list(earlier) + _near_the_raise([m for m in runnable if m.key not in known], trial, function)
    # (a change that mends, or brings the answers far nearer, says where the slip is: the other changes of its
    # statement are tried before the rest -- a normalisation's `axis=0` made `axis=1`, beside the statement moved
    # out of its loop, or written into another row, which mend by undoing it, found first in a slow DP's search)
    pointing, located = [], set()
    position = 0
    while position < len(queue):
        for lines in [_lines_changed(student, m) for m in candidates[-1:]] + pointing:
            if lines - located and len(located) < POINTED_LINES:   # (a few places: each is a sort of the rest)
                located |= lines
                queue[position:] = sorted(queue[position:], key=lambda m, at=lines: not _lines_changed(student, m) & at)
        pointing.clear()
        mutant = queue[position]
        position += 1
        if mutant.key not in known and any(m.key in known for m in candidates):
            # A change told on an earlier check of the function gives this check's answers too: that search
            # looked for the other changes mending alike (told beside it), this one need not look again.
            complete = shared.setdefault("repair complete", {}).get(function, complete)
            break
        if clock.left() <= (confirming if candidates else reserve if near and variant.replayable else 0) \
                or (tries is not None and variant.screenings >= tries):
            complete = False
            break
        if mutant.key in ruled_out:
            continue
        values = variant.screened(mutant, failing, screen, subtle)
        exact = [] if values is None or subtle else [variant.right(v, references[i], variant.students[i])
                                                     for v, i in zip(values, failing)]
        if mutant.key in known and exact and not all(exact):
            partly.append(mutant)
        if exact and all(exact):
            candidates.append(mutant)
            exactly.add(mutant.key)
            if all(variant.distance(v, references[i]) == 0 for v, i in zip(values, failing)):
                to_the_bit.add(mutant.key)
            continue
        if values is not None and np.isfinite(off):
            apart = sum(variant.distance(v, references[i]) for v, i in zip(values, failing))
            if apart < 0.9 * off:
                near.append((apart, mutant))
                near_answers[mutant.key] = values
                if apart < POINTING * off:
                    pointing.append(_lines_changed(student, mutant))
            elif apart < NEARER * off:   # (judged by the check after the nearer ones; never paired)
                slightly.append((apart, mutant))
                near_answers[mutant.key] = values
            elif _drawn_otherwise(values, [variant.students[i] for i in failing]):
                restyled.append((apart, mutant))
                near_answers[mutant.key] = values
            # Far nearer, not the reference's to the last grey level (the student's own recipe: a
            # resize where the reference warps), or the reference's exactly on some failing inputs
            # and not on others (their own least squares on noisy points, where one ill-posed point
            # outweighs every other in a sum): the check's own tolerances judge it.
            if (apart * (2 if subtle else REPLAY_NEARER) <= off or any(exact)) \
                    and variant.passes_check(mutant, values, failing):
                candidates.append(mutant)
                continue
        elif values is not None and (np.isfinite(sum(variant.distance(v, references[i]) for v, i in zip(values, failing)))
                                     or all(_near_shape(v, references[i]) for v, i in zip(values, failing))) \
                and variant.passes_check(mutant, values, failing):
            # The student's answers were not of the reference's form (no matches kept at all, an
            # exception): a change that gives answers of that form is judged by the check itself.
            candidates.append(mutant)
            continue
        if clock.left() > 0:
            ruled_out.add(mutant.key)
            # (told on an earlier check of the function, and here nearer the expected answers on none
            # of the failing inputs: no account of this failure -- one nearer somewhere, but not
            # confirmed, is no refutation: a legitimate least squares is far off on an ill-posed point,
            # and the check run again with it may fail for want of time or of what the grading shared)
            # (a distance that cannot be measured -- the student's answer and the reference's apart where
            # the API leaves the value open, NaN or not behind the camera -- refutes nothing either)
            if mutant.key in known and values is not None and not any(exact) and all(
                    np.isfinite(variant.distance(variant.students[i], references[i]))
                    and not variant.distance(v, references[i]) < 0.9 * variant.distance(variant.students[i], references[i])
                    for v, i in zip(values, failing)):
                _refuted(trial, student.fix(mutant), function)
    if not candidates:
        # A function with many right answers (a rectification) comes only somewhat nearer the
        # reference's when mended: the nearest changes are judged by the check itself, the first that
        # passes it and those exactly as near (the same answers from another place: names swapped where
        # they are made, or where they are used -- the confirmation tells them apart).
        passed, refused, judged = None, set(), set()
        # (a drawing in a style of the student's own -- OpenCV's random colours, circles at the ends --
        # is no nearer the reference's pixels when a line is added: where no change is nearer, the
        # changes that redraw it are judged by the check, nearest first)
        slightly = slightly or ([] if near else restyled)
        ordered = [(apart, mutant, False) for apart, mutant in sorted(near, key=lambda pair: pair[0])] \
            + [(apart, mutant, True) for apart, mutant in sorted(slightly, key=lambda pair: pair[0])]
        for apart, mutant, slight in ordered:
            if clock.left() <= 0 or (passed is not None and apart > passed):
                break
            if (variant.slight_replays >= SLIGHT_REPLAYS) if slight else (variant.replays >= REPLAYS - PAIR_REPLAYS):
                continue
            # (a change whose answers are another's the check refused -- `q[0] + -w1` beside `q[0] - w1` --
            # is refused too: its replay goes to the next nearest)
            answers = _answers_key(near_answers[mutant.key])
            if answers in refused:
                continue
            if mutant.key in variant.checked:
                continue
            judged.add(mutant.key)
            if not variant.passes_check(mutant, near_answers[mutant.key], failing, slight=slight):
                refused.add(answers)
                continue
            candidates.append(mutant)
            passed = apart
        # A nearer change the check had no time to judge is not ruled out for the function's later checks
        # (a drawing's own recipe keeps every change's answers far from the reference's: the right one
        # may be the fourth nearest).
        ruled_out.difference_update(m.key for _, m in near + slightly if m.key not in judged)
    fixes, lines, halfway = [], set(), set()
    numbers = _numbers_given(student, function, inputs)
    shown = [(mutant, variant.fix(mutant)) for mutant in candidates]
    # The smallest change of the text first: the student's slip is a few characters (`R.T` for `R`),
    # where a change that compensates for it elsewhere on the line rewrites more (`c @ R.T`).
    # (a change an earlier check of the function confirmed first: one mistake, one repair told)
    # (and an exchange of two items before a copy of one over the other, on the same line)
    # (a matrix divided by another of its own entries, `F / F[2, 2]` -> `F / F[1, 2]`, changes only its
    # scale: it mends by that entry's not being 0 on these inputs -- the division is the slip, not the entry)
    # (and a change of a step before the step's removal: a statement taken out mends an input by never
    # running -- `dist = np.asarray(dist) if dist else None` -- where the change of its test mends every input)
    # (but not before a line made its twin line's again -- `if img1.ndim == 3` in the line converting img2, the line
    # above's copy --: beside it, a test given the twin's half, `img1.ndim == 3 and img2.ndim == 3`, has no precedence)
    # (and a change giving the reference's answers before one the check only accepts: on noisy points
    # `x2 * P2[2]` for `y2 * P2[2]` -- view 2's y equation dropped -- passes, `P2[0]` -> `P2[1]` is exact;
    # and its very numbers before answers within rounding: `-s * (h - 1) / 2` -> `-s / (h - 1) / 2`, a
    # shift of a thousandth of a pixel on a large image, beside the entry made 0)
    # (and a term taken out before a change inside it that mends alike: `int(abs(s) / h)` for `int(abs(s) *
    # h)` makes the extra width vanish on every image tried, where `w + int(abs(s) * h)` -> `w` says it)
    shown = [(m, f) for m, f in shown if f is not None]
    # (the same change made by an operator of its own and by the counterpart alignment: the operator's is kept,
    # whose words say what the slip is -- which came first depended on what an earlier check had time to find)
    own_words = {f.changes for _, f in shown if f.operator != "aligned"}
    shown = [(m, f) for m, f in shown if f.operator != "aligned" or f.changes not in own_words]
    dropped = [f for m, f in shown if f.operator == "drop_term" and m.key in exactly]
    # (and where a library refused a value's type, a conversion before the changes that only steer round
    # the value: an empty colour, None, mends a drawing that NumPy integers broke)
    refused_type = bool(getattr(trial, "raised", None)) and trial.raised[0] == function \
        and _TYPE_REFUSED.search(str(trial.raised[3] or "")) is not None
    mirrored = any(f.operator == "mirror" for _, f in shown)
    # (a floor division made a true one before a change that keeps it: `(S[0] + S[1]) // 2` -> `2 // (S[0] +
    # S[1])` gives E's own scale exactly, the floor of 1.41 being 1 -- the slip is the floor)
    floors = {f.changes[0][0] for _, f in shown if f.operator == "true_division"}
    shown = sorted(((m, f) for m, f in shown if not student.renormalises(m)
                    and not student.colours_with_a_size(m)),
                   key=lambda pair: (pair[0].key not in known, not student.removes_a_mask_guard(pair[0]),
                                     not (refused_type and _converts(pair[0])),
                                     _floor_kept(pair[1], floors),
                                     pair[0].key not in exactly, pair[1].operator != "twin_test" or mirrored,
                                     not student.extra_block(pair[0]),
                                     _undoes_a_step(student, *pair),
                                     student.bypasses(pair[0]), pair[0].key not in to_the_bit,
                                     student.copies_an_item(pair[0]), student.departs_from_reference(pair[0]),
                                     _inside_a_dropped_term(pair[1], dropped),
                                     pair[1].operator in REMOVALS, pair[1].size, pair[1].written))
    if shown:
        clock.draw_on_spare(confirming)
    for mutant, fix in shown:
        if len(fixes) >= FIXES or clock.left() <= 0:
            break
        if fix.changes[0][0] in lines or _dehomogenisation_dropped(fix) or student.skips_a_right_step(mutant) \
                or _one_argument_twice(fix) or _neutral_operand_written(fix) \
                or student.compares_with_its_own_size(mutant) or student.reduces_a_number(mutant, numbers) \
                or student.negates_a_size(mutant) or student.leaves_a_step_unused(mutant):
            continue
        confirmed = (variant.confirmed(mutant, failing) or variant.confirmed_by_check(mutant, failing, inputs)) \
            and not variant.writes_inputs(mutant)
        untested = confirmed and variant.guard_untested(mutant, failing)
        if confirmed and not untested and not student.steers_round_a_guard(mutant) \
                and not student.narrows_a_mask_guard(mutant) and not variant.breaks_other_checks(mutant):
            # (a block's one statement taken out is its test never true: told as the test, where the slip likely is)
            never = student.block_never_run(mutant)
            told = student.test_taken_out(never) if never is not None else None
            mutant, fix = (never, told) if told is not None else (mutant, fix)
            fixes.append((mutant, fix))
            lines.add(fix.changes[0][0])
        elif untested and getattr(variant, "untested_guard", None) is not None:
            # (the test made constant is confirmed as the change was: the test itself is where the answers go
            # wrong -- `if p1 != 0 and p2 != 0:` leaves out terms that are 0 anyway where it would be false --
            # and taking it out is told, not one of the ways of rewriting it)
            guard = variant.untested_guard
            told = student.test_taken_out(guard)
            if told is not None and not variant.breaks_other_checks(guard):
                fixes.append((guard, told))
                lines.add(told.changes[0][0])
        elif clock.left() > 0 and not (mutant.key in variant.checked and not variant.other_checks()):
            ruled_out.add(mutant.key)   # (one the check passed with waits for another check to confirm it)
            halfway.add(mutant.key)     # right on the failing inputs, not on all: half of a slip made twice?
            if mutant.key in known:
                partly.append(mutant)
    # (changes at the lines of one filter's test, each mending alike -- the test turned round, the value tested
    # made the row index, the bound made a number -- mend by letting the filter keep everything: where taking
    # the filter out mends too, that is told, not one of the ways of making it keep all)
    unfiltered = student.filter_all_feed(fixes)
    if unfiltered is not None and clock.left() > 0 and variant.confirmed(unfiltered, failing) \
            and not variant.writes_inputs(unfiltered) and not variant.breaks_other_checks(unfiltered) \
            and variant.fix(unfiltered) is not None:
        fixes = [(unfiltered, variant.fix(unfiltered))]
    # A change in a helper shared with other graded functions is not told where one of them has passed
    # every check of its own so far in this grading: a helper it runs rightly is no place for this
    # function's fix (`dsize or size` -> `dsize and size` in a warp helper mends a scale by breaking the
    # warps). (One not graded yet says nothing: the helper may be where the slip is, `_object_points`.)
    # One mistake, one repair told: where a change an earlier check of the function confirmed mends this one
    # too, it is told alone (a second change beside it that mends alike -- the output's entries exchanged,
    # `[p[3], p[4], p[5]]` -> `[p[4], p[3], p[5]]`, beside the rows' `[0, 0, 0, y, x, 1]` -- compensates).
    if any(mutant.key in known for mutant, _ in fixes):
        fixes = [(mutant, fix) for mutant, fix in fixes if mutant.key in known]
    elif any(mutant.key in exactly for mutant, _ in fixes):
        # (and a change told on an earlier check, here right on some inputs only -- failing or confirming --
        # is no account of the mistake where another is confirmed: `np.unique(src, axis=1)` mends points
        # whose first x is below their first y, the line's removal every point set)
        for mutant in partly:
            _refuted(trial, student.fix(mutant), function)
    # (and a change inside a step is told alone beside one skipping the step: the skip leaves its slip; a
    # change inside a branch beside one steering the code round the branch, likewise)
    fixes = [pair for pair in fixes if not student.bypasses(pair[0])] or fixes
    fixes = [pair for pair in fixes if not _undoes_a_step(student, *pair)] or fixes
    # (and a step of the student's own taken out whole is told alone: the changes that make it do nothing --
    # its gain made 1, its test never true -- work round it)
    # (unless a change inside it does to a twin what the block does to one -- `dst[order]` beside `src[order]`: the
    # step was meant, and half made)
    blocks = [pair for pair in fixes if student.extra_block(pair[0])]
    halves_made = [pair for pair in fixes if pair[1].operator in ADDITIONS
                   and any(student.inside_block(block, pair[1]) for block, _ in blocks)]
    # (and where the block's own test, given the twin it forgot, mends alike -- `if whole(tx):` made `if whole(tx)
    # and whole(ty):` --, the step was meant, and its test is the slip; it is tried first, on the block's line)
    tests_made = [pair for pair in fixes if pair[1].operator == "twin_test"]
    fixes = halves_made or tests_made or blocks or fixes
    # (and an angle's arguments put in arctan2's order, y first -- `np.arctan2(x, y)` -> `np.arctan2(y, x)` --
    # told alone: the exchanges that mend alike downstream, a cos and a sin swapped, compensate for it)
    fixes = [pair for pair in fixes if _arctan2_ordered(pair[1])] or fixes
    passing = passing_functions(trial)
    fixes = [pair for pair in fixes if not student.sharing(pair[1].where, function) & passing]
    if fixes:
        # A change in a helper this function shares with other graded functions (the warp's
        # interpolation) mends its answers by breaking theirs: told only when nothing else is. A
        # change in its own code and one in a helper only it runs are both told (a band's sign
        # flipped where the pyramid is built, or undone where it is collapsed).
        kept = [pair for pair in fixes if not student.shared(pair[1].where, function)]
        if kept and all(student.departs_from_reference(m) for m, _ in kept) and any(
                student.shared(f.where, function) and not student.departs_from_reference(m) for m, f in fixes):
            # (every place of its own is written as the reference writes it -- `_eight_point_core(x1, x2)` --
            # where the shared helper's place is not: the helper is where the slip is, for every caller)
            kept = []
        # (a comparison made strict or not changes only ties: beside another fix it is one by chance --
        # `ssd <= best` beside the update moved where it belongs -- and is not told)
        kept = [pair for pair in (kept or fixes) if not _ties_only(pair[1])] or kept
        # (two normalisations side by side -- np.cov's n - 1 beside a sum divided by n --, made to agree, are the
        # account of the answers: another change mending alike does so by a coincidence of these inputs'
        # sizes -- a count of three points made the 2 of their coordinates)
        kept = [pair for pair in kept if pair[1].operator == "estimator"] or kept
        # (points made homogeneous with a 0 where the 1 belongs are directions: beside another change that
        # mends alike -- a camera's column of ones made zeros -- that one is the fix, this one compensates)
        kept = [pair for pair in kept if not _homogeneous_zeroed(pair[1], student.text)] or kept
        # (a step the reference never takes, taken out, is the fix itself: told as any change is)
        # (and a guard refusing entries the function goes on to treat, taken out, is the fix too)
        removals = all(fix.operator in REMOVALS and not _extra_step(fix, student.reference_source, function)
                       and not student.removes_a_mask_guard(mutant) and not student.extra_block(mutant)
                       for mutant, fix in fixes)
        if removals and not complete:
            # (a step taken out, found before the other changes were all tried, is likely a compensation --
            # the division by a w made Z by the matrix's last row -- and nothing says it is not: told by none
            # of this check, nor kept as found; a later check of the function, given the time, finds the
            # change or confirms it)
            return None
        found = variant.repair(variant.nearest(kept or fixes), complete)
        if not removals or clock.left() <= RESERVE:
            return found
        # Only steps taken out mend it (the division by a w written 0, an inv(T) undoing rows filled with
        # raw pixels): likely compensations. One slip made at several places, if it mends the answers too,
        # is told instead (`x[i, 0], x[i, 1]` where `x_norm`'s belong).
        fallback, near = found, []
    else:
        fallback = None
    # (a search bounded by its tries -- beside a check's own name -- makes only the pairs of one slip
    # made twice, which the code shows, not those of the nearest changes)
    near_all = list(near)
    near = [] if tries is not None or fallback is not None else \
        [m for _, m in sorted(near, key=lambda pair: pair[0])][:PAIR_CHANGES] or list(kept_near)
    if tries is None and fallback is None:
        kept_near[:] = near
    pairs = [(a, b) for a, b in itertools.combinations(near, 2) if _apart(a, b)]
    pairs.sort(key=lambda pair: not _same_slip(*pair))   # the same slip twice first
    # The same slip at two places, even where mending one alone brings the answers no nearer (two
    # reshapes where two transposes belong: one transpose alone mixes the coordinates further).
    tried = {(a.key, b.key) for a, b in pairs}
    slips: dict = {}
    for mutant in runnable:   # (of the lines the failing input runs, as the single changes)
        if (tries is not None or fallback is not None) and mutant.operator in REMOVALS:
            continue   # (beside a name of the effect, or a removal found, a step taken out twice compensates)
        slips.setdefault((mutant.where, mutant.edits[0][2], student.slip(mutant)), []).append(mutant)
    size = lambda pair: student.fix(pair[0]).size + student.fix(pair[1]).size  # noqa: E731
    new = lambda a, b: _apart(a, b) and (a.key, b.key) not in tried  # noqa: E731
    # The slip made at two neighbours first, of all its places: `x2, y2` written where `x1, y1`
    # belong, side by side in one row (a line copied from image 2's with its names half changed).
    # (or at the same place of two lines written alike for two images: one line copied for the other),
    # before the nearest changes' pairs: where the code says the slip was made twice, it is tried first.
    alike = [(a, b) for same in slips.values() for a, b in itertools.combinations(same[:40], 2) if _apart(a, b)]
    # (a change told on an earlier check of the function is likely half of such a slip where it mends no more:
    # `np.round(np.cos(t), 2)` mended where the angle's sine rounds exactly, its twin with it at another angle)
    halves = lambda pair: pair[0].key in halfway or pair[1].key in halfway \
        or pair[0].key in known or pair[1].key in known  # noqa: E731
    # (then those whose two halves each brought the answers nearer alone: `inv(R1)` -> `R1` mends one
    # image of a rectified pair, its copy `inv(R2)` -> `R2` the other)
    nearer = {m.key for _, m in near_all}
    halves_nearer = lambda pair: pair[0].key in nearer and pair[1].key in nearer  # noqa: E731
    first = lambda pair: (not halves(pair), not halves_nearer(pair), size(pair))  # noqa: E731
    beside = sorted((pair for pair in alike if student.neighbours(*pair)), key=first)[:NEIGHBOUR_PAIRS]
    # (and two names exchanged between two lines written alike: `K2_inv @ p1`, `K1_inv @ p2` where each
    # image's own belongs -- "2 -> 1" at one line, "1 -> 2" at its twin)
    crossed = [(a, b) for (where, kind, slip), same in slips.items() if kind == "other_name"
               for b in slips.get((where, kind, _crossed_slip(slip)), [])[:40] for a in same[:40]
               if a.line < b.line and _apart(a, b) and student.mirrored(a, b)]
    mirrored = sorted((pair for pair in alike + crossed if student.mirrored(*pair)), key=first)
    copied = mirrored[:COPIED_PAIRS]
    # (and a pair (x, y) written with one name for both halves, each given its own twin: `side` -> `width`
    # in the first item, `height` in the second)
    copied += _twins_given_pairs(student, runnable, new)[:COPIED_PAIRS]
    side = sorted(beside + copied, key=lambda pair: not halves(pair))
    # (then a step of the student's own and the line written for it, changed together -- `s = np.sort(s)`
    # taken out and `s[0] = 0.0` made `s[-1] = 0.0`: neither alone brings the answers nearer)
    own = _own_step_pairs(student, function, runnable, new) if tries is None and fallback is None else []
    sides = {(a.key, b.key) for a, b in side + own}
    pairs = side + own + [(a, b) for a, b in pairs if (a.key, b.key) not in sides and (b.key, a.key) not in sides]
    # Then each slip's pairs, smallest first, one slip after another in turns (as the single changes):
    # many small slips' pairs would otherwise fill the count before a larger slip's second pair.
    # (a slip made at exactly two places first: both of them are the whole slip -- `np.nan` where `np.inf` belongs,
    # where the table is made and where its border is marked -- where a slip of many places is half made by a pair)
    turns = [(len(same) > 2, sorted(((a, b) for a, b in itertools.combinations(same[:8], 2) if new(a, b) and (a, b) not in side),
                                    key=size)) for same in slips.values()]
    twice = sorted(((turn, many, pair) for many, group in turns for turn, pair in enumerate(group)),
                   key=lambda item: (item[0], item[1], size(item[2])))
    pairs += [pair for *_, pair in twice[:SAME_SLIP_PAIRS]]
    # (and, while the time lasts -- a function quick to call --, the rest of those the code shows, then the rest of
    # each slip's pairs: `flip @ inv(K1)` and `flip @ inv(K2)`, a step copied into two lines written alike, come
    # after many smaller pairs of one slip)
    pairs += [pair for pair in mirrored[COPIED_PAIRS:] if (pair[0].key, pair[1].key) not in sides] \
        + [pair for *_, pair in twice[SAME_SLIP_PAIRS:]]
    # One slip made at every place it can be (three to a few: rows written at `i`, `i + 1` of A and of
    # b where `2 * i`, `2 * i + 1` belong), before any pair: a pair mends half of it.
    # (those made line after line first, as a block of rows is written; then the smallest changes)
    everywhere = sorted((same for (_, kind, _), same in slips.items() if 3 <= len(same) <= EVERYWHERE
                         and kind not in NOT_EVERYWHERE
                         and all(_apart(a, b) for a, b in itertools.combinations(same, 2))),
                        key=lambda same: (max(m.line for m in same) - min(m.line for m in same) > 2 * len(same),
                                          sum(student.fix(m).size for m in same) / len(same)))[:EVERYWHERE_GROUPS]
    # (after the slip made at two neighbours, the likelier where the code shows it)
    grouped = [replace(same[0], edits=tuple(edit for m in sorted(same, key=lambda m: m.line) for edit in m.edits))
               for same in everywhere]
    combined = [replace(first, edits=first.edits + second.edits) for first, second in pairs[:len(side)]] + grouped \
        + [replace(first, edits=first.edits + second.edits) for first, second in pairs[len(side):]]
    # Each pair's answers first; those right on the failing inputs are confirmed at once, and judged by
    # the check before those only nearer (where the student's answers are absurd -- a division by a w
    # of nearly 0 -- every pair is far nearer, and the check's replays would go to the first few).
    exact_pairs, near_pairs = [], []
    # (a pair the code shows -- at neighbours, or copied between two lines -- accepted, the other such pairs
    # accepted too are told beside it: one exchange at the lines that make two values and its twin at the
    # lines that use them mend alike, and where the values first go wrong chooses between them (_upstream))
    shown: list = []
    for index, both in enumerate(combined):
        if clock.left() <= 0 or (shown and index >= len(side)):
            break
        if student.compares_with_its_own_size(both) \
                or any(student.reduces_a_number(replace(both, edits=(edit,)), numbers) for edit in both.edits):
            continue
        values = variant.answers(both, failing, inputs)
        if values is None or variant.fix(both) is None:
            continue
        if subtle:
            near_pairs.append((False, 0.0, len(near_pairs), both, values))
        elif all(variant.right(v, references[i], variant.students[i]) for v, i in zip(values, failing)):
            if _accepted_pair(variant, both, failing):
                if index >= len(side):
                    return variant.repair([_one_half_enough(variant, both, failing, inputs, references)])
                shown.append(_one_half_enough(variant, both, failing, inputs, references))
                continue
            exact_pairs.append((both, values))
        elif np.isfinite(off) and fallback is None:   # (beside a removal found: only exact pairs replace it)
            apart = sum(variant.distance(v, references[i]) for v, i in zip(values, failing))
            if PAIR_NEARER * apart <= off:   # (the student's own recipe: as singles)
                near_pairs.append((PAIR_FAR_NEARER * apart > off, apart, len(near_pairs), both, values))
    if shown:
        return variant.repair(shown)
    # (right on the failing inputs, and not on inputs derived from them: their own recipe -- the library's
    # triangulation where the reference solves its own system -- judged by the checks)
    # (those far nearer first, by their distance; then those only somewhat nearer -- a function with many right
    # answers, a rectification mended in both homographies, comes only somewhat nearer the reference's)
    for both, values in exact_pairs + [(both, values) for *_, both, values in sorted(near_pairs, key=lambda n: n[:3])]:
        if clock.left() <= 0 or variant.replays >= REPLAYS:
            return fallback
        if both.key not in variant.checked and variant.passes_check(both, values, failing, pair=True) \
                and _accepted_pair(variant, both, failing):
            return variant.repair([_one_half_enough(variant, both, failing, inputs, references, judged=True)])
    return fallback


def _twins_given_pairs(student, runnable, new) -> list:
    """Pairs of changes giving one name's uses in two neighbouring items of a tuple or list each a twin name
    (:meth:`_Student.twins_given`)."""
    named = [m for m in runnable if len(m.edits) == 1 and m.edits[0][2] == "other_name" and isinstance(m.edits[0][3], str)]
    payloads = {m.edits[0][3] for m in named}
    paired = {name for name in payloads if any(twin_names(name, other) for other in payloads if other != name)}
    named = [m for m in named if m.edits[0][3] in paired]
    return [(a, b) for a, b in itertools.combinations(named, 2) if a.edits[0][1] != b.edits[0][1]
            and twin_names(a.edits[0][3], b.edits[0][3]) and new(a, b) and student.twins_given(a, b)]


def _own_step_pairs(student, function, runnable, new) -> list:
    """Pairs of changes at two statements of the student's own, one after the other, the second reading
    what the first binds (:meth:`_Student.own_steps`): each statement's first few changes."""
    steps = student.own_steps(function)
    wanted = {place for step in steps for place in step}
    at: dict = {}
    for mutant in runnable:
        place = student._place_of(mutant) if wanted else None
        fix = student.fix(mutant) if place in wanted else None
        # (a statement made to assign a name to itself is told as the statement taken out, its twin change)
        if fix is not None and not any(_assigns_itself(after) for _, _, after in fix.changes):
            at.setdefault(place, []).append(mutant)
    # (the step taken out first, the next line changed with it: the likeliest of such slips is a step
    # the reference does not take; then each statement's likeliest changes, as the single changes' turns)
    pairs = [(i + j, a.operator not in REMOVALS, a, b) for first, second in steps
             for i, a in enumerate(at.get(first, [])[:STEP_CHANGES])
             for j, b in enumerate(at.get(second, [])[:STEP_CHANGES]) if new(a, b)]
    return [(a, b) for *_, a, b in sorted(pairs, key=lambda pair: (pair[1], pair[0]))][:STEP_PAIRS]


_STACKING = ("column_stack", "hstack", "vstack", "concatenate", "stack", "append", "dstack", "c_", "r_", "pad")


_REDUCTIONS = {"min", "max", "amin", "amax", "nanmin", "nanmax", "mean", "nanmean", "median", "nanmedian", "sum",
               "nansum", "std", "ptp", "percentile", "nanpercentile"}


def _numbers_given(student, function: str, inputs) -> set:
    """The parameters of ``function`` given a single number (not an array) on every one of ``inputs``."""
    fn = _defs(student.tree).get(function)
    if fn is None or not inputs:
        return set()
    names = [a.arg for a in (*fn.args.posonlyargs, *fn.args.args)]
    numbers = set()
    for position, name in enumerate(names):
        values = [call[1][position] if position < len(call[1]) else call[2].get(name, None) for call in inputs]
        if all(isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool) for v in values):
            numbers.add(name)
    return numbers


def _near_shape(value, reference) -> bool:
    """Whether ``value`` is an image of nearly the reference's size (each side within 2%, the channels the
    same): a panorama one column narrower, in another reference frame the API allows, is no distance
    apart for :func:`naming.distance`, yet the check itself may accept it."""
    if not (isinstance(value, np.ndarray) and isinstance(reference, np.ndarray) and naming.has_image(reference)
            and value.ndim == reference.ndim and value.shape != reference.shape and value.shape[2:] == reference.shape[2:]):
        return False
    return all(abs(a - b) <= max(2, 0.02 * b) for a, b in zip(value.shape[:2], reference.shape[:2]))


def _stacks(value, name: str) -> bool:
    """Whether ``value`` stacks ``name`` whole with something else (`np.column_stack([pts, ones])`,
    `np.c_[pts, 1]`, `np.hstack((pts, np.ones((n, 1))))`)."""
    call = value.func if isinstance(value, ast.Call) else value.value if isinstance(value, ast.Subscript) else None
    if call is None or _dotted(call).rsplit(".", 1)[-1] not in _STACKING:
        return False
    items = value.args if isinstance(value, ast.Call) else [value.slice]
    pieces = [e for item in items for e in (item.elts if isinstance(item, (ast.List, ast.Tuple)) else [item])]
    return any(isinstance(piece, ast.Name) and piece.id == name for piece in pieces)


def _crossed_slip(slip: str) -> str:
    """The slip undoing ``slip`` of a name (:meth:`_Student.slip`): "2 -> 1" for "1 -> 2"."""
    try:
        parts = ast.literal_eval(slip)
    except (ValueError, SyntaxError):
        return ""
    return repr(parts[::-1]) if isinstance(parts, tuple) and len(parts) == 2 else ""


def _one_half_enough(variant, both, failing, inputs, references, judged: bool = False) -> tuple:
    """``(mutant, fix)`` to tell for an accepted pair of changes: one of its two changes alone where it
    is accepted as the pair was (`_transfer_errors(Hs, dst, src)` -> `(Hs, src, dst)` mends RANSAC alone;
    the tie-break's `np.where` exchanged beside it changes nothing that matters), else the pair."""
    if len(both.edits) == 2 and variant.clock.left() > 0:
        for edit in both.edits:
            half = replace(both, edits=(edit,), operator=edit[2])
            if variant.fix(half) is None:
                continue
            values = variant.answers(half, failing, inputs)
            if values is None:
                continue
            if judged:   # (each half is given a replay of its own: the pair's search may have used them all)
                variant.replays = min(variant.replays, REPLAYS - 1)
                accepted = half.key not in variant.checked and variant.passes_check(half, values, failing, pair=True)
            else:
                accepted = all(variant.right(v, references[i], variant.students[i]) for v, i in zip(values, failing))
            if accepted and _accepted_pair(variant, half, failing):
                return half, variant.fix(half)
    return both, variant.fix(both)


def _accepted_pair(variant, both, failing) -> bool:
    """A pair of changes held to what a single change is: confirmed, writing into no input, testing its
    guard, and breaking none of the grading's other checks of the function (two compensating changes --
    the mean depth inverted twice -- mend the default z_avg and break a given one)."""
    return not variant.student.renormalises(both) and variant.confirmed(both, failing) and not variant.writes_inputs(both) \
        and not variant.guard_untested(both, failing) and not variant.student.steers_round_a_guard(both) \
        and not variant.breaks_other_checks(both)


FIXES = 3         # the most fixes told (one per line)
POINTING = 0.25   # a change this much nearer the expected answers says where to look next
POINTED_LINES = 12   # at most this many lines pointed at in one search
# changes the student's code itself points at -- a line copied from its twin's with one name left, a step
# done to one of two like inputs or twin terms only -- tried before every other kind's first
# (and an OpenCV 0/1 mask used as an index, known by its name: a slow pipeline's search reaches it first)
SHOWN_BY_THE_CODE = {"mirror", "clip_range", "sibling_step", "sibling_line", "factor_pair", "select_mask", "twin_step", "boolean_mask", "derived_name", "measure_first", "identity",
                     "first_term", "own_values", "estimator", "unused_name"}
REMOVALS = {"drop_factor", "drop_division", "drop_centring", "drop_statement", "extra_step", "unwrap", "drop_conversion",
            "drop_mask", "drop_slice", "neutral", "drop_epsilon"}   # changes that take a step out
BRANCHING = {"compare", "logic", "negate", "default"}   # changes of which branch runs
ALIGNED = {"aligned", "add_step", "extra_step"}   # changes that make a statement its counterpart in the reference (aligned.py)
ADDITIONS = {"sibling_step", "factor_pair", "twin_step", "sibling_argument"}   # changes that add a twin's step beside a line
RESERVE = 0.8     # seconds kept for confirming the fixes found, once one is
CONFIRMATION_CALLS = 6   # or the time of this many of the student's calls, if longer (at most half the time)
CONFIRMATION_INPUTS = 15  # about as many inputs a change is confirmed on (derived, seen, given otherwise, ...)
REPLAY_NEARER = 5  # a change this many times nearer the reference's answers is judged by the check itself
PAIR_NEARER = 1.5   # (a pair of changes, fewer than the single ones: judged by the check from this many times)
PAIR_FAR_NEARER = 3   # (those this many times nearer judged first)
REPLAYS = 5       # the most changes a failed check is replayed with
# A change bringing the answers this much nearer the reference's is judged by the check where none gives
# them, after those at least a tenth nearer: a drawing in the student's own style (cv2.drawMatches'
# circles and colours) stays far from the reference's, and the two lines `matches[:10]` left out are a
# few per cent of the difference.
NEARER = 0.98
SLIGHT_REPLAYS = 4   # the replays of a check kept for those (the check's own others and its pairs' stay theirs)
PAIR_REPLAYS = 1  # of which kept for pairs of changes
SHARING_CHECKS = 8  # the checks of the other graded functions running a changed helper replayed with it (worsens_sharing_checks)
OTHER_CHECKS = 3  # the grading's other checks of a function a change judged by a check must pass too
PAIR_CHANGES = 6   # the nearest single changes combined in pairs
SAME_SLIP_PAIRS = 30   # pairs of one change made at two places, tried besides
NEIGHBOUR_PAIRS = 8    # of which at two neighbouring items (of one list, tuple or call), tried first
STEP_CHANGES = 10      # of a statement of the student's own, the changes paired with the next statement's
STEP_PAIRS = 24        # the most such pairs tried
COPIED_PAIRS = 16      # and at the same place of two lines written alike (`H1 = ...`, `H2 = ...`), first too
EVERYWHERE = 6         # the most places of one slip changed at once
EVERYWHERE_GROUPS = 10  # slips so changed
# changes that say nothing made everywhere at once (every sign, every index's axis, every statement)
NOT_EVERYWHERE = {"accumulate", "axis", "sign", "add_sub", "drop_statement", "bound", "compare", "negate", "logic",
                  "drop_keyword", "literal", "guard"}   # (an argument's position, a number: alike in kind only)


NOVEL_STATEMENTS = 3   # statements the reference never writes, whose changes are tried first (no more)
RAISE_FIRST = 24   # changes of the lines up to a raise tried before the others, at most
RAISE_REACH = 6   # lines before the one that raised where a change is tried first
GUARD_TESTS = BRANCHING | {"magnitude"}   # changes of what a test decides (the guard of a raise: tried first of all)


# what a library says when it is given a value of the wrong type (OpenCV's format and parsing errors)
_TYPE_REFUSED = re.compile(r"Point[23][fd]|not numeric|Unsupported format|wrong type|data type|CV_32F|depth")


def _converts(mutant) -> bool:
    """Whether ``mutant`` changes a value's type only (float32 where float64 was made, Python numbers)."""
    return all(e[2] in ("python_numbers", "float32") or (e[2] == "dtype" and e[3] == "np.float32")
               for e in mutant.edits)


def _near_the_raise(mutants, trial, function) -> list:
    """``mutants`` with those of the few lines up to the one where the student's ``function`` raised
    first (each group in its order): the slip is mostly there or just before (a canvas one image
    high, then an image copied into it)."""
    raised = getattr(trial, "raised", None)
    if not raised or raised[0] != function:
        return mutants
    lines = getattr(trial, "raised_lines", ())
    near = lambda m: any(0 <= line - m.line <= RAISE_REACH for line in lines)  # noqa: E731
    # (a few of them first: a raise far downstream of the slip -- an overflow in an iteration count made
    # from errors never divided by w -- must not spend the search on the lines around it)
    first = [m for m in mutants if near(m)][:RAISE_FIRST]
    # (and of those, a change of the test right above the raise first: a guard that raises on valid data
    # is wrong itself -- `if area <= 0: raise` for a triangle listed clockwise -- where a change of the
    # value it tests would only steer round it)
    guard = lambda m: m.operator in GUARD_TESTS and any(0 <= line - m.line <= 1 for line in lines)  # noqa: E731
    # (but a line made its counterpart's or its twin line's again before all: the slip the code shows -- `img1.ndim`
    # in the test of the line converting img2 -- where negating that test only steers round it)
    first.sort(key=lambda m: (m.operator not in ALIGNED and m.operator != "mirror", not guard(m)))
    # (and where a library says it was given a value of the wrong type -- "objectPoints should contain
    # ... Point3f", "Scalar value for argument 'color' is not numeric" -- a conversion anywhere in the
    # function before them: the array is made far from the call it reaches)
    if _TYPE_REFUSED.search(str(raised[3] or "")):
        first = [m for m in mutants if _converts(m)] + [m for m in first if not _converts(m)]
    chosen = {id(m) for m in first}
    return first + [m for m in mutants if id(m) not in chosen]


def _is_image(value) -> bool:
    return isinstance(value, np.ndarray) and value.dtype == np.uint8 and value.ndim >= 2


def _flat_arguments(call) -> list:
    """A call's arguments, the items of its lists and tuples among them."""
    _, args, kwargs = call
    flat = []
    for value in list(args) + list(kwargs.values()):
        flat += list(value) if isinstance(value, (list, tuple)) else [value]
    return flat


def _inside_a_dropped_term(fix: "Fix", dropped: list) -> bool:
    """Whether ``fix`` changes code inside a term that one of the ``dropped`` fixes (a term of a sum taken
    out) removes from the same line: it mends by making that term vanish on the inputs tried."""
    line, before = fix.changes[0][0], fix.changes[0][1]
    return fix.operator != "drop_term" and any(
        other.changes[0][0] == line and before in other.changes[0][1] and before not in other.changes[0][2]
        for other in dropped)


def _homogeneous_zeroed(fix: "Fix", text: str) -> bool:
    """Whether the fix makes the column of ones stacked beside points zeros (`np.hstack([X, np.ones(...)])`
    -> `np.zeros(...)`): the points' homogeneous 1 made 0."""
    if len(fix.changes) != 1:
        return False
    line, before, after = fix.changes[0]
    lines = text.splitlines()
    shown = lines[line - 1] if 0 < line <= len(lines) else ""
    # (a column sized by the points' count, `np.ones((len(pts), 1))`, not a matrix's, `np.ones((3, 1))`)
    sized = re.match(r"(?:np|numpy)\.ones\(\(([^,()]+(?:\([^()]*\))?[^,()]*),", before)
    return sized is not None and not sized.group(1).strip().isdigit() \
        and after.startswith(("np.zeros", "numpy.zeros")) \
        and any(stack in shown for stack in ("hstack", "column_stack", "concatenate", "np.c_"))


def _ties_only(fix: "Fix") -> bool:
    """Whether the fix only makes a comparison strict or not (`<` <-> `<=`): it changes ties alone."""
    if fix.operator != "compare" or len(fix.changes) != 1:
        return False
    _, before, after = fix.changes[0]
    loose = lambda text: re.sub(r"([<>])=", r"\1", text)  # noqa: E731
    return before != after and loose(before) == loose(after)


_SIZE_TWINS = re.compile(r"\b(?:h|w|H|W|height|width|rows|cols|n_rows|n_cols|shape)\b")
_SIZE_CODE = re.compile(r"\.shape\b|\bresize\b|\breshape\b|\bpad\b|\bpyr(?:Down|Up)\b|\bdsize\b|\blen\(|\[[^\]]*:")


def _sized_otherwise(answer, reference) -> bool:
    """Whether the answer's first array is an image of another size than the reference's (not its transpose)."""
    first = lambda value: value[0] if isinstance(value, (tuple, list)) and value else value  # noqa: E731
    got, want = first(answer), first(reference)
    # (an image: its size set by a resize, a crop, a canvas; an array of points of another shape is reshaped,
    # stacked or transposed -- any of their changes)
    return isinstance(got, np.ndarray) and isinstance(want, np.ndarray) and naming.has_image(want) \
        and got.ndim == want.ndim and got.shape != want.shape and got.shape[:2] != want.shape[1::-1]


def _rows_for_columns(answer, reference) -> bool:
    """Whether the answer's first array is the reference's shape with rows and columns exchanged."""
    first = lambda value: value[0] if isinstance(value, (tuple, list)) and value else value  # noqa: E731
    got, want = np.shape(first(answer)) if isinstance(first(answer), np.ndarray) else (), \
        np.shape(first(reference)) if isinstance(first(reference), np.ndarray) else ()
    return len(got) >= 2 and len(want) >= 2 and got[:2] != want[:2] and got[:2] == want[1::-1] and got[2:] == want[2:]


def _apart(first, second) -> bool:
    """Two changes at different places (neither inside the other: the edits must both apply)."""
    (where_a, ordinal_a, _, _), (where_b, ordinal_b, _, _) = first.edits[0], second.edits[0]
    return (where_a, ordinal_a) != (where_b, ordinal_b)


def _same_slip(first, second) -> bool:
    return first.edits[0][2:] == second.edits[0][2:]


class _Variants:
    """Calling variants of the student's function in the companion sandbox, and confirming them."""

    def __init__(self, trial, model, student, function, inputs, references, clock):
        self.trial, self.model, self.student, self.function = trial, model, student, function
        self.inputs, self.references, self.clock = inputs, references, clock
        self.students = [call[3] for call in _recorded(trial)[function][-CALLS_PER_FUNCTION:]]
        self.companion = trial.sandbox.companion()
        self.forbid = () if getattr(trial, "forbidden_allowed", False) else \
            tuple(trial.lab.forbidden.get(function, ())) + tuple(trial.forbid.get(function, ()))
        self.confirmations = None   # (inputs and variants, the reference's answers, usable variants)
        self.crossing: set = set()   # the variants on the other side of a threshold (see confirmed)
        self.beyond: set = set()     # the variants with the check's whole numbers and 0/1 masks given otherwise
        self.untaken: set | None = None   # of which those the student's own code does not answer
        self.keeping: set = set()    # variants (other modes, other channels) where answers must be kept or mended
        self.exchanged: set = set()  # the variants with the twin parameters exchanged (see _unmended_exchange)
        self.translated: set = set()  # the variants with a translation for a homography (the check's own images)
        self.holed: set = set()      # the variants with a point given as NaN (see _breaks_holed)
        self.small: set = set()      # the variants with the images small (a change in what their size gives only)
        self.turned: set = set()     # the variants with the images turned a quarter (portrait for landscape)
        self.widened: set = set()    # the variants made unlike the check's inputs (see _widened)
        self.single: set = set()     # the variants given a single point (see _single_point, _one_point)
        self.channels: set = set()   # of keeping, the variants with the images in the other number of channels
        self.seen = trial.sandbox.shared.setdefault("repair seen", {}).setdefault(function, [])
        self.seconds_per_call = trial.student_seconds / max(1, len(trial.calls))
        # (what one variant's answer may hold: a right one holds the reference's, an image of floats where 8 bits
        # are asked 8 times that; the grader holds every variant's answers while it compares them)
        self.answer_bytes = 2**20 + 16 * max([array_bytes(reference) for reference in references], default=0)
        self.projective = not any(naming.error_kind(answer) is None and _within(answer, reference, 1e-4, 1.0)
                                  for answer, reference in zip(self.students, references))
        self.replayable = _replayable(trial)
        self.checked: dict = {}     # change -> its spread, where the check itself judged it right
        self.replays = 0
        self.slight_replays = 0
        self.screenings = 0         # changes run on the screening input
        self.theirs: dict = {}      # confirmation input -> the student's own answer there
        self.confirmed_by_checks = False   # a change the check judged, confirmed by its other checks
        self.passed_others: set = set()    # changes with which the function's other checks passed
        self.writes: dict = {}   # change (None: the student's own code) -> the calls it changed an input of
        # Changes the check judged whose answers on the failing inputs were close to the reference's
        # (a couple of grey levels, 1%): only their spread says what the student's recipe legitimately
        # gives elsewhere; a change far from the reference (a copy removed, no rectification at all)
        # has a spread that would let anything through, and is confirmed by other checks only.
        self.close: set = set()

    def source(self, mutant) -> str | None:
        """The changed defs of the student's module (None when the change cannot be written). Written
        anew each time: a change runs again only when confirmed (3% of the runs measured), and keeping
        every change's source would hold a large def's text thousands of times."""
        try:
            return ast.unparse(mutated_defs(self.student.tree, mutant.edits, self.student.text))
        except (ValueError, SyntaxError, RecursionError):
            return None

    def answers(self, mutant, indices, every) -> list | None:
        """The variant's answers on ``every[i]`` for ``i`` in ``indices`` (None when it did not answer;
        ``mutant`` None: the student's own code's)."""
        source = self.source(mutant) if mutant is not None else ""
        if source is None:
            return None
        # As long as the student's own calls took, and more: a slow function's variant cut short
        # says nothing of the change (and costs a restart of the companion's worker).
        timeout = max(VARIANT_TIMEOUT, 3 * self.seconds_per_call * len(indices))
        outcome = self.companion.call_variant(
            self.trial.lab.module, source, self.function, [every[i][1:] for i in indices], forbid=self.forbid,
            timeout=max(0.05, min(timeout, self.clock.wall_left())), max_bytes=self.answer_bytes * len(indices))
        value = outcome.value if outcome.ok else None
        for said in outcome.modified if outcome.ok else ():   # "k:name": the k-th call changed its input
            number = said.partition(":")[0]
            if number.isdigit() and int(number) < len(indices):
                self.writes.setdefault(None if mutant is None else mutant.key, set()).add(_key(every[indices[int(number)]]))
        if not (isinstance(value, list) and len(value) == len(indices)):
            return None
        confirming = self.confirmations is not None and every is self.confirmations[0]
        return [_one_point(answer) if confirming and i in self.single else answer for answer, i in zip(value, indices)]

    def fix(self, mutant) -> Fix | None:
        """The mutant's changes shown in the student's code (None when one cannot be shown briefly)."""
        return self.student.fix(mutant)

    def disconnects(self, mutant) -> bool:
        """Whether the change works around a step the graded function leaves out (:func:`_disconnects`)."""
        source = self.source(mutant)
        try:
            changed = parse(source).body if source else []
        except (SyntaxError, ValueError, RecursionError, MemoryError):
            return False
        before = _defs(self.student.tree)
        edited = {fn.name: fn for fn in changed if isinstance(fn, ast.FunctionDef) and fn.name in before}
        graded = before.get(self.function)
        if graded is not None and self.student.extra_block(mutant):
            # (a step of the student's own taken out whole leaves unused only what fed it -- the mask a gain was
            # measured over: the step's own parts, no step of the function's disconnected -- unless the API
            # gave the function a value only that step used)
            parameters = {a.arg for a in (*graded.args.posonlyargs, *graded.args.args, *graded.args.kwonlyargs)}
            return bool(parameters & (_live(graded) - _live(edited.get(self.function, graded))))
        return graded is not None and _disconnects(graded, edited.get(self.function, graded),
                                                   frozenset(edited) - {self.function}, frozenset(before))

    def ran(self, index) -> set | None:
        """The lines of the student's file their own code runs on ``self.inputs[index]`` (a change
        elsewhere leaves that answer as it is, so it mends nothing there), kept per input; None when
        the traced call did not answer in time."""
        kept = self.trial.sandbox.shared.setdefault("repair lines run", {})
        key = (self.function, _key(self.inputs[index]))
        if key not in kept:
            timeout = max(VARIANT_TIMEOUT, 4 * self.seconds_per_call)
            outcome = self.companion.call_variant(
                self.trial.lab.module, "", self.function, [self.inputs[index][1:]], forbid=self.forbid,
                timeout=max(0.05, min(timeout, self.clock.wall_left())), trace=True)
            lines = outcome.value.get("lines") if outcome.ok and isinstance(outcome.value, dict) else None
            kept[key] = {line for line in lines if isinstance(line, int)} if isinstance(lines, list) else None
        return kept[key]

    def screened(self, mutant, failing, screen, subtle=False) -> list | None:
        """The variant's answers on the ``failing`` inputs, when on the ``screen`` one (the smallest)
        it answers right or nearer the reference's than the student's own; else None."""
        self.screenings += 1
        first = self.answers(mutant, [screen], self.inputs)
        if first is None or len(failing) == 1:
            return first
        value, reference, theirs = first[0], self.references[screen], self.students[screen]
        if (subtle or not self.right(value, reference, theirs)) \
                and not self.distance(value, reference) < 0.9 * self.distance(theirs, reference):
            return None
        rest = [i for i in failing if i != screen]
        others = self.answers(mutant, rest, self.inputs)
        if others is None:
            return None
        answered = {**dict(zip(rest, others)), screen: value}
        return [answered[i] for i in failing]

    def passes_check(self, mutant, values, failing, pair: bool = False, slight: bool = False) -> bool:
        """Whether the failed check, run again with every call answered by the variant, passes: its
        tolerances come from the spread of legitimate work, where :func:`right`'s are the reference's
        rounding. At most :data:`REPLAYS` per check; a property on the examples that decided it (its
        failing one: Hypothesis would draw and shrink anew for each variant). ``values``: the variant's
        answers on the ``failing`` inputs (how far from the reference's the check accepts them is the
        spread its confirmation allows)."""
        if slight:   # (a change only a few per cent nearer: replays of its own, after the others')
            if not self.replayable or self.slight_replays >= SLIGHT_REPLAYS or self.clock.left() <= 0:
                return False
            self.slight_replays += 1
        elif not self.replayable or self.replays >= REPLAYS - (0 if pair else PAIR_REPLAYS) or self.clock.left() <= 0:
            return False   # (a replay is kept for the pairs: where a single change's answers are absurd,
        else:              # every change looks far nearer, and the single ones would use them all)
            self.replays += 1
        if _redraws(self.fix(mutant)) or self._replay(mutant, (self.trial.check, self.trial.property_examples)) is not True:
            return False
        self.checked[mutant.key] = max((self.distance(v, self.references[i]) for v, i in zip(values, failing)),
                                       default=0.0)
        if values and all(_close(v, self.references[i]) for v, i in zip(values, failing)):
            self.close.add(mutant.key)
        return True

    def _replay(self, mutant, kept) -> bool | None:
        """Whether a check passes run again with every call answered by the variant; ``kept``: the
        check and its properties' examples (:func:`remember_check`). None when it says nothing of
        the function: it never called it, or a property of it has no examples (not run yet)."""
        fraction = self._replayed_fraction(self.source(mutant), kept, {self.function})
        return fraction if fraction is None or fraction is False else fraction >= 1.0

    def _replayed_fraction(self, source, kept, functions) -> float | bool | None:
        """The share of its points a check earns run again with every call answered by ``source`` (a variant's
        module; False where there is none or no time is left); None when it says nothing of ``functions``: it
        called none of them, or a property of it has no examples (not run yet)."""
        check, examples = kept
        if source is None or self.clock.left() <= 0:
            return False
        sandbox = _Replayed(self, source)
        replayed = _ReplayedTrial(sandbox, check, self.trial.forbid, self.trial.inputs, examples)
        replayed.forbidden_allowed = getattr(self.trial, "forbidden_allowed", False)
        try:
            with np.errstate(all="ignore"):   # (as the runner runs a check: a variant's NaN judged, not warned of)
                verdict = check.func(replayed)
        except _NotReplayed:
            return None
        except Exception:  # noqa: BLE001 - a failed check, the variant's exception, a call out of time
            verdict = Verdict(0.0)
        if sandbox.cut_short:
            return None   # (the repairs' time ran out in a call: the check says nothing of the variant)
        # (a call of the function that raised is a call too: the check fails by the variant's exception --
        # `not rank != 8` refuses the exact pairs the student's own code fitted)
        raised = getattr(replayed, "raised", None)
        if not any(call[0] in functions for call in replayed.calls + replayed.served) \
                and not (raised and raised[0] in functions):
            return None
        if verdict is None:
            return 1.0
        fraction = verdict.fraction if isinstance(verdict, Verdict) else 0.0
        return float(fraction) if isinstance(fraction, (int, float)) and fraction == fraction else 0.0

    def confirmed(self, mutant, failing) -> bool:
        """Whether the variant is also right on the trial's other calls and on confirmation inputs
        derived from the failing ones (where the reference answers); never one that disconnects the
        half of a step the student left out (:func:`_disconnects`)."""
        if self.disconnects(mutant):
            return False
        others = [i for i in range(len(self.inputs)) if i not in failing]
        if others and mutant.key not in self.checked and not self._right_on(mutant, others, self.inputs,
                                                                             self.references):
            return False   # (a change the check judged ran on them when the check ran again)
        if self.confirmations is None:
            # The function's calls in the grading's earlier checks (an image of another size, other
            # arguments), then inputs derived from the failing ones: a change right by coincidence
            # on one check's inputs (rotating by the image's width, 360 degrees) is wrong elsewhere.
            given = {_key(call) for call in self.inputs}
            variants = [call for call in self.seen if _key(call) not in given][:SEEN_CONFIRMATIONS]
            for i in failing[:2]:
                seed = int(fingerprint(self.function, "repair", i, self.inputs[i][1])[:8], 16)
                variants += naming.derived_calls(self.inputs[i], VARIANTS // min(2, len(failing)), seed,
                                             self.model.defaults.get(self.function, ()))
                widened = _widened(self.inputs[i], self.model.defaults.get(self.function, ()))
                self.widened.update(range(len(self.inputs) + len(variants), len(self.inputs) + len(variants) + len(widened)))
                variants += widened + _one_enlarged(self.inputs[i]) + _fewer(self.inputs[i])
                single = _single_point(self.inputs[i])
                self.single.update(range(len(self.inputs) + len(variants), len(self.inputs) + len(variants) + len(single)))
                variants += single + _reordered(self.inputs[i]) + _points_moved(self.inputs[i])
                variants += _rescaled(self.inputs[i], _up_to_scale(self.model.source).get(self.function, ()))
                translated = _translated(self.inputs[i], _up_to_scale(self.model.source).get(self.function, ()))
                self.translated.update(range(len(self.inputs) + len(variants), len(self.inputs) + len(variants) + len(translated)))
                variants += translated
                # (the two views' roles turned round: a canvas as high as img2, right where img2 is
                # the taller, is wrong where img1 is)
                exchanged = naming.twins_exchanged(self.inputs[i], getattr(self.model, "twins", {}).get(self.function, ()))
                self.exchanged.update(range(len(self.inputs) + len(variants), len(self.inputs) + len(variants) + len(exchanged)))
                variants += exchanged
            # (and its images small, for a change in what is computed from their size only: there a
            # student's own recipe may differ from the reference's legitimately -- at the borders, which
            # a small image is mostly made of)
            small = _small(self.inputs[failing[0]])
            self.small = set(range(len(self.inputs) + len(variants), len(self.inputs) + len(variants) + len(small)))
            variants += small
            # (and its images turned a quarter, portrait where they were landscape: a change that mends only the
            # check's own shape -- a centre's y from the height where x still comes from a square's side -- is not)
            turned = _turned(self.inputs[failing[0]])
            self.turned = set(range(len(self.inputs) + len(variants), len(self.inputs) + len(variants) + len(turned)))
            variants += turned
            variants += _greyed(self.inputs[failing[0]])   # (the same images, grey: the API takes both)
            # (and the values the check chose given otherwise: whole numbers made fractional, 0/1 masks soft)
            beyond = [call for i in failing[:2]
                      for call in _beyond(self.inputs[i], self.model.defaults.get(self.function, ()))]
            self.beyond = set(range(len(self.inputs) + len(variants), len(self.inputs) + len(variants) + len(beyond)))
            variants += beyond
            # (and each optional argument given left out, as None: a test of it changed -- `if dist` ->
            # `if dist is not None` -- and the test dropped answer alike where it is given)
            # (never the seed: left out, the answers are drawn anew and the reference's are no truth for them)
            optional = [o for o in self.model.optional.get(self.function, ()) if o[0] not in _DRAWN]
            variants += naming.left_out(self.inputs[failing[0]], optional)
            # (and a point given as NaN, the API's value for one that has none)
            holed = _holed(self.inputs[failing[0]])
            self.holed = set(range(len(self.inputs) + len(variants), len(self.inputs) + len(variants) + len(holed)))
            variants += holed
            # (and the other side of a threshold, for a changed condition only: a student's own
            # recipe may differ from the reference's legitimately there -- a resize's shrink)
            crossing = [call for i in failing[:2]
                        for call in _widened(self.inputs[i], self.model.defaults.get(self.function, ()), (0.5,))]
            self.crossing = set(range(len(self.inputs) + len(variants), len(self.inputs) + len(variants) + len(crossing)))
            variants += crossing
            # (and the function's other modes, cost="ncc" beside "ssd", and its images in the other
            # number of channels: there a change must leave the student's answers as they are, or make
            # them right -- names swapped where both modes read them mend one mode's call by breaking
            # the other's; `shape[::-1][1:]` mends a colour image's size by breaking a grey one's)
            modes = naming.mode_calls(self.inputs[failing[0]], getattr(self.model, "modes", {}).get(self.function, ()))
            channels = naming.other_channels(self.inputs[failing[0]])
            start = len(self.inputs) + len(variants)
            self.keeping = set(range(start, start + len(modes) + len(channels)))
            # (strict -- no exception kept -- only where every image is turned: a mix of a grey and a
            # BGR image, a stereo pair's halves unlike, may be refused by right code and by the fix alike)
            self.channels = set(range(start + len(modes), start + len(modes) + min(1, len(channels))))
            variants += modes + channels
            # (and an optional argument the reference resolves to a number given one: the student's code
            # that takes it rightly must keep doing so -- `s` -> `block_size` mends a default smoothness
            # of 400 by 5, near the right 6, and breaks every smoothness the caller gives)
            resolved = getattr(self.model, "resolved", {}).get(self.function, ())
            given = [call for i in failing[:2] for call in _given(self.inputs[i], resolved)]
            # (and the values the student's own tests compare a number with: there too -- `angle_deg % 180 == 0`
            # at 180 -- a change of what a branch does must keep their answers or make them right)
            own = _defs(self.student.tree).get(self.function)
            given += [call for i in failing[:2] for call in _branch_values(self.inputs[i], own)]
            self.keeping.update(range(len(self.inputs) + len(variants), len(self.inputs) + len(variants) + len(given)))
            variants += given
            every = self.inputs + variants
            try:
                runner = naming.helper()
                runner.prepare(self.model.source, self.model.module, every, max(1.0, self.clock.wall_left()))
                indices = list(range(len(self.inputs), len(every)))
                wanted = dict(zip(indices, runner.run((), indices, max(0.5, self.clock.wall_left()))))
                wanted.update({i: _one_point(wanted[i]) for i in self.single.intersection(wanted)})
                self.confirmations = (every, wanted, [i for i in indices if naming.error_kind(wanted[i]) is None])
            except HelperFailed:   # the reference too slow on them (a whole pipeline): no confirmation here
                self.confirmations = (every, {}, None)
        every, wanted, usable = self.confirmations
        if usable is not None and self.keeping and not self._answers_kept(mutant, every, wanted):
            return False
        if usable is not None and self.untaken is None:   # (values the student's own code does not take)
            asked = sorted(self.beyond.intersection(usable))
            own = self._own(asked, every) if asked else []
            self.untaken = set(asked) if own is None else \
                {i for i, answer in zip(asked, own) if naming.error_kind(answer) is not None}
        if usable is not None and (self._refuted_beyond(mutant, every, wanted)
                                   or self._breaks_holed(mutant, every, wanted)):
            return False
        if usable is not None:   # (those given otherwise refute a change only by a wrong answer: above)
            sized = bool(self.small) and self.student.reads_size(mutant)
            usable = [i for i in usable if i not in self.keeping and i not in self.beyond and i not in self.holed
                      and (mutant.operator in BRANCHING or i not in self.crossing)
                      and (i not in self.small or sized)]
        if usable is not None and (not usable or self._right_on(mutant, usable, every, wanted)):
            # A condition changed sends inputs down another branch: the inputs derived from the failing
            # ones mostly stay on the same side of it, so the grading's other checks of the function
            # judge too (`w >= width` -> `w <= width` mended a crop and broke every shrink).
            # (and so does a change of what an argmin/argmax reads: a choice, like a branch, made the same
            # on inputs near the failing ones -- `np.argmin(S)` -> `np.argmin(P)` picks index 3 there by chance)
            return (mutant.operator not in BRANCHING and not self.student.chooses(mutant)) \
                or self.passes_other_checks(mutant)
        if mutant.key not in self.checked:
            return False
        if usable and self.checked[mutant.key] == 0.0 and self._wrong_where_exact(mutant, usable, every, wanted):
            return False
        if usable and self._unmended_when_turned(mutant, usable, every, wanted):
            return False
        # A function with many right answers (a rectification, an estimator on noisy points: its own
        # least squares) is far from the reference's where it is right: the grading's other checks of
        # it judge. Nearer the reference than the student's own answers on derived inputs is no
        # confirmation: where theirs are far off, a degenerate change is nearer too (a pyramid of no
        # levels passed "blending an image with itself leaves it unchanged"); and numbers on inputs
        # that lost the check's structure (a perturbed F is no longer of rank 2) are nearer by chance.
        if not self._unmended_exchange(mutant, every, wanted) and self.passes_other_checks(mutant):
            self.confirmed_by_checks = True
            return True
        return False

    def _refuted_beyond(self, mutant, every, wanted) -> bool:
        """Whether a change is wrong where the check's numbers or 0/1 masks are given otherwise
        (:func:`_beyond`): not the reference's answer there, and farther from it than three times the
        spread the check accepted of it (the student's recipe may differ from the reference's
        legitimately, as on the check's own inputs; a change the check did not judge, within the
        leeway of a confirmation input) -- right only on the check's choice of
        values (`*` where `/` belongs mends a 0/1 mask clipped to [0, 1], and breaks every soft one;
        `INTER_LINEAR & WARP_INVERSE_MAP`, nearest-neighbour, mends whole shifts only)."""
        indices = sorted(i for i in self.beyond - (self.untaken or set())
                         if i in wanted and naming.error_kind(wanted[i]) is None)
        values = self.answers(mutant, indices, every) if indices else None
        if values is None:
            return False
        # (a change giving exactly the reference's answers on the check's inputs follows the reference's
        # recipe: there it must give them up to rounding, not within the leeway of another recipe)
        spread = 1.5 * self.checked.get(mutant.key, 0.0)
        exact = mutant.key in self.checked and spread == 0
        # (a change that raises there only shows its recipe does not take such a value -- cv2.resize no
        # negative factor -- where a wrong answer shows the change is right by the check's choice alone)
        return any(naming.error_kind(value) is None and not self.right(value, wanted[i], confirming=not exact)
                   and self.distance(value, wanted[i]) > 3 * spread for value, i in zip(values, indices))

    def _wrong_where_exact(self, mutant, indices, every, wanted) -> bool:
        """Whether a change that gave the reference's very answers on the check's inputs (so follows the
        reference's recipe, not one of the many right ones) answers wrongly on a confirmation input without
        images: the other checks do not judge it then (`2 ** n // width` for `width // 2 ** n` gives the reference's
        stripes at n = width = 1, and at 16 and 4 bits -- the example check -- and at no width between).
        A change raising there is not refuted by it: the student's other code may raise there too."""
        # (inputs without images only: on a perturbed photograph a pipeline's own matching differs from the
        # reference's legitimately, as a right stitch's canvas does -- and the check's own images warped by
        # a translation, where no matching is done: a change following the reference's warp to the grey
        # level on the check's input does so there)
        indices = [i for i in indices if i in self.translated
                   or not any(_is_image(value) for value in _flat_arguments(every[i]))]
        values = self.answers(mutant, indices, every) if indices else None
        return values is not None and any(naming.error_kind(value) is None and not self.right(value, wanted[i])
                                          for value, i in zip(values, indices))

    def _breaks_holed(self, mutant, every, wanted) -> bool:
        """Whether a change raises where a point is given as NaN (:func:`_holed`) while the reference and
        the student's own code both answer there: it breaks what their code handles (removing the
        `continue` that skips a point off the image skips no NaN point either). What either answers
        there is not judged: the API only recommends what a NaN point gives."""
        indices = sorted(i for i in self.holed if i in wanted and naming.error_kind(wanted[i]) is None)
        own = self._own(indices, every) if indices else None
        answering = [i for i, answer in zip(indices, own or ()) if naming.error_kind(answer) is None]
        values = self.answers(mutant, answering, every) if answering else None
        return values is not None and any(naming.error_kind(value) is not None for value in values)

    def _unmended_exchange(self, mutant, every, wanted) -> bool:
        """Whether, on an input with the twin parameters exchanged (`sx=0.8, sy=2.0` for `sx=2.0, sy=0.8`:
        an input of the check's own kind, not a perturbed one), the variant answers exactly as the student's
        code does while that answer is far outside the spread the check accepted: a change that leaves a
        wrong answer as it was is not the fix, whatever the other checks say (`max(new_h, h)` ->
        `max(new_h, sx)` mends a shrink in y and leaves the same shrink in x wrong)."""
        indices = sorted(i for i in self.exchanged if i in wanted and naming.error_kind(wanted[i]) is None)
        if not indices or mutant.key not in self.checked:
            return False
        values, own = self.answers(mutant, indices, every), self._own(indices, every)
        if values is None or own is None:
            return False
        spread = 1.5 * self.checked[mutant.key] + 1e-9

        def as_theirs(value, theirs, wanted) -> bool:
            # (an answer of theirs that cannot be measured against the reference's -- (2, 3) where (12, 3)
            # is asked -- is left as it was only by the very same answer: no distance is "1% of" infinity)
            off, same = self.distance(theirs, wanted), self.distance(value, theirs)
            return off > 3 * spread and (same <= 0.01 * off if np.isfinite(off) else same == 0)
        return any(as_theirs(value, theirs, wanted[i]) for value, theirs, i in zip(values, own, indices))

    def writes_inputs(self, mutant) -> bool:
        """Whether the variant wrote into its caller's arrays on a call where the student's own code
        does not (drawing on `image` where `image.copy()` belonged mends the picture by changing the
        caller's): not a fix a caller can use."""
        calls = {_key(call): call for call in self.inputs + list(self.confirmations[0] if self.confirmations else [])}
        for key in self.writes.get(mutant.key, set()) - self.writes.get(None, set()):
            if key in calls and self.answers(None, [0], [calls[key]]) is not None \
                    and key not in self.writes.get(None, set()):
                return True
        return False

    def guard_untested(self, mutant, failing) -> bool:
        """Whether a change of a condition mends no more than removing the condition does: the code
        with that condition always true, or always false, is confirmed as the change was (right on
        the failing and the confirmation inputs; or, where the check judged the change, passing it
        and the function's other checks). The
        checks then cannot tell the change from dropping a guard that does not matter (a bounds test
        before cv2.circle, which clips): the change is not confirmed as the slip."""
        if self.student.raising_guard(mutant, getattr(self.trial, "raised_lines", ())):
            return False   # (the student's own test raised on a valid input: that test is the slip, not a guard)
        if mutant.edits[0][2] == "twin_test":
            return False   # (a test of one twin given the other's is what the code shows half written: a shortcut
            #                 taken out mends too, as any shortcut's removal does, and says less)
        if mutant.edits[0][2] in ALIGNED:
            return False   # (the test made the reference's own, `img2.ndim == 3` for `img1.ndim == 3`: the slip the
            #                 code shows; where these inputs need no test -- SIFT takes a colour image too --, the
            #                 test taken out mends as well, and says less)
        self.untested_guard = None
        for guard in self.student.guards(mutant):
            values = self.answers(guard, failing, self.inputs)
            if values is None or self.clock.left() <= 0:
                return True   # (the guard could not be tried in the time: the change cannot be told from it)
            if mutant.key in self.checked:   # (the change was judged by the check: so is the guard)
                replayed = self._replay(guard, (self.trial.check, self.trial.property_examples))
                if replayed is None or (replayed is True
                                        and (not self.other_checks() or self.passes_other_checks(guard))):
                    return True   # (a guard not replayed, out of replays, is as untested)
            elif all(self.right(v, self.references[i], self.students[i]) for v, i in zip(values, failing)) \
                    and self.confirmed(guard, failing) and not self._righter_elsewhere(mutant, guard):
                self.untested_guard = guard   # (confirmed itself: the test is where the answers go wrong)
                return True   # (as the change was: right on the confirmation inputs too)
        return False

    def _righter_elsewhere(self, mutant, other) -> bool:
        """Whether on the function's other modes (and images of the other number of channels) the
        change answers as the reference where ``other`` does not (a colour per line on BGR images:
        the change mends it, a condition made always false does not)."""
        every, wanted, _ = self.confirmations or ((), {}, None)
        indices = sorted(i for i in self.keeping if i in wanted and naming.error_kind(wanted[i]) is None)
        if not indices:
            return False
        mine, theirs = self.answers(mutant, indices, every), self.answers(other, indices, every)
        if mine is None or theirs is None:
            return False
        return any(self.right(a, wanted[i], confirming=True) and not self.right(b, wanted[i], confirming=True)
                   for a, b, i in zip(mine, theirs, indices))

    def breaks_other_checks(self, mutant) -> bool:
        """Whether the variant fails one of the grading's other checks of the function: a change that
        mends the failing calls by breaking what other calls need is not the slip (names swapped where
        they are made, mending a call that takes them in the wrong order and breaking the cost="ncc"
        branch that takes them in the right one); or, in a helper other graded functions run too, lowers
        the score of one of their checks (:meth:`worsens_sharing_checks`). Unknown (out of time, not
        replayable): False."""
        if mutant.key not in self.passed_others:
            for kept in self.other_checks():
                if self.clock.left() <= 0:
                    return False
                if self._replay(mutant, kept) is False and self.clock.left() > 0:
                    return True
        return self.worsens_sharing_checks(mutant)

    def worsens_sharing_checks(self, mutant) -> bool:
        """Whether the variant, a change in a helper that other graded functions run too, scores lower than the
        student's own code on one of the checks of those functions run so far: `dsize or (h, w)` made `dsize and
        (h, w)` in a warp helper mends a translation's default size by breaking every size a caller gives, on a
        check that failed for the default size too (a check they passed already rules it out earlier, see
        :func:`passing_functions`). Out of time before each of those checks is known: True (not told); a check
        that cannot be replayed (a property without its examples) says nothing."""
        sharing = self.student.sharing(mutant.where, self.function)
        if not sharing:
            return False
        source = self.source(mutant)
        for kept, own in self._sharing_checks(sorted(sharing, key=lambda other: (-self._gives_changed(mutant, other), other))):
            if own is None:   # (not run yet in this grading: the student's own code's score is measured here)
                own = self._replayed_fraction(self.student.text, kept, sharing)
            fraction = self._replayed_fraction(source, kept, sharing) if isinstance(own, float) else None
            if own is False or fraction is False or self.clock.left() <= 0:
                return True   # (not known in the time: a change that may break the other callers is not told)
            if isinstance(fraction, float) and fraction < own - 1e-9:
                return True
        return False

    def _gives_changed(self, mutant, function: str) -> int:
        """How ``function`` calls the helper the change is in, as evidence against the change: 2 where it passes one
        of its own parameters on as a parameter the changed line reads (`warp_affine(image, M, dsize)` calling a
        `_warp` whose `dsize or (h, w)` is changed: its callers choose that value), 1 where it gives the helper such a
        parameter, 0 otherwise."""
        fix = self.fix(mutant)
        helper, caller = self.student._defs.get(mutant.where), self.student._defs.get(function)
        if fix is None or helper is None or caller is None:
            return 0
        line, changed = fix.changes[0][:2]
        try:   # (the names of the code changed -- `dsize or (height, width)` --, else of its whole line)
            read = {node.id for node in walk(parse(changed.strip(), mode="eval")) if isinstance(node, ast.Name)}
        except (SyntaxError, ValueError, RecursionError, AttributeError):
            read = {node.id for node in walk(helper) if isinstance(node, ast.Name) and getattr(node, "lineno", 0) == line}
        arguments = helper.args
        positional = [a.arg for a in arguments.posonlyargs + arguments.args]
        read &= set(positional) | {a.arg for a in arguments.kwonlyargs}
        own = {a.arg for a in caller.args.posonlyargs + caller.args.args + caller.args.kwonlyargs}
        best = 0
        for node in walk(caller):
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == mutant.where:
                given = [(keyword.arg, keyword.value) for keyword in node.keywords] + list(zip(positional, node.args))
                for parameter, value in given:
                    if parameter in read:
                        best = max(best, 2 if isinstance(value, ast.Name) and value.id in own else 1)
        return best

    def _sharing_checks(self, sharing: list) -> list:
        """[((check, its properties' examples), the student's score there or None)]: at most :data:`SHARING_CHECKS`
        checks of the graded functions ``sharing``, in that order -- for each, those run so far where the student's
        code earned points (a change can lower no other score), then the lab's checks naming it not run yet (as
        public or hidden as this one; the exercise order is the lab's, so a helper's other callers are often
        graded later)."""
        from ..stubs import functions_called

        shared = self.trial.sandbox.shared
        scored, done = shared.get(CHECK_FRACTIONS, {}), shared.get("checks run", set())
        later = [check for exercise in self.trial.check.exercise.lab.exercises.values() for check in exercise.checks
                 if check.id not in done and not check.advice and check.hidden == self.trial.check.hidden]
        kept = {}
        for function in sharing:
            ran = [((check, examples), scored[check.id]) for check, examples in shared.get(("checks calling", function), [])
                   if check is not self.trial.check and scored.get(check.id, 0) > 0]
            for entry in ran + [((check, []), None) for check in later if function in functions_called(check)]:
                kept.setdefault(entry[0][0].id, entry)
        return list(kept.values())[:SHARING_CHECKS]

    def nearest(self, fixes) -> list:
        """Of several confirmed fixes [(mutant, fix)], those whose answers on the confirmation inputs
        are as near the reference's as the nearest's (within half as far again): a change compensating
        for the slip elsewhere -- the normalisation undone by dropping the centring it undoes -- passes
        the checks too, but on noisy points answers with another least squares than the fix's."""
        every, wanted, usable = self.confirmations or ((), {}, None)
        if len(fixes) < 2 or not usable or self.clock.left() <= 0:
            return fixes
        apart, plain = [], []
        for mutant, fix in fixes:
            values = self.answers(mutant, usable, every)
            apart.append(float("inf") if values is None else
                         sum(self.distance(v, wanted[i]) for v, i in zip(values, usable)))
            plain.append(float("inf") if values is None else
                         sum(naming.distance(v, wanted[i]) for v, i in zip(values, usable)))
        best = min(apart)
        if not np.isfinite(best):
            return fixes
        near = [(pair, flat) for pair, far, flat in zip(fixes, apart, plain) if far <= 1.5 * best + 1e-9 * (1.0 + best)]
        # Of those alike up to scale and sign, those that give the reference's very numbers: a camera centre's
        # sign flipped turns a rectifying rotation R into -R, the same homographies up to sign, where the
        # fix of the cross product's order gives R itself.
        exact = min(flat for _, flat in near)
        near = [pair for pair, flat in near if not np.isfinite(exact) or flat <= 1.5 * exact + 1e-9 * (1.0 + exact)]
        # A step removed from a line that reads what another fix's line makes (`std_l * std_r` -> `std_r`
        # below the line making `std_l` wrong) undoes the slip's effect there without mending it: not told.
        near = [(mutant, fix) for mutant, fix in near
                if not (mutant.operator in REMOVALS and any(self.student.feeds(other, mutant)
                                                            for other, _ in near if other is not mutant))] or near
        # A step added to a twin beside a line of its own (`xl = xl[:, 0]` -> `xl, xr = xl[:, 0], xr[:, 0]`)
        # where a name used in another's place is mended too (`xr = xl[:, 0]` -> `xr = xr[:, 0]`): the
        # added step does the twin's work twice, and breaks inputs the two lines treat apart.
        return [(mutant, fix) for mutant, fix in near if mutant.operator not in ADDITIONS] \
            if any(mutant.operator not in ADDITIONS for mutant, _ in near) else near

    def _answers_kept(self, mutant, every, wanted) -> bool:
        """Whether in the function's other modes (on its images in the other number of channels, with an
        optional number given) the variant answers as the student's own code does, or as the reference does."""
        indices = sorted(i for i in self.keeping if i in wanted and naming.error_kind(wanted[i]) is None)
        if not indices:
            return True
        values, own = self.answers(mutant, indices, every), self._own(indices, every)
        if values is None or own is None:
            return False
        # (the same exception counts as the same answer -- except on the images of the other channel count:
        # code that raises there for the mistake that is mended here raises no more once it is mended, so a
        # change leaving it raising is no fix: `w = w[..., None]` removed where its test is inverted)
        kept = lambda v, theirs, i: (naming.error_kind(v) == naming.error_kind(theirs) and i not in self.channels) \
            if naming.error_kind(theirs) else self.right(v, theirs, confirming=True)  # noqa: E731
        # (a change the check judged -- the student's own recipe -- is held to the spread the check accepted)
        spread = 1.5 * self.checked[mutant.key] + 1e-9 if mutant.key in self.checked else None
        near = lambda v, i: spread is not None and naming.error_kind(v) is None \
            and self.distance(v, wanted[i]) <= spread  # noqa: E731
        return all(self.right(v, wanted[i], confirming=True) or near(v, i) or kept(v, theirs, i)
                   for v, theirs, i in zip(values, own, indices))

    def _unmended_when_turned(self, mutant, usable, every, wanted) -> bool:
        """Whether on the images turned a quarter the change answers as the student's own code does, where
        that is wrong: a change the check's other shapes accept, mending nothing there (an answer merely
        still far from the reference's -- a drawing in the student's own style -- refutes nothing)."""
        turned = sorted(self.turned.intersection(usable))
        if not turned:
            return False
        values, own = self.answers(mutant, turned, every), self._own(turned, every)
        if values is None or own is None:
            return False
        return any(naming.error_kind(theirs) is None and not self.right(theirs, wanted[i], theirs)
                   and naming.distance(value, theirs) == 0 for value, theirs, i in zip(values, own, turned))

    def _own(self, indices, every) -> list | None:
        """The student's own answers on ``every[i]`` for ``indices`` (the trial's, or asked once per
        confirmation input and kept); None when their code failed to answer."""
        missing = [i for i in indices if i >= len(self.students) and i not in self.theirs]
        if missing:
            own = self.answers(None, missing, every)
            if own is None:
                return None
            self.theirs.update(zip(missing, own))
        return [self.students[i] if i < len(self.students) else self.theirs[i] for i in indices]

    def other_checks(self) -> list:
        """The grading's other checks that called the function, with their properties' examples; then
        the exercise's checks not run yet (as public or hidden as this one: a hidden check's inputs
        never reach a public phase's sandbox), which count only where they call it."""
        shared = self.trial.sandbox.shared
        ran = shared.get(("checks calling", self.function), [])
        done = shared.get("checks run", set())
        later = [(check, []) for check in self.trial.check.exercise.checks
                 if check is not self.trial.check and not check.advice and check.hidden == self.trial.check.hidden
                 and check.id not in done]
        return ([kept for kept in ran if kept[0] is not self.trial.check] + later)[:OTHER_CHECKS]

    def confirmed_by_check(self, mutant, failing, inputs) -> bool:
        """Whether a change right on the failing inputs but not on the confirmation inputs (an
        estimator's answer on noisy points depends on its own least squares: the student's and the
        reference's differ there legitimately) is confirmed as one the check judges: the check passes
        run again with it, and so do the grading's other checks of the function, or it comes nearer."""
        if mutant.key in self.checked:
            return False   # (judged by the check already: not confirmed)
        values = self.answers(mutant, failing, inputs)
        return values is not None and self.passes_check(mutant, values, failing) and self.confirmed(mutant, failing)

    def passes_other_checks(self, mutant) -> bool:
        """Whether the grading's other checks of the function (:meth:`other_checks`; at least one that
        calls it, at most :data:`OTHER_CHECKS`) pass when run again with the variant."""
        confirming = 0
        for kept in self.other_checks():
            outcome = self._replay(mutant, kept)
            if outcome is False:
                return False
            confirming += outcome is True
        if confirming:
            self.passed_others.add(mutant.key)
        return confirming > 0

    def repair(self, fixes, complete: bool = True) -> Repair:
        """The repair told for ``fixes`` [(mutant, fix)], kept for the grading's later checks."""
        self.trial.sandbox.shared["repair found"][self.function] = [mutant for mutant, _ in fixes]
        self.trial.sandbox.shared.setdefault("repair complete", {})[self.function] = complete
        usable = (self.confirmations[2] or []) if self.confirmations else []
        # (the step a change skips is read for the changes told only: reading it walks the def, once per change)
        # (a centring taken out, where the reference centres too, mends by making the two ends agree: the end
        # that does not account for it -- a denormalising matrix without its translation -- is where to look)
        told = sorted((replace(fix, skips=self.student.skipped_step(mutant),
                               needed=fix.operator == "drop_centring" and len(fixes) == 1
                               and not _extra_step(fix, self.student.reference_source, self.function))
                       for mutant, fix in fixes),
                      key=lambda fix: (fix.where != self.function, fix.changes[0][0]))
        checked = "" if not any(mutant.key in self.checked for mutant, _ in fixes) else \
            "checks" if self.confirmed_by_checks else "nearer"
        return Repair(self.function, tuple(told), len(self.inputs) + len(usable), complete, checked)   # as the code runs

    def _right_on(self, mutant, indices, every, wanted) -> bool:
        values = self.answers(mutant, indices, every)
        if values is None:
            return False
        # (on the small images, a change is right only as the reference is, to rounding, or as near as it
        # was on the check's own inputs: what a change to an image's size mends alike at every size -- a
        # fraction of a pixel on a large image -- is three grey levels on a small one)
        if mutant.key not in self.checked:
            wrong = [(v, i) for v, i in zip(values, indices) if not self.right(v, wanted[i], confirming=i not in self.small)]
            if not wrong:
                return True
            # (an input derived for confirming -- a single point, fewer points -- on which the change raises as
            # the student's own code raises there refutes nothing: the slip mended need not change how the code
            # meets a degenerate input, `s = sqrt(2) / 0` of one point)
            # (but not on an input made larger, which nothing makes degenerate: `- n_bits` -> `- u` shifts by a
            # negative count at width 3 as the student's code does, and is right at the width 1 a search shrank to)
            if any(naming.error_kind(v) is None or i < len(self.inputs) or i in self.widened for v, i in wrong) \
                    or len(wrong) == len(values):
                return False   # (and a change no input confirms -- every one raising -- is no confirmed change)
            own = self._own([i for _, i in wrong], every)
            return own is not None and all(naming.error_kind(theirs) == naming.error_kind(v)
                                           for (v, _), theirs in zip(wrong, own))
        if mutant.key not in self.close:
            return False
        # A change the check judged right is confirmed against the student's own answers (their recipe
        # differs from the reference's legitimately, by a measure the check knows, not this): within
        # the spread the check accepted, and where theirs are wrong, half as far at most.
        spread = 1.5 * self.checked[mutant.key] + 1e-9
        own = self._own(indices, every)
        if own is None:
            return False
        for value, theirs, i in zip(values, own, indices):
            if self.right(value, wanted[i], confirming=i not in self.small):
                continue
            # Within the spread the check accepted, always: "far nearer than theirs" alone is no
            # confirmation where theirs are far off (a pyramid of no levels blends an image with
            # itself exactly, and is nearer the reference's blend than uint8 bands that wrap round).
            apart, off = self.distance(value, wanted[i]), self.distance(theirs, wanted[i])
            if apart > spread or (2 * apart > off if _wrong(theirs, wanted[i]) else apart > max(spread, 1.5 * off)):
                return False
        return True

    def distance(self, value, reference) -> float:
        """:func:`naming.distance`, up to scale and sign where :meth:`right` judges so: an essential
        matrix mended is the reference's up to sign, and its plain distance says it is as far as the
        student's own."""
        if isinstance(value, (tuple, list)) and isinstance(reference, (tuple, list)) and len(value) == len(reference) > 1 \
                and all(isinstance(v, np.ndarray) for v in value):
            # (each part's distance summed: a change mending one part of a pair -- one epipole of two -- is nearer)
            return float(sum(naming.distance(v, r, projective=self.projective) for v, r in zip(value, reference)))
        return naming.distance(value, reference, projective=self.projective)

    def right(self, value, reference, student=None, confirming: bool = False) -> bool:
        """:func:`right`, up to scale only where no failing answer of the student's is the reference's
        up to scale (then scale is the mistake, and any variant that leaves it would look right)."""
        return right(value, reference, student, confirming, projective=self.projective)


def remember_check(trial, fraction: float | None = None) -> None:
    """Keep the check of a trial that ran (passed or not), with its properties' examples, under each
    student function it called: a change judged by running a failed check again must pass these too
    (:meth:`_Variants.passes_other_checks`); and the share of its points the student's own code earned
    (``fraction``): a change in a helper other graded functions run must not lower theirs
    (:meth:`_Variants.worsens_sharing_checks`)."""
    shared = getattr(trial.sandbox, "shared", None)
    if shared is None:
        return
    shared.setdefault("checks run", set()).add(trial.check.id)
    if fraction is not None:
        shared.setdefault(CHECK_FRACTIONS, {})[trial.check.id] = fraction
    if not _replayable(trial):
        return
    for function in dict.fromkeys(call[0] for call in trial.calls):
        kept = shared.setdefault(("checks calling", function), [])
        if all(check is not trial.check for check, _ in kept):
            kept.append((trial.check, [list(examples) for examples in trial.property_examples]))


def _replayable(trial) -> bool:
    """Whether the trial's check can be run again with a variant answering: each of its properties
    has the examples that decided it (not one Hypothesis could not reproduce)."""
    examples = getattr(trial, "property_examples", None)
    return getattr(trial, "check", None) is not None and examples is not None \
        and len(examples) == getattr(trial, "_properties", -1) and all(examples)


class _ReplayedTrial(Trial):
    """A trial whose properties run on the examples that decided them in the grading, no more."""

    def __init__(self, sandbox, check, forbid, inputs, examples):
        super().__init__(sandbox, check, forbid, inputs)
        self._examples = examples

    def for_all(self, strategy, body, *, max_examples=None, describe=repr):
        index = self._properties
        self._properties += 1
        if index >= len(self._examples) or not self._examples[index]:
            raise _NotReplayed()
        for example in self._examples[index]:
            body(example)


class _NotReplayed(Exception):
    """A property of a check run again without the examples that decided it."""


class _Replayed:
    """The trial's sandbox as a check run again meets it (:meth:`_Variants.passes_check`): every call
    answered by the variant in the companion, within the repairs' time; nothing shared with the
    grading (a value another check computed from the student's own code is computed again)."""

    def __init__(self, variants: _Variants, source: str):
        self.variants, self.source = variants, source
        self.shared: dict = {}
        self.submission_dir = getattr(variants.trial.sandbox, "submission_dir", None)
        self.cut_short = False   # a call stopped by the repairs' time, not by the check's own limit

    def call(self, module, function, args=(), kwargs=None, *, timeout, forbid=()):
        from ...sandbox.supervisor import CallOutcome

        left = self.variants.clock.wall_left()
        outcome = self.variants.companion.call_variant(
            module, self.source, function, [(tuple(args), dict(kwargs or {}))], forbid=forbid,
            timeout=max(0.05, min(timeout or np.inf, left)))
        if not outcome.ok:
            self.cut_short |= outcome.kind == "timeout" and left < (timeout or np.inf)
            return outcome
        value = outcome.value[0] if isinstance(outcome.value, list) and len(outcome.value) == 1 else None
        if isinstance(value, dict) and "__error__" in value:
            return CallOutcome(ok=False, kind="exception", message=str(value["__error__"]), seconds=outcome.seconds)
        return CallOutcome(ok=True, value=value, seconds=outcome.seconds)


# A check's own name of a mistake says what the answers show ("the rotation goes the opposite way",
# "the channels are not kept"); a repair found beside it says where in the student's code. Searched
# among fewer changes than where nothing names the mistake (the name is said either way): a count,
# not a time, bounds it, so a grading tells the same beside a name however busy the machine is (a
# regrade, a batch on another machine), unless the time, far above what the count takes, runs out.
BESIDE_NAMES = True
BESIDE_TRIES = 45
BESIDE_SECONDS = 4.0


def _beside(verdict) -> bool:
    """Whether a repair may be told beside the check's own name of the mistake: not beside a name that
    already points into the code (a reading of it -- :func:`..claims.from_code` --, a line) nor one a repair
    made."""
    from ..claims import GUESSED, READ_IN_CODE
    from ..inplace import MISTAKE as CHANGED_IN_PLACE

    message = str(verdict.message)
    if verdict.mistake in READ_IN_CODE:   # (a name said after reading the code points into it already)
        return False
    if _said_from_code(message):   # (as does a guarded name's other wording, said of what the code was read to do)
        return False
    if verdict.mistake in GUESSED:   # (a cause guessed from measures: a confirmed change takes its place)
        return True
    # (nor beside a caller's array changed in place, measured where the effect shows: the write is the slip,
    # and a change elsewhere that mends the second call's answers -- a rounding made a floor -- compensates)
    return BESIDE_NAMES and not verdict.mistake.startswith(MISTAKE) and verdict.mistake != CHANGED_IN_PLACE \
        and "reading your code" not in message.lower() and re.search(r"\(line \d+\)", message) is None


def _said_from_code(message: str) -> bool:
    """Whether ``message`` holds a guarded diagnosis in the wording said where the code was read to do what it
    asks (a :func:`..claims.guard`'s ``instead`` naming what the code does, "your code {found}": "the shear goes the
    opposite way: your code passes cv2.WARP_INVERSE_MAP ..."): a change beside it -- the matrix's sign, which
    compensates for the flag -- would point elsewhere than the step read."""
    from ..claims import GUARDED

    for hint in GUARDED.values():
        instead = getattr(hint, "instead", None) or ""
        lead = instead.split("{found}", 1)[0]
        if "{found}" in instead and "your code" in lead and len(lead) >= 20 and lead in message:
            return True
    return False


def _flag_never_passed(fix: Fix, reference_source: str) -> bool:
    """Whether ``fix`` takes out an OpenCV flag (`| cv2.WARP_INVERSE_MAP`) that the reference module never names."""
    if fix.operator != "drop_flag":
        return False
    taken = {flag for _, before, after in fix.changes
             for flag in set(re.findall(r"\bcv2?\.([A-Z][A-Z0-9_]+)", before)) - set(re.findall(r"\bcv2?\.([A-Z][A-Z0-9_]+)", after))}
    return bool(taken) and not any(re.search(rf"\b{flag}\b", reference_source) for flag in taken)


def _upstream(repair: Repair, trial) -> Repair:
    """``repair`` without the places after the first of the student's values to go wrong
    (:func:`autograder.engine.traced.first_departure`), in the def where it does, when another place
    is at it or before: a change downstream of it undoes it (`return T.T` after T built transposed; a
    column taken from the wrong one of two names unpacked in the wrong order)."""
    if len(repair.fixes) < 2 or not trial.calls:
        return repair
    # A place written as the reference writes it (`k ^ k >> 1`) is not where the slip is, when another
    # place mends alike: changed, it compensates for the slip further on (`g >> n_bits - i`), however
    # the values flow from one to the other.
    model = naming.model_for(trial.lab)
    # An OpenCV flag the reference never passes, taken out, is the slip: a change elsewhere that mends alike
    # compensates for it (a shear's sign turned beside cv2.WARP_INVERSE_MAP), wherever the values flow.
    extra = tuple(fix for fix in repair.fixes if model is not None and _flag_never_passed(fix, model.source))
    if extra and len(extra) < len(repair.fixes):
        return replace(repair, fixes=extra)
    own = tuple(fix for fix in repair.fixes if model is None or not _departs(fix, model.source))
    if own and len(own) < len(repair.fixes):
        repair = replace(repair, fixes=own)
        if len(own) < 2:
            return repair
    # A returned value changed whole (`return T` -> `return T.T`) beside a change of a line of the same
    # def that makes it: the first undoes the second's slip after the fact.
    wrapped = lambda fix: len(fix.changes) == 1 and fix.changes[0][1].startswith("return ") \
        and fix.changes[0][1][len("return "):] in fix.changes[0][2][len("return "):]  # noqa: E731
    kept = tuple(fix for fix in repair.fixes if not (wrapped(fix) and any(
        other is not fix and other.where == fix.where and other.changes[0][0] < fix.changes[0][0]
        and not wrapped(other) for other in repair.fixes)))
    repair = replace(repair, fixes=kept) if kept else repair
    if len(repair.fixes) < 2:
        return repair
    from .. import outputs, traced
    from ..hints import code_of

    # An OpenCV call's outputs unpacked out of their documented order: reordering that unpack is the fix,
    # a name read in its sibling's place downstream only mends one of its uses (`u, w, vt = cv2.SVDecomp(F)`
    # read as `w[:, -1]`).
    code = code_of(trial)
    misread = {(fix.where, m.line) for fix in repair.fixes if fix.where in code.functions
               for m in outputs.misread(code.functions[fix.where])}
    kept = tuple(fix for fix in repair.fixes if (fix.where, fix.changes[0][0]) in misread)
    if kept and len(kept) < len(repair.fixes):
        return replace(repair, fixes=kept)

    function, args, kwargs, _ = next((c for c in reversed(trial.calls) if c[0] == repair.function), trial.calls[-1])
    try:
        found = traced.first_departure(trial, function, args, kwargs)
    except Exception:  # noqa: BLE001 - the repair stands without it
        return repair
    if found is None:   # (values too large to record: the code's own data flow says what comes first)
        return _downstream_dropped(repair, code)
    where, line = found
    after = lambda fix: fix.where == where and min(change[0] for change in fix.changes) > line  # noqa: E731
    # (and a change of a line before it, whose values are the reference's, compensates for the slip further on:
    # A built as A^T by `np.column_stack` makes `A @ A.T` right, where `A.T @ A` is the fix)
    before = lambda fix: fix.where == where and max(change[0] for change in fix.changes) < line  # noqa: E731
    # (where every fix is before it or after it, the departure is a step of the student's own no single change
    # mends -- centred points the reference never makes --: it says nothing of which fix is the slip)
    kept = tuple(fix for fix in repair.fixes if not after(fix) and not before(fix))
    return replace(repair, fixes=kept) if kept and len(kept) < len(repair.fixes) else repair


def _downstream_dropped(repair: Repair, code) -> Repair:
    """``repair`` without the fixes at a line that reads, in the same def, what another fix's earlier line
    assigns (directly or through the lines between): each mends every input, so the later one undoes
    the earlier one's slip after the fact (`u - d + 0.5` -> `- 0.5` for columns counted from 1 by
    `np.arange(1, width + 1)` above it)."""
    def assigned(fn, line) -> set:
        return {t.id for node in walk(fn) if isinstance(node, (ast.Assign, ast.AugAssign)) and node.lineno == line
                for target in (node.targets if isinstance(node, ast.Assign) else [node.target])
                for t in walk(target) if isinstance(t, ast.Name)}

    def reaches(fn, line, later) -> bool:   # what `line` assigns flows into `later`
        names = assigned(fn, line)
        for node in sorted((n for n in walk(fn) if isinstance(n, (ast.Assign, ast.AugAssign))
                            and line < n.lineno <= later), key=lambda n: n.lineno):
            if {n.id for n in walk(node.value) if isinstance(n, ast.Name)} & names:
                if node.lineno == later:
                    return True
                names |= assigned(fn, node.lineno)
        return any(n.id in names for node in walk(fn) if getattr(node, "lineno", None) == later
                   for n in walk(node) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load))

    kept = []
    for fix in repair.fixes:
        fn = code.functions.get(fix.where)
        line = fix.changes[0][0]
        if fn is not None and any(other is not fix and other.where == fix.where and other.changes[0][0] < line
                                  and reaches(fn, other.changes[0][0], line) for other in repair.fixes):
            continue
        kept.append(fix)
    return replace(repair, fixes=tuple(kept)) if kept and len(kept) < len(repair.fixes) else repair


CHECK_FRACTIONS = "check fractions"   # the grading's {check id: the share of its points the student's code earned}
TOLD_BESIDE = "repair told beside"   # the grading's {(function, a check's own mistake): (that check, one complete change)}


def _told_beside_before(verdict, trial):
    """The verdict of a check naming a mistake its own way (``verdict.mistake``) that an earlier check of the
    grading named alike, of the same functions, and told with a confirmed change of the student's code beside
    it: pointed to that check, not searched again (the same change on every check of a slow function -- a
    block matcher's ten checks on photographs, each confirmation a block matching -- took the grading's whole
    time for naming, and the functions graded after it had none). The check's fixed hint gives way where that
    change was the one complete account (as :func:`named_by_repair` does for a change confirmed earlier).
    None where it was not told."""
    told = trial.sandbox.shared.get(TOLD_BESIDE, {})
    functions = [function for function in _recorded(trial) if function in getattr(naming.model_for(trial.lab), "mutants", {})]
    earlier = [told.get((function, verdict.mistake)) for function in functions]
    if not verdict.mistake or not earlier or None in earlier:
        return None
    check, complete = earlier[0] if len(set(earlier)) == 1 else (earlier[0][0], False)
    first, newline, rest = str(verdict.message).partition("\n")
    from ..claims import without_guessed_cause, without_where_to_look

    lead = without_where_to_look(first).rstrip()
    if without_guessed_cause(lead, verdict.mistake) != lead:
        return None   # (a cause guessed from the answers: a change confirmed on this check's inputs may refute it)
    lead += "" if not lead or lead[-1] in ".:;!?" else "."
    pointer = f'The same mistake is named at the check "{check}", with the change of your code that mends it there.'
    return replace(verdict, message=f"{lead} {pointer}{newline}{rest}", hint="" if complete else verdict.hint)


def named_by_repair(verdict, trial, traceback_text: str = ""):
    """A failed check's verdict with a confirmed repair told at the end of its first line (in place of
    its fixed hint), when the verdict names nothing or only the error model names it; beside the
    check's own name of the mistake (which stays, with its hint) when :func:`_beside` allows; unchanged
    otherwise (see the module docstring).

    ``traceback_text``: the student's code raised. A change that mends an index past a sequence's end
    but is confirmed only by the check passing (a drawing's colours are not compared exactly:
    `_PALETTE[i]` -> `lines[i]` passes) gives way to what the student's own values show where it raised
    (:func:`..traced.named`: `i` is 8 where `_PALETTE` holds 8 items), a measurement of their code.

    A repair told where the error model named a mutant of the reference takes its place: both are
    confirmed on the student's answers, but the repair is a change of the code the student wrote,
    shown as it is, where a mutant's sentence describes the reference's code in words that may fit
    the student's less well."""
    by_mutant = verdict.mistake.startswith("mutant:") and naming.APPENDED in str(verdict.message)
    by_hand = not by_mutant and bool(verdict.mistake or "looks like" in str(verdict.message).lower())
    if by_hand and not _beside(verdict):
        return verdict
    if by_hand:
        pointed = _told_beside_before(verdict, trial)
        if pointed is not None:
            return pointed
    found_before = {function: {repr(m.edits) for m in mutants}
                    for function, mutants in trial.sandbox.shared.get("repair found", {}).items()}
    repair = name_by_repair(trial, BESIDE_SECONDS, BESIDE_TRIES, said=str(verdict.message),
                            named=str(verdict.mistake)) if by_hand \
        else name_by_repair(trial)
    if repair is None:
        return verdict
    if by_hand and repair.fixes and student_steers(trial, repair):
        return verdict   # (beside the check's own name, a change that only steers the code round a branch adds nothing)
    repair = _upstream(repair, trial)
    if by_hand and verdict.mistake:
        # (beside the check's own name, the changes whose operator's words the name uses are told, where there are
        # some: `sq_err < threshold ** 2` beside "the squared error is compared with the threshold", not `np.sum`
        # made `np.mean`, which mends by halving what the name says is compared)
        agreeing = tuple(fix for fix in repair.fixes if _agrees_with(fix.operator, verdict.mistake))
        if agreeing and len(agreeing) < len(repair.fixes):
            repair = replace(repair, fixes=agreeing)
    # (what later checks take as known is what is told: a compensation dropped here is no fix for them)
    found = trial.sandbox.shared.setdefault("repair found", {})
    told = {repr(fix.edits) for fix in repair.fixes}
    found[repair.function] = [m for m in found.get(repair.function, []) if repr(m.edits) in told] \
        or found.get(repair.function, [])
    student = _student_code(trial)
    ran = set().union(*(lines for (function, _), lines in trial.sandbox.shared.get("repair lines run", {}).items()
                        if function == repair.function and lines))
    around = [student.around_a_branch(fix, ran) for fix in repair.fixes] if student is not None else []
    if around and all(around):   # (every place mends by skipping a shortcut: the shortcut is told)
        repair = replace(repair, fixes=tuple(dict.fromkeys(around)))
    if traceback_text and repair.checked and not by_hand:
        from .. import traced

        shown = traced.named(verdict, trial, traceback_text)
        if shown.mistake == traced.INDEX:   # (an index past a sequence's end, and a change reading another one)
            return shown
    first, newline, rest = str(verdict.message).partition("\n")
    if by_hand:   # the check's name of the effect stays, with where it comes from in their code
        # (its advice on the usual places to look gives way to the place the change shows)
        from ..claims import without_where_to_look

        lead = without_where_to_look(first).rstrip()
        lead += "" if not lead or lead[-1] in ".:;!?" else "."
        # (its fixed hint gives way to a change an earlier check of the function confirmed and that mends
        # this one too: a recipe beside the change sends the student to look elsewhere -- "check that the
        # block shifted by max_disparity is compared too" beside two arguments exchanged)
        known = repair.complete and len(repair.fixes) == 1 \
            and repr(repair.fixes[0].edits) in found_before.get(repair.function, set())
        # (a cause the check guessed from its measures (claims.guessed) is refuted by a change confirmed on
        # this check's inputs too: the change takes its place)
        from ..claims import without_guessed_cause

        guessed = without_guessed_cause(lead, verdict.mistake)
        if guessed != lead:
            return replace(verdict, message=f"{guessed} {repair.sentence}.{newline}{rest}", mistake=repair.mistake,
                           hint="")
        if verdict.mistake:   # (the check's name stands beside the change: its later checks point here)
            trial.sandbox.shared.setdefault(TOLD_BESIDE, {}).setdefault(
                (repair.function, verdict.mistake), (trial.check.name, repair.complete and len(repair.fixes) == 1))
        return replace(verdict, message=f"{lead} {repair.sentence}.{newline}{rest}",
                       hint="" if known else verdict.hint)
    if by_mutant:
        first = first.split(" " + naming.APPENDED, 1)[0]
    lead = first.rstrip()
    lead += "" if not lead or lead[-1] in ".:;!?" else "."
    # The change shown is the evidence; a fixed hint beside it would only guess at another cause.
    return replace(verdict, message=f"{lead} {repair.sentence}.{newline}{rest}", mistake=repair.mistake, hint="")
