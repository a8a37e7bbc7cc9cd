"""Which image functions lose points when their answer breaks the API's form rule.

The API: "a function that takes an image returns the same dtype and channel count unless
stated otherwise". For every function of the six labs that takes an image and returns one,
the reference is graded four times, its image answer (the first element of a tuple answer)
converted after the call: a grey input's answer made BGR, a BGR input's answer made grey,
the answer as float64, and as float32 divided by 255. Each line prints the points kept in
the exercises that grade the function and the checks that took points, with their first
line, so a reader sees which conversions no check holds and whether the cause is named
("the channels are not kept ...").

    python benchmarks/channel_rules.py [lab07 ...]

Where the contract narrows the rule (draw_points and project_onto_image take BGR only,
stitch takes BGR images, block_matching returns a float disparity), a full score for the
conversion it rules out is no gap.

Measured 2026-11-28 (OpenCV 5.0), after the fixes: every float answer and every grey answer
for a BGR input loses points, named "the channels are not kept" where the shape is an image's
of the asked size; a BGR answer for a grey input keeps full marks only in lab 7's scale and
warp_affine and lab 8's warp_to_reference (no check gives them a grey image: left, as no
realistic code converts there), lab 8's stitch and stitch_many and lab 9's drawings (BGR
only by the contract). Before: 14 of the 60 gradings ended in a grader error (a difference
map of two channel counts, lab 10's undistort_image among them); lab 11's draw_epipolar_lines
kept full marks for BGR from grey, lab 10's undistort_image and lab 12's rectify for grey
from BGR (each now loses points: a check of its own, or half of the grey-input check).
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

FUNCTIONS = {
    "lab07_transformations": ["translate", "rotate", "scale", "shear", "warp_affine"],
    "lab08_homographies": ["apply_homography", "warp_to_reference", "stitch", "stitch_many", "blend_multiband"],
    "lab09_camera": ["draw_points", "project_onto_image"],
    "lab10_camera2": ["undistort_image"],
    "lab11_two_view": ["draw_epipolar_lines"],
    "lab12_stereo": ["rectify"],
}

# o: the function's uint8 image answer; first: its first image argument
CONVERSIONS = {
    "grey -> BGR": "cv2.cvtColor(o, cv2.COLOR_GRAY2BGR) if o.ndim == 2 and first.ndim == 2 else o",
    "BGR -> grey": "cv2.cvtColor(o, cv2.COLOR_BGR2GRAY) if o.ndim == 3 and first.ndim == 3 else o",
    "float64": "o.astype(np.float64)",
    "float32 / 255": "o.astype(np.float32) / 255.0",
}

WRAPPER = '''
_reference_{f} = {f}
def _converted_{f}(o, first):
    o = np.asarray(o)
    return {conversion}
def {f}(*args, **kwargs):
    given = args[0] if args else next(iter(kwargs.values()))
    first = np.asarray(given[0] if isinstance(given, (list, tuple)) else given)
    out = _reference_{f}(*args, **kwargs)
    if isinstance(out, tuple):
        return tuple(_converted_{f}(x, first) if isinstance(x, np.ndarray) and x.dtype == np.uint8 else x
                     for x in out)
    return _converted_{f}(out, first)
'''


def main(argv: list[str]) -> int:
    sys.path.insert(0, str(ROOT))
    os.environ.setdefault("AUTOGRADER_CACHE_DIR", tempfile.mkdtemp(prefix="channel-rules-store-"))
    from autograder.engine.registry import select
    from autograder.engine.runner import grade
    from autograder.instructor import verify

    for module, functions in FUNCTIONS.items():
        lab = "lab" + module[3:5]
        if argv and lab not in argv:
            continue
        reference = (ROOT / "reference_solutions" / f"{module}.py").read_text()
        for function in functions:
            exercises = [e.id for e in select([lab]) if function in e.signatures]
            for name, conversion in CONVERSIONS.items():
                with tempfile.TemporaryDirectory() as folder:
                    source = WRAPPER.format(f=function, conversion=conversion)
                    Path(folder, f"{module}.py").write_text(verify.with_mutation(reference, source))
                    result = grade(folder, exercises, pictures="none")
                checks = [c for e in result.exercises for c in e.checks if c.max_score > 0]
                kept, total = sum(c.score for c in checks), sum(c.max_score for c in checks)
                print(f"{module:22} {function:20} {name:14} {kept:g}/{total:g}", flush=True)
                for c in checks:
                    if c.score < c.max_score:
                        print(f"    - {c.name}: {(c.message.splitlines() or [''])[0][:160]}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
