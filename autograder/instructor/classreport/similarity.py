"""Which submissions look alike, lab by lab: leads for a person to read, never a verdict.

Uses `copydetect <https://github.com/blingenf/copydetect>`_ (the optional
``similarity`` extra): each lab module is tokenised (names, strings and
comments filtered out, so renamed variables and rewritten comments do not hide
a copy), fingerprinted by winnowing (so reordered functions do not either),
and the skeleton's own code is removed as boilerplate. Every pair of students
who handed in the same module is compared; a pair's score is the mean of the
two files' shares of code found in the other.

Sources are read per student from a folder with one entry per student (a
folder, ``.zip`` or notebook, as :func:`autograder.loading.submission.load_submission`
reads them): the submissions folder, or a batch's RESULTS folder where each
student's folder keeps the submitted modules.
"""

from __future__ import annotations

import io
import itertools
import statistics
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from markupsafe import Markup, escape

from ...engine.results import write_atomically
from ...loading.submission import SubmissionError, load_submission
from ..bundle import PROJECT_ROOT

SKELETON_DIR = PROJECT_ROOT / "assignments"
NOISE_THRESHOLD = 25        # shortest filtered token run that counts as a match (copydetect's default)
GUARANTEE_THRESHOLD = 30    # runs this long are always found (copydetect's default)
SHOWN_PER_LAB = 10          # pairs listed per lab even below the threshold, for comparison
CODE_SHOWN_PER_LAB = 30     # pairs above the threshold shown side by side
MAX_SOURCE_CHARS = 200_000  # a lab module is a few hundred lines; a huge file is compared by its start
ALIGN_ABOVE = 0.2           # pairs sharing fewer fingerprints than this are not aligned (see compare_module)
_NOT_STUDENTS = {"__MACOSX", "index.html", "similarity.html"}


class SimilarityUnavailable(RuntimeError):
    """copydetect is not installed (a dependency of the grader: an install that lacks it is broken)."""


def _copydetect():
    try:
        import copydetect
        from copydetect import utils
    except ImportError:  # pragma: no cover - exercised where the extra is missing
        raise SimilarityUnavailable(
            "the similarity report needs copydetect, a dependency of the grader: install the grader again as the "
            "README says (python -m pip install -c constraints.txt -e .)") from None
    return copydetect, utils


# ---------------------------------------------------------------- finding the sources
def lab_modules() -> dict[str, str]:
    """Module name -> lab key, for every registered lab."""
    from ...engine.registry import discover

    return {lab.module: lab.key for lab in discover().values()}


def collect_sources(folder, modules) -> dict[str, dict[str, str]]:
    """Student -> module -> source, for every student in ``folder`` with some of ``modules``.

    With the batch installed, ``folder`` is read as ``autograder batch`` reads a
    class (Gradescope, Canvas and Moodle downloads too, with the same student
    ids). Otherwise, and for a RESULTS folder, each entry -- a student's folder,
    ``.zip`` or ``.ipynb`` -- is one student. Entries holding none of the
    modules, and files that are not submissions (CSV, HTML, the gradebook), are
    left out; unreadable ones are listed by the batch, not here.
    """
    folder = Path(folder)
    if not folder.exists():
        raise SubmissionError(f"not found: {folder}")
    modules = list(modules)
    sources: dict[str, dict[str, str]] = {}
    with tempfile.TemporaryDirectory(prefix="similarity-") as scratch:
        entries = None
        if not (folder / "gradebook.sqlite").exists():
            entries = _batch_entries(folder, modules, Path(scratch))
        for student, entry in entries if entries is not None else _entries(folder):
            try:
                with load_submission(entry, modules) as submission:
                    found = {m: _read_source(submission.path / f"{m}.py")
                             for m in modules if (submission.path / f"{m}.py").exists()}
            except SubmissionError:
                continue
            if found:
                sources[student] = found
    return sources


def _read_source(path: Path) -> str:
    with open(path, encoding="utf-8", errors="replace") as f:
        return f.read(MAX_SOURCE_CHARS)


def _entries(folder: Path) -> list[tuple[str, Path]]:
    """One student per folder, ``.zip`` or ``.ipynb`` at the top of ``folder``."""
    if not folder.is_dir():
        raise SubmissionError(f"not a folder of submissions: {folder}")
    return [(entry.stem if entry.is_file() else entry.name, entry) for entry in sorted(folder.iterdir())
            if not entry.name.startswith(".") and entry.name not in _NOT_STUDENTS
            and (entry.is_dir() or entry.suffix in (".zip", ".ipynb"))]


def _batch_entries(folder: Path, modules: list[str], scratch: Path) -> list[tuple[str, Path]] | None:
    """The class as ``autograder batch`` reads it, each student's files laid out under ``scratch``."""
    try:
        from ..batch.ingest import read_class
    except ImportError:   # the batch is not part of this installation
        return None
    out = []
    for entry in read_class(folder, modules, modules):
        if entry.error:
            continue
        target = scratch / entry.student_id
        for relative, data in entry.files.items():   # relative POSIX paths, checked by the batch's reader
            path = target / relative
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_bytes(data)
        target.mkdir(exist_ok=True)
        out.append((entry.student_id, target))
    return out


def skeleton_sources(modules, skeleton_dir=SKELETON_DIR) -> dict[str, str]:
    """The skeleton's code per module: what every student starts from, never a match."""
    return {m: (Path(skeleton_dir) / f"{m}.py").read_text(encoding="utf-8")
            for m in modules if (Path(skeleton_dir) / f"{m}.py").exists()}


# ---------------------------------------------------------------- comparing
@dataclass
class SimilarPair:
    """Two students' versions of one module, and how much of each is found in the other."""

    module: str
    student_a: str
    student_b: str
    share_a: float            # fraction of a's (non-skeleton) code matched in b
    share_b: float
    highlighted_a: Markup = field(repr=False, default=Markup(""))   # escaped source, <mark>ed matches
    highlighted_b: Markup = field(repr=False, default=Markup(""))
    slices: tuple = field(repr=False, compare=False, default=())   # copydetect's matched regions
    aligned: bool = True      # shares measured by copydetect; else estimated from common fingerprints

    @property
    def score(self) -> float:
        return (self.share_a + self.share_b) / 2


@dataclass
class LabSimilarity:
    module: str
    lab: str
    students: int             # students whose module has code beyond the skeleton
    pairs: list[SimilarPair]  # every compared pair, most similar first
    clusters: list[list[str]] = field(default_factory=list)   # students with identical code, 2 or more each

    def identical_to(self, student: str) -> list[str]:
        """The others in ``student``'s cluster of identical code (who stands for them in ``pairs``)."""
        for cluster in self.clusters:
            if student in cluster:
                return [s for s in cluster if s != student]
        return []

    def leads(self, threshold: float) -> list[SimilarPair]:
        """The aligned pairs scoring at least ``threshold``, most similar first."""
        return [p for p in self.pairs if p.aligned and p.score >= threshold]

    @property
    def median(self) -> float | None:
        return statistics.median(p.score for p in self.pairs) if self.pairs else None


def compare_module(module: str, sources: dict[str, str], skeleton: str = "", lab: str = "",
                   noise: int = NOISE_THRESHOLD, guarantee: int = GUARANTEE_THRESHOLD,
                   align_above: float = ALIGN_ABOVE, aligned_at_least: int = SHOWN_PER_LAB) -> LabSimilarity:
    """Compare every pair of ``sources`` (student -> source of ``module``), skeleton excluded.

    Every pair is first scored by the share of fingerprints the two files have
    in common (a set intersection, microseconds); copydetect aligns the files
    (exact shares, matching regions) for the pairs scoring at least
    ``align_above`` and for the ``aligned_at_least`` best ones. A class of 300
    has 44,850 pairs per lab, almost all of them far apart.
    """
    copydetect, utils = _copydetect()
    window = guarantee - noise + 1
    filename = f"{module}.py"   # the extension picks copydetect's Python tokeniser
    boilerplate = []
    if skeleton:
        boilerplate = copydetect.CodeFingerprint(filename, noise, 1, fp=io.StringIO(skeleton)).hashes
    boilerplate = sorted(boilerplate)
    prints = {}
    for student, source in sources.items():
        fingerprint = copydetect.CodeFingerprint(filename, noise, window, boilerplate, fp=io.StringIO(source))
        if fingerprint.token_coverage > 0:   # an untouched skeleton has nothing of its own
            prints[student] = fingerprint
    students = len(prints)
    # Identical code (the same fingerprints: names and comments aside) is one cluster, listed once;
    # its first student stands for it among the pairs (253 identical pairs are one line, not 253).
    by_code: dict[frozenset, list[str]] = {}
    for student in sorted(prints):
        by_code.setdefault(frozenset(prints[student].hashes), []).append(student)
    clusters = [members for members in by_code.values() if len(members) > 1]
    for members in clusters:
        for student in members[1:]:
            del prints[student]
    pairs = []
    for a, b in itertools.combinations(sorted(prints), 2):
        common = len(prints[a].hashes & prints[b].hashes)
        pairs.append(SimilarPair(module, a, b, common / max(len(prints[a].hashes), 1),
                                 common / max(len(prints[b].hashes), 1), aligned=False))
    pairs.sort(key=lambda p: -p.score)
    for rank, pair in enumerate(pairs):
        if rank >= aligned_at_least and pair.score < align_above:
            break
        _, (share_a, share_b), slices = copydetect.compare_files(prints[pair.student_a], prints[pair.student_b])
        pair.share_a, pair.share_b, pair.slices, pair.aligned = float(share_a), float(share_b), slices, True
    pairs.sort(key=lambda p: (-p.aligned, -p.score, p.student_a, p.student_b))
    return LabSimilarity(module, lab or module, students, pairs, sorted(clusters, key=lambda c: (-len(c), c)))


def highlight(pair: SimilarPair, sources: dict[str, str]) -> None:
    """Fill in the pair's escaped sources with the matching regions marked."""
    _, utils = _copydetect()
    slices_a, slices_b = pair.slices
    for attr, student, slices in (("highlighted_a", pair.student_a, slices_a),
                                  ("highlighted_b", pair.student_b, slices_b)):
        code = sources[student]
        if len(slices) and len(slices[0]):
            marked, _ = utils.highlight_overlap(code, slices, "<mark>", "</mark>", escape_html=True)
        else:
            marked = str(escape(code))
        setattr(pair, attr, Markup(marked))


def compare_class(sources: dict[str, dict[str, str]], skeletons: dict[str, str] | None = None,
                  labs: dict[str, str] | None = None, threshold: float = 0.6,
                  code_shown: int = CODE_SHOWN_PER_LAB) -> list[LabSimilarity]:
    """Compare the class lab by lab; pairs at or above ``threshold`` get their sources highlighted."""
    skeletons = skeletons or {}
    labs = labs or {}
    modules = sorted({m for per_student in sources.values() for m in per_student},
                     key=lambda m: (labs.get(m, m), m))
    results = []
    for module in modules:
        module_sources = {s: per[module] for s, per in sources.items() if module in per}
        result = compare_module(module, module_sources, skeletons.get(module, ""), labs.get(module, ""),
                                align_above=min(ALIGN_ABOVE, threshold))
        for pair in result.leads(threshold)[:code_shown]:
            highlight(pair, module_sources)
        results.append(result)
    return results


# ---------------------------------------------------------------- the page
def similarity_html(results: list[LabSimilarity], threshold: float, course_title: str = "",
                    shown: int = SHOWN_PER_LAB, code_shown: int = CODE_SHOWN_PER_LAB) -> str:
    import datetime as dt

    from .overview import environment

    return environment().get_template("similarity.html.j2").render(
        results=results, threshold=threshold, course_title=course_title, shown=shown,
        code_shown=code_shown,
        generated=dt.datetime.now(dt.timezone.utc).strftime("%Y-%m-%d %H:%M %Z"))


def write_similarity_report(folder, out_path, threshold: float = 0.6, course_title: str = "",
                            skeleton_dir=SKELETON_DIR) -> list[LabSimilarity]:
    """Compare the submissions in ``folder`` and write ``similarity.html`` to ``out_path``.

    The single entry point for ``autograder similarity`` and ``autograder batch --similarity``.
    """
    labs = lab_modules()
    sources = collect_sources(folder, labs)
    if not sources and (Path(folder) / "gradebook.sqlite").exists():
        raise SubmissionError(f"{folder} keeps no student sources: give the SUBMISSIONS folder the batch read")
    results = compare_class(sources, skeleton_sources(labs, skeleton_dir), labs, threshold)
    write_atomically(out_path, similarity_html(results, threshold, course_title))
    return results
