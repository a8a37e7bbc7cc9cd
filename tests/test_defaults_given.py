"""A default the student's def gives other than the API's is named where a failing call left it out
(issue 35: a translate whose defaults tx and ty were exchanged was told only how far its image was off)."""

from __future__ import annotations

import textwrap

from autograder.engine import defaults_given
from autograder.engine.hints import read_code
from conftest import failing_messages, mutant

REFERENCE = textwrap.dedent("""
    def translate(image, tx=100, ty=50):
        return image

    def match(a, b, ratio=0.75, cross=False, name="orb", size=None):
        return a
    """)


def told(source, *calls):
    return defaults_given.left_out(read_code(textwrap.dedent(source)), REFERENCE, list(calls))


def test_defaults_other_than_the_apis_are_found_only_where_the_call_left_them_out():
    swapped = "def translate(image, tx=50, ty=100):\n    return image\n"
    assert told(swapped, ("translate", ("img",), {})) == ("translate", [("tx", 50, 100), ("ty", 100, 50)])
    assert told(swapped, ("translate", ("img", 100), {})) == ("translate", [("ty", 100, 50)])
    assert told(swapped, ("translate", ("img",), {"tx": 1, "ty": 2})) is None   # (both given: no evidence)
    sentence = defaults_given.sentence("translate", [("tx", 50, 100), ("ty", 100, 50)])
    assert sentence == ("your `translate` gives `tx` the default 50 and `ty` the default 100, where the API's "
                        "defaults are tx=100, ty=50 (this call leaves them out)")


def test_the_same_value_written_otherwise_and_defaults_written_as_expressions_are_not_named():
    alike = "def match(a, b, ratio=.75, cross=False, name='orb', size=None):\n    return a\n"
    assert told(alike, ("match", (1, 2), {})) is None
    assert told("def translate(image, tx=100.0, ty=50.0):\n    return image\n", ("translate", (1,), {})) is None
    assert told("def translate(image, tx=W // 2, ty=50):\n    return image\n", ("translate", (1,), {})) is None
    assert told("def match(a, b, ratio=0.75, cross=0, name='orb', size=None):\n    return a\n",
                ("match", (1, 2), {})) == ("match", [("cross", 0, False)])   # (0 is not False: a flag's type)


def test_a_translate_with_its_defaults_exchanged_is_told_so_in_grading(tmp_path):
    source = """
        def translate(image, tx=50, ty=100):
            M = np.float32([[1, 0, tx], [0, 1, ty]])
            return cv2.warpAffine(image, M, (image.shape[1], image.shape[0]))
        """
    messages = failing_messages(mutant(tmp_path, "lab07_transformations", source), "lab07.ex1")
    assert any("Your `translate` gives `tx` the default 50 and `ty` the default 100, where the API's defaults "
               "are tx=100, ty=50" in m for m in messages), messages


def test_a_long_literal_default_is_told_in_a_few_characters():
    long = "def match(a, b, ratio=0.75, cross=False, name='" + "x" * 5000 + "', size=None):\n    return a\n"
    found = told(long, ("match", (1, 2), {}))
    assert found is not None and found[1][0][0] == "name"
    assert len(defaults_given.sentence(*found)) < 200


def test_every_default_of_the_api_is_left_out_by_some_public_check(monkeypatch):
    """A default other than the API's is caught only by a call that leaves the parameter out: every
    defaulted parameter of every graded function (but a random seed's None) is left out by a public
    check (a simulate_aperture whose n_rays defaulted to 50 got full marks: every check gave n_rays)."""
    import ast
    import collections

    from autograder.engine import checks
    from autograder.engine.registry import discover
    from autograder.engine.runner import grade
    from conftest import REFERENCE

    calls = collections.defaultdict(set)   # (module, function) -> {(positional count, keywords given)}
    original = checks.Trial.call

    def recorded(self, function, *args, **kwargs):
        calls[(self.check.exercise.lab.module, function)].add((len(args), frozenset(kwargs)))
        return original(self, function, *args, **kwargs)

    monkeypatch.setattr(checks.Trial, "call", recorded)
    never = []
    for key, lab in discover().items():
        grade(str(REFERENCE), [key], pictures="none", include_hidden=False)
        api = {name for exercise in lab.exercises.values() for name in exercise.signatures}
        for fn in ast.parse((REFERENCE / f"{lab.module}.py").read_text()).body:
            if not (isinstance(fn, ast.FunctionDef) and fn.name in api):
                continue
            names = [a.arg for a in fn.args.args]
            for position, default in enumerate(fn.args.defaults, len(names) - len(fn.args.defaults)):
                name = names[position]
                if name == "seed":
                    continue
                if not any(given <= position and name not in keywords for given, keywords in calls[(lab.module, fn.name)]):
                    never.append(f"{fn.name}({name}={ast.unparse(default)})")
    assert not never, never
