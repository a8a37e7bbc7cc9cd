"""Ground truth for lab 13 by construction, and what the usual mistakes give instead."""

import numpy as np


def scene(height: int = 48, width: int = 64, seed: int = 13) -> np.ndarray:
    """A grey uint8 image using every level 0..255: a diagonal ramp with noise."""
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[:height, :width]
    ramp = (x * 255.0 / (width - 1) + y * 40.0 / (height - 1)) % 256
    return np.clip(ramp + rng.normal(0, 6, ramp.shape), 0, 255).astype(np.uint8)


def dim(height: int = 40, width: int = 56, low: int = 70, high: int = 150) -> np.ndarray:
    """A low-contrast uint8 image: levels from ``low`` to ``high`` only."""
    ramp = np.linspace(low, high, width)[None, :] + np.zeros((height, 1))
    return np.round(ramp).astype(np.uint8)


def histogram(image: np.ndarray, bins: int = 256) -> np.ndarray:
    """Counts of grey levels: bin ``i`` holds the levels in [i * 256 / bins, (i + 1) * 256 / bins)."""
    return np.bincount((image.astype(np.int64).ravel() * bins) // 256, minlength=bins)


def histogram_mistakes(image: np.ndarray, bins: int = 256) -> dict:
    counts = histogram(image, bins)
    return {
        "a normalised histogram: the counts are divided by the number of pixels": counts / image.size,
        "the bins span the image's own darkest and brightest levels, not 0 to 256":
            np.histogram(image, bins)[0],
        "a cumulative histogram": np.cumsum(counts),
    }


def stretch(image: np.ndarray) -> np.ndarray:
    """Min-max contrast stretch to 0..255, rounded, uint8; a constant image gives zeros."""
    low, high = float(image.min()), float(image.max())
    if high == low:
        return np.zeros_like(image, dtype=np.uint8)
    return np.round((image - low) * 255.0 / (high - low)).astype(np.uint8)


def stretch_mistakes(image: np.ndarray) -> dict:
    low, high = int(image.min()), int(image.max())
    scaled = (image.astype(np.float64) - low) * 255.0 / max(high - low, 1)
    with np.errstate(over="ignore"):
        wrapped = ((image - np.uint8(low)) * np.uint8(255)) // np.uint8(max(high - low, 1))
    return {
        "the arithmetic is done in uint8, so (image - min) * 255 wraps around": wrapped,
        "the values are truncated, not rounded": np.floor(scaled),
        "the minimum is not subtracted (image * 255 / max)": np.round(image * 255.0 / max(high, 1)),
        "the result is scaled to 0..1, not 0..255": scaled / 255.0,
    }
