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
