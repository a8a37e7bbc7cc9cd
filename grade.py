#!/usr/bin/env python3
"""Grade your lab work: ``python grade.py`` (everything), ``python grade.py lab07``,
``python grade.py lab07.ex2``, or ``python grade.py --submission PATH``.

Scores appear in the terminal; details and pictures in ``feedback.html``.
"""

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent
sys.path.insert(0, str(ROOT))  # works from a fresh clone even before `pip install -e .`

from autograder.cli import grade_py_main  # noqa: E402

if __name__ == "__main__":
    sys.exit(grade_py_main(root=ROOT))
