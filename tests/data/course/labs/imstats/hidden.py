"""Lab 13 - hidden checks: inputs the students never saw."""

import numpy as np

from . import truth
from .suite import TIES, ex2, judge, stretch_probe


@ex2.check("stretch of a constant image is all zeros", points=1, hidden=True)
def stretch_constant(t):
    image = np.full((20, 30), 77, np.uint8)
    judge(t, "stretch(constant image)", t.call("stretch", image), truth.stretch(image), {}, dtype_kind="u")


@ex2.check("stretch of a bright narrow band", points=2, hidden=True)
def stretch_bright(t):
    image = truth.dim(low=200, high=230)
    judge(t, "stretch(bright image)", t.call("stretch", image), truth.stretch(image),
          truth.stretch_mistakes(image), probe=stretch_probe(t), dtype_kind="u", off_by_one_share=TIES)

