"""``autograder review RESULTS``: grade the lab reports with the course's rubric, in the browser.

A local web application (Flask, served by Werkzeug's threaded server on 127.0.0.1
only) over a batch's gradebook: per student and exercise, the explanation from the
student's report (rendered inert, :mod:`autograder.reports.markdown`), the figures
the batch made from the student's code, the automatic verdict and named mistakes,
and the rubric, keyboard-driven. Every change is written to the gradebook at once
(see :mod:`.app`).
"""

from .app import ReviewSession, create_app, serve

__all__ = ["ReviewSession", "create_app", "serve"]
