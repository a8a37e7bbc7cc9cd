"""cv-autograder: sandboxed, geometry-aware grading for computer-vision labs."""

__version__ = "0.1.0"
