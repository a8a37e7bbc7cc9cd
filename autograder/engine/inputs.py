"""The inputs each submission's property checks draw.

Reproducible must not mean the same for everyone: with one fixed set of inputs, a
table of the right answers to them (recorded from any grading) earns every point
of a property check. So Hypothesis's seed is the submission's own: an HMAC of the
submission's content under the course's secret (``inputs_secret`` in the course
configuration, else ``$AUTOGRADER_INPUTS_SECRET``, else none). The same files draw
the same inputs on every run and machine; any change to them (a table of answers
included) draws others, and the content includes every file the worker may import.

Without a secret (a student grading their own work) the inputs follow the content
alone. With the course's secret, which the student bundle never carries, nobody
without it knows the inputs of the official grading before it runs: trying
variants of one's files at home until one happens to meet only easy inputs tells
nothing about the official grading.

Checks that draw their own inputs (hidden checks: angles, scenes, noise) draw them from
:meth:`Inputs.generator` (``t.rng`` in a check), under the same key: a hidden input
that leaked from one grading is not the next submission's.

No Hypothesis here: a replayed property never imports it (see :mod:`autograder.engine.examples`).
"""

from __future__ import annotations

import hashlib
import hmac
import os
from dataclasses import dataclass

import numpy as np

SECRET_VARIABLE = "AUTOGRADER_INPUTS_SECRET"


@dataclass(frozen=True)
class Inputs:
    """Where one submission's property checks draw their inputs from.

    ``key`` is 32 bytes (HMAC-SHA256 of the submission's content hash under the
    course secret); ``secret`` says whether a course secret went into it (then the
    student's own run of the same files draws other inputs); ``rerun`` is how to
    draw them again, the text before and after an exercise's id (``("python grade.py ", "")``,
    ``('check("', '")')``): what a failing property's message tells the student to run.
    """

    key: bytes
    secret: bool = False
    rerun: tuple[str, str] = ("python grade.py ", "")

    @classmethod
    def for_submission(cls, content_hash: str, secret: str | bytes | None = None) -> "Inputs":
        """The inputs of the submission whose content hashes to ``content_hash``.

        ``secret`` None means ``$AUTOGRADER_INPUTS_SECRET`` (unset or empty: no secret).
        """
        if secret is None:
            secret = os.environ.get(SECRET_VARIABLE, "")
        if not isinstance(secret, (str, bytes)):
            raise TypeError(f"the inputs secret must be text or bytes, not {type(secret).__name__}")
        secret = secret.encode() if isinstance(secret, str) else secret
        key = hmac.new(secret, b"property inputs|" + content_hash.encode(), hashlib.sha256).digest()
        return cls(key, bool(secret))

    def seed(self, check_id: str, index: int) -> int:
        """Hypothesis's seed for the ``index``-th property of the check ``check_id`` (128 bits)."""
        digest = hmac.new(self.key, f"{check_id}|{index}".encode(), hashlib.sha256).digest()
        return int.from_bytes(digest[:16], "big")

    def generator(self, check_id: str, purpose: str = "inputs") -> np.random.Generator:
        """A NumPy generator for the check ``check_id``'s own draws (a hidden check's angles,
        scenes, noise), seeded with 256 bits of an HMAC under this submission's key.

        The message has its own prefix, so the draws are independent of the properties'
        seeds (:meth:`seed`); ``purpose`` tells apart several generators of one check.
        """
        digest = hmac.new(self.key, f"generator|{check_id}|{purpose}".encode(), hashlib.sha256).digest()
        return np.random.Generator(np.random.PCG64(int.from_bytes(digest, "big")))


# What a check run outside a grading draws (a suite's test of one check): the empty content's inputs.
NO_SUBMISSION = Inputs.for_submission("", secret="")
