"""A course's grading configuration (``--config COURSE``), a small JSON file.

Example ``course.json``::

    {"select": ["lab07", "lab08"], "public_visibility": "visible",
     "hidden_visibility": "after_published", "call_timeout": 10,
     "exercise_budget": 60, "submission_budget": 480}

``call_timeout`` bounds one call into the student's code, ``exercise_budget`` and
``submission_budget`` the student time (calls, timeouts and worker restarts)
of one exercise and of the whole submission; checks left when a budget is spent
score 0 as "time budget exhausted". Keep ``submission_budget`` below the
Gradescope assignment's own timeout, so results are always written.

Every key is optional; unknown keys and bad values are refused with a message.
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
    exercise_budget: float = 60.0                       # student seconds per exercise
    submission_budget: float = 480.0                    # student seconds per submission

    def __post_init__(self):
        for name in ("public_visibility", "hidden_visibility", "stdout_visibility"):
            if getattr(self, name) not in VISIBILITIES:
                raise CourseConfigError(f"{name} must be one of {VISIBILITIES}, got {getattr(self, name)!r}")
        if not (isinstance(self.select, list) and all(isinstance(s, str) for s in self.select)):
            raise CourseConfigError("select must be a list of names like 'lab07' or 'lab07.ex2'")
        for name in ("call_timeout", "exercise_budget", "submission_budget"):
            value = getattr(self, name)
            if isinstance(value, bool) or not (isinstance(value, (int, float)) and value > 0):
                raise CourseConfigError(f"{name} must be a positive number of seconds")

    def limits(self):
        """The sandbox limits this course asks for."""
        from .sandbox import Limits

        return Limits(call_timeout=self.call_timeout, exercise_budget=self.exercise_budget,
                      submission_budget=self.submission_budget)

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
