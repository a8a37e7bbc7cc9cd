"""Instructor batch grading: a class in one command (``autograder batch``).

- :mod:`.ingest` reads the class (folders, zips, notebooks, Gradescope, Canvas, Moodle);
- :mod:`.task` grades one submission as plain data in, plain data out;
- :mod:`.gradebook` keeps the results (SQLite, resumable);
- :mod:`.exports` turns them into grades and CSVs (course points, overrides, late rule, roster);
- :mod:`.run` ties them together; :mod:`.cluster` runs the tasks on Dask.
"""
