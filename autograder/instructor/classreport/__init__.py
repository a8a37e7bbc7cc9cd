"""Class insight: the class overview page and the similarity report.

- :func:`~autograder.instructor.classreport.overview.render_overview` writes ``RESULTS/index.html``
  from a list of :class:`~autograder.instructor.classreport.analysis.StudentRecord`.
- :mod:`autograder.instructor.classreport.similarity` compares the class's submissions lab by lab.
"""

from .analysis import StudentRecord, summarise
from .overview import render_overview

__all__ = ["StudentRecord", "summarise", "render_overview"]
