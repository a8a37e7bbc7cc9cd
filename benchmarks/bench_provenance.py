"""How well figure provenance tells a figure from another (autograder.instructor.review.provenance).

    python grade.py reference_solutions lab07 lab08 --figures /tmp/figures --quiet
    python benchmarks/bench_provenance.py /tmp/figures

For the figures in the folder, prints the lowest scores (whole, detail) of a figure against
itself rescaled and JPEG-compressed (these must match), and the highest of two different
figures of one shape, and of a figure with one of three panels shifted, turned, replaced or
darkened (these must not), beside the thresholds.
"""

from __future__ import annotations

import itertools
import sys
from pathlib import Path

import cv2
import numpy as np

from autograder.instructor.review.provenance import SAME_DETAIL, SAME_WHOLE, same_shape, scores
from autograder.sandbox.report_reader import thumbnail


def jpeg(image, scale, quality):
    small = cv2.resize(image, None, fx=scale, fy=scale, interpolation=cv2.INTER_AREA)
    return cv2.imdecode(cv2.imencode(".jpg", small, [cv2.IMWRITE_JPEG_QUALITY, quality])[1], cv2.IMREAD_COLOR)


def altered(image, how):
    """``image`` with its right third shifted, turned, replaced by the middle one, or darkened."""
    image = image.copy()
    height, width = image.shape[:2]
    third = width // 3
    right = image[:, width - third:]
    if how == "replaced":
        image[:, width - third:] = image[:, width - 2 * third:width - third]
    elif how == "turned":
        image[:, width - third:] = cv2.warpAffine(right, cv2.getRotationMatrix2D((third / 2, height / 2), 5, 1),
                                                  (third, height), borderValue=(255, 255, 255))
    elif how == "shifted":
        image[:, width - third:] = cv2.warpAffine(right, np.float32([[1, 0, 12], [0, 1, 6]]), (third, height),
                                                  borderValue=(255, 255, 255))
    else:
        image[:, width - third:] = (right * 0.7).astype(np.uint8)
    return image


def main(folder: str) -> None:
    images = {path.stem: cv2.imread(str(path)) for path in sorted(Path(folder).glob("*.png"))}
    thumbs = {name: thumbnail(image) for name, image in images.items()}
    same = [(scores(thumbnail(jpeg(image, s, q)), thumbs[name]), f"{name} at {s:.0%}, JPEG {q}")
            for name, image in images.items() for s, q in ((0.25, 30), (0.3, 40), (0.5, 60), (1.5, 80))]
    different = [(scores(thumbs[a], thumbs[b]), f"{a} / {b}") for a, b in itertools.combinations(images, 2)
                 if same_shape(images[a].shape[1], images[a].shape[0], images[b].shape[1], images[b].shape[0])]
    changed = [(scores(thumbnail(jpeg(altered(image, how), 0.5, 70)), thumbs[name]), f"{name}, a panel {how}")
               for name, image in images.items() for how in ("shifted", "turned", "replaced", "darkened")]
    print(f"{len(images)} figures; thresholds: whole >= {SAME_WHOLE}, detail >= {SAME_DETAIL}")
    for title, found, pick in (("same figure (must match): lowest", same, min),
                               ("different figures (must not): highest", different, max),
                               ("a panel changed (must not): highest", changed, max)):
        for part, index in (("whole", 0), ("detail", 1)):
            value, name = pick(((s[index], n) for s, n in found), default=(float("nan"), "-"))
            print(f"{title} {part}: {value:.3f} ({name})")
    wrong = [n for (w, d), n in same if not (w >= SAME_WHOLE and d >= SAME_DETAIL)]
    wrong += [n for (w, d), n in different + changed if w >= SAME_WHOLE and d >= SAME_DETAIL]
    print(f"decided wrongly: {len(wrong)} of {len(same) + len(different) + len(changed)}", *wrong[:10], sep="\n  ")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "figures")
