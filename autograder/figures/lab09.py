"""Lab 9's figures: projections for several focal lengths, points drawn on a photo."""

import numpy as np

from . import FigureUnavailable, Panel, common_extent, figure


def _cube():
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (4, 6)], float)
    edges = np.linspace(0, 1, 8)[:, None]
    pairs = [(a, b) for a in range(8) for b in range(a + 1, 8) if np.sum(corners[a] != corners[b]) == 1]
    return np.vstack([corners[a] + edges * (corners[b] - corners[a]) for a, b in pairs])


FRAME = (320.0, 240.0)  # the image the intrinsic matrix below makes: f = 300, centre (160, 120)


def _rotation(axis: str, degrees: float) -> np.ndarray:
    import cv2

    rvec = np.zeros(3)
    rvec["xyz".index(axis)] = np.deg2rad(degrees)
    return cv2.Rodrigues(rvec)[0]


@figure("lab09.ex1", "pinhole_project(cube, f) for f = 1")
def pinhole(call):
    return [Panel("pinhole_project(cube, f=1)", points={"projection": call("pinhole_project", _cube(), 1.0)},
                  axes=("x = f X / Z", "y = f Y / Z"))]


@figure("lab09.ex2", "project_with_intrinsics(intrinsic_matrix(300, 160, 120), cube)")
def intrinsics(call):
    K = call("intrinsic_matrix", 300.0, 160.0, 120.0)
    projected = call("project_with_intrinsics", K, _cube())
    return [Panel("pixels; grey: the 320 x 240 image", points={"projection": projected},
                  frame=FRAME, axes=("column x", "row y"))]


def _seen_by(call, K, R, t):
    return call("project", call("camera_matrix", K, R, t), _cube())


@figure("lab09.ex3", "project(camera_matrix(K, R, t), cube): the camera turned about the cube")
def full_camera(call):
    K = np.array([[300.0, 0, 160], [0, 300.0, 120], [0, 0, 1]])
    centre = np.array([0.0, 0.0, 5.0])
    R = _rotation("y", 30.0)
    t = centre - R @ centre  # the cube's centre stays 5 in front of the camera
    return [Panel("R = I, t = 0", points={"projection": _seen_by(call, K, np.eye(3), np.zeros(3))},
                  frame=FRAME, axes=("column x", "row y")),
            Panel("R: 30° about y, t keeps the cube ahead", points={"projection": _seen_by(call, K, R, t)},
                  frame=FRAME, axes=("column x", "row y"))]


@figure("lab09.ex3-extension", "the effects of R and t: project(camera_matrix(K, R, t), cube)")
def rotations_and_translations(call):
    K = np.array([[300.0, 0, 160], [0, 300.0, 120], [0, 0, 1]])
    poses = [("R = I, t = 0", np.eye(3), (0, 0, 0)),
             ("R: 15° about y (pan)", _rotation("y", 15.0), (0, 0, 0)),
             ("R: 30° about z (roll)", _rotation("z", 30.0), (0, 0, 0)),
             ("t = (1, 0, 0)", np.eye(3), (1, 0, 0)),
             ("t = (0, 0, 3): farther", np.eye(3), (0, 0, 3)),
             ("t = (0, 0, -2): nearer", np.eye(3), (0, 0, -2))]
    return [Panel(title, points={"projection": _seen_by(call, K, R, np.array(t, float))},
                  frame=FRAME, axes=("column x", "row y")) for title, R, t in poses]


@figure("lab09.ex4", "project_focal_lengths(cube, [100, 300, 600]) and simulate_aperture")
def focal_lengths(call):
    focal = [100.0, 300.0, 600.0]
    projections = np.asarray(call("project_focal_lengths", _cube(), focal), dtype=float)
    if projections.ndim != 3 or len(projections) != len(focal):  # (and not a million rows to unpack)
        raise FigureUnavailable(f"project_focal_lengths() returned shape {projections.shape}; "
                                f"expected ({len(focal)}, N, 2)")
    extent = common_extent(*projections)  # one scale for all three: the picture grows with f
    panels = [Panel(f"f = {f:g}", points={"projection": p}, extent=extent) for f, p in zip(focal, projections)]
    rays = [np.asarray(call("simulate_aperture", _cube(), 300.0, aperture, 20, 0), dtype=float).reshape(-1, 2)
            for aperture in (0.0, 0.05, 0.15)]
    extent = common_extent(*rays)
    panels += [Panel(f"simulate_aperture, f = 300, aperture {aperture:g}", points={"20 rays a point": r},
                     extent=extent) for aperture, r in zip((0.0, 0.05, 0.15), rays)]
    return panels


@figure("lab09.ex5", "project_onto_image(photo, P, points)")
def onto_image(call):
    from fixtures.lab09 import photo

    image = photo("astronaut", (320, 240))
    K = np.array([[300.0, 0, 160], [0, 300.0, 120], [0, 0, 1]])
    P = K @ np.hstack([np.eye(3), np.zeros((3, 1))])
    marked, _ = call("project_onto_image", image, P, _cube())
    return [Panel("input", image), Panel("project_onto_image", marked)]


@figure("lab09.ext2", "distort_points(grid, dist): barrel, pincushion, tangential")
def distortion(call):
    line = np.linspace(-0.6, 0.6, 41)
    ticks = np.linspace(-0.6, 0.6, 7)
    grid = np.vstack([np.column_stack([np.full_like(line, v), line]) for v in ticks]
                     + [np.column_stack([line, np.full_like(line, v)]) for v in ticks])
    cases = [("no distortion", (0.0, 0.0, 0.0, 0.0, 0.0)), ("k1 = -0.3: barrel", (-0.3, 0.0, 0.0, 0.0, 0.0)),
             ("k1 = +0.3: pincushion", (0.3, 0.0, 0.0, 0.0, 0.0)),
             ("p1 = 0.05: tangential", (0.0, 0.0, 0.05, 0.0, 0.0))]
    return [Panel(title, points={"distorted grid": call("distort_points", grid, np.array(dist))},
                  axes=("normalised x", "normalised y")) for title, dist in cases]
