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
    assert "rotated by about -30 degrees where 30 is asked" in said, said
    said = told(fitted_affine(warp(source, cv2.getRotationMatrix2D((119.5, 89.5), 30, 1.25)), source), asked, source)
    assert "scaled by 1.25 where 1.00 is asked" in said, said
    assert told(fitted_affine(warp(source, asked), source), asked, source) == ""


@pytest.mark.parametrize("name", ["astronaut", "camera", "coffee"])
def test_a_small_angle_is_fitted_to_a_tenth_of_a_degree(name):
    # (06i: 90 taken as radians by cv2.getRotationMatrix2D turns the image 1.57 degrees; keypoints alone fitted 1.3)
    image = photo(name, (160, 120))
    for angle in (np.degrees(np.pi / 2) * np.pi / 180, 30 * np.pi / 180):
        got = warp(image, cv2.getRotationMatrix2D((79.5, 59.5), angle, 1.0))
        fitted = fitted_affine(got, image)
        assert fitted is not None
        turned = np.degrees(np.arctan2(-fitted[1, 0], fitted[0, 0]))
        assert abs(turned - angle) < 0.1, (name, angle, turned)


def test_an_image_no_affine_map_reproduces_has_no_fitted_map(source):
    noise = np.random.default_rng(0).integers(0, 256, source.shape, dtype=np.uint8)
    assert fitted_affine(noise, source) is None
    blurred = cv2.GaussianBlur(warp(source, cv2.getRotationMatrix2D((119.5, 89.5), 30, 1.0)), (0, 0), 4.0)
    assert fitted_affine(blurred, source) is None


def test_the_blur_measure_leaves_out_maps_that_shrink_where_averaging_is_legitimate(source):
    """cv2.resize with INTER_AREA (the right call for shrinking) keeps little fine detail at a quarter of the size:
    such maps are not measured; a shear keeps the area and is."""
    from autograder.engine.compare import DETAIL_KEPT, detail_kept
    from autograder.engine.judges import _keeps_its_scale

    quarter = np.float64([[0.25, 0, 0], [0, 0.25, 0]])
    assert not _keeps_its_scale(quarter) and _keeps_its_scale(np.float64([[1, 0.5, 0], [0, 1, 0]]))
    expected = warp(source, quarter)
    inside = warp(np.full(source.shape[:2], 255, np.uint8), quarter, interpolation=cv2.INTER_NEAREST) > 0
    shrunk = cv2.resize(source, None, fx=0.25, fy=0.25, interpolation=cv2.INTER_AREA)
    canvas = np.zeros_like(source)
    canvas[:shrunk.shape[0], :shrunk.shape[1]] = shrunk
    assert detail_kept(canvas, expected, inside) > 0.3   # (measured, and not judged: below DETAIL_KEPT on some photos)
    sheared = warp(source, np.float64([[1, 0.5, 0], [0, 1, 0]]))
    assert detail_kept(cv2.GaussianBlur(sheared, (3, 3), 0), sheared, sheared.max(axis=2) > 0) < DETAIL_KEPT
