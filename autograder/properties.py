"""The Hypothesis profile used for grading (and for the grader's own tests).

Grading must be reproducible: the same submission gets the same examples, and so
the same score, on every run and machine. Hence derandomised generation, no
example database (nothing written into the student's folder), no deadline (the
worker's timeout governs time) and a bounded number of examples.
"""

from hypothesis import HealthCheck, Phase, Verbosity, settings

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
