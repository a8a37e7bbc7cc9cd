"""A course's grading configuration (``--config COURSE``), a small JSON file.

Example ``course.json``::

    {"select": ["lab07", "lab08"], "public_visibility": "visible",
     "hidden_visibility": "after_published", "call_timeout": 10}

Every key is optional; unknown keys and bad values are refused with a message.

``similarity_threshold`` (default 0.5): the similarity report (``autograder
similarity``) shows pairs of submissions whose score -- the mean share of each
file's own code (skeleton excluded) found in the other -- is at least this,
side by side. Disguised copies score about 0.9, independent work about 0.1.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field, fields
from pathlib import Path

VISIBILITIES = ("visible", "hidden", "after_due_date", "after_published")


class CourseConfigError(ValueError):
    """The course configuration file is malformed."""


@dataclass(frozen=True)
class CourseConfig:
    select: list[str] = field(default_factory=list)     # labs/exercises graded; empty = all
    public_visibility: str = "visible"                  # Gradescope visibility of public checks
    hidden_visibility: str = "after_published"          # ... and of hidden checks
    stdout_visibility: str = "hidden"                   # the grader's own log
    call_timeout: float = 10.0                          # seconds per call into student code
    similarity_threshold: float = 0.5                   # similarity report: pairs shown side by side

    def __post_init__(self):
        for name in ("public_visibility", "hidden_visibility", "stdout_visibility"):
            if getattr(self, name) not in VISIBILITIES:
                raise CourseConfigError(f"{name} must be one of {VISIBILITIES}, got {getattr(self, name)!r}")
        if not (isinstance(self.select, list) and all(isinstance(s, str) for s in self.select)):
            raise CourseConfigError("select must be a list of names like 'lab07' or 'lab07.ex2'")
        if not (isinstance(self.call_timeout, (int, float)) and self.call_timeout > 0):
            raise CourseConfigError("call_timeout must be a positive number of seconds")
        if not (isinstance(self.similarity_threshold, (int, float)) and 0 < self.similarity_threshold <= 1):
            raise CourseConfigError("similarity_threshold must be a number in (0, 1]")

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
