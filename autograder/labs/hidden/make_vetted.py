"""Measure which drawn scenes of the hidden checks correct pipelines get full marks on; write ``_vetted.py``.

A hidden check that draws a whole scene (a panorama's views, each placed and tilted at random) can draw one
where a correct pipeline is itself at the edge of the judge's bounds: its homographies, chained, put a far
image's corners a few pixels off. Measured on 200 submissions' draws, the reference solution lost the points
of ``stitch_many``'s hidden checks on about one in seventy. The checks listed here draw their scene from the
scenes kept by this script (:func:`._draws.vetted`): those on which the reference and the lab sheet's recipe
(``cv2.findHomography`` with RANSAC in place of the reference's own) both get full marks.

    python -m autograder.labs.hidden.make_vetted [candidates per check]   # rewrites _vetted.py

Re-run it whenever these checks, their scenes (``fixtures/``) or the reference solutions change;
``tests/test_hidden_inputs.py`` grades the reference on a sample of the kept scenes.
"""

from __future__ import annotations

import shutil
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
REFERENCE = ROOT / "reference_solutions"
CHECKS = ("lab08.ext2::hidden_many", "lab08.ext2::hidden_many_five")
# The lab sheet's recipe in the reference's place: OpenCV's RANSAC (other samples, its own refit).
RECIPES = {"lab08_homographies.py": ("H, _ = homography_ransac(pts_mov, pts_ref, threshold=3.0, seed=0)",
                                     "H, _ = cv2.findHomography(pts_mov, pts_ref, cv2.RANSAC, 3.0)")}


def recipe_folder(into: Path) -> Path:
    """The reference solutions with :data:`RECIPES`' lines written as the sheet's recipe."""
    shutil.copytree(REFERENCE, into, dirs_exist_ok=True)
    for name, (line, recipe) in RECIPES.items():
        text = (into / name).read_text()
        if text.count(line) != 1:
            raise SystemExit(f"{name}: {line!r} is not one line of the reference: update RECIPES")
        (into / name).write_text(text.replace(line, recipe))
    return into


def full_marks(folder: Path, check, scene: int) -> bool:
    """Whether ``check`` gives full marks to the modules of ``folder`` on the vetted scene ``scene``."""
    from autograder.engine.inputs import Inputs
    from autograder.engine.runner import run_check
    from autograder.sandbox.supervisor import Sandbox

    from . import _vetted

    _vetted.VETTED[check.id] = (scene,)
    with Sandbox(folder) as sandbox:
        result = run_check(sandbox, check, "none", inputs=Inputs.for_submission("0" * 64, secret="vetting"))
    return result.score >= result.max_score


def main(candidates: int = 320) -> None:
    from autograder.engine.registry import discover

    checks = {c.id: c for lab in discover().values() for e in lab.exercises.values() for c in e.checks}
    kept: dict[str, tuple[int, ...]] = {}
    with tempfile.TemporaryDirectory() as scratch:
        recipe = recipe_folder(Path(scratch) / "recipe")
        for key in CHECKS:
            good = tuple(scene for scene in range(1, candidates + 1)
                         if full_marks(REFERENCE, checks[key], scene) and full_marks(recipe, checks[key], scene))
            print(f"{key}: {len(good)} of {candidates} scenes kept", flush=True)
            kept[key] = good
    lines = [f'    "{key}": (\n' + "".join(f"        {', '.join(map(str, scenes[i:i + 16]))},\n"
                                        for i in range(0, len(scenes), 16)) + "    ),\n"
             for key, scenes in kept.items()]
    head = Path(__file__).with_name("_vetted.py").read_text().split("VETTED")[0]
    Path(__file__).with_name("_vetted.py").write_text(head + "VETTED: dict[str, tuple[int, ...]] = {\n"
                                                      + "".join(lines) + "}\n")


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:2]))
