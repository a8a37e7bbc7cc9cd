"""``autograder new-lab NAME --into FOLDER``: a course lab to start from.

It writes the parts of a lab folder (:mod:`autograder.engine.labfolders`) with one small
worked exercise (``brighten(image, delta=40)``: public checks, a hidden check, ground
truth and its mistakes, a reference, a skeleton and a mistakes table) that passes
``autograder verify`` as it is. Replace the exercise with the lab's own.
"""

from __future__ import annotations

import json
import os
import re
from pathlib import Path
from string import Template

from ..engine.labfolders import HIDDEN, MISTAKES, REFERENCE, SKELETON, SUITE
from ..engine.registry import discover

TEMPLATES = Path(__file__).resolve().parent / "templates" / "new_lab"
_NAME = re.compile(r"(lab\d\d)_([a-z][a-z0-9_]*)")


class NewLabError(ValueError):
    """The name is not a lab module's name, or the folder is not empty."""


def new_lab(name: str, into, title: str = "") -> list[Path]:
    """Write a lab whose student module is ``name`` (``lab13_flow``: its key is ``lab13``)
    into the folder ``into`` (created; it must be empty). Returns the files written."""
    match = _NAME.fullmatch(name)
    if not match:
        raise NewLabError(f"{name!r} is not a lab's module name: lab<two digits>_<words>, like lab13_flow "
                          "(the file students hand in, and the lab's key lab13)")
    key = match.group(1)
    built_in = discover().get(key)
    if built_in is not None and built_in.folder is None:
        raise NewLabError(f"{key} is a built-in lab's key ({built_in.title}): a course lab needs a new one, "
                          f"like lab13_{match.group(2)}")
    if title and not title.isprintable():
        raise NewLabError("the title is one line of text")
    folder = Path(into)
    if folder.exists() and (not folder.is_dir() or any(folder.iterdir())):
        raise NewLabError(f"{folder} exists and is not an empty folder")
    title = title or match.group(2).replace("_", " ").capitalize()
    # In docstrings as text (quotes and backslashes escaped); in Lab(...) as a Python literal.
    values = {"key": key, "module": name, "title": title.replace("\\", "\\\\").replace('"', '\\"'),
              "title_literal": repr(title)}
    targets = {SUITE: "suite.py", HIDDEN: "hidden.py", "truth.py": "truth.py", MISTAKES: "mistakes.py",
               f"{REFERENCE}/{name}.py": "reference.py", f"{SKELETON}/{name}.py": "skeleton.py"}
    written = []
    for target, template in targets.items():
        path = folder / target
        path.parent.mkdir(parents=True, exist_ok=True)
        text = Template((TEMPLATES / f"{template}.tmpl").read_text(encoding="utf-8")).substitute(values)
        path.write_text(text, encoding="utf-8")
        written.append(path)
    return written


def course_entry(folder, course) -> str:
    """What to write in the course configuration ``course`` so that it grades the lab in
    ``folder``: its ``"labs"`` line (the course's labs so far, then this one), or the whole
    file when there is none yet. The folder is written relative to the course file, as the
    course reads it, whenever it can be (not on another drive); absolute otherwise."""
    course = Path(course)
    target = Path(folder).resolve()
    try:
        entry = Path(os.path.relpath(target, course.resolve().parent)).as_posix()
    except ValueError:   # another drive (Windows): only an absolute path reaches it
        entry = target.as_posix()
    try:
        data = json.loads(course.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        data = None
    if not isinstance(data, dict):
        return json.dumps({"labs": [entry]})
    labs = data.get("labs") if isinstance(data.get("labs"), list) else []
    return '"labs": ' + json.dumps([lab for lab in labs if lab != entry] + [entry])
