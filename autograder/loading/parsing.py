"""Parsing and compiling Python text in the grader's own process: one at a time, and bounded.

CPython 3.11's ``ast`` module is not thread-safe: two threads building AST objects at
once (``ast.parse``, ``compile`` of source or of a tree) share one recursion counter and
fail with ``SystemError: AST constructor recursion depth mismatch`` (CPython gh-106905).
The grader reads submissions from parallel lanes (threads), so every ``ast.parse`` and
``compile`` in :mod:`autograder` goes through :func:`parse` or :func:`compile_source`,
which hold :data:`PARSE_LOCK` for the call (``tests/test_linear_reading.py`` holds the
package to it).

The lock makes a long parse stall every lane, and the parser's cost grows with the
text: 1 MB of ``a;a;...`` (480,000 statements) took 10 s and 0.9 GB of AST objects, 1 MB
of ``[a, a, ...]`` 8 s and 0.7 GB (a loaded 2-core machine). So text from a submission
is parsed only within :data:`MAX_PARSE_CHARS` characters and :data:`MAX_PARSE_STATEMENTS`
statements, counted before parsing by :func:`statement_bound` (at most ~150 MB and a
second or two); beyond them :class:`TooLarge` is raised (a ``ValueError``, which every
reader already treats as "cannot be read"; each says so in its own words).
"""

from __future__ import annotations

import ast
import copy
import threading
from collections import deque

PARSE_LOCK = threading.RLock()   # re-entrant: a parse never waits on its own thread
MAX_PARSE_CHARS = 200_000        # ~5,000 lines: worst case ~150 MB of AST objects, a second or two
MAX_PARSE_STATEMENTS = 20_000    # lines plus ";": a lab module holds a few hundred statements


class TooLarge(ValueError):
    """Text beyond what the grader parses in its own process; the message says which bound."""


def statement_bound(text: str) -> int:
    """At least the number of statements ``text`` can hold: its lines plus its semicolons
    (each statement after a line's first needs one). Counted in C, linear; ``;`` inside
    strings and comments count too, so it may be more, never less."""
    return text.count("\n") + text.count(";") + 1


def check_size(text: str, max_chars: int | None = MAX_PARSE_CHARS,
               max_statements: int | None = MAX_PARSE_STATEMENTS) -> None:
    """Raise :class:`TooLarge` when ``text`` is beyond the bounds (None: not checked)."""
    if max_chars is not None and len(text) > max_chars:
        raise TooLarge(f"more than {max_chars:,} characters")
    if max_statements is not None and statement_bound(text) > max_statements:
        raise TooLarge(f"more than {max_statements:,} statements (lines and ';')")


def parse(text: str, filename: str = "<unknown>", mode: str = "exec", *,
          max_chars: int | None = MAX_PARSE_CHARS, max_statements: int | None = MAX_PARSE_STATEMENTS) -> ast.AST:
    """``ast.parse(text, filename, mode)`` under :data:`PARSE_LOCK`, within the bounds
    (None: that bound is not checked, for the grader's own text).

    Raises
    ------
    TooLarge
        Before parsing, for text beyond the bounds.
    SyntaxError, ValueError, RecursionError, MemoryError
        As :func:`ast.parse` does.
    """
    check_size(text, max_chars, max_statements)
    with PARSE_LOCK:
        return ast.parse(text, filename, mode)


def compile_source(source, filename: str, mode: str = "exec", **options):
    """``compile(source, filename, mode, **options)`` under :data:`PARSE_LOCK` (source text
    or an AST: both build or read AST objects)."""
    with PARSE_LOCK:
        return compile(source, filename, mode, **options)


# Reading a submission walks and copies its trees tens of thousands of times a grading (the error
# model's mutants, the repairs, the hints' reading): ast.walk's two nested generators per node and
# copy.deepcopy's generic machinery were a fifth of the grader's own time naming a mistake.

def walk(node: ast.AST):
    """Every node under ``node`` (itself first) in :func:`ast.walk`'s order, breadth first, about
    twice as fast. As ``ast.walk`` does, a node's children are read before the node is given to
    the caller: a caller that replaces a node's children, or wraps the node in a new one, walks
    what the tree held before (read after, a wrapper holding the node would be walked into, and
    wrapped again, without end)."""
    todo = deque([node])
    take, add, extend = todo.popleft, todo.append, todo.extend
    while todo:
        node = take()
        for name in node._fields:
            value = getattr(node, name, None)
            if isinstance(value, ast.AST):
                add(value)
            elif value.__class__ is list:
                extend([item for item in value if isinstance(item, ast.AST)])
        yield node


def copy_tree(value):
    """A copy of an AST node or a list of them, as :func:`copy.deepcopy` makes it, in a third of
    the time: every node with fields or positions is new; the field-less markers (``Load``,
    ``Add``, ...) are shared, as :func:`ast.parse` shares them. What else a node holds -- the
    readers' caches kept on it (``_walked``, ``_uses_of``: nodes of its tree) -- is deep-copied
    as deepcopy copies it, the tree's nodes in it standing for their copies. Any other value is
    deep-copied."""
    if not (isinstance(value, ast.AST) or value.__class__ is list):
        return copy.deepcopy(value)
    memo: dict = {}     # id of an original node -> its copy (deepcopy's memo, for the extras below)
    extras: list = []   # (copy, attribute, original value) of what is neither a field nor a position
    if isinstance(value, ast.AST):
        copied = _copied_node(value, memo, extras)
    else:
        copied = [_copied_node(item, memo, extras) if isinstance(item, ast.AST) else copy.deepcopy(item, memo)
                  for item in value]
    for new, name, kept in extras:
        new.__dict__[name] = copy.deepcopy(kept, memo)
    return copied


_SHARED = (str, int, float, complex, bytes, bool, type(None), type(Ellipsis))   # immutable field values


def _copied_node(node: ast.AST, memo: dict, extras: list) -> ast.AST:
    if not node._fields and not node.__dict__:
        memo[id(node)] = node
        return node   # a context or operator marker: immutable in practice, shared by the parser
    new = node.__class__.__new__(node.__class__)
    memo[id(node)] = new
    attributes = new.__dict__
    for name, value in node.__dict__.items():
        if isinstance(value, ast.AST):
            value = _copied_node(value, memo, extras)
        elif value.__class__ is list:
            value = [_copied_node(item, memo, extras) if isinstance(item, ast.AST) else item for item in value]
        elif not isinstance(value, _SHARED):
            extras.append((new, name, value))
            continue
        attributes[name] = value
    return new
