"""Lab 13 - image statistics: the public checks (an example course lab, written for the tests)."""

import numpy as np

from autograder.engine import strategies as st
from autograder.engine.judges import call_probe, name_mistake
from autograder.engine.registry import Lab

from . import truth

lab = Lab("lab13", module="lab13_image_stats", title="Image statistics")


def mean_level_gap(a, b) -> float:
    """Mean absolute difference, in grey levels (or counts), of two same-shaped answers."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    return float(np.abs(a - b).mean()) if a.shape == b.shape else float("inf")


def judge(t, what, got, expected, mistakes, *, probe=None, dtype_kind="iu", off_by_one_share=0.0):
    """``got`` equals ``expected`` (up to ``off_by_one_share`` of its entries one apart: the
    rounding ties legitimate variants break differently), or fails, naming the mistake
    that explains it here and on the ``probe``'s input too."""
    got = t.expect_array(got, what, shape=expected.shape, kind="iuf")
    difference = np.abs(got.astype(float) - expected)
    close = difference.max() <= 1 and np.mean(difference > 0) <= off_by_one_share
    if close and got.dtype.kind in dtype_kind:
        return
    named = name_mistake(t, got, mistakes, mean_level_gap, tolerance=1e-6, truth=expected, probe=probe)
    if named:
        t.fail(f"{what} is wrong: it looks like {named}.", mistake=named)
    if close:
        t.fail(f"{what} has dtype {got.dtype}: the values are right, but the result must be "
               f"{'uint8' if dtype_kind == 'u' else 'integer'}")
    t.fail(f"{what} differs at {int(np.sum(difference > 0))} of {difference.size} entries "
           f"(up to {difference.max():g} apart)")


def histogram_probe(t):
    """A second input where the mistakes answer differently: levels 33..201, 32 bins."""
    image = truth.dim(low=33, high=201)
    return call_probe(t, "histogram", (image,), {"bins": 32}, truth=truth.histogram(image, 32),
                      candidates=lambda: truth.histogram_mistakes(image, 32), shape=(32,))


def stretch_probe(t):
    image = truth.dim(height=24, width=90, low=90, high=181)
    return call_probe(t, "stretch", (image,), truth=truth.stretch(image),
                      candidates=lambda: truth.stretch_mistakes(image), shape=image.shape)


# ================================================================== ex1 histogram
ex1 = lab.exercise("ex1", "Histogram", functions=["histogram(image, bins=256)"])


@ex1.check("histogram of a ramp with every grey level", points=2)
def histogram_scene(t):
    image = truth.scene()
    judge(t, "histogram(image)", t.call("histogram", image), truth.histogram(image),
          truth.histogram_mistakes(image), probe=histogram_probe(t))


@ex1.check("histogram of a dim image with 16 bins", points=2)
def histogram_16(t):
    image = truth.dim()
    judge(t, "histogram(image, bins=16)", t.call("histogram", image, bins=16), truth.histogram(image, 16),
          truth.histogram_mistakes(image, 16), probe=histogram_probe(t))


@ex1.check("histogram for any bin count dividing 256", points=1)
def histogram_property(t):
    image = truth.dim(low=0, high=255)

    def holds(bins):
        judge(t, f"histogram(image, bins={bins})", t.call("histogram", image, bins=bins),
              truth.histogram(image, bins), truth.histogram_mistakes(image, bins), probe=histogram_probe(t))

    t.for_all(st.sampled_from([2, 4, 8, 32, 64, 128]), holds, max_examples=6)


# ================================================================== ex2 contrast stretch
ex2 = lab.exercise("ex2", "Contrast stretch", functions=["stretch(image)"])

# Legitimate variants (np.round, np.rint, cv2.normalize with NORM_MINMAX, int(v + 0.5))
# differ only where (v - min) * 255 / (max - min) ends in exactly .5: at most one level, on
# under 2% of the dim image's pixels. Truncation, the nearest mistake, differs on half of them.
TIES = 0.02


@ex2.check("stretch of a dim image fills 0..255", points=3)
def stretch_dim(t):
    image = truth.dim()
    judge(t, "stretch(dim image)", t.call("stretch", image), truth.stretch(image),
          truth.stretch_mistakes(image), probe=stretch_probe(t), dtype_kind="u", off_by_one_share=TIES)
    t.images("the dim image and its stretch", source=image, expected=truth.stretch(image))


@ex2.check("stretch of a ramp that already spans 0..255 changes nothing", points=1)
def stretch_identity(t):
    image = truth.dim(low=0, high=255)
    judge(t, "stretch(full-range image)", t.call("stretch", image), truth.stretch(image),
          truth.stretch_mistakes(image), probe=stretch_probe(t), dtype_kind="u", off_by_one_share=TIES)
