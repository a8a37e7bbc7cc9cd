"""The instructor's tools: the course configuration, a whole class, Gradescope, the student bundle.

- :mod:`.course` -- one course's decisions (labs, points, limits, hidden checks, late rule, LMS);
- :mod:`.batch` -- a class graded in one command, kept in a resumable gradebook, exported to the LMS;
- :mod:`.classreport` -- the class overview and the similarity report;
- :mod:`.gradescope` -- ``autograder.zip`` and the ``results.json`` it writes;
- :mod:`.bundle` -- the repository students receive;
- :mod:`.apidoc` -- the assignment API reference, generated from the skeletons and the registry.
"""
