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
