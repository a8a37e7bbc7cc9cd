"""A default the student's def gives a parameter other than the API's, where a failing call left that
parameter out (read, never run).

``translate(image, tx=50, ty=100)`` where the API writes ``tx=100, ty=50``: a check calling
``translate(image)`` gets another shift, and only its size says so. The defaults are compared as the
literals both defs write (the reference's are the API's); a call that gives the parameter is no
evidence, nor is a default written as an expression.
"""

from __future__ import annotations

import ast
import functools

from ..loading.parsing import parse
from .claims import from_code
from .hints import Code, signature_of_def

MISTAKE = "a default value other than the API's"


def _literal_defaults(fn: ast.FunctionDef) -> dict:
    """Parameter -> the literal its default is (those written as expressions left out)."""
    arguments = fn.args
    positional = arguments.posonlyargs + arguments.args
    pairs = list(zip(positional[len(positional) - len(arguments.defaults):], arguments.defaults)) \
        + [(a, d) for a, d in zip(arguments.kwonlyargs, arguments.kw_defaults) if d is not None]
    found = {}
    for argument, default in pairs:
        try:
            found[argument.arg] = ast.literal_eval(default)
        except (ValueError, TypeError, SyntaxError, RecursionError):
            continue
    return found


@functools.lru_cache(maxsize=16)
def _reference_defaults(source: str) -> dict:
    """Function -> its literal defaults, of the reference module ``source`` (the API's)."""
    tree = parse(source, max_chars=None, max_statements=None)   # (the reference's text: trusted)
    return {fn.name: _literal_defaults(fn) for fn in tree.body if isinstance(fn, ast.FunctionDef)}


def _same(a, b) -> bool:
    if isinstance(a, bool) or isinstance(b, bool):
        return a is b
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return float(a) == float(b)
    return type(a) is type(b) and a == b


def left_out(code: Code, reference_source: str, calls) -> tuple[str, list] | None:
    """``(function, [(parameter, theirs, the API's)])`` of the first call that left out parameters whose
    default in the student's def is not the API's; None when none did."""
    api = _reference_defaults(reference_source)
    for call in calls:
        function, args, kwargs = call[0], call[1], call[2]
        fn, wanted = code.functions.get(function), api.get(function)
        signature = signature_of_def(fn) if fn is not None else None
        if signature is None or not wanted:
            continue
        try:
            given = set(signature.bind(*args, **kwargs).arguments)
        except TypeError:
            continue
        theirs = _literal_defaults(fn)
        differing = [(name, theirs[name], wanted[name]) for name in wanted
                     if name in theirs and name not in given and not _same(theirs[name], wanted[name])]
        if differing:
            return function, differing
    return None


def left_to_its_own(trial, parameter: str) -> bool:
    """Whether a call the check ``trial`` made left ``parameter`` out, where the student's def gives it a
    default other than the API's: a check naming what the value does (a colour "reversed") would
    name the effect of that default as another cause."""
    from .hints import code_of
    from .mutants import naming

    model = naming.model_for(trial.lab)
    calls = list(trial.calls) + ([trial.raised] if getattr(trial, "raised", None) else [])
    if model is None or not calls:
        return False
    found = left_out(code_of(trial), model.source, calls)
    return found is not None and any(name == parameter for name, _, _ in found[1])


def _shown(value, limit: int = 40) -> str:
    text = repr(value)
    return text if len(text) <= limit else text[:limit - 3] + "..."


def sentence(function: str, differing: list) -> str:
    """"your `translate` gives `tx` the default 50 and `ty` the default 100, where the API's are ..."."""
    differing = differing[:4]   # (bounded: a literal of any length is told in a few characters)
    theirs = " and ".join(f"`{name}` the default {_shown(value)}" for name, value, _ in differing)
    api = ", ".join(f"{name}={_shown(value)}" for name, _, value in differing)
    # read: the student's def and the reference's (the API's) defaults, for parameters this call left out
    return from_code(f"your `{function}` gives {theirs}, where the API's {'defaults are' if len(differing) > 1 else 'default is'} "
                     f"{api} (this call leaves {'them' if len(differing) > 1 else 'it'} out)")


def sentence_for(trial, parameter: str) -> str:
    """The sentence naming the student's own default of ``parameter`` where the check ``trial``'s calls
    left it out and their def writes another literal than the API's; "" otherwise."""
    from .hints import code_of
    from .mutants import naming

    model = naming.model_for(trial.lab)
    calls = list(trial.calls)
    if model is None or not calls:
        return ""
    found = left_out(code_of(trial), model.source, calls)
    if found is None:
        return ""
    function, differing = found
    differing = [d for d in differing if d[0] == parameter]
    return sentence(function, differing) if differing else ""
