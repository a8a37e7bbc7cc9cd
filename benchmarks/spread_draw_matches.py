"""Lab 8 ex3 tolerances, measured: is every match line of draw_matches found, and nothing else?

judge_match_drawing (autograder/labs/lab08.py) compares the drawing with the two images side by
side: a pixel is drawn on when a channel moved by more than DRAWN_LEVELS; a match line is found
when LINE_FOUND of the points along it (away from its ends and the other lines) have a drawn
pixel within 2 px; a straight stroke (>= 40 px, not axis-parallel) mostly away from every match
line is a line that joins no match. This prints, on the checks' inputs, the smallest share found
on any line for legitimate drawings (cv2.drawMatches under 300 colour seeds, keypoint sizes and
flags, fixed match colours, black included; own cv2.line drawings, thickness 1-2, LINE_8/AA,
random colours over 0..255, truncated coordinates; the reference) and the largest share left on
the line a mistake leaves out, and the strokes found joining no match.

    python benchmarks/spread_draw_matches.py
"""

from __future__ import annotations

import cv2
import numpy as np

import importlib.util
from pathlib import Path

from autograder.labs import lab08 as L

spec = importlib.util.spec_from_file_location(
    "reference", Path(__file__).resolve().parents[1] / "reference_solutions" / "lab08_homographies.py")
reference = importlib.util.module_from_spec(spec)
spec.loader.exec_module(reference)


def bgr(image):
    return cv2.cvtColor(image, cv2.COLOR_GRAY2BGR) if image.ndim == 2 else image


def opencv(size=3, flags=0, color=None, seed=None, pairing=lambda n: [(i, i) for i in range(n)]):
    def draw(img1, img2, pts1, pts2):
        if seed is not None:
            cv2.setRNGSeed(seed)
        k1 = [cv2.KeyPoint(float(x), float(y), size) for x, y in pts1]
        k2 = [cv2.KeyPoint(float(x), float(y), size) for x, y in pts2]
        matches = [cv2.DMatch(i, j, 0) for i, j in pairing(len(k1))]
        kw = {} if color is None else {"matchColor": color}
        return cv2.drawMatches(bgr(img1), k1, bgr(img2), k2, matches, None, flags=flags, **kw)
    return draw


def own(color=None, thickness=1, line=cv2.LINE_AA, seed=0, circles=0, rounding=True, extra=None, divider=False,
        labels=False):
    def draw(img1, img2, pts1, pts2):
        canvas = L.plain_composite(img1, img2)
        w1 = img1.shape[1]
        rng = np.random.default_rng(seed)
        snap = np.round if rounding else np.trunc
        for (x1, y1), (x2, y2) in zip(pts1, pts2):
            colour = color if color is not None else tuple(int(v) for v in rng.integers(0, 256, 3))
            a, b = (int(snap(x1)), int(snap(y1))), (int(snap(x2 + w1)), int(snap(y2)))
            cv2.line(canvas, a, b, colour, thickness, line)
            if circles:
                cv2.circle(canvas, a, circles, colour, 1, line)
                cv2.circle(canvas, b, circles, colour, 1, line)
        if labels:
            for i, (x, y) in enumerate(pts1):
                cv2.putText(canvas, str(i), (int(x) + 4, int(y) - 4), cv2.FONT_HERSHEY_SIMPLEX, 0.4, (0, 255, 255), 1)
        if divider:
            cv2.line(canvas, (w1, 0), (w1, canvas.shape[0] - 1), (255, 255, 255), 1)
            cv2.rectangle(canvas, (0, 0), (canvas.shape[1] - 1, canvas.shape[0] - 1), (0, 255, 255), 1)
        if extra is not None:
            extra(canvas, pts1, pts2, w1)
        return canvas
    return draw


def unequal_case():
    img1, img2 = L.photo("chelsea", (120, 140)), L.photo("astronaut", (280, 200))
    return img1, img2, *L.UNEQUAL_POINTS


def one_match_case():
    img1, img2, pts1, pts2 = L.drawing_case()
    return img1, img2, pts1[L.ONE_MATCH : L.ONE_MATCH + 1], pts2[L.ONE_MATCH : L.ONE_MATCH + 1]


LEGITIMATE = {"reference": reference.draw_matches}
for s in range(300):
    LEGITIMATE[f"cv2.drawMatches, RNG seed {s}"] = opencv(seed=s)
for size in (1, 10, 30):
    LEGITIMATE[f"cv2.drawMatches, keypoint size {size}"] = opencv(size=size, seed=1)
for size in (20, 40):
    LEGITIMATE[f"cv2.drawMatches, rich keypoints of size {size}"] = opencv(
        size=size, flags=cv2.DrawMatchesFlags_DRAW_RICH_KEYPOINTS, seed=2)
for colour in [(0, 255, 0), (0, 0, 255), (255, 0, 0), (255, 255, 255), (0, 0, 0), (0, 255, 255)]:
    LEGITIMATE[f"cv2.drawMatches, matchColor {colour}"] = opencv(color=colour)
    for thickness in (1, 2):
        for line in (cv2.LINE_AA, cv2.LINE_8):
            LEGITIMATE[f"own cv2.line {colour}, thickness {thickness}, {'AA' if line == cv2.LINE_AA else '8'}"] = \
                own(color=colour, thickness=thickness, line=line)
for s in range(100):
    LEGITIMATE[f"own cv2.line, random colours 0..255, seed {s}"] = own(seed=s)
LEGITIMATE["own cv2.line, truncated coordinates"] = own(color=(0, 255, 0), rounding=False)
LEGITIMATE["own cv2.line, circles of radius 12 at the ends"] = own(color=(0, 255, 0), circles=12)
LEGITIMATE["own cv2.line, each match numbered (cv2.putText)"] = own(color=(0, 255, 0), labels=True)
LEGITIMATE["own cv2.line, a divider at x = W1 and a frame"] = own(color=(0, 255, 0), divider=True)


def extra_from_origin(canvas, pts1, pts2, w1):
    cv2.line(canvas, (0, 0), (int(pts2[-1, 0] + w1), int(pts2[-1, 1])), (0, 255, 0), 1, cv2.LINE_AA)


MISTAKES = {
    "the last match is left out (range(n - 1))": opencv(seed=0, pairing=lambda n: [(i, i) for i in range(n - 1)]),
    "the first match is left out": opencv(seed=0, pairing=lambda n: [(i, i) for i in range(1, n)]),
    "matches paired off by one (i, i + 1)": opencv(seed=0, pairing=lambda n: [(i, (i + 1) % n) for i in range(n)]),
    "an extra line from the origin": own(color=(0, 255, 0), extra=extra_from_origin),
}


def measure(img1, img2, pts1, pts2, got):
    plain = L.plain_composite(img1, img2)
    starts, ends = pts1, pts2 + [img1.shape[1], 0]
    changed = np.abs(got.astype(np.int16) - plain).max(axis=2) > L.DRAWN_LEVELS
    return L.segments_drawn(changed, starts, ends), L.stray_segments(changed, starts, ends)


def main():
    cases = {"drawing_case (12 matches)": L.drawing_case(), "unequal widths (5 matches)": unequal_case(),
             "one match": one_match_case()}
    for case, (img1, img2, pts1, pts2) in cases.items():
        print(f"== {case}")
        rows = []
        for name, draw in LEGITIMATE.items():
            found, stray = measure(img1, img2, pts1, pts2, draw(img1, img2, pts1, pts2))
            rows.append((found.min(), len(stray), name))
        rows.sort()
        print(f"  legitimate: smallest share found on a line {rows[0][0]:.2f} ({rows[0][2]}); "
              f"strokes joining no match: at most {max(r[1] for r in rows)}")
        for name, draw in MISTAKES.items():
            found, stray = measure(img1, img2, pts1, pts2, draw(img1, img2, pts1, pts2))
            print(f"  mistake {name}: lines found {int((found >= L.LINE_FOUND).sum())}/{len(found)}, largest share on "
                  f"a line not found {max([f for f in found if f < L.LINE_FOUND], default=float('nan')):.2f}, "
                  f"strokes joining no match {len(stray)}")


if __name__ == "__main__":
    main()
