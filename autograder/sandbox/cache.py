"""Ground truth kept between gradings: a store of deterministic results, keyed by content.

Rendering a scene or a calibration view costs tens of milliseconds and gives the
same pixels every time on one installation. :func:`persistent` keeps such
results on disk, so a student who grades again (or an instructor grading a
class) computes them once:

- the key is a SHA-256 of everything the result depends on: the decorated
  function's name, its arguments (arrays by dtype, shape and bytes; dataclasses
  field by field), the source files of its package, and the versions of Python,
  NumPy and OpenCV. Anything else in the arguments (an object it cannot
  digest) means no caching for that call;
- values are plain data written with :mod:`autograder.sandbox.transport` (never pickle)
  behind an HMAC-SHA256 of the frame and of the entry's place in the store, under
  the store's key (the file ``key`` in it: 32 random bytes, readable by the
  grader's user only). A checksum anyone can recompute would prove nothing: an
  entry whose MAC fails (truncated, corrupt, moved, or written by anything that
  does not hold the key) is a miss, never an error, and the value is computed
  again;
- the store is used only while :func:`enabled` says so. The runner enables it
  while grading where the worker cannot reach the grader's files (the
  namespaced confinement levels): a submission can neither read the key nor
  write ground truth. A worker at the ``process-group`` level runs as the
  grader's user and could do both, so the store is off for its grading, and the
  sandbox :func:`revokes <revoke>` the key before such a worker starts and again
  once it has stopped: whatever it may have learnt or written is never trusted
  afterwards (the next grading makes a new key and computes afresh). Outside a
  grading (the grader's own tests, scripts) results are computed;
- it lives in ``$AUTOGRADER_CACHE_DIR``, else ``$XDG_CACHE_HOME/cv-autograder``,
  else ``~/.cache/cv-autograder`` (never in the repository), in folders only
  the grader's user may enter; ``AUTOGRADER_CACHE_DIR=off`` switches it off.
  A folder that is missing, read-only or not the user's own just means no
  store. Results of other versions of the code are removed when a new one is
  written, so the store holds one version's results (tens of megabytes).
"""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import hashlib
import hmac
import inspect
import logging
import os
import secrets
import shutil
import stat
import sys
import tempfile
import threading
from pathlib import Path

import numpy as np

from . import transport

_MAX_ENTRY_BYTES = 64 * 2**20
_KEY_FILE, _KEY_BYTES = "key", 32
_enabled = False
_keys: dict[Path, bytes] = {}   # store folder -> its key, read once per process (see revoke)
_keys_lock = threading.Lock()


@contextlib.contextmanager
def enabled(flag: bool = True):
    """Use the persistent store (read and write) inside this block, when ``flag``."""
    global _enabled
    before, _enabled = _enabled, bool(flag)
    try:
        yield
    finally:
        _enabled = before


def is_enabled() -> bool:
    return _enabled


def location() -> Path | None:
    """The store's folder (which may not exist yet), or None when switched off."""
    configured = os.environ.get("AUTOGRADER_CACHE_DIR")
    if configured is not None:
        return None if configured.strip().lower() in ("", "off", "0", "none") else Path(configured)
    base = os.environ.get("XDG_CACHE_HOME") or (Path.home() / ".cache" if "HOME" in os.environ else None)
    return Path(base) / "cv-autograder" if base else None


def persistent(function=None, *, libraries: tuple[str, ...] = ()):
    """Keep ``function``'s results (plain data: arrays, numbers, tuples...) in the store.

    ``function`` must be deterministic: the same arguments, code and libraries give
    the same result. ``libraries`` names further distributions it reads data or code
    from (``("scikit-image",)``); Python, NumPy and OpenCV always count. While the
    store is not :func:`enabled` it is simply called.
    """
    if function is None:
        return functools.partial(persistent, libraries=libraries)
    name = f"{function.__module__}.{function.__qualname__}"
    # The code of its whole package counts: it may call helpers in the package's other modules.
    sources = sorted(Path(inspect.getfile(function)).parent.glob("*.py"))

    @functools.wraps(function)
    def stored(*args, **kwargs):
        if not _enabled:
            return function(*args, **kwargs)
        try:
            folder = _folder(name, _code_version(name, tuple(sources), libraries))
            key = _key(name, args, kwargs)
        except (TypeError, OSError, ValueError):
            return function(*args, **kwargs)
        found = _read(folder, key) if folder is not None else None
        if found is not None:
            return found
        result = function(*args, **kwargs)
        if folder is not None:
            _write(folder, key, result)
        return result

    return stored


def load(name: str, version: str, key: str):
    """The value saved under ``key`` for this ``version`` of ``name``, or None
    (also when the store is not enabled)."""
    folder = _folder(name, version) if _enabled else None
    return _read(folder, _hashed(key)) if folder is not None else None


def save(name: str, version: str, key: str, value) -> None:
    """Keep ``value`` (plain data) under ``key``, when the store is enabled."""
    folder = _folder(name, version) if _enabled else None
    if folder is not None:
        _write(folder, _hashed(key), value)


def _hashed(key: str) -> str:
    return hashlib.sha256(key.encode()).hexdigest()


def revoke() -> None:
    """Stop trusting the store as it is: its key is deleted (here and on disk), so no entry
    written until now is read again; the next grading that uses the store makes a new key.

    Called around every worker that could read or write the grader's files (the
    ``process-group`` level): what it saw of the key, or wrote, is worth nothing.
    """
    root = location()
    with _keys_lock:
        _keys.clear()
        _folder_for.cache_clear()  # its folders are checked again too: the worker could have swapped them
        if root is None:
            return
        try:
            os.unlink(root / _KEY_FILE)
        except (FileNotFoundError, NotADirectoryError):
            pass
        except OSError as exc:  # a store the worker cannot write either (read-only): nothing to undo
            logging.getLogger("autograder").warning("the store's key %s was not deleted: %s", root / _KEY_FILE, exc)


# ------------------------------------------------------------------ keys
@functools.lru_cache(maxsize=None)
def _code_version(name: str, sources: tuple[Path, ...], libraries: tuple[str, ...] = ()) -> str:
    """What a stored result of ``name`` depends on besides its arguments."""
    import cv2
    from importlib import metadata

    digest = hashlib.sha256(name.encode())
    for source in sources:
        digest.update(source.read_bytes())
    digest.update(f"{sys.version}|{np.__version__}|{cv2.__version__}".encode())
    for library in libraries:
        try:
            digest.update(f"|{library} {metadata.version(library)}".encode())
        except metadata.PackageNotFoundError:
            digest.update(f"|{library} missing".encode())
    return digest.hexdigest()[:24]


def _key(name: str, args, kwargs) -> str:
    digest = hashlib.sha256(name.encode())
    _digest(("args", args, "kwargs", sorted(kwargs.items())), digest)
    return digest.hexdigest()


def _digest(value, digest) -> None:
    """Feed ``value`` into ``digest`` unambiguously; TypeError for what cannot be digested."""
    t = type(value)
    if value is None or t in (bool, int, float, complex, str):
        digest.update(f"{t.__name__}:{value!r};".encode())
    elif t is np.ndarray:
        if value.dtype.kind not in "biufc":
            raise TypeError(f"cannot digest an array of dtype {value.dtype}")
        digest.update(f"ndarray:{value.dtype.str}:{value.shape};".encode())
        digest.update(np.ascontiguousarray(value).data)
    elif isinstance(value, np.generic):
        _digest(np.asarray(value), digest)
    elif t in (tuple, list):
        digest.update(f"{t.__name__}:{len(value)}(".encode())
        for item in value:
            _digest(item, digest)
        digest.update(b")")
    elif dataclasses.is_dataclass(value) and not isinstance(value, type):
        digest.update(f"{t.__module__}.{t.__qualname__}(".encode())
        for field in dataclasses.fields(value):
            digest.update(f"{field.name}=".encode())
            _digest(getattr(value, field.name), digest)
        digest.update(b")")
    else:
        raise TypeError(f"cannot digest a {t.__qualname__}")


# ------------------------------------------------------------------ files
def _private_folder(path: Path) -> bool:
    """Create ``path`` (mode 700) if needed; True if it is a real folder of ours no one else may write."""
    try:
        path.mkdir(mode=0o700, parents=True, exist_ok=True)
        info = os.lstat(path)
    except OSError:
        return False
    return (stat.S_ISDIR(info.st_mode) and info.st_uid == os.geteuid()
            and not info.st_mode & (stat.S_IWGRP | stat.S_IWOTH))


@functools.lru_cache(maxsize=None)
def _folder_for(root: Path, name: str, version: str) -> Path | None:
    top, folder = root / name, root / name / version
    if not (_private_folder(root) and _private_folder(top) and _private_folder(folder)):
        return None
    return folder


def _key_of(root: Path) -> bytes | None:
    """The store's key: ``root/key``, made now if there is none or it is not a private
    file of ours of the right size; None if none can be made (then nothing is stored)."""
    with _keys_lock:
        if root not in _keys:
            key = _read_key(root / _KEY_FILE)
            if key is None:
                with contextlib.suppress(OSError):
                    os.unlink(root / _KEY_FILE)  # not one we made: replaced
                key = _make_key(root)
            if key is None:
                return None
            _keys[root] = key
        return _keys[root]


def _read_key(path: Path) -> bytes | None:
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW)
    except OSError:
        return None
    with os.fdopen(fd, "rb") as file:
        info = os.fstat(file.fileno())
        if (not stat.S_ISREG(info.st_mode) or info.st_uid != os.geteuid()
                or info.st_mode & (stat.S_IRWXG | stat.S_IRWXO) or info.st_size != _KEY_BYTES):
            return None
        key = file.read(_KEY_BYTES + 1)
    return key if len(key) == _KEY_BYTES else None


def _make_key(root: Path) -> bytes | None:
    """A new key, written whole before it appears under its name (another process making
    one at the same moment wins or loses as a whole: then its key is read)."""
    try:
        with tempfile.NamedTemporaryFile(dir=root, prefix=".key-", delete=False) as file:
            os.fchmod(file.fileno(), 0o600)
            file.write(secrets.token_bytes(_KEY_BYTES))
        try:
            os.link(file.name, root / _KEY_FILE)
        finally:
            os.unlink(file.name)
    except FileExistsError:
        pass
    except OSError as exc:
        logging.getLogger("autograder").debug("no store key: %s", exc)
        return None
    return _read_key(root / _KEY_FILE)


def _mac(key: bytes, folder: Path, entry: str, frame: bytes) -> bytes:
    """The entry's MAC: its frame and its place (an entry moved to another name fails)."""
    place = f"{folder.parent.name}/{folder.name}/{entry}\0".encode()
    return hmac.new(key, place + frame, hashlib.sha256).digest()


def _folder(name: str, version: str) -> Path | None:
    root = location()
    if root is None:
        return None
    return _folder_for(root, name, version)


def _read(folder: Path, key: str):
    secret = _key_of(folder.parents[1])
    if secret is None:
        return None
    try:
        fd = os.open(folder / key, os.O_RDONLY | os.O_NOFOLLOW)
    except OSError:
        return None
    try:
        with os.fdopen(fd, "rb") as file:
            info = os.fstat(file.fileno())
            if (not stat.S_ISREG(info.st_mode) or info.st_uid != os.geteuid()
                    or info.st_size > _MAX_ENTRY_BYTES + 32):
                return None
            data = file.read()
        mac, frame = data[:32], data[32:]
        if not hmac.compare_digest(_mac(secret, folder, key, frame), mac):
            return None
        return transport.decode(frame, max_bytes=_MAX_ENTRY_BYTES)
    except (OSError, transport.TransportError):
        return None


def _write(folder: Path, key: str, value) -> None:
    secret = _key_of(folder.parents[1])
    if secret is None:
        return
    try:
        frame = transport.encode(value, max_bytes=_MAX_ENTRY_BYTES)
    except transport.TransportError:
        return  # not plain data: computed every time
    try:
        _remove_other_versions(folder)
        with tempfile.NamedTemporaryFile(dir=folder, prefix=".tmp-", delete=False) as file:
            file.write(_mac(secret, folder, key, frame) + frame)
        os.replace(file.name, folder / key)
    except OSError as exc:
        logging.getLogger("autograder").debug("cache not written: %s", exc)
        with contextlib.suppress(OSError, NameError):
            os.unlink(file.name)


@functools.lru_cache(maxsize=None)
def _remove_other_versions(folder: Path) -> None:
    """Results of older code are never read again: delete them (once per process)."""
    for sibling in folder.parent.iterdir():
        if sibling != folder and sibling.is_dir() and not sibling.is_symlink():
            shutil.rmtree(sibling, ignore_errors=True)
