"""A course's grading configuration (``--config COURSE``), a small JSON file.

Example ``course.json``::

    {"select": ["lab07", "lab08"], "public_visibility": "visible",
     "hidden_visibility": "after_published", "call_timeout": 10,
     "forbid": {"lab08.homography_ransac": ["cv2.findHomography"]}}

Every key is optional; unknown keys and bad values are refused with a message.

``forbid`` (off by default) adds the instructor's own rules to the lab sheet's:
inside the student function ``labNN.function``, calling any of the listed
library functions (``module.name``) fails the check with "... which this
exercise asks you to implement yourself". The feedback lists the rule under
the exercise, so students see it before they lose a point.
"""

from __future__ import annotations

import json
import re
from dataclasses import asdict, dataclass, field, fields
from pathlib import Path

VISIBILITIES = ("visible", "hidden", "after_due_date", "after_published")
_STUDENT_FUNCTION = re.compile(r"lab\d\d\.[A-Za-z_]\w*")          # lab08.homography_ransac
_LIBRARY_FUNCTION = re.compile(r"[A-Za-z_]\w*(\.[A-Za-z_]\w*)+")   # cv2.findHomography


class CourseConfigError(ValueError):
    """The course configuration file is malformed."""


@dataclass(frozen=True)
class CourseConfig:
    select: list[str] = field(default_factory=list)     # labs/exercises graded; empty = all
    public_visibility: str = "visible"                  # Gradescope visibility of public checks
    hidden_visibility: str = "after_published"          # ... and of hidden checks
    stdout_visibility: str = "hidden"                   # the grader's own log
    call_timeout: float = 10.0                          # seconds per call into student code
    forbid: dict = field(default_factory=dict)          # "lab08.homography_ransac": ["cv2.findHomography"]

    def __post_init__(self):
        for name in ("public_visibility", "hidden_visibility", "stdout_visibility"):
            if getattr(self, name) not in VISIBILITIES:
                raise CourseConfigError(f"{name} must be one of {VISIBILITIES}, got {getattr(self, name)!r}")
        if not (isinstance(self.select, list) and all(isinstance(s, str) for s in self.select)):
            raise CourseConfigError("select must be a list of names like 'lab07' or 'lab07.ex2'")
        if not (isinstance(self.call_timeout, (int, float)) and self.call_timeout > 0):
            raise CourseConfigError("call_timeout must be a positive number of seconds")
        self._check_forbid()

    def _check_forbid(self):
        example = '{"lab08.homography_ransac": ["cv2.findHomography"]}'
        if not isinstance(self.forbid, dict):
            raise CourseConfigError(f"forbid must be an object like {example}")
        for function, libraries in self.forbid.items():
            if not (isinstance(function, str) and _STUDENT_FUNCTION.fullmatch(function)):
                raise CourseConfigError(f"forbid: {function!r} is not a student function like "
                                        f"'lab08.homography_ransac' (example: {example})")
            if not (isinstance(libraries, list) and libraries
                    and all(isinstance(n, str) and _LIBRARY_FUNCTION.fullmatch(n) for n in libraries)):
                raise CourseConfigError(f"forbid[{function!r}] must be a non-empty list of library "
                                        f"functions like 'cv2.findHomography' (example: {example})")

    def forbidden(self, lab: str) -> dict[str, tuple[str, ...]]:
        """The instructor's extra forbids for one lab: student function -> library functions."""
        return {key.split(".", 1)[1]: tuple(names) for key, names in self.forbid.items()
                if key.split(".", 1)[0] == lab}

    @classmethod
    def load(cls, path) -> "CourseConfig":
        try:
            data = json.loads(Path(path).read_text(encoding="utf-8"))
        except (OSError, ValueError) as exc:
            raise CourseConfigError(f"cannot read course configuration {path}: {exc}") from None
        if not isinstance(data, dict):
            raise CourseConfigError(f"{path}: expected a JSON object")
        known = {f.name for f in fields(cls)}
        unknown = sorted(set(data) - known)
        if unknown:
            raise CourseConfigError(f"{path}: unknown keys {unknown}; known keys are {sorted(known)}")
        return cls(**data)

    def to_json(self) -> str:
        return json.dumps(asdict(self), indent=2) + "\n"
