"""PDF reports and a report's pictures, read in a sandbox worker: the grader's side.

A student's PDF is hostile input (a decompression bomb, an object graph with no end, a
file that is no PDF, an encrypted one). :class:`ReportReader` never parses one in the
grader's process: it sends its bytes to a :class:`~autograder.sandbox.supervisor.Sandbox`
worker running :mod:`autograder.sandbox.report_reader` (pypdf, Pillow), within
:data:`PDF_SECONDS` of wall clock and :data:`PDF_MEMORY` of memory per file, and takes
back plain data through the sandbox's transport (never pickle). A worker that timed out,
ran out of memory or died is dropped; the next file gets a fresh one. Whatever goes wrong
is one sentence in :attr:`PdfText.error` ("it is encrypted ..."), which the report shows
as "report.pdf: the PDF's text could not be read: it is encrypted ...".

What is read (:class:`PdfText`): each page's text, and the thumbnails of its pictures
(:func:`autograder.sandbox.report_reader.thumbnail`), for the figure provenance on the
review screen. :func:`pdf_sections` splits the text into exercises with
:func:`~.headings.plain_text_sections` (strict headings: "Exercise 2", "Ex. 2",
"2. Rotation", an exercise's title on a line of its own).

Results are kept in the grader's store (:mod:`autograder.sandbox.cache`), keyed by the
file's (or picture's) SHA-256 and the reader's code and libraries, where the store is
trusted (the namespaced confinement levels): a class graded again does not parse its PDFs
or thumbnail its pictures again. :meth:`ReportReader.prefetch` reads a class's PDFs side by
side, each reader's worker in a thread of its own, before they are asked for one by one.
"""

from __future__ import annotations

import base64
import bisect
import hashlib
import shutil
import tempfile
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from importlib import metadata
from pathlib import Path

import numpy as np

from ..sandbox import cache, confine, report_reader
from ..sandbox.supervisor import Limits, Sandbox, WorkerStartError
from .headings import ExerciseNames, Section, plain_text_sections

PDF_SECONDS = 20.0                 # wall clock to read one PDF (pages, text and pictures)
PICTURE_SECONDS = 10.0             # to thumbnail the pictures of one notebook
PDF_MEMORY = 768 * 2**20           # the worker and all it starts
MAX_PDF_BYTES = 20 * 2**20         # a larger PDF is not sent (the upload's own cap is the same)
MAX_PICTURE_BYTES = 8 * 2**20      # one picture of a notebook's outputs
MAX_FILES = 2000                   # PDFs read in workers by one reader (a class's); the rest are noted, unread
_CACHE_NAME = "loading.pdf_report"
UNCONFINED = ("it was not read: this machine cannot confine the reader's worker "
              "(the batch's --allow-unconfined reads it anyway)")
_PICTURE_CACHE_NAME = "loading.pdf_report.pictures"


@dataclass(frozen=True)
class Picture:
    """A picture of the report, as the worker thumbnailed it.

    ``where``: "page 3" or "cell 12"; ``number``: its place among the file's pictures
    (from 1); ``width``/``height``: its own size in pixels; ``thumb``: ``THUMB x THUMB``
    grey ``uint8`` (:func:`autograder.sandbox.report_reader.thumbnail`)."""

    where: str
    number: int
    width: int
    height: int
    thumb: np.ndarray


@dataclass(frozen=True)
class PdfText:
    """What a PDF holds: ``pages`` (text, page 1 first), ``pictures``, ``notes`` (what was
    left out), ``error`` (why nothing was read; "" when the text was)."""

    pages: tuple[str, ...] = ()
    pictures: tuple[Picture, ...] = ()
    notes: tuple[str, ...] = ()
    error: str = ""

    @property
    def text(self) -> str:
        """The pages' texts, one after the other (a line break between two pages)."""
        return "\n".join(self.pages)

    def page_at(self, position: int) -> int:
        """The page (from 1) that holds ``position`` of :attr:`text`."""
        starts, at = [], 0
        for page in self.pages:
            starts.append(at)
            at += len(page) + 1
        return max(bisect.bisect_right(starts, position), 1)


def pdf_sections(pdf: PdfText, names: ExerciseNames, path: str, most: int,
                 unsure: list | None = None) -> list[Section]:
    """The exercises' sections of the PDF's text (see :func:`~.headings.plain_text_sections`)."""
    return plain_text_sections(pdf.text, names, names.lab_of_path(path), most, unsure)


class ReportReader:
    """Reads PDFs and pictures in sandbox workers, one file per call; a context manager
    (the worker is stopped at the end). Never raises for what a file holds."""

    def __init__(self, confinement: confine.Confinement | None = None, allow_unconfined: bool = False):
        self._confinement = confinement
        # At the process-group level a worker runs as the grader's user and sees its files: a
        # decoder's flaw (Pillow's are C) would reach them. Read there only when the batch may
        # grade unconfined too (--allow-unconfined).
        self._allow_unconfined = allow_unconfined
        self._box: Sandbox | None = None
        self._folder: Path | None = None
        self.files_read = 0
        self._ahead: dict[str, list] = {}     # SHA-256 -> [the worker's answer read ahead, times still to be asked]
        self._failed: dict[str, str] = {}     # SHA-256 -> why it could not be read (a file handed in twice: once)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self) -> None:
        if self._box is not None:
            self._box.close()
            self._box = None
        if self._folder is not None:
            shutil.rmtree(self._folder, ignore_errors=True)
            self._folder = None

    # -------------------------------------------------------------- public
    def pdf(self, data: bytes) -> PdfText:
        """What the PDF ``data`` holds, read in a worker (or the store)."""
        if len(data) > MAX_PDF_BYTES:
            return PdfText(error=f"it is {len(data) / 2**20:.1f} MiB, more than the {MAX_PDF_BYTES >> 20} MiB read")
        if not self._may_read():
            return PdfText(error=UNCONFINED)
        key = hashlib.sha256(data).hexdigest()
        if key in self._failed:
            return PdfText(error=self._failed[key])
        found, stored = None, False
        if key in self._ahead:   # read ahead: held until its last copy in the class is asked for
            found, self._ahead[key][1] = self._ahead[key][0], self._ahead[key][1] - 1
            if self._ahead[key][1] <= 0:
                del self._ahead[key]
        if found is None:
            with cache.enabled(self._trusted_store()):
                found = cache.load(_CACHE_NAME, _version(), key)
            stored = found is not None
        if found is None and self.files_read >= MAX_FILES:
            return PdfText(error=f"more than {MAX_FILES:,} PDFs were handed in; this one was not read")
        if found is None:
            self.files_read += 1
            found = self._read_pdf(data)
        if isinstance(found, str):
            self._failed[key] = found
            return PdfText(error=found)
        if not stored:
            with cache.enabled(self._trusted_store()):
                cache.save(_CACHE_NAME, _version(), key, found)
        return _pdf_text(found)

    def prefetch(self, pdfs: list[bytes], readers: int) -> None:
        """Read the PDFs of ``pdfs`` not in the store yet with up to ``readers`` workers side by
        side (a reader of its own in a thread each: its worker lives and ends in that thread),
        ahead of :meth:`pdf` asking for them one by one. A class's first batch reads its PDFs
        ``readers`` times faster; a file's answer is the same either way."""
        if not self._may_read():
            return
        todo, copies = [], {}
        with cache.enabled(self._trusted_store()):
            for data in pdfs:
                key = hashlib.sha256(data).hexdigest()
                copies[key] = copies.get(key, 0) + 1
                if copies[key] > 1 or key in self._ahead or key in self._failed or len(data) > MAX_PDF_BYTES:
                    continue
                if cache.load(_CACHE_NAME, _version(), key) is None:
                    todo.append((key, data))
        todo = todo[:MAX_FILES - self.files_read]
        readers = min(readers, len(todo))
        if readers < 2:
            return

        def read(chunk):
            with ReportReader(self._confinement) as reader:
                return [(key, reader._read_pdf(data)) for key, data in chunk]

        with ThreadPoolExecutor(readers) as pool:
            for answers in pool.map(read, [todo[i::readers] for i in range(readers)]):
                for key, found in answers:   # kept in the store by pdf(), in this thread, when asked
                    self.files_read += 1
                    if isinstance(found, str):
                        self._failed[key] = found
                    else:
                        self._ahead[key] = [found, copies[key]]

    def _read_pdf(self, data: bytes):
        """The worker's answer for the PDF ``data``, or the sentence saying why there is none."""
        return self._call("read_pdf", (np.frombuffer(data, dtype=np.uint8),), PDF_SECONDS)

    def pictures(self, blobs: list[tuple[str, bytes]]) -> tuple[list[Picture], list[str]]:
        """Thumbnails of encoded pictures ``(where, bytes)`` (a notebook's image outputs):
        the pictures read, and sentences for those that could not be."""
        kept = [(where, blob) for where, blob in blobs if len(blob) <= MAX_PICTURE_BYTES]
        problems = [f"the picture in {where} is larger than {MAX_PICTURE_BYTES >> 20} MiB; it was not compared"
                    for where, blob in blobs if len(blob) > MAX_PICTURE_BYTES]
        kept = kept[:report_reader.MAX_IMAGES]
        if not kept:
            return [], problems
        if not self._may_read():
            return [], problems + [f"the pictures were not compared: {UNCONFINED}"]
        # Each picture's answer is kept in the store: a class graded again sends none of its
        # notebooks' unchanged pictures to a worker again.
        keys = [hashlib.sha256(blob).hexdigest() for _, blob in kept]
        with cache.enabled(self._trusted_store()):
            known = {key: found for key in set(keys)
                     if (found := cache.load(_PICTURE_CACHE_NAME, _version(), key)) is not None}
        missing = list(dict.fromkeys(key for key in keys if key not in known))
        if missing:
            blob_of = dict(zip(keys, (blob for _, blob in kept)))
            answer = self._call("read_images", ([np.frombuffer(blob_of[key], dtype=np.uint8) for key in missing],),
                                PICTURE_SECONDS)
            if isinstance(answer, str):
                return [], problems + [f"the pictures could not be read: {answer}"]
            with cache.enabled(self._trusted_store()):
                for key, found in zip(missing, answer if isinstance(answer, list) else []):
                    known[key] = found
                    cache.save(_PICTURE_CACHE_NAME, _version(), key, found)
        pictures = []
        for number, ((where, _), key) in enumerate(zip(kept, keys), 1):
            picture = _picture(known.get(key), where, number)
            if picture is not None:
                pictures.append(picture)
        return pictures, problems

    # -------------------------------------------------------------- the worker
    def _may_read(self) -> bool:
        return self._allow_unconfined or (self._confinement or confine.detect()).level != "process-group"

    def _trusted_store(self) -> bool:
        """The store is read and written only where no worker could have written it."""
        return (self._confinement or confine.detect()).level != "process-group"

    def _sandbox(self) -> Sandbox:
        if self._box is None:
            if self._folder is None:
                self._folder = Path(tempfile.mkdtemp(prefix="autograder-report-"))
                shutil.copy(Path(report_reader.__file__), self._folder / f"{report_reader.MODULE}.py")
            limits = Limits(call_timeout=PDF_SECONDS, memory=PDF_MEMORY, max_result_bytes=64 * 2**20,
                            timeouts_per_function=1, exercise_budget=10 * PDF_SECONDS)
            self._box = Sandbox(self._folder, limits, self._confinement)
        return self._box

    def _call(self, function: str, args: tuple, seconds: float):
        """``function(*args)`` of the reader in a worker: its value, or the sentence saying why
        there is none. A worker whose call failed is not used again."""
        try:
            box = self._sandbox()
            outcome = box.call(report_reader.MODULE, function, args, timeout=seconds)
        except WorkerStartError as exc:
            self.close()
            return f"no worker could be started to read it ({exc})"
        if outcome.ok:
            return outcome.value
        self._box.close()   # a fresh worker (and strikes, budget) for the next file
        self._box = None
        return _failure(outcome.kind, outcome.message, seconds)


def _failure(kind: str, message: str, seconds: float) -> str:
    return {"timeout": f"reading it took longer than {seconds:g} seconds",
            "budget": f"reading it took longer than {seconds:g} seconds",
            "memory": f"reading it needed more than {PDF_MEMORY >> 20} MiB of memory",
            "recursion": "its objects are nested too deeply to be read",
            "crashed": "the reader stopped on it (the worker crashed)",
            "output_too_large": "what it holds is too large to be read"}.get(
        kind, f"the reader failed on it ({kind}: {' '.join(message.split())[:160]})")


def _version() -> str:
    """The reader's code and the libraries it parses with: a change reads every PDF again."""
    digest = hashlib.sha256(Path(report_reader.__file__).read_bytes())
    for library in ("pypdf", "pillow", "numpy", "opencv-python-headless"):
        try:
            digest.update(f"{library}={metadata.version(library)};".encode())
        except metadata.PackageNotFoundError:
            digest.update(f"{library}=none;".encode())
    return digest.hexdigest()[:16]


def _pdf_text(found) -> PdfText:
    """The worker's answer (plain data, untrusted: checked field by field) as a :class:`PdfText`."""
    if not isinstance(found, dict):
        return PdfText(error="the reader answered something else than a PDF's contents")
    pages = tuple(p for p in found.get("pages", ()) if isinstance(p, str))[:report_reader.MAX_PAGES]
    pictures = tuple(filter(None, (
        _picture(image, f"page {image.get('page')}", image.get("number"))
        for image in found.get("images", ())[:report_reader.MAX_IMAGES] if isinstance(image, dict))))
    notes = tuple(n for n in found.get("notes", ()) if isinstance(n, str))[:10]
    error = found.get("error") if isinstance(found.get("error"), str) else ""
    return PdfText(pages, pictures, notes, error)


def _picture(found, where: str, number) -> Picture | None:
    if not isinstance(found, dict) or "thumb" not in found:
        return None
    thumb, width, height = found["thumb"], found.get("width"), found.get("height")
    side = report_reader.THUMB
    if not (isinstance(thumb, np.ndarray) and thumb.dtype == np.uint8 and thumb.shape == (side, side)
            and type(width) is int and type(height) is int and width > 0 and height > 0 and type(number) is int):
        return None
    return Picture(where, number, width, height, thumb)


def notebook_pictures(notebook: dict, most: int = report_reader.MAX_IMAGES) -> list[tuple[int, bytes]]:
    """The PNG and JPEG outputs of a notebook's code cells: ``(cell number from 1, bytes)``,
    the first ``most``. Base64 is decoded here (plain text); the pictures are not."""
    found = []
    cells = notebook.get("cells") if isinstance(notebook, dict) else None
    for number, cell in enumerate(cells if isinstance(cells, list) else (), 1):
        outputs = cell.get("outputs") if isinstance(cell, dict) and cell.get("cell_type") == "code" else None
        for output in outputs if isinstance(outputs, list) else ():
            data = output.get("data") if isinstance(output, dict) else None
            if not isinstance(data, dict):
                continue
            for kind in ("image/png", "image/jpeg"):
                encoded = data.get(kind)
                encoded = "".join(encoded) if isinstance(encoded, list) and all(
                    isinstance(x, str) for x in encoded) else encoded
                if isinstance(encoded, str) and len(encoded) <= MAX_PICTURE_BYTES * 4 // 3 + 4:
                    try:
                        found.append((number, base64.b64decode(encoded, validate=False)))
                    except ValueError:
                        continue
                    break
            if len(found) >= most:
                return found
    return found
