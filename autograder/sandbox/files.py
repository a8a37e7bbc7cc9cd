"""Reading files someone else wrote: only regular files, never what a link points to.

The grader may run as root and every file of a submission or a class upload is
written by a student, so reading is deny-by-default: a file is opened without
following links (``O_NOFOLLOW``), must be a regular file, and every cap
(:class:`Caps`) is checked before a byte is read. What is not read is named with
its reason (``refused``: path -> sentence), never an exception.

Used by the sandbox to copy a submission into a worker's scratch folder, and by
loading (:mod:`autograder.loading.submission`, the batch's class uploads) to read one.
"""

from __future__ import annotations

import os
import stat
from dataclasses import dataclass
from pathlib import Path, PurePosixPath


@dataclass(frozen=True)
class Caps:
    """What loading a submission reads at most; each checked before reading or inflating."""

    file_bytes: int = 2 * 2**20         # one .py file
    notebook_bytes: int = 8 * 2**20     # one .ipynb (parsing JSON costs ~25x its size at worst)
    entries: int = 2000                 # folder entries or archive members looked at
    total_bytes: int = 50 * 2**20       # everything copied or inflated together
    depth: int = 4                      # folders below the submission's top


CAPS = Caps()
SOURCE_SUFFIXES = (".py", ".ipynb")
SKIPPED_FOLDERS = ("__MACOSX", "__pycache__")


class Refused(Exception):
    """One file is not read; the message says why."""


def display_name(name: str) -> str:
    """A file name safe to show and to encode (undecodable bytes replaced)."""
    return name.encode("utf-8", "surrogateescape").decode("utf-8", "replace")


def check_name(relative: str, caps: Caps) -> None:
    try:
        relative.encode("utf-8")
    except UnicodeEncodeError:
        raise Refused("its name is not valid UTF-8; rename it") from None
    if any(ord(c) < 32 or ord(c) == 127 for c in relative):
        raise Refused("its name holds control characters; rename it")
    parts = PurePosixPath(relative).parts
    if relative.startswith("/") or ".." in parts:
        raise Refused("its name points outside the submission")
    if len(parts) - 1 > caps.depth:
        raise Refused(f"it is more than {caps.depth} folders deep")


def read_regular(path: Path, limit: int) -> bytes:
    """The bytes of a regular file, never following a link, refusing what is over ``limit``."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
    except OSError as exc:
        raise Refused("it is a symbolic link" if os.path.islink(path)
                       else f"it cannot be read ({exc.strerror})") from None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise Refused("it is not a regular file")
        if info.st_size > limit:
            raise Refused(f"it is larger than {mib(limit)}")
        chunks, size = [], 0
        while size <= limit:
            chunk = os.read(fd, min(1 << 20, limit + 1 - size))
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
        if size > limit:
            raise Refused(f"it is larger than {mib(limit)}")
        return b"".join(chunks)
    finally:
        os.close(fd)


def mib(n: int) -> str:
    return f"{n / 2**20:g} MiB"


def limit_for(name: str, caps: Caps) -> int:
    if name.endswith(".zip"):  # an archive handed in within a folder: its members are capped again
        return caps.total_bytes
    return caps.notebook_bytes if name.endswith(".ipynb") else caps.file_bytes


def read_one(path: Path, relative: str, refused, caps, total) -> bytes | None:
    """``path``'s bytes, counted in ``total`` (a one-item list); None, and the reason in
    ``refused``, when it is not read."""
    try:
        check_name(relative, caps)
        data = read_regular(path, limit_for(relative, caps))
        if total[0] + len(data) > caps.total_bytes:
            raise Refused(f"the submission holds more than {mib(caps.total_bytes)} of sources")
    except Refused as exc:
        refused[display_name(relative)] = str(exc)
        return None
    total[0] += len(data)
    return data


def write_file(target: Path, data: bytes) -> None:
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_bytes(data)


def copy_regular_files(source: Path, target: Path, refused: dict | None = None,
                       caps: Caps = CAPS, suffixes=SOURCE_SUFFIXES) -> dict[str, str]:
    """Copy the regular ``suffixes`` files under ``source`` into ``target``
    (as :func:`read_regular_files` reads them). Returns ``refused``: path inside
    ``source`` -> reason."""
    refused = {} if refused is None else refused
    for relative, data in read_regular_files(source, refused, caps, suffixes).items():
        write_file(Path(target) / relative, data)
    return refused


def read_regular_files(source: Path, refused: dict | None = None,
                       caps: Caps = CAPS, suffixes=SOURCE_SUFFIXES) -> dict[str, bytes]:
    """The regular ``suffixes`` files under ``source``: relative POSIX path -> bytes.

    Symbolic links (to files or folders), devices, pipes and sockets are refused,
    never followed; so are hidden entries, ``__pycache__`` and what breaks a cap.
    What is refused goes into ``refused``: path inside ``source`` -> reason.
    """
    refused = {} if refused is None else refused
    source, files = Path(source), {}
    seen, total = 0, [0]
    pending = [(source, 0)]
    while pending:
        folder, depth = pending.pop()
        try:
            entries = sorted(os.scandir(folder), key=lambda e: e.name)
        except OSError as exc:
            refused[display_name(os.path.relpath(folder, source))] = f"cannot be listed ({exc.strerror})"
            continue
        for entry in entries:
            seen += 1
            relative = os.path.relpath(entry.path, source).replace(os.sep, "/")
            if seen > caps.entries:
                refused[display_name(relative)] = (f"the submission holds more than {caps.entries} "
                                                    "files; the rest was not read")
                return files
            if entry.name.startswith(".") or entry.name in SKIPPED_FOLDERS:
                continue
            if entry.is_symlink():
                if entry.name.endswith(suffixes) or _points_to_folder(entry):
                    refused[display_name(relative)] = "it is a symbolic link"
                continue
            if entry.is_dir(follow_symlinks=False):
                if depth < caps.depth:
                    pending.append((Path(entry.path), depth + 1))
                continue
            if entry.name.endswith(suffixes):
                data = read_one(Path(entry.path), relative, refused, caps, total)
                if data is not None:
                    files[relative] = data
    return files


def _points_to_folder(entry) -> bool:
    try:
        return entry.is_dir(follow_symlinks=True)
    except OSError:
        return False
