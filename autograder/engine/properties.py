"""The Hypothesis profile used for grading (and for the grader's own tests).

Grading must be reproducible: the same submission gets the same examples, and so
the same score, on every run and machine. Hence derandomised generation (each
property's seed is the submission's, :class:`autograder.engine.inputs.Inputs`: other
files draw other examples), no example database and no storage in the working
directory (nothing written into the student's folder), no deadline (the worker's
timeout governs time) and a bounded number of examples.
"""

import atexit
import os
import secrets
import shutil
import tempfile
from pathlib import Path

from hypothesis import HealthCheck, Phase, Verbosity, settings
from hypothesis.configuration import set_hypothesis_home_dir


def _private_storage() -> None:
    """Keep Hypothesis's storage (its cache of constants found in source files,
    written even without an example database) out of the working directory.

    A private folder per process, removed at exit: a shared one in /tmp could be
    planted by another user of the machine to steer the generated examples, so its
    name is unguessable. Hypothesis makes it only when it writes there: most
    processes never do, and one killed (a grading stopped, a helper past its time,
    where no exit handler runs) leaves nothing behind.
    An explicit ``HYPOTHESIS_STORAGE_DIRECTORY`` is respected.
    """
    if os.environ.get("HYPOTHESIS_STORAGE_DIRECTORY"):
        return
    folder = Path(tempfile.gettempdir()) / f"autograder-hypothesis-{secrets.token_hex(16)}"
    atexit.register(shutil.rmtree, folder, ignore_errors=True)
    set_hypothesis_home_dir(folder)


_private_storage()


def _no_local_constants() -> None:
    """Draw examples from Hypothesis's own constants only, never from "local" source files.

    Hypothesis mixes into its examples constants it finds in the modules it deems
    local (not in site-packages) that happen to be imported. For grading that
    would make the examples depend on how the grader is installed (an editable
    checkout sees the lab suites' constants, Gradescope's site-packages copy does
    not) and on which other modules were imported, so the same submission could
    meet other inputs on another machine; scanning them also costs seconds.
    The hook is internal to Hypothesis, whose version ``constraints.txt`` pins.
    """
    try:
        from hypothesis.internal.conjecture import providers
        empty = providers.Constants()
    except (ImportError, AttributeError, TypeError):  # another Hypothesis: nothing to switch off
        return
    if callable(getattr(providers, "_get_local_constants", None)):
        providers._get_local_constants = lambda: empty


_no_local_constants()

GRADING = "grading"
settings.register_profile(
    GRADING,
    derandomize=True,
    database=None,
    deadline=None,
    max_examples=25,
    print_blob=False,
    report_multiple_bugs=False,
    verbosity=Verbosity.quiet,
    suppress_health_check=list(HealthCheck),
    # The "explain" phase re-runs failing examples to annotate them for humans
    # reading a pytest report; grading reports the shrunk example itself.
    phases=[p for p in Phase if p.name != "explain"],
)


def grading_settings(max_examples: int | None = None) -> settings:
    """The grading profile, optionally with another bound on the examples."""
    profile = settings.get_profile(GRADING)
    return settings(profile, max_examples=max_examples) if max_examples else profile
