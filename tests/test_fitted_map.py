"""The map a wrong warp applied, fitted to the student's image and told against the map asked (fitted_map)."""

from __future__ import annotations

import cv2
import numpy as np
import pytest

from autograder.engine.fitted_map import centroid_of, fitted_affine, told
from fixtures.images import photo, warp


@pytest.fixture(scope="module")
def source():
    return photo("astronaut", (240, 180))


def test_a_rotation_about_another_centre_is_told_with_its_fixed_point(source):
    asked = cv2.getRotationMatrix2D((119.5, 89.5), 30, 1.0)
    centre = tuple(float(v) for v in centroid_of(source))
    got = warp(source, cv2.getRotationMatrix2D(centre, 30, 1.0))
    fitted = fitted_affine(got, source)
    said = told(fitted, asked, source)
    assert said.startswith("warped about the point") and "brightness centroid" in said, said
    other = warp(source, cv2.getRotationMatrix2D((40.0, 30.0), 30, 1.0))
    said = told(fitted_affine(other, source), asked, source)
    assert "(40, 30)" in said and "centroid" not in said, said


def test_another_angle_or_scale_is_told_and_the_map_asked_tells_nothing(source):
    asked = cv2.getRotationMatrix2D((119.5, 89.5), 30, 1.0)
    said = told(fitted_affine(warp(source, cv2.getRotationMatrix2D((119.5, 89.5), -30, 1.0)), source), asked, source)
    assert "rotated by -30 degrees where 30 is asked" in said, said
    said = told(fitted_affine(warp(source, cv2.getRotationMatrix2D((119.5, 89.5), 30, 1.25)), source), asked, source)
    assert "scaled by 1.25 where 1.00 is asked" in said, said
    assert told(fitted_affine(warp(source, asked), source), asked, source) == ""


def test_an_image_no_affine_map_reproduces_has_no_fitted_map(source):
    noise = np.random.default_rng(0).integers(0, 256, source.shape, dtype=np.uint8)
    assert fitted_affine(noise, source) is None
    blurred = cv2.GaussianBlur(warp(source, cv2.getRotationMatrix2D((119.5, 89.5), 30, 1.0)), (0, 0), 4.0)
    assert fitted_affine(blurred, source) is None
