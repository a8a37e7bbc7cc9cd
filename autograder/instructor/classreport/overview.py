"""The class overview page (``RESULTS/index.html``): what the class got wrong.

One self-contained HTML file, no JavaScript: score histograms (inline SVG),
pass rate per check, the most common named mistakes per exercise with links
to the students' feedback pages, incidents (timeouts, crashes, import failures,
forbidden calls) per student, and a link to every student's page.

:func:`render_overview` is a pure function of plain data (a list of
:class:`~autograder.instructor.classreport.analysis.StudentRecord`), so it renders the
same from a fresh batch or from a stored gradebook.
"""

from __future__ import annotations

import datetime as _dt
import re
from urllib.parse import quote

from jinja2 import Environment, PackageLoader, select_autoescape

from ...engine.results import write_atomically
from ...engine.versions import describe
from .analysis import ClassSummary, StudentRecord, summarise
from .charts import MEAN_COLOUR, MEDIAN_COLOUR, histogram_svg

_SCHEME = re.compile(r"^\s*([a-z][a-z0-9+.-]*):", re.IGNORECASE)


def safe_href(href: str) -> str:
    """A link to a student's page: relative paths (or http/https) only, spaces and the like quoted."""
    if not href:
        return ""
    scheme = _SCHEME.match(href)
    if scheme and scheme.group(1).lower() not in ("http", "https"):
        return ""
    return quote(href, safe="/#?=&%:;@+,~")


def _num(x) -> str:
    # (to the hundredth, as the gradebook's exports write a grade: 10.33, not three significant digits' 10.3)
    return "–" if x is None else f"{round(float(x), 2):g}" if abs(x) < 1e6 else f"{x:.0f}"


def environment() -> Environment:
    """The Jinja2 environment of the class pages (templates beside the feedback page's)."""
    env = Environment(loader=PackageLoader("autograder.reports", "templates"),
                      autoescape=select_autoescape(["html", "j2"]), trim_blocks=True, lstrip_blocks=True)
    env.filters["num"] = _num
    env.filters["href"] = safe_href
    env.filters["percent"] = lambda x: f"{x:.0f}%"
    env.globals.update(histogram=histogram_svg, mean_colour=MEAN_COLOUR, median_colour=MEDIAN_COLOUR)
    return env


def overview_html(students: list[StudentRecord], course_title: str = "",
                  generated: _dt.datetime | None = None, reports=(), changes=()) -> str:
    """The class overview page as a string; ``reports`` are (label, relative link) pairs;
    ``changes`` the final grades the last run moved (:class:`..batch.changes.Change`)."""
    summary: ClassSummary = summarise(students)
    generated = generated or _dt.datetime.now(_dt.timezone.utc)
    # The NumPy/OpenCV that judged the gradings shown (more than one only if kept gradings differ).
    judged_with = sorted({describe(s.result.get("versions") or {}) for s in students if s.result} - {""})
    return environment().get_template("class_overview.html.j2").render(
        summary=summary, course_title=course_title, reports=list(reports), changes=list(changes),
        generated=generated.strftime("%Y-%m-%d %H:%M %Z").strip(), judged_with=judged_with)


def render_overview(students: list[StudentRecord], out_path, course_title: str = "",
                    generated: _dt.datetime | None = None, reports=(), changes=()) -> None:
    """Write the class overview page to ``out_path`` (atomically).

    Parameters
    ----------
    students : list of StudentRecord
        The class, graded or not; order is kept in the list of students.
    out_path : path
        Usually ``RESULTS/index.html``; each record's ``feedback_href`` is
        relative to its folder.
    course_title : str
        Shown in the heading.
    """
    write_atomically(out_path, overview_html(students, course_title, generated, reports, changes))
