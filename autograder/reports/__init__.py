"""Renderers of a :class:`~autograder.results.GradingResult`: terminal, HTML, JSON, Gradescope."""
