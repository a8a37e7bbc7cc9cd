"""Lab 13 - image statistics.

Fill in each function; ``python grade.py lab13`` grades them.
"""

import numpy as np


def histogram(image, bins=256):
    """Counts of the grey levels of ``image`` (uint8, shape (H, W)).

    Returns an integer array of shape (bins,): bin i counts the pixels whose level v
    has i * 256 / bins <= v < (i + 1) * 256 / bins. The counts add up to H * W.
    """
    raise NotImplementedError


def stretch(image):
    """Min-max contrast stretch of ``image`` (uint8, shape (H, W)).

    Returns a uint8 array of the same shape: the darkest level becomes 0, the brightest
    255, linearly in between, rounded to the nearest level. A constant image gives zeros.
    """
    raise NotImplementedError
