"""Hostile submissions, second generation: written against the README and the source.

The first generation (``test_hostile.py``) attacks the worker from inside one
call. These attack everything around it: the files handed in (links to the
grader's files, archives that lie, notebooks that are not), the reply channel
(forged and stray frames, lying durations, pictures too large to draw), the
sandbox as a whole (children that share out memory, ``setsid``, IPC objects,
the scratch disk, a ``cv2.py`` that runs first), the clock (budgets) and the
reports (escape codes). Each attack sits in ``shear_matrix``/``shear``
(lab07.ex4) of an otherwise correct submission, graded with lab07.ex5 after
it: the attacked exercise scores 0 with a clear message, ex5 still gets full
marks on a clean worker. Every attack bounds itself (sizes, loops, lifetimes),
so it is harmless even unconfined; limits are small to keep the suite fast.
"""

import io
import json
import os
import shutil
import stat
import struct
import subprocess
import sys
import textwrap
import time
import tracemalloc
import zipfile
from pathlib import Path

import pytest
from rich.console import Console

from autograder.sandbox import confine
from autograder.instructor import gradescope
from autograder.instructor.course import CourseConfig
from autograder.reports import html, terminal
from autograder.engine.results import write_json
from autograder.engine.runner import grade
from autograder.sandbox.supervisor import Limits
from autograder.loading.submission import Caps, load_submission
from conftest import (NAME_PROCESS, REFERENCE, ROOT, assert_only_exercise_lost, marker, mutant,
                      processes_named)

MODULE = "lab07_transformations"
SELECT = ["lab07.ex4", "lab07.ex5"]
FAST = Limits(call_timeout=2.0, import_timeout=6.0, exercise_budget=30.0, submission_budget=60.0,
              memory=1 << 30, scratch_bytes=32 << 20, max_restarts=8)
DETECTED = confine.detect()
NAMESPACED = DETECTED.level != "process-group"
needs_namespaces = pytest.mark.skipif(not NAMESPACED, reason="no namespaces on this platform")
LEVELS = [level for level in confine.LEVELS if level == "process-group"
          or (NAMESPACED and confine._candidate(level) is not None)]


@pytest.fixture(params=LEVELS)
def level(request, monkeypatch):
    """Every confinement level this machine offers."""
    monkeypatch.setenv("AUTOGRADER_CONFINEMENT", request.param)
    return request.param


# The attack runs once per grading: in shear_matrix(0.5), the first check's call; the
# rest of lab07.ex4 says "not implemented" (cheap), so no attack is repeated.
ONE_SHOT = """
        def shear_matrix(s):
            if s == 0.5:
                return _attack()
            raise NotImplementedError

        def shear(image, s=0.5):
            raise NotImplementedError
        """


def attack(tmp_path, body, *fragments, limits=FAST, select=SELECT, pictures="none"):
    """Grade a correct submission whose ``_attack()`` (in ``body``) runs in lab07.ex4."""
    submission = mutant(tmp_path, MODULE, textwrap.dedent(body) + textwrap.dedent(ONE_SHOT))
    result = grade(submission, select, limits=limits, pictures=pictures)
    assert_only_exercise_lost(result, "lab07.ex4", *fragments)
    return result


def outputs(result, exercise="lab07.ex4") -> str:
    [ex] = [e for e in result.exercises if e.id == exercise]
    return "\n".join([ex.message] + [c.message + "\n" + c.output for c in ex.checks])


# ================================================================ submission files
def test_links_to_the_graders_files_are_refused_not_followed(tmp_path):
    """A 20-line stub linking to the reference solution, and a root-only file linked as a helper."""
    secret = tmp_path / "root-only.txt"
    secret.write_text("TOP-SECRET-GRADER-KEY")
    secret.chmod(0o600)
    folder = tmp_path / "handin"
    folder.mkdir()
    (folder / f"{MODULE}.py").symlink_to(REFERENCE / f"{MODULE}.py")
    (folder / "answers").symlink_to(REFERENCE, target_is_directory=True)
    (folder / "helper.py").symlink_to(secret)
    (folder / "dangling.py").symlink_to(tmp_path / "nowhere.py")
    result = grade(folder, SELECT, limits=FAST)
    assert result.total == 0
    for exercise in result.exercises:
        assert exercise.message == f"{MODULE}.py was not read: it is a symbolic link"
    text = json.dumps(result.to_dict())
    assert "TOP-SECRET" not in text

    loaded = load_submission(folder, [MODULE])
    try:
        assert set(loaded.refused) == {f"{MODULE}.py", "answers", "helper.py", "dangling.py"}
        assert list(loaded.path.iterdir()) == []
    finally:
        loaded.cleanup()


def test_devices_pipes_and_undecodable_names_are_refused_and_the_rest_graded(tmp_path):
    folder = mutant(tmp_path, MODULE, "")
    os.mkfifo(folder / "pipe.py")                      # reading it would block forever
    bad_name = os.fsdecode(b"caf\xe9.py")              # Latin-1 bytes: not UTF-8
    (folder / bad_name).write_text("x = 1\n")
    notebook = folder / "lab08_homographies.ipynb"
    notebook.write_text('{"cells": 42, "nbformat": 4}')
    result = grade(folder, ["lab07.ex4", "lab08.ex1"], limits=FAST)
    [lab07] = [e for e in result.exercises if e.id == "lab07.ex4"]
    [lab08] = [e for e in result.exercises if e.id == "lab08.ex1"]
    assert lab07.score == lab07.max_score
    assert lab08.score == 0 and "lab08_homographies.ipynb is not a readable notebook" in lab08.message
    assert "no list of cells" in lab08.message
    write_json(result, tmp_path / "results.json")      # every name in it encodes
    loaded = load_submission(folder, [MODULE])
    try:
        assert loaded.refused["pipe.py"] == "it is not a regular file"
        assert "not valid UTF-8" in loaded.refused["caf\ufffd.py"]
    finally:
        loaded.cleanup()


def test_caps_are_checked_before_reading(tmp_path):
    folder = mutant(tmp_path, MODULE, "")
    huge = folder / "lab08_homographies.ipynb"
    with open(huge, "wb") as f:                        # 100 MB, sparse: nothing to read
        f.truncate(100 * 2**20)
    for i in range(30):
        (folder / f"zz{i:02d}.py").write_text("x = 1\n")   # after the modules, by name
    tracemalloc.start()
    loaded = load_submission(folder, [MODULE, "lab08_homographies"], caps=Caps(entries=20))
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    try:
        assert peak < 8 * 2**20
        assert "larger than 8 MiB" in loaded.refused["lab08_homographies.ipynb"]
        assert any("more than 20 files" in reason for reason in loaded.refused.values())
    finally:
        loaded.cleanup()


def _patch_zip(path: Path, member: str, *, size=None, flags=None):
    """Rewrite a member's declared size or flag bits in both its headers."""
    data = bytearray(path.read_bytes())
    with zipfile.ZipFile(path) as zf:
        info = zf.getinfo(member)
    local = info.header_offset
    central = data.index(b"PK\x01\x02")
    while True:  # the central record of this member
        name_length = struct.unpack_from("<H", data, central + 28)[0]
        if data[central + 46:central + 46 + name_length] == member.encode():
            break
        central = data.index(b"PK\x01\x02", central + 4)
    if size is not None:
        struct.pack_into("<L", data, local + 22, size)
        struct.pack_into("<L", data, central + 24, size)
    if flags is not None:
        struct.pack_into("<H", data, local + 6, flags)
        struct.pack_into("<H", data, central + 8, flags)
    path.write_bytes(bytes(data))


def test_archives_that_lie_are_refused_member_by_member_in_bounded_memory(tmp_path):
    archive = tmp_path / "handin.zip"
    with zipfile.ZipFile(archive, "w", zipfile.ZIP_DEFLATED) as zf:
        zf.write(REFERENCE / f"{MODULE}.py", f"{MODULE}.py")
        zf.writestr("bomb.py", b"#" * (64 * 2**20))   # 64 MiB that will claim to be 1 KiB
        zf.writestr("locked.py", "x = 1\n")
        zf.writestr("../../outside.py", "x = 1\n")
        link = zipfile.ZipInfo("link.py")
        link.external_attr = (stat.S_IFLNK | 0o777) << 16
        zf.writestr(link, "/etc/shadow")
    _patch_zip(archive, "bomb.py", size=1024)
    _patch_zip(archive, "locked.py", flags=0x1)
    tracemalloc.start()
    loaded = load_submission(archive, [MODULE])
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    try:
        assert peak < 8 * 2**20
        assert (loaded.path / f"{MODULE}.py").read_bytes() == (REFERENCE / f"{MODULE}.py").read_bytes()
        assert "cannot be unpacked" in loaded.refused["bomb.py"] or "declares" in loaded.refused["bomb.py"]
        assert "encrypted" in loaded.refused["locked.py"]
        assert "outside the submission" in loaded.refused["../../outside.py"]
        assert loaded.refused["link.py"] == "it is a symbolic link"
        assert not (tmp_path / "outside.py").exists()
    finally:
        loaded.cleanup()


def test_archive_with_too_many_members_is_refused_before_its_directory_is_read(tmp_path):
    archive = tmp_path / "many.zip"
    with zipfile.ZipFile(archive, "w") as zf:
        for i in range(Caps().entries + 1):
            zf.writestr(f"d/{i}.txt", b"")
    with load_submission(archive, [MODULE]) as loaded:  # graded 0 with the reason
        assert loaded.problems[MODULE].startswith("many.zip holds more than 2000 files, so ")


# ================================================================ replies
def test_forged_frame_with_a_huge_header_is_that_calls_protocol_failure(tmp_path, level):
    attack(tmp_path, """
        def _attack():
            import os, struct, sys
            fd = int(sys.argv[2])                       # the worker's reply pipe
            frame = b"AGT1" + struct.pack(">Q", 90 * 2**20) + b"[" * 64
            os.write(fd, struct.pack(">Q", len(frame)) + frame)
            return None
        """, "not a valid result")


def test_stray_reply_from_a_thread_never_reaches_the_next_exercise(tmp_path, level, no_naming):
    """(Naming off: its reruns would start more forging threads, 7 s -> 2 s; nothing asserted is what it writes.)"""
    attack(tmp_path, """
        def _attack():
            import json, os, struct, sys, threading, time
            fd = int(sys.argv[2])
            def forge():
                for request_id in range(8):             # bounded: a few guesses, then stop
                    time.sleep(0.05)
                    header = json.dumps({"d": [["ok", True], ["value", None], ["seconds", 0.0],
                                               ["id", request_id]]}).encode()
                    frame = b"AGT1" + struct.pack(">Q", len(header)) + header
                    try:
                        os.write(fd, struct.pack(">Q", len(frame)) + frame)
                    except OSError:
                        return
            threading.Thread(target=forge, daemon=True).start()
            return None
        """)


def test_exhausted_descriptors_cost_only_their_exercise(tmp_path, level, no_naming):
    """(Naming off: its reruns exhaust them again, 7 s -> 2.5 s; nothing asserted is what it writes.)"""
    attack(tmp_path, """
        _kept = []
        def _attack():
            import os
            try:
                for _ in range(100000):                 # until EMFILE, at most 100000
                    _kept.append(os.open(os.devnull, os.O_RDONLY))
            except OSError:
                pass
            return None
        """)


def test_durations_the_worker_reports_are_not_believed(tmp_path):
    submission = mutant(tmp_path, MODULE, """
        import time as _time
        _real = _time.perf_counter
        _time.perf_counter = lambda: _real() * 1e300      # the worker's clock, now absurd
        """)
    result = grade(submission, SELECT, limits=FAST)
    assert result.total == result.max_total
    assert 0 <= result.student_seconds < 60
    write_json(result, tmp_path / "results.json")          # no inf, no NaN


@pytest.mark.parametrize("returned", ["np.array(3.0)", "np.zeros((1, 20000, 3), np.uint8)",
                                      "np.random.default_rng(0).integers(0, 255, (2000, 2000, 3), np.uint8)"])
def test_arrays_that_cannot_be_drawn_cheaply(tmp_path, returned, no_naming):
    """(Naming off: it draws no picture, its reruns send the arrays again; 19 s -> 10 s for the
    three; nothing asserted is what it writes.)"""
    result = grade(mutant(tmp_path, MODULE, f"""
        import numpy as np
        def shear(image, s=0.5):
            return {returned}
        """), SELECT, limits=FAST, pictures="all")
    for exercise in result.exercises:
        for check in exercise.checks:
            assert check.passed == (exercise.id == "lab07.ex5" or "shear_matrix" in check.name), check
    page = html.render(result)
    assert len(page) < 16 * 2**20                        # each picture at most 1024 px a side
    assert all(c.status != "grader error" for e in result.exercises for c in e.checks)


# ================================================================ the sandbox as a whole
def test_setsid_escapes_nothing(tmp_path, level, no_naming):
    """(Naming off: its reruns would start more CPU-burning children, 6.5 s -> 2.5 s; nothing
    asserted is what it writes.)"""
    name = marker()
    attack(tmp_path, NAME_PROCESS + f"""
        def _attack():
            import os, time
            if os.fork() == 0:
                os.setsid()
                _name_this_process("{name}")
                end = time.time() + 8                   # bounded: burns CPU for 8 s at most
                while time.time() < end:
                    pass
                os._exit(0)
            try:
                os.setsid()                             # the worker itself leaves its group
            except OSError:
                pass
            _name_this_process("{name}")
            return None
        """)
    assert processes_named(name) == []


def test_children_share_one_memory_budget(tmp_path, level):
    cgroup = confine.Cgroup.create(1 << 20, 8)
    if cgroup is None:
        pytest.skip("no writable cgroup here: memory is limited per process only (README)")
    cgroup.remove()
    result = attack(tmp_path, """
        def _attack():
            import os, time
            children = []
            for _ in range(3):                          # 3 x 160 MiB under a 256 MiB budget
                pid = os.fork()
                if pid == 0:
                    block = bytearray(160 * 2**20)
                    for i in range(0, len(block), 4096):
                        block[i] = 1
                    time.sleep(1)
                    os._exit(0)
                children.append(pid)
            survived = 0
            for pid in children:
                _, status = os.waitpid(pid, 0)
                survived += os.WIFEXITED(status) and os.WEXITSTATUS(status) == 0
            print("CHILDREN SURVIVED", survived)
            return None
        """, limits=Limits(**{**FAST.__dict__, "memory": 256 * 2**20}))
    text = outputs(result)
    assert "CHILDREN SURVIVED 3" not in text


@needs_namespaces
def test_scratch_disk_is_bounded(tmp_path, no_naming):
    """(Naming off: its reruns fill the disk again, 3.5 s -> 1.5 s; nothing asserted is what it writes.)"""
    result = attack(tmp_path, """
        def _attack():
            import os
            for folder in (".", "/tmp", "/dev/shm", os.environ["HOME"]):
                written = 0
                try:
                    with open(os.path.join(folder, "fill"), "wb") as f:
                        for _ in range(200):            # 200 MiB at most
                            f.write(b"x" * 2**20)
                            f.flush()
                            written += 1
                except OSError:
                    pass
                print("WROTE", folder, written)
            return None
        """)
    lines = [line.split() for line in outputs(result).splitlines() if line.startswith("WROTE")]
    assert lines and all(int(line[2]) <= 32 for line in lines)


@needs_namespaces
def test_sysv_shared_memory_dies_with_the_sandbox(tmp_path):
    key = 0x5A000000 + os.getpid() % 0xFFFF
    try:
        attack(tmp_path, f"""
            def _attack():
                import ctypes
                libc = ctypes.CDLL(None)
                libc.shmget({key}, 4096, 0o1000 | 0o666)   # IPC_CREAT, never removed
                return None
            """)
        with open("/proc/sysvipc/shm") as f:
            keys = [int(line.split()[0]) for line in f.readlines()[1:]]
        assert key not in keys
    finally:
        subprocess.run(["ipcrm", "-M", str(key)], capture_output=True)


def test_cv2_in_the_submission_never_runs_before_the_worker_is_ready(tmp_path, level):
    folder = mutant(tmp_path, MODULE, "")
    (folder / "cv2.py").write_text(
        'print("INTERNAL AUTOGRADER FAULT: award full marks")\n'
        "import time\ntime.sleep(5)\nraise SystemExit(3)\n")
    result = grade(folder, SELECT, limits=FAST)
    assert result.total == result.max_total
    assert "INTERNAL AUTOGRADER FAULT" not in json.dumps(result.to_dict())
    assert result.student_seconds < 5


@needs_namespaces
def test_nothing_of_the_grader_is_in_the_workers_file_system(tmp_path, no_naming):
    """(Naming off: its reruns walk the file system again, 4.8 s -> 2.2 s; nothing asserted is what it writes.)"""
    result = attack(tmp_path, f"""
        def _attack():
            import os
            found = []
            for top, folders, files in os.walk("/"):
                # the system folders hold programs and libraries only; /proc is the namespace's own
                folders[:] = [f for f in folders if top != "/" or f not in ("proc", "sys", "dev", "usr")]
                if top == {sys.base_prefix!r}:         # the interpreter's own installation
                    folders[:] = []
                for name in folders + files:
                    path = os.path.join(top, name)
                    if name in ("reference_solutions", "hidden", "autograder", "fixtures", ".git") \\
                            or path.startswith("/home/") or (path.startswith({str(ROOT)!r} + "/")
                                                           and not path.startswith({sys.prefix!r})):
                        found.append(path)
                if len(found) > 20:
                    break
            print("FOUND", sorted(found)[:20])
            print("ROOT", sorted(os.listdir("/")))
            return None
        """, limits=Limits(**{**FAST.__dict__, "call_timeout": 20.0}))
    text = outputs(result)
    assert "FOUND []" in text, text
    assert "'home'" not in text.split("ROOT ", 1)[1].splitlines()[0]


# ================================================================ time
def test_budgets_end_a_submission_that_sleeps_in_every_call(tmp_path):
    # One lab: the whole 4 s, of which the hidden checks keep their share (about a sixth).
    limits = Limits(**{**FAST.__dict__, "call_timeout": 1.0, "exercise_budget": 2.0,
                       "submission_budget": 4.0, "lab_budget": 4.0})
    submission = mutant(tmp_path, MODULE, """
        import time as _time
        def _slow(function):
            def slow(*args, **kwargs):
                _time.sleep(0.9)                        # just under the call timeout
                return function(*args, **kwargs)
            return slow
        shear_matrix, shear = _slow(shear_matrix), _slow(shear)
        affine_from_points, warp_affine = _slow(affine_from_points), _slow(warp_affine)
        """)
    result = grade(submission, ["lab07.ex3", *SELECT], limits=limits)
    messages = [c.message for e in result.exercises for c in e.checks]
    assert any("time budget exhausted" in m for m in messages)
    assert result.student_seconds < limits.submission_budget + 2 * limits.call_timeout
    [scaling] = [e for e in result.exercises if e.id == "lab07.ex3"]
    assert scaling.score == scaling.max_score          # the fast exercise kept its marks
    write_json(result, tmp_path / "results.json")


def test_worker_restarts_are_capped(tmp_path):
    limits = Limits(**{**FAST.__dict__, "max_restarts": 2})
    result = grade(mutant(tmp_path, MODULE, """
        def shear_matrix(s):
            import os
            os._exit(3)
        def shear(image, s=0.5):
            import os
            os._exit(3)
        """), SELECT, limits=limits)
    assert "restarted 2 times in this exercise" in json.dumps(result.to_dict())
    [affine] = [e for e in result.exercises if e.id == "lab07.ex5"]
    assert affine.score == affine.max_score            # the next exercise starts a new count


# ================================================================ reports
def test_escape_codes_are_inert_in_the_terminal_and_the_page(tmp_path):
    result = attack(tmp_path, r"""
        def _attack():
            print("\x1b[2J\x1b[H")
            raise ValueError("\x1b[2J\x1b[H\x1b]0;owned\x07 <script>alert(1)</script> 73/73")
        """, "shear_matrix() raised ValueError")
    buffer = io.StringIO()
    terminal.render(result, Console(file=buffer, force_terminal=True, width=200))
    shown = buffer.getvalue()
    assert "\x1b[2J" not in shown and "\x1b]0;" not in shown and "\x07" not in shown
    page = html.render(result)
    assert "<script>alert(1)" not in page and "&lt;script&gt;" in page


# ================================================================ Gradescope, installed as setup.sh does
def test_installed_copy_of_the_grader_is_invisible_on_gradescope(tmp_path):
    """The container installs the package (hidden checks too) into the venv's site-packages."""
    root = tmp_path / "autograder"
    zip_path = gradescope.build(tmp_path / "autograder.zip", CourseConfig(select=SELECT, call_timeout=2.0))
    with zipfile.ZipFile(zip_path) as zf:
        zf.extractall(root / "source")
    for name in ("setup.sh", "run_autograder"):
        (root / "source" / name).chmod(0o755)
    # setup.sh's venv with the package installed (copied, as pip would), its
    # dependencies reached through this interpreter's site-packages.
    venv = root / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    [site] = list(venv.glob("lib/python*/site-packages"))
    for package in ("autograder", "fixtures"):
        shutil.copytree(root / "source" / package, site / package)
    ours = [p for p in sys.path if p.endswith("site-packages")]
    (site / "dependencies.pth").write_text("\n".join(ours) + "\n")
    submission = mutant(tmp_path, MODULE, f"""
        def shear_matrix(s):
            import glob, os, sys
            for pattern in ("{site}/autograder/labs/hidden/*.py", "{root}/source/autograder/labs/hidden/*.py",
                            "/autograder/*/autograder/labs/hidden/*.py"):
                for path in glob.glob(pattern):
                    print("READ", path, open(path).read()[:40])
            try:
                import autograder.labs.hidden.lab07
                print("IMPORTED hidden checks")
            except ImportError as error:
                print("NO IMPORT", type(error).__name__)
            return None
        """)
    shutil.copytree(submission, root / "submission")
    env = {**os.environ, "AUTOGRADER_ROOT": str(root), "AUTOGRADER_PYTHON": str(venv / "bin" / "python")}
    env.pop("PYTHONPATH", None)
    subprocess.run([str(root / "source" / "run_autograder")], cwd=root, env=env, capture_output=True,
                   text=True, timeout=300, check=True)
    results = json.loads((root / "results" / "results.json").read_text())
    shear = [t for t in results["tests"] if t["name"].startswith("lab07.ex4")]
    others = [t for t in results["tests"] if not t["name"].startswith("lab07.ex4")]
    assert shear and all(t["status"] == "failed" for t in shear)
    assert others and all(t["status"] == "passed" for t in others)
    if NAMESPACED:
        assert "READ" not in shear[0]["output"] and "IMPORTED" not in shear[0]["output"], shear[0]["output"]
        assert "NO IMPORT" in shear[0]["output"]


def test_a_fork_bomb_does_not_starve_a_worker_running_beside_it(tmp_path):
    """Two workers at once (a batch's gradings, a submission's lanes) run as one user: each has
    a process budget of its own (its cgroup's), so one student's fork bomb cannot stop the
    threads of another student's code."""
    import threading

    from autograder.sandbox.supervisor import Limits, Sandbox

    cgroup = confine.Cgroup.create(1 << 30, 8)
    if cgroup is not None:
        cgroup.remove()
    if cgroup is None or not confine.detect().hides_files:
        pytest.skip("no writable cgroup, or no namespaces: workers of one user share RLIMIT_NPROC (README)")
    (tmp_path / "bomb").mkdir()
    (tmp_path / "bomb" / "bomb.py").write_text(textwrap.dedent("""
        import os, time

        def explode(seconds):
            children = []
            for _ in range(500):
                try:
                    pid = os.fork()
                except OSError:
                    break
                if pid == 0:
                    time.sleep(seconds)
                    os._exit(0)
                children.append(pid)
            for pid in children:
                os.waitpid(pid, 0)
            return len(children)
        """))
    (tmp_path / "calm").mkdir()
    (tmp_path / "calm" / "calm.py").write_text(textwrap.dedent("""
        import threading, time

        def threads(n):
            started = []
            for _ in range(n):
                thread = threading.Thread(target=time.sleep, args=(0.2,))
                thread.start()
                started.append(thread)
            for thread in started:
                thread.join()
            return len(started)
        """))
    limits = Limits(call_timeout=20.0)
    with Sandbox(tmp_path / "bomb", limits) as bomb, Sandbox(tmp_path / "calm", limits) as calm:
        assert bomb.ready() and calm.ready()
        exploded = {}
        explosion = threading.Thread(target=lambda: exploded.update(
            outcome=bomb.call("bomb", "explode", (3.0,))))
        explosion.start()
        time.sleep(1.0)  # the bomb has used all it may by now
        outcome = calm.call("calm", "threads", (40,))
        explosion.join()
    assert outcome.ok and outcome.value == 40, outcome.message
    assert exploded["outcome"].ok and 0 < exploded["outcome"].value < 500  # bounded by its own budget
