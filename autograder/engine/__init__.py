"""The grading engine: checks, judges and the runner. It knows no lab.

Lab suites (:mod:`autograder.labs`) register exercises and checks here; the runner
loads a submission (:mod:`autograder.loading`), calls it through the sandbox
(:mod:`autograder.sandbox`) and returns a
:class:`~autograder.engine.results.GradingResult`, plain data for every report.

- :mod:`.registry` -- labs, exercises, checks, discovery and selection;
- :mod:`.checks`, :mod:`.judges`, :mod:`.compare` -- how a check calls and judges a function;
- :mod:`.strategies`, :mod:`.properties`, :mod:`.examples`, :mod:`.inputs` -- property checks
  whose inputs are each submission's own;
- :mod:`.stubs` -- what can only say "not implemented yet", known without running it;
- :mod:`.pictures` -- the evidence pictures a check attaches;
- :mod:`.runner` -- one grading, start to end; :mod:`.results` -- what it returns.
"""
