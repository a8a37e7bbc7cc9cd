"""An installed grader (not editable: a wheel, Gradescope's pip install) holds every file the
package reads: each file of the package that is not Python is named by the package data."""

from __future__ import annotations

import fnmatch
import subprocess

import pytest

from conftest import ROOT

tomllib = pytest.importorskip("tomllib")   # Python 3.11+; the rule does not depend on the version


def test_every_data_file_of_the_package_is_in_its_package_data():
    settings = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["package-data"]
    tracked = subprocess.run(["git", "ls-files", *settings], cwd=ROOT, capture_output=True, text=True,
                             check=True).stdout.split()
    left_out = []
    for path in tracked:
        package, _, inside = path.partition("/")
        if path.endswith(".py") or "/__pycache__/" in path:
            continue
        if not any(fnmatch.fnmatch(inside, pattern) for pattern in settings[package]):
            left_out.append(path)
    assert left_out == [], "add these to [tool.setuptools.package-data] in pyproject.toml"


def _guarded(node, parents) -> bool:
    """Whether the import ``node`` sits in a ``try`` whose handlers catch ImportError (an
    optional feature that says which install adds it)."""
    for parent in parents.get(node, []):
        if isinstance(parent, __import__("ast").Try) and any(
                handler.type is not None and any(name in __import__("ast").unparse(handler.type)
                                                 for name in ("ImportError", "ModuleNotFoundError"))
                for handler in parent.handlers):
            return True
    return False


def test_every_command_runs_on_the_quick_start_install():
    """Every package the grader imports (at the top or lazily, any command) is one of the
    project's dependencies, so the README's install runs every documented command; an
    optional feature's import (Dask) is guarded and says which extra adds it."""
    import ast
    import sys
    from importlib.metadata import packages_distributions
    from packaging.requirements import Requirement

    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    required = {Requirement(r).name.lower().replace("_", "-") for r in project["dependencies"]}
    distributions = packages_distributions()
    unlisted = []
    for path in sorted((ROOT / "autograder").rglob("*.py")):
        tree = ast.parse(path.read_text())
        parents: dict = {}
        def walk(node, chain):
            inner = chain + [node] if isinstance(node, ast.Try) else chain
            for child in ast.iter_child_nodes(node):
                parents[child] = inner
                walk(child, inner)
        walk(tree, [])
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                names = [node.module]
            else:
                continue
            for name in names:
                top = name.split(".")[0]
                if top in sys.stdlib_module_names or top in ("autograder", "fixtures") \
                        or (path.parent / f"{top}.py").exists():   # the worker's own files, beside it
                    continue
                dists = {d.lower().replace("_", "-") for d in distributions.get(top, [top])}
                if not dists & required and not _guarded(node, parents):
                    unlisted.append(f"{path.relative_to(ROOT)}:{node.lineno} imports {name}")
    assert unlisted == [], "\n".join(unlisted) + "\nadd these packages to [project] dependencies, or guard the import " \
                           "with a message naming the extra that adds it"
