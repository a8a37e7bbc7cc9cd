"""What running a notebook from the top defines: the statements grading keeps.

Grading imports a notebook as a module, where its demo code (loading files,
plotting, printing, calling the student's own functions on examples) must not
run: it may need files the grader does not have, take long, or fail. Yet every
definition a graded function relies on must be there, as it is after running
the notebook from the top. So each top-level statement, in notebook order, is
kept exactly when it is a definition and everything it needs is kept:

- ``def`` and ``class`` statements are kept (a body runs only when called);
  only what runs when they are defined (decorators, default values, bases,
  annotations, a class's body) must be kept, else they are left out too;
- imports are kept, unless every statement using them is left out (a
  plotting cell's ``import seaborn as sns`` goes with the plots), or the
  library is not available where grading runs (its names are then left out:
  statements using them are too, and a function using it fails when called);
- an assignment is kept when its value is a *pure expression* of kept names:
  literals, names, arithmetic (``H = K @ R``), indexing, attributes,
  comprehensions, lambdas (``to_h = lambda p: ...``), and calls that build a
  constant or a callable from the libraries (``np.array([[800, 0, 320], ...])``,
  ``np.deg2rad(30)``, ``np.linalg.inv(K)``, ``functools.partial(f, k=3)``,
  ``np.vectorize(f)``, ``cv2.SIFT_create()``, pure methods such as
  ``K.astype(float)``); so is a change to a kept value (``K[0, 2] = cx``,
  ``POINTS.append((1, 2))``, ``x += 1``);
- ``if``/``for``/``try`` blocks are kept whole when every statement in them is;
- every other call is demo code: ``cv2.imread``, ``plt.show()``, ``print``,
  and calling a function the notebook defines (``translate(img)``);
- a statement that reads a name whose latest binding was left out is left out
  ("needs img"), and so is one reading a name no earlier cell defines.

A kept statement computing a value may still fail when run (``ratio = 1 / 0``,
``Kinv = np.linalg.inv(K)`` of a singular K): it is *guarded*, written
``with <suppress Exception>: ratio = 1 / 0`` on its own line (lines keep their
numbers), so that it is skipped, as Jupyter goes on after a failing cell, instead
of failing the import; what reads it then fails as it would in the notebook
(``autograder validate`` names such a statement). Definitions and imports are not
guarded: their errors are reported at their cell and line.

Running the notebook top to bottom defines the same names with the same values,
except those left out: a notebook that runs cleanly never loses a definition it
needs, unless a function reads a global computed by demo code (the notes name it).
"""

from __future__ import annotations

import ast
import builtins
import sys
from collections import ChainMap
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Callable, Iterable

from .parsing import parse, walk

# ------------------------------------------------------------------ what is pure
# Library calls that build a constant (cheap, silent, no files), by module; "*": all of it.
PURE_CALLS = {
    "numpy": {
        "array", "asarray", "asanyarray", "ascontiguousarray", "asfortranarray", "copy",
        "float16", "float32", "float64", "int8", "int16", "int32", "int64", "uint8", "uint16",
        "uint32", "uint64", "bool_", "complex64", "complex128", "dtype", "finfo", "iinfo",
        "eye", "identity", "zeros", "ones", "full", "empty", "zeros_like", "ones_like", "full_like",
        "empty_like", "diag", "diagflat", "arange", "linspace", "logspace", "geomspace", "meshgrid",
        "indices", "tri", "triu", "tril", "vander", "deg2rad", "rad2deg", "radians", "degrees",
        "sqrt", "cbrt", "square", "cos", "sin", "tan", "arccos", "arcsin", "arctan", "arctan2",
        "cosh", "sinh", "tanh", "exp", "log", "log2", "log10", "abs", "absolute", "hypot", "floor",
        "ceil", "round", "around", "rint", "clip", "sign", "stack", "vstack", "hstack", "dstack",
        "column_stack", "row_stack", "concatenate", "block", "dot", "matmul", "cross", "outer",
        "inner", "kron", "transpose", "reshape", "ravel", "squeeze", "expand_dims", "tile", "repeat",
        "roll", "flip", "fliplr", "flipud", "rot90", "where", "maximum", "minimum", "sum", "prod",
        "mean", "cumsum", "min", "max", "amin", "amax", "argmin", "argmax", "trace", "pad",
        "array_equal", "allclose", "isclose", "mod", "remainder", "power", "divide", "multiply",
        "add", "subtract", "negative", "reciprocal", "append", "insert", "delete", "unique",
        "sort", "argsort", "count_nonzero", "nonzero", "isfinite", "isnan", "nan_to_num",
        "broadcast_to", "atleast_1d", "atleast_2d", "atleast_3d", "swapaxes", "moveaxis",
    },
    "numpy.linalg": {"*"},
    "numpy.fft": {"*"},
    "numpy.random": {"default_rng", "RandomState", "Generator", "PCG64", "SeedSequence"},
    "math": {"*"}, "cmath": {"*"}, "operator": {"*"}, "typing": {"*"}, "string": {"*"},
    "fractions": {"Fraction"}, "decimal": {"Decimal"},
    "itertools": {"product", "permutations", "combinations", "combinations_with_replacement",
                  "chain", "islice", "accumulate", "starmap", "zip_longest", "repeat", "pairwise"},
    "collections": {"OrderedDict", "defaultdict", "deque", "Counter", "ChainMap"},
    "functools": {"reduce"}, "copy": {"copy", "deepcopy"},
    "cv2": {"getRotationMatrix2D", "getAffineTransform", "getPerspectiveTransform",
            "invertAffineTransform", "getGaussianKernel", "getStructuringElement", "getDerivKernels",
            "getGaborKernel", "Rodrigues", "KeyPoint", "DMatch", "BFMatcher", "FlannBasedMatcher",
            "createCLAHE"},
    "builtins": {
        "abs", "all", "any", "ascii", "bin", "bool", "bytes", "callable", "chr", "complex", "dict",
        "divmod", "enumerate", "filter", "float", "format", "frozenset", "hasattr", "hash", "hex",
        "int", "isinstance", "issubclass", "iter", "len", "list", "map", "max", "min", "next", "oct",
        "ord", "pow", "range", "repr", "reversed", "round", "set", "slice", "sorted", "str", "sum",
        "tuple", "type", "zip", "object",
    },
}
# Calls that build a callable (never calling what they are given) or a class.
CALLABLE_BUILDERS = {
    "functools.partial", "functools.partialmethod", "functools.lru_cache", "functools.cache",
    "functools.wraps", "functools.singledispatch", "functools.cmp_to_key", "numpy.vectorize",
    "numpy.frompyfunc", "operator.itemgetter", "operator.attrgetter", "operator.methodcaller",
    "builtins.staticmethod", "builtins.classmethod", "builtins.property",
}
CLASS_BUILDERS = {"collections.namedtuple", "typing.NamedTuple", "typing.TypedDict",
                  "dataclasses.make_dataclass", "enum.Enum", "enum.IntEnum", "enum.Flag"}
# Library calls kept as statements of their own: set-up with no output and no files.
SETUP_CALLS = {"numpy.random.seed", "random.seed", "numpy.set_printoptions", "numpy.seterr",
               "warnings.filterwarnings", "warnings.simplefilter"}
# Methods of a kept value that only compute (``K.astype(float)``, ``", ".join(names)``).
PURE_METHODS = {
    "copy", "astype", "reshape", "transpose", "flatten", "ravel", "dot", "tolist", "sum", "mean",
    "max", "min", "squeeze", "item", "conj", "conjugate", "round", "clip", "any", "all", "cumsum",
    "cumprod", "prod", "std", "var", "argmax", "argmin", "argsort", "nonzero", "swapaxes", "take",
    "diagonal", "trace", "view", "format", "join", "split", "rsplit", "splitlines", "upper", "lower",
    "strip", "lstrip", "rstrip", "replace", "startswith", "endswith", "title", "capitalize", "zfill",
    "center", "ljust", "rjust", "encode", "decode", "count", "index", "find", "rfind", "partition",
    "rpartition", "casefold", "keys", "values", "items", "get", "fromkeys", "union", "intersection",
    "difference", "symmetric_difference", "issubset", "issuperset",
}
# Methods that change the kept value they are called on, as statements (``POINTS.append(p)``).
MUTATING_METHODS = {"append", "extend", "insert", "update", "add", "setdefault", "sort", "reverse",
                    "fill", "remove", "discard", "clear", "pop", "popitem", "setflags", "resize"}
# Names only Jupyter defines: a statement reading them depends on the notebook's own run.
JUPYTER_NAMES = {"display", "get_ipython", "In", "Out", "_", "__", "___", "_i", "_ii", "_iii",
                 "_ih", "_oh", "_dh"}
_MODULE_NAMES = {"__name__", "__doc__", "__file__", "__spec__", "__loader__", "__package__",
                 "__builtins__", "__annotations__", "__dict__"}
_BUILTINS = (set(dir(builtins)) | _MODULE_NAMES) - JUPYTER_NAMES
_PLOTTING = ("matplotlib", "pylab", "seaborn", "plotly", "bokeh", "IPython", "ipywidgets", "google.colab")
_FILES = ("read", "load", "open", "imread", "VideoCapture", "urlopen", "urlretrieve", "get", "fetch",
          "download", "listdir", "glob", "scandir", "walk")
_AUTOGRADER = "autograder"
# Written before a line of kept values: a statement that raises is skipped (no new name is bound).
GUARD = 'with __import__("contextlib").suppress(Exception): '
_GUARDED = (ast.Assign, ast.AugAssign, ast.AnnAssign, ast.Expr, ast.Delete)
_UNAVAILABLE = " is not available where grading runs"
_FOR_THE_NOTEBOOK = "for the notebook: grading needs no autograder import"


@dataclass
class Omission:
    """A statement left out of grading.

    Attributes
    ----------
    cell : int
        The cell's number (from 1 at the top, Markdown cells included).
    line : int
        The statement's first line in its cell (from 1).
    text : str
        The statement as written (its first line).
    reason : str
        Why, in a few words: ``"a call: demo code"``, ``"needs img"``.
    users : list of (str, str)
        ``(function, name)``: a kept function whose body reads a name the statement
        would have defined; it fails when called (``("translate", "img")``).
    listed : bool
        False for statements that only show a value (``img.shape`` at a cell's end):
        nothing is lost by leaving them out, so notes do not list them.
    """

    cell: int
    line: int
    text: str
    reason: str
    users: list[tuple[str, str]] = field(default_factory=list)
    listed: bool = True


@dataclass
class CellCode:
    """One code cell given to :func:`analyse`: its lines (magics already out) and how to take it."""

    number: int
    lines: list[str]
    mode: str = "analyse"   # "analyse" | "keep" (tagged grade, or everything) | "skip" (tagged skip)


@dataclass
class Selection:
    """What :func:`analyse` decided: per cell, its lines as the module holds them (a line
    shared by kept and left-out statements rewritten, ``pass`` for the latter; a line of
    kept values guarded, see the module docstring) and whether each is kept; and the
    statements left out, in notebook order."""

    lines: dict[int, list[str]]
    kept: dict[int, list[bool]]
    omissions: list[Omission]
    guarded: dict[int, set[int]] = field(default_factory=dict)   # per cell: indices of its guarded lines


# ------------------------------------------------------------------ availability
def available_at_grading(module: str, local: Iterable[str] = ()) -> bool:
    """Whether ``import module`` can succeed where student code runs: the standard library,
    the libraries the sandbox lets the worker see (see :data:`autograder.sandbox.confine.ALLOWED_LIBRARIES`
    and what they require, when installed here), and the submission's own modules ``local``.

    The same answer at every confinement level, so a notebook grades alike everywhere.
    """
    top = module.split(".", 1)[0]
    if not top or top in local:
        return bool(top)
    if top in sys.stdlib_module_names or top in sys.builtin_module_names:
        return True
    return top in _allowed_top_level_names()


@lru_cache(maxsize=1)
def _allowed_top_level_names() -> frozenset[str]:
    from ..sandbox import confine

    names = set()
    for site in confine._site_folders(sys.path):  # noqa: SLF001 - the sandbox's own view of the sites
        names |= {entry.removesuffix(".py") for entry in confine.allowed_entries(Path(site))}
    return frozenset(names)


# ------------------------------------------------------------------ bindings
@dataclass
class _Binding:
    """The latest binding of a top-level name."""

    kept: bool
    kind: str                 # "module" | "symbol" (from an import) | "function" | "class" | "datatype" | "value"
    qualified: str = ""       # for imports: "numpy", "numpy.linalg.inv"
    statement: int = -1       # index of the binding statement
    why: str = ""             # for a binding left out: its reason


@dataclass
class _Statement:
    node: ast.stmt
    cell: int
    kept: bool = True
    reason: str = ""
    listed: bool = True
    used_by_kept: bool = False
    used_by_left_out: bool = False
    for_notebook: bool = False   # left out as the notebook's own use of autograder (check())


class _Analysis:
    def __init__(self, importable: Callable[[str], bool]):
        self.importable = importable
        self.names: dict[str, _Binding] = {}
        self.stars: list[tuple[str, int]] = []     # (module, statement index) of kept `import *`
        self.statements: list[_Statement] = []
        self.future_allowed = True                 # `from __future__` only before anything else
        self.postponed_annotations = False

    # -------------------------------------------------------------- names
    def lookup(self, name: str) -> _Binding | None:
        binding = self.names.get(name)
        if binding is None and name not in _BUILTINS and self.stars:
            module, index = self.stars[-1]
            return _Binding(True, "symbol", f"{module}.{name}", index)
        return binding

    def missing(self, reads: Iterable[str], unknown: bool = True) -> str:
        """Why a statement reading ``reads`` cannot run as the module has it, or ``""``: a name
        whose binding is left out, or (with ``unknown``) a name nothing defines."""
        names = sorted(set(reads))
        for name in names:
            binding = self.lookup(name)
            if binding is not None and not binding.kept:
                return f"needs {name}"
        for name in names if unknown else ():
            if self.lookup(name) is None and name not in _BUILTINS:
                if name in JUPYTER_NAMES:
                    return f"needs {name}, which only Jupyter defines"
                return f"needs {name}, which no earlier cell defines"
        return ""

    def mark_uses(self, reads: Iterable[str], kept: bool) -> None:
        for name in set(reads):
            binding = self.lookup(name)
            if binding is not None and binding.statement >= 0:
                statement = self.statements[binding.statement]
                if kept:
                    statement.used_by_kept = True
                else:
                    statement.used_by_left_out = True

    def bind(self, names: Iterable[str], kept: bool, kind: str = "value", index: int = -1, why: str = ""):
        for name in names:
            self.names[name] = _Binding(kept, kind, statement=index, why=why)

    # -------------------------------------------------------------- statements
    def add(self, node: ast.stmt, cell: int, mode: str) -> _Statement:
        index = len(self.statements)
        statement = _Statement(node, cell)
        self.statements.append(statement)
        reads: set[str] = set()
        if mode == "skip":
            statement.kept, statement.reason = False, "the cell is tagged skip-grading"
        elif mode == "keep":
            _Reads(self, reads).statement(node)
        else:
            try:
                statement.reason, statement.listed = self.judge(node, reads)
            except RecursionError:  # an expression nested deeper than the judging recursion goes
                reads.clear()
                statement.reason, statement.listed = self.judge_flat(node, reads), True
            statement.kept = not statement.reason
        if not statement.kept and (statement.reason == _FOR_THE_NOTEBOOK or any(
                getattr(self.lookup(name), "why", "") == _FOR_THE_NOTEBOOK for name in reads)):
            # check("lab07.ex1"), its import and what uses its report: expected, not worth a note
            statement.listed, statement.for_notebook = False, True
        if isinstance(node, ast.ImportFrom) and node.module == "__future__":
            if not self.future_allowed:
                statement.kept, statement.reason = False, "allowed only at the top of a module"
            elif statement.kept and any(a.name == "annotations" for a in node.names):
                self.postponed_annotations = True
        elif statement.kept and not (isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant)):
            self.future_allowed = False  # the module's first statement is now another one
        self.mark_uses(reads, statement.kept)
        self.record_bindings(node, index, statement)
        return statement

    def judge(self, node: ast.stmt, reads: set[str]) -> tuple[str, bool]:
        """``(reason, listed)``: why ``node`` is left out (``""``: it is kept)."""
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            return self.judge_import(node), True
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            # A name nothing defines is left for the import to report, with its cell and line.
            _Reads(self, reads).definition(node)
            return self.missing(reads, unknown=False), True
        if isinstance(node, ast.Expr):
            return self.judge_expression_statement(node.value, reads)
        if isinstance(node, ast.If) and _is_main_block(node):
            return "a main block: demo code", True
        if isinstance(node, (ast.If, ast.For, ast.Try)) or type(node).__name__ == "TryStar":
            return self.judge_block(node, reads), True
        if isinstance(node, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
            return self.judge_assignment(node, reads), True
        if isinstance(node, (ast.Pass, ast.Global, ast.Nonlocal)):
            return "", True
        if isinstance(node, ast.Delete):
            for target in node.targets:
                _Reads(self, reads).expression(target)
            return self.missing(reads), True
        kinds = {ast.Assert: "a test: demo code", ast.Raise: "raises: demo code",
                 ast.While: "a loop: demo code", ast.With: "a with block: demo code"}
        return kinds.get(type(node), "demo code"), True

    def judge_flat(self, node: ast.stmt, reads: set[str]) -> str:
        """A statement too deeply nested for :meth:`judge` (``x = 1 + 1 + ... + 1``), read without
        recursion: an assignment or expression without a call is kept when its names are."""
        if not isinstance(node, (ast.Assign, ast.AugAssign, ast.AnnAssign, ast.Expr)):
            return "too deeply nested to read: demo code"
        for inner in walk(node):
            if isinstance(inner, (ast.Call, ast.Await, ast.Yield, ast.YieldFrom, ast.Lambda, ast.NamedExpr,
                                  ast.ListComp, ast.SetComp, ast.GeneratorExp, ast.DictComp)):
                return "a call: demo code"
            if isinstance(inner, ast.Name) and not isinstance(inner.ctx, ast.Store):
                reads.add(inner.id)
        return self.missing(reads)

    def judge_import(self, node) -> str:
        modules = ([node.module or ""] if isinstance(node, ast.ImportFrom) else [a.name for a in node.names])
        if isinstance(node, ast.ImportFrom) and node.level:
            return ""  # relative: reported at grading as it would be
        if any(m.split(".")[0] == _AUTOGRADER for m in modules):
            return _FOR_THE_NOTEBOOK
        missing = [m for m in modules if m != "__future__" and not self.importable(m)]
        if missing:
            return f"{missing[0]}{_UNAVAILABLE}"
        return ""

    def judge_expression_statement(self, value: ast.expr, reads: set[str]) -> tuple[str, bool]:
        """A statement of one expression: kept when it is a docstring, a change to a kept
        value or a set-up call; else left out (listed only when it would have done something)."""
        if isinstance(value, ast.Constant):
            return "", True   # a docstring
        if isinstance(value, ast.Call):
            reason = self.judge_mutation_call(value, reads)
            if reason is not None:
                return reason, True
            if self.qualified(value.func) in SETUP_CALLS:
                return _Pure(self, reads).arguments(value) or self.missing(reads), True
        impure = _Pure(self, reads).why_not(value)
        return impure or "shows a value", bool(impure)  # a value shown: nothing is lost

    def judge_mutation_call(self, call: ast.Call, reads: set[str]) -> str | None:
        """A kept value's mutating method (``POINTS.append(p)``): ``""`` if kept, a reason if
        not, None when ``call`` is no such call."""
        chain = _chain(call.func)
        if not chain or len(chain) < 2 or chain[-1] not in MUTATING_METHODS:
            return None
        binding = self.lookup(chain[0])
        if binding is None or binding.kind in ("module", "symbol"):
            return None
        pure = _Pure(self, reads)
        reads.add(chain[0])
        reason = pure.arguments(call, callee_calls=True)
        return reason or self.missing(reads)

    def judge_block(self, node, reads: set[str]) -> str:
        """``if``/``for``/``try``: kept whole when every statement in it would be kept."""
        pure = _Pure(self, reads)
        tests = [node.test] if isinstance(node, ast.If) else [node.iter] if isinstance(node, ast.For) else []
        for test in tests:
            reason = pure.why_not(test)
            if reason:
                return reason
        # try: import seaborn / except ImportError: ... works wherever it runs.
        guarded = isinstance(node, ast.Try) and any(_catches_import_errors(h) for h in node.handlers)
        inner = _Analysis((lambda module: True) if guarded else self.importable)
        # The block's bindings over the names outside it, not a copy of them: a copy per block
        # made a cell of many blocks after many names quadratic.
        inner.names, inner.stars = ChainMap({}, self.names), list(self.stars)
        inner.future_allowed = False
        if isinstance(node, ast.For):
            inner.bind(_targets(node.target), True)
        bodies = [node.body, node.orelse]
        if not isinstance(node, (ast.If, ast.For)):
            bodies += [node.finalbody] + [h.body for h in node.handlers]
            for handler in node.handlers:
                if handler.type is not None:
                    reason = pure.why_not(handler.type)
                    if reason:
                        return reason
                if handler.name:
                    inner.bind([handler.name], True)
        for body in bodies:
            for statement in body:
                inner_reads: set[str] = set()
                reason, _ = inner.judge(statement, inner_reads)
                if reason:
                    return reason
                reads |= {n for n in inner_reads if n not in inner.names or n in self.names}
                inner.record_bindings(statement, -1, _Statement(statement, 0))
        return self.missing(reads)

    def judge_assignment(self, node, reads: set[str]) -> str:
        targets = node.targets if isinstance(node, ast.Assign) else [node.target]
        pure = _Pure(self, reads)
        for target in targets:
            for base in _mutated(target):  # K[0, 2] = ... / f.cache = ... / x += ...
                binding = self.lookup(base)
                if binding is not None and binding.kind in ("module", "symbol"):
                    return "changes a library's settings: demo code"
                reads.add(base)
            reason = pure.why_not(target)
            if reason:
                return reason
        if isinstance(node, ast.AugAssign):
            reads |= _targets(node.target)
        if isinstance(node, ast.AnnAssign) and not self.postponed_annotations:
            reason = pure.why_not(node.annotation)
            if reason:
                return reason
        if node.value is not None:
            reason = pure.why_not(node.value)
            if reason:
                return reason
        return self.missing(reads)

    # -------------------------------------------------------------- bindings made
    def record_bindings(self, node: ast.stmt, index: int, statement: _Statement) -> None:
        kept, why = statement.kept, _FOR_THE_NOTEBOOK if statement.for_notebook else statement.reason
        if isinstance(node, ast.Import):
            for alias in node.names:
                name = alias.asname or alias.name.split(".")[0]
                qualified = alias.name if alias.asname else name
                self.names[name] = _Binding(kept, "module", qualified, index, why)
        elif isinstance(node, ast.ImportFrom):
            module = ("." * node.level) + (node.module or "")
            for alias in node.names:
                if alias.name == "*":
                    if kept:
                        self.stars.append((module, index))
                    continue
                self.names[alias.asname or alias.name] = _Binding(kept, "symbol", f"{module}.{alias.name}",
                                                                  index, why)
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            self.bind([node.name], kept, "function", index, why)
        elif isinstance(node, ast.ClassDef):
            self.bind([node.name], kept, "class", index, why)
        elif isinstance(node, ast.Delete):
            for target in node.targets:
                for name in _targets(target):
                    _unbind(self.names, name)
        elif isinstance(node, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            kind = self.kind_of(node.value) if kept and node.value is not None else "value"
            alias = self.qualified(node.value) if kind == "symbol" else ""
            for target in targets:
                if isinstance(target, ast.Name):
                    if isinstance(node, ast.AugAssign) and kept:
                        continue  # the same binding, changed
                    self.names[target.id] = _Binding(kept, kind, alias, index, why)
                elif isinstance(target, (ast.Tuple, ast.List)):
                    self.bind(_targets(target), kept, "value", index, why)
                elif not kept:  # K[0, 2] = cx left out: K is not what running the notebook gives
                    self.bind(_mutated(target), False, "value", index, f"{why}, changing it")
        elif not isinstance(node, ast.Expr):  # blocks: what they bind, kept or left out with them
            self.bind(_defined_by(node), kept, "value", index, why)

    def kind_of(self, value: ast.expr) -> str:
        """What an assigned value is: a callable or class of the notebook (calling it runs
        student code), another name for a library's (``inv = np.linalg.inv``: "symbol"),
        or a plain value."""
        if isinstance(value, ast.Lambda):
            return "function"
        chain = _chain(value)
        if chain:
            binding = self.lookup(chain[0])
            if binding is not None and binding.kind in ("module", "symbol"):
                return "symbol"
            if binding is not None and len(chain) == 1:
                return binding.kind
            return "value"
        if isinstance(value, ast.Call):
            called = self.qualified(value.func)
            if called in CLASS_BUILDERS:
                return "datatype"
            if called in CALLABLE_BUILDERS or (isinstance(value.func, ast.Call)
                                               and self.qualified(value.func.func) in CALLABLE_BUILDERS):
                return "function"
        return "value"

    def qualified(self, func: ast.expr) -> str:
        """``numpy.linalg.inv`` for ``np.linalg.inv`` (imports resolved), ``builtins.len``; else ``""``."""
        chain = _chain(func)
        if not chain:
            return ""
        binding = self.lookup(chain[0])
        if binding is None:
            return f"builtins.{'.'.join(chain)}" if chain[0] in _BUILTINS else ""
        if binding.kind in ("module", "symbol"):
            return ".".join([binding.qualified, *chain[1:]])
        return ""

    # -------------------------------------------------------------- the end
    def finish(self) -> None:
        """Imports used only by statements left out are left out with them (those a kept
        function's body reads stay: the body runs when the function is called). An import
        of what grading lacks that nothing uses at all is kept as written: a misspelt module
        is reported at its cell and line."""
        read_by_bodies = set().union(*self.readers().values())
        for statement in self.statements:
            node = statement.node
            if not isinstance(node, (ast.Import, ast.ImportFrom)) or statement.used_by_kept \
                    or _bound_names(node) & read_by_bodies:
                continue
            if statement.kept and statement.used_by_left_out:
                statement.kept, statement.reason = False, "used only by statements left out"
            elif statement.reason.endswith(_UNAVAILABLE) and not statement.used_by_left_out:
                statement.kept, statement.reason = True, ""

    def readers(self) -> dict[str, set[str]]:
        """The kept functions (and lambdas) by name, with the global names their bodies read."""
        found: dict[str, set[str]] = {}
        for statement in self.statements:
            if not statement.kept:
                continue
            node = statement.node
            for inner in walk(node):
                if isinstance(inner, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
                    name = getattr(inner, "name", None) or _lambda_name(node)
                    found.setdefault(name, set()).update(_body_globals(inner))
        return found


def _unbind(names, name: str) -> None:
    """``del name``: gone from ``names``, a dict or (in a block) a ChainMap over the names
    outside it, where it is then bound to None (looked up as not bound)."""
    if isinstance(names, ChainMap):
        names.maps[0].pop(name, None)
        if any(name in outer for outer in names.maps[1:]):
            names.maps[0][name] = None
    else:
        names.pop(name, None)


def _lambda_name(statement: ast.stmt) -> str:
    targets = getattr(statement, "targets", None) or [getattr(statement, "target", None)]
    names = [t.id for t in targets if isinstance(t, ast.Name)]
    return names[0] if names else "a lambda"


# ------------------------------------------------------------------ expressions
class _Pure:
    """Judges whether an expression only computes from kept names (collecting them in ``reads``)."""

    def __init__(self, analysis: _Analysis, reads: set[str]):
        self.analysis, self.reads = analysis, reads

    def why_not(self, node: ast.AST, local: frozenset = frozenset()) -> str:
        """``""`` when ``node`` is pure, else why not, in a few words."""
        if node is None or isinstance(node, (ast.Constant, ast.expr_context)):
            return ""
        if isinstance(node, ast.Name):
            if not isinstance(node.ctx, ast.Store) and node.id not in local:
                self.reads.add(node.id)
            return ""
        if isinstance(node, ast.Call):
            return self.call(node, local)
        if isinstance(node, ast.Lambda):
            return self.each(node.args.defaults + [d for d in node.args.kw_defaults if d is not None], local)
        if isinstance(node, (ast.ListComp, ast.SetComp, ast.GeneratorExp, ast.DictComp)):
            return self.comprehension(node, local)
        if isinstance(node, (ast.Await, ast.Yield, ast.YieldFrom)):
            return "demo code"
        if isinstance(node, ast.NamedExpr):
            return self.why_not(node.value, local)
        return self.each(list(ast.iter_child_nodes(node)), local)

    def each(self, nodes, local) -> str:
        for child in nodes:
            reason = self.why_not(child, local)
            if reason:
                return reason
        return ""

    def comprehension(self, node, local) -> str:
        inner = set(local)
        for number, generator in enumerate(node.generators):
            reason = self.why_not(generator.iter, frozenset(inner) if number else local)
            if reason:
                return reason
            inner |= _targets(generator.target)
            reason = self.each(generator.ifs, frozenset(inner))
            if reason:
                return reason
        parts = [node.key, node.value] if isinstance(node, ast.DictComp) else [node.elt]
        return self.each(parts, frozenset(inner))

    def call(self, node: ast.Call, local) -> str:
        reason = self._call(node, local)
        if reason:  # what it reads all the same: imports it uses, names it depends on
            for value in list(node.args) + [k.value for k in node.keywords]:
                self.why_not(value, local)
        return reason

    def _call(self, node: ast.Call, local) -> str:
        analysis = self.analysis
        func = node.func
        if isinstance(func, ast.Call):   # functools.lru_cache(maxsize=None)(f)
            if analysis.qualified(func.func) not in CALLABLE_BUILDERS:
                return "a call: demo code"
            return self.why_not(func, local) or self.arguments(node, local=local)
        chain = _chain(func)
        if chain is None:  # np.array(x).astype(float), "{}".format(x), (K @ R).dot(t)
            if isinstance(func, ast.Attribute) and func.attr in PURE_METHODS:
                return self.why_not(func.value, local) or self.arguments(node, local=local)
            return "a call: demo code"
        if chain[0] in local:
            return "a call: demo code"
        binding = analysis.lookup(chain[0])
        if binding is not None:
            self.reads.add(chain[0])  # marks what it names used (by a statement kept or not)
        called = analysis.qualified(func)
        if called:
            builds = called in CALLABLE_BUILDERS or called in CLASS_BUILDERS
            # os.path.join(...), cv2.__version__.startswith(...): a pure method of a library's value
            method = len(chain) >= 3 and chain[-1] in PURE_METHODS
            if builds or method or _is_pure_call(called):
                return self.arguments(node, callee_calls=not builds, local=local)
            return _impure_reason(called)
        if binding is None:  # "needs translate, which no earlier cell defines" (or what it is given)
            self.reads.add(chain[0])
            return "output" if chain == ["display"] else self.arguments(node, local=local)
        if not binding.kept:  # "needs img"
            return self.arguments(node, local=local)
        if binding.kind == "datatype" and len(chain) == 1:
            return self.arguments(node, local=local)
        if binding.kind in ("function", "class"):
            return f"runs {'.'.join(chain)}(): demo code"
        if len(chain) >= 2 and chain[-1] in PURE_METHODS:
            return self.arguments(node, local=local)
        return "a call: demo code"

    def arguments(self, node: ast.Call, callee_calls: bool = True, local=frozenset()) -> str:
        """The call's arguments are pure; a function of the notebook (or a lambda) handed to a
        call that would run it (``list(map(translate, images))``) is demo code."""
        values = list(node.args) + [k.value for k in node.keywords]
        for value in values:
            if callee_calls and self._runs_student_code(value):
                return "runs your code: demo code"
            reason = self.why_not(value, local)
            if reason:
                return reason
        return ""

    def _runs_student_code(self, value: ast.expr) -> bool:
        """A function or class of the notebook, or a lambda calling one (``key=lambda p: p[1]``
        computes; ``key=lambda p: f(p)`` runs the notebook's ``f``)."""
        if isinstance(value, ast.Starred):
            value = value.value
        if isinstance(value, ast.Lambda):
            return any(isinstance(n, ast.Call) and self._runs_student_code(n.func) for n in walk(value.body))
        chain = _chain(value)
        if chain and len(chain) == 1:
            binding = self.analysis.lookup(chain[0])
            return binding is not None and binding.kind in ("function", "class")
        return False


def _is_pure_call(qualified: str) -> bool:
    module, _, name = qualified.rpartition(".")
    allowed = PURE_CALLS.get(module, ())
    detector = module.split(".")[0] == "cv2" and (name.endswith("_create") or name.startswith("create"))
    return "*" in allowed or name in allowed or detector


def _impure_reason(qualified: str) -> str:
    if qualified.startswith(tuple(p + "." for p in _PLOTTING)):
        return "plotting"
    if qualified in ("builtins.print", "builtins.input", "builtins.display"):
        return "output"
    name = qualified.rpartition(".")[2]
    if qualified == "builtins.open" or any(word.lower() in name.lower() for word in _FILES):
        return "reads a file: demo code"
    return "a call: demo code"


# ------------------------------------------------------------------ reads of statements
class _Reads:
    """The names a statement reads when it runs (bodies of functions excepted: they run when called)."""

    def __init__(self, analysis: _Analysis, reads: set[str]):
        self.analysis, self.reads = analysis, reads

    def expression(self, node) -> None:
        for inner in _evaluated(node):
            if isinstance(inner, ast.Name) and not isinstance(inner.ctx, ast.Store):
                self.reads.add(inner.id)

    def definition(self, node) -> None:
        """What running a ``def`` or ``class`` statement evaluates."""
        for decorator in node.decorator_list:
            self.expression(decorator)
        if isinstance(node, ast.ClassDef):
            for base in node.bases + [k.value for k in node.keywords]:
                self.expression(base)
            bound: set[str] = set()
            for statement in node.body:  # a class body runs now
                if isinstance(statement, (ast.FunctionDef, ast.AsyncFunctionDef)):
                    before = set(self.reads)
                    self.definition(statement)
                    self.reads -= {n for n in self.reads - before if n in bound}
                    bound.add(statement.name)
                    continue
                names: set[str] = set()
                _Reads(self.analysis, names).expression(statement)
                self.reads |= names - bound
                bound |= {n.id for n in walk(statement) if isinstance(n, ast.Name)
                          and isinstance(n.ctx, ast.Store)}
            return
        arguments = node.args
        for default in arguments.defaults + [d for d in arguments.kw_defaults if d is not None]:
            self.expression(default)
        if not self.analysis.postponed_annotations:
            annotations = [a.annotation for a in arguments.posonlyargs + arguments.args + arguments.kwonlyargs
                           + [arguments.vararg, arguments.kwarg] if a is not None and a.annotation is not None]
            for annotation in annotations + ([node.returns] if node.returns else []):
                self.expression(annotation)

    def statement(self, node) -> None:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            self.definition(node)
        else:
            self.expression(node)


def _evaluated(node):
    """The nodes under ``node`` evaluated now: not the bodies of functions and lambdas
    (only their defaults and decorators), not comprehension variables."""
    pending = [node]
    while pending:
        current = pending.pop()
        if isinstance(current, ast.Lambda):
            pending += current.args.defaults + [d for d in current.args.kw_defaults if d is not None]
            continue
        if isinstance(current, (ast.FunctionDef, ast.AsyncFunctionDef)):
            pending += current.decorator_list + current.args.defaults + \
                [d for d in current.args.kw_defaults if d is not None]
            continue
        if isinstance(current, (ast.ListComp, ast.SetComp, ast.GeneratorExp, ast.DictComp)):
            local = set()
            for generator in current.generators:
                local |= _targets(generator.target)
            inner = [g.iter for g in current.generators] + [i for g in current.generators for i in g.ifs]
            inner += [current.key, current.value] if isinstance(current, ast.DictComp) else [current.elt]
            for child in inner:
                yield from (n for n in _evaluated(child)
                            if not (isinstance(n, ast.Name) and n.id in local))
            continue
        yield current
        pending += list(ast.iter_child_nodes(current))


def _body_globals(function) -> set[str]:
    """The names a function's (or lambda's) body reads that are not its own: globals (or builtins)."""
    arguments = function.args
    local = {a.arg for a in arguments.posonlyargs + arguments.args + arguments.kwonlyargs
             + [arguments.vararg, arguments.kwarg] if a is not None}
    body = function.body if isinstance(function.body, list) else [function.body]
    loads, declared_global = set(), set()
    for statement in body:
        for inner in walk(statement):
            if isinstance(inner, ast.Name):
                (loads.add if not isinstance(inner.ctx, ast.Store) else local.add)(inner.id)
            elif isinstance(inner, ast.Global):
                declared_global |= set(inner.names)
            elif isinstance(inner, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                local.add(inner.name)
            elif isinstance(inner, (ast.Import, ast.ImportFrom)):
                local |= {(a.asname or a.name.split(".")[0]) for a in inner.names}
            elif isinstance(inner, ast.arg):
                local.add(inner.arg)
            elif isinstance(inner, ast.ExceptHandler) and inner.name:
                local.add(inner.name)
    return loads - (local - declared_global)


# ------------------------------------------------------------------ small helpers
def _chain(node) -> list[str] | None:
    """``["np", "linalg", "inv"]`` for ``np.linalg.inv``; None for anything but names and attributes."""
    parts = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    if not isinstance(node, ast.Name):
        return None
    return [node.id, *reversed(parts)]


def _targets(node) -> set[str]:
    """The names an assignment target binds."""
    if isinstance(node, ast.Name):
        return {node.id}
    if isinstance(node, (ast.Tuple, ast.List)):
        return set().union(*(_targets(e) for e in node.elts)) if node.elts else set()
    if isinstance(node, ast.Starred):
        return _targets(node.value)
    return set()


def _mutated(target) -> set[str]:
    """The names whose value an assignment to ``target`` changes in place (``K`` for ``K[0, 2]``)."""
    if isinstance(target, (ast.Tuple, ast.List)):
        return set().union(*(_mutated(e) for e in target.elts)) if target.elts else set()
    if isinstance(target, ast.Starred):
        return _mutated(target.value)
    if isinstance(target, (ast.Subscript, ast.Attribute)):
        node = target.value
        while isinstance(node, (ast.Subscript, ast.Attribute)):
            node = node.value
        return {node.id} if isinstance(node, ast.Name) else set()
    return set()


def _bound_names(node) -> set[str]:
    return {(a.asname or a.name.split(".")[0]) for a in node.names if a.name != "*"}


def _catches_import_errors(handler: ast.ExceptHandler) -> bool:
    caught = handler.type
    names = [caught] if not isinstance(caught, ast.Tuple) else caught.elts
    return caught is None or any(_chain(n) and _chain(n)[-1] in (
        "ImportError", "ModuleNotFoundError", "Exception", "BaseException") for n in names)


def _is_main_block(node: ast.If) -> bool:
    test = node.test
    return (isinstance(test, ast.Compare) and isinstance(test.left, ast.Name) and test.left.id == "__name__"
            and any(isinstance(c, ast.Constant) and c.value == "__main__" for c in test.comparators))


def _statement_lines(node: ast.stmt) -> tuple[int, int]:
    """First and last line (1-based) of a statement, decorators included."""
    first = min([node.lineno] + [d.lineno for d in getattr(node, "decorator_list", [])])
    return first, node.end_lineno or node.lineno


# ------------------------------------------------------------------ the whole notebook
def analyse(cells: list[CellCode], importable: Callable[[str], bool] | None = None) -> Selection:
    """Decide, statement by statement in notebook order, what grading keeps (module docstring).

    Parameters
    ----------
    cells : list of CellCode
        The code cells, in order, their magics already commented out.
    importable : callable, optional
        ``importable("seaborn")``: whether an import can succeed where grading runs
        (default :func:`available_at_grading`).

    Returns
    -------
    Selection
        A cell that does not parse is kept whole: its error is reported at grading,
        naming its cell and line.
    """
    analysis = _Analysis(importable or available_at_grading)
    parsed: dict[int, list[tuple[_Statement, ast.stmt]]] = {}
    for cell in cells:
        try:  # the caller bounds the code (notebooks.convert); the cell's own bound is the parser's
            tree = parse("\n".join(cell.lines))
        except (SyntaxError, ValueError, RecursionError, MemoryError):  # ValueError: NUL bytes (3.10), TooLarge
            parsed[cell.number] = None
            analysis.future_allowed = analysis.future_allowed and cell.mode == "skip"
            continue
        try:
            parsed[cell.number] = [(analysis.add(node, cell.number, cell.mode), node) for node in tree.body]
        except RecursionError:  # nested beyond reading anywhere: kept whole, for the import to report
            parsed[cell.number] = None
    analysis.finish()
    read_by: dict[str, list[str]] = {}  # name -> the kept functions whose bodies read it
    for function, names in analysis.readers().items():
        for name in names:
            read_by.setdefault(name, []).append(function)
    selection = Selection({}, {}, [])
    for cell in cells:
        statements = parsed[cell.number]
        if statements is None:  # kept whole (unless tagged skip-grading): the import reports it
            _take_whole(selection, cell)
            continue
        lines, kept = _cell_lines(cell.lines, statements)
        selection.lines[cell.number], selection.kept[cell.number] = lines, kept
        selection.guarded[cell.number] = _guarded_lines(statements) if cell.mode == "analyse" else set()
        for statement, node in statements:
            if statement.kept:
                continue
            first, _ = _statement_lines(node)
            defined = _defined_by(node)
            users = sorted((function, name) for name in defined for function in read_by.get(name, ()))
            selection.omissions.append(Omission(cell.number, first, _first_line(cell.lines[first - 1], node),
                                                statement.reason, users, statement.listed))
    return selection


def taken_whole(cells: list[CellCode]) -> Selection:
    """Every cell whole, nothing read (a cell tagged skip-grading left out): what :func:`analyse`
    gives a cell that does not parse, for code too large to read."""
    selection = Selection({}, {}, [])
    for cell in cells:
        _take_whole(selection, cell)
    return selection


def _take_whole(selection: Selection, cell: CellCode) -> None:
    selection.lines[cell.number] = list(cell.lines)
    selection.kept[cell.number] = [cell.mode != "skip"] * len(cell.lines)
    selection.guarded[cell.number] = set()


MAX_OMISSION_TEXT = 200   # characters of a statement an Omission keeps (notes show 50)


def _first_line(line: str, node: ast.stmt) -> str:
    """The first line of ``node``, which starts on ``line``: the statement's own part when it
    shares the line (``img = load()`` of ``img = load(); K = np.eye(3)``), at most
    :data:`MAX_OMISSION_TEXT` characters (so a line of thousands of statements is not kept
    once per statement)."""
    if getattr(node, "decorator_list", None) or not line.isascii():  # columns are UTF-8 bytes
        return line.strip()[:MAX_OMISSION_TEXT]
    end = node.end_col_offset if node.end_lineno == node.lineno and node.end_col_offset is not None else len(line)
    return line[node.col_offset:min(end, node.col_offset + 4 * MAX_OMISSION_TEXT)].strip()[:MAX_OMISSION_TEXT]


def _defined_by(node: ast.stmt) -> set[str]:
    """The top-level names a statement binds (not the local names of functions it defines)."""
    if isinstance(node, ast.Assign) and all(isinstance(t, (ast.Name, ast.Tuple, ast.List)) for t in node.targets):
        return set().union(*(_targets(t) for t in node.targets))  # the common case, without a walk
    names, pending = set(), [node]
    while pending:
        inner = pending.pop()
        if isinstance(inner, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.add(inner.name)
            continue
        if isinstance(inner, (ast.Lambda, ast.ListComp, ast.SetComp, ast.GeneratorExp, ast.DictComp)):
            continue  # their names are their own
        if isinstance(inner, ast.Name) and isinstance(inner.ctx, ast.Store):
            names.add(inner.id)
        elif isinstance(inner, (ast.Import, ast.ImportFrom)):
            names |= _bound_names(inner)
        elif isinstance(inner, ast.ExceptHandler) and inner.name:
            names.add(inner.name)
        pending += list(ast.iter_child_nodes(inner))
    return names


def _cell_lines(lines: list[str], statements) -> tuple[list[str], list[bool]]:
    """The cell's lines with their kept flags. A line shared by kept and left-out statements
    (``img = load(); K = np.eye(3)``) keeps the kept ones and has ``pass`` for the others."""
    owners: list[list[tuple[bool, ast.stmt]]] = [[] for _ in lines]
    for statement, node in statements:
        first, last = _statement_lines(node)
        for index in range(first - 1, min(last, len(lines))):
            owners[index].append((statement.kept, node))
    out, kept = list(lines), [False] * len(lines)
    for index, owned in enumerate(owners):
        if not owned:
            continue
        if all(k for k, _ in owned):
            kept[index] = True
        elif any(k for k, _ in owned):
            out[index] = _without_statements(lines[index], index + 1, [n for k, n in owned if not k])
            kept[index] = True
    return out, kept


def _guarded_lines(statements) -> set[int]:
    """The indices of the lines to guard: those starting a line of simple statements (the
    left-out ones are ``pass``) of which one is a kept value."""
    starting: dict[int, list[tuple[bool, ast.stmt]]] = {}
    for statement, node in statements:
        starting.setdefault(node.lineno - 1, []).append((statement.kept, node))
    return {index for index, found in starting.items()
            if any(n.col_offset == 0 and (not k or isinstance(n, _GUARDED)) for k, n in found)
            and any(k and isinstance(n, _GUARDED) and not _is_docstring(n) for k, n in found)}


def _is_docstring(node: ast.stmt) -> bool:
    return isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant)


def _without_statements(line: str, number: int, left_out: list[ast.stmt]) -> str:
    """``line`` with each left-out statement's part replaced by ``pass`` (ast columns are UTF-8
    bytes); built from pieces in one pass, however many statements share the line."""
    data = line.encode("utf-8")
    spans = []
    for node in left_out:
        start = node.col_offset if node.lineno == number else 0
        end = node.end_col_offset if node.end_lineno == number else len(data)
        spans.append((start, end))
    pieces, done = [], 0
    for start, end in sorted(spans):
        if start < done:  # statements of one line never overlap; were they to, the first wins
            continue
        pieces += [data[done:start], b"pass"]
        done = end
    pieces.append(data[done:])
    return b"".join(pieces).decode("utf-8", "replace")
