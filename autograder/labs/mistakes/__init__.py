"""The built-in labs' mistakes tables, one module per lab (``labNN.py``), read by
``autograder verify`` (:mod:`autograder.instructor.verify`) and the project's tests.

Each module holds ``MISTAKES``: case name -> ``(exercise id, source, fragments)``, where
``source`` redefines functions of the reference solution (it is appended to it) and
every fragment must appear in the message of a check that fails; optionally ``ADVICE``
(same form: conventions that earn a tip, never lose a point) and ``FEWER_MISTAKES``
(exercise id -> why its algorithm has fewer than five realistic mistakes).

The tables are the grader's, not the students': they describe the checks' answers
closely (a case is the reference with one slip), so neither the student bundle nor
the Gradescope zip ships this folder, as neither ships the hidden checks.
"""


# ------------------------------------------------------------------ a reference def with one line changed
def reference_def_with(module: str, function: str, line: str, changed: str) -> str:
    """The reference solution's ``def function`` (of ``reference_solutions/<module>.py``, docstring left out)
    with its one line ``line`` (stripped text) written as ``changed`` (lines apart by newlines, at that line's
    indentation): a case that is the reference with one slip, without copying the rest of the def into the table."""
    import ast
    import textwrap
    from pathlib import Path

    from ...loading.parsing import parse

    source = (Path(__file__).resolve().parents[3] / "reference_solutions" / f"{module}.py").read_text()
    node = next(n for n in parse(source, max_chars=None, max_statements=None).body if isinstance(n, ast.FunctionDef) and n.name == function)
    body = node.body[1:] if isinstance(node.body[0], ast.Expr) and isinstance(node.body[0].value, ast.Constant) \
        else node.body
    written = source.splitlines()
    kept = written[node.lineno - 1:node.lineno] + written[body[0].lineno - 1:node.end_lineno]
    matches = [i for i, text in enumerate(kept) if text.strip() == line]
    if len(matches) != 1:
        raise ValueError(f"{module}.{function}: {line!r} is not one line of the reference's def")
    indent = kept[matches[0]][:len(kept[matches[0]]) - len(kept[matches[0]].lstrip())]
    kept[matches[0]] = "\n".join(indent + part for part in changed.split("\n"))
    return "\n" + textwrap.indent(textwrap.dedent("\n".join(kept)), " " * 8) + "\n"


# ------------------------------------------------------------------ cases made alike in every lab
def one_point_by_length(function: str, exercise: str, signature: str, points: str, test: str) -> dict:
    """The case of ``function`` telling a single (X, Y, Z) point by its number of rows (``test``, on the
    parameter ``points``): three points are taken for one (the API's convention of k points of k
    coordinates)."""
    call = ", ".join(part.split("=")[0].strip() for part in signature.split(","))
    single = call.replace(points, f"{points}.reshape(-1)[:3]", 1)
    return {f"{function} takes 3 points for one point": (exercise, f"""
        _reference_rows = {function}
        def {function}({signature}):
            {points} = np.asarray({points}, dtype=np.float64)
            if {test}:   # a single (X, Y, Z) point
                return _reference_rows({single})
            return _reference_rows({call})
        """, [f"`{test}` (line", "3 points are 3 rows"])}


def columns_by_first_axis(function: str, exercise: str, signature: str, arrays: tuple, test: str) -> dict:
    """The case of ``function`` accepting 2D points given as columns, (2, N), by their first axis (``test``):
    two points, (2, 2), are transposed too."""
    converted = "\n".join(f"            {name} = np.asarray({name}, dtype=np.float64)" for name in arrays)
    return {f"{function} takes 2 points for points given as columns": (exercise, f"""
        _reference_rows = {function}
        def {function}({signature}):
{converted}
            if {test}:   # points given as columns, (2, N)
                {", ".join(arrays)} = {", ".join(f"{name}.T" for name in arrays)}
            return _reference_rows({signature})
        """, [f"`{test}` (line", "2 points are 2 rows"])}
