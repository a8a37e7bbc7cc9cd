"""Renderers of a :class:`~autograder.engine.results.GradingResult`: terminal, HTML, JSON, Gradescope."""
