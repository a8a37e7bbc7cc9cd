"""The error model: mutants of the reference solutions that name a student's mistake (see :mod:`.naming`)."""
