"""The built-in labs' mistakes tables, one module per lab (``labNN.py``), read by
``autograder verify`` (:mod:`autograder.instructor.verify`) and the project's tests.

Each module holds ``MISTAKES``: case name -> ``(exercise id, source, fragments)``, where
``source`` redefines functions of the reference solution (it is appended to it) and
every fragment must appear in the message of a check that fails; optionally ``ADVICE``
(same form: conventions that earn a tip, never lose a point) and ``FEWER_MISTAKES``
(exercise id -> why its algorithm has fewer than five realistic mistakes).

The tables are the grader's, not the students': they describe the checks' answers
closely (a case is the reference with one slip), so neither the student bundle nor
the Gradescope zip ships this folder, as neither ships the hidden checks.
"""
