"""Every legitimate dynamic-programming stereo of the blind rounds, graded on lab 12's ex5.

The whole lab 12 modules of ``benchmarks/blind_legit/*/C/v*/`` and the lone ``dp_stereo`` files of this
folder (spliced into the reference module, as a student's file would hold them) are graded on ``lab12.ex5``
in a fresh process each; the line printed per file is its score and what the weak-texture check said
(its bad-pixel rate beside the reference's and block matching's). A benchmark: it prints figures.

    python benchmarks/blind_legit/2026-12-06o-dp/grade_weak_texture.py
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
sys.path.insert(0, str(ROOT))

from autograder.instructor.verify import with_mutation  # noqa: E402


def submission(path: Path, folder: Path) -> None:
    """``folder`` made a submission holding ``path``'s lab 12 (a whole module, or a dp_stereo spliced in)."""
    if path.name == "dp_stereo.py":
        reference = (ROOT / "reference_solutions" / "lab12_stereo.py").read_text()
        (folder / "lab12_stereo.py").write_text(with_mutation(reference, path.read_text()))
    else:
        for module in path.parent.glob("*.py"):   # (a lab 12 file may import the author's lab 11)
            (folder / module.name).write_text(module.read_text())


def main() -> None:
    files = sorted(HERE.parent.glob("*/C/v*/lab12_stereo.py")) + sorted(HERE.glob("*/v*/dp_stereo.py"))
    for path in files:
        with tempfile.TemporaryDirectory() as tmp:
            folder = Path(tmp)
            submission(path, folder)
            out = folder / "result.json"
            subprocess.run([sys.executable, str(ROOT / "grade.py"), "lab12.ex5", "--submission", str(folder),
                            "--json", str(out), "--no-html", "--quiet"], capture_output=True, cwd=ROOT)
            exercise = json.loads(out.read_text())["exercises"][0]
        weak = [c for c in exercise["checks"] if "weak" in c["name"]]
        said = "; ".join(f"{c['score']:g}/{c['max_score']:g} {c['message'].splitlines()[0][:110]}" for c in weak)
        print(f"{str(path.relative_to(HERE.parent)):40s} {exercise['score']:5.1f}/{exercise['max_score']:g}  {said}",
              flush=True)


if __name__ == "__main__":
    main()
