"""Which NumPy and OpenCV judge a grading, and which OpenCV major a course grades with.

A few OpenCV calls behave differently between majors 4 and 5 (see
:mod:`autograder.engine.version_differences`), so a score can depend on the version: every
result records the versions that judged it (:func:`judged_with`), and a course chooses its
major (``"opencv": "4"`` or ``"5"`` in course.json, default :data:`DEFAULT_OPENCV`), which
decides the pins its student bundle and Gradescope install (:func:`constraints_file`) and
which environment ``autograder batch`` accepts (:func:`check_opencv`).

Student code runs in a worker started with the grader's own interpreter
(:data:`autograder.sandbox.confine.INTERPRETER` is ``sys.executable``), so the versions the
grader imports here are the ones the student's code imported.
"""

from __future__ import annotations

import platform
from pathlib import Path

OPENCV_MAJORS = ("4", "5")
DEFAULT_OPENCV = "5"
# The pins of each major, at the repository's root; .ci/lock writes both (the same pins but OpenCV's).
CONSTRAINTS = {"5": "constraints.txt", "4": "constraints-opencv4.txt"}
PROJECT_ROOT = Path(__file__).resolve().parents[2]


class OpenCVMismatch(RuntimeError):
    """The installed OpenCV is not the major the course grades with; the message says how to fix it."""


def judged_with() -> dict[str, str]:
    """``{"python": "3.11.7", "numpy": "2.2.6", "opencv": "5.0.0"}``: the versions grading here."""
    import cv2
    import numpy

    return {"python": platform.python_version(), "numpy": numpy.__version__, "opencv": cv2.__version__}


def installed_opencv_major() -> str:
    """The installed OpenCV's major version, ``"4"`` or ``"5"``."""
    import cv2

    return cv2.__version__.split(".")[0]


def describe(versions: dict) -> str:
    """``"NumPy 2.2.6, OpenCV 5.0.0"`` (what reports print); ``""`` for a result stored
    before versions were recorded."""
    named = [f"{label} {versions[key]}" for key, label in (("numpy", "NumPy"), ("opencv", "OpenCV"))
             if versions.get(key)]
    return ", ".join(named)


def constraints_file(major: str, root: Path = PROJECT_ROOT) -> Path:
    """The pins of OpenCV ``major`` (``"4"`` or ``"5"``): what a course's installs use as constraints.txt."""
    if major not in CONSTRAINTS:
        raise ValueError(f"opencv must be one of {list(OPENCV_MAJORS)}, got {major!r}")
    return root / CONSTRAINTS[major]


def install_line(major: str) -> str:
    """The command, run in the repository, that installs the pins of OpenCV ``major``."""
    return f'python -m pip install -c {CONSTRAINTS[major]} -e .'


def check_opencv(major: str) -> None:
    """Raise :class:`OpenCVMismatch` (one sentence: what is installed, what the course wants,
    the command that installs it) unless the installed OpenCV's major is ``major``.

    Refused rather than warned about: a batch's scores are the class's grades, and a
    submission whose code depends on a version difference would score differently from the
    bundle the students tested with (the gradebook would keep those scores too)."""
    installed = installed_opencv_major()
    if installed != major:
        import cv2

        raise OpenCVMismatch(
            f"this course grades with OpenCV {major} (\"opencv\" in its configuration) but OpenCV "
            f"{cv2.__version__} is installed here: install the course's pins with "
            f"`{install_line(major)}` in the grader's folder, or set \"opencv\": \"{installed}\".")
