"""The student's tools besides ``grade.py``: ``check()`` in a notebook and ``autograder validate``."""
