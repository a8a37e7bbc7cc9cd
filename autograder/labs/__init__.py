"""Lab check suites. Each module registers one lab (see :mod:`autograder.engine.registry`)."""
