"""Lab 9's figures: projections for several focal lengths, points drawn on a photo."""

import numpy as np

from . import Panel, figure


def _cube():
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (4, 6)], float)
    edges = np.linspace(0, 1, 8)[:, None]
    pairs = [(a, b) for a in range(8) for b in range(a + 1, 8) if np.sum(corners[a] != corners[b]) == 1]
    return np.vstack([corners[a] + edges * (corners[b] - corners[a]) for a, b in pairs])


@figure("lab09.ex4", "project_focal_lengths(cube, [100, 300, 600])")
def focal_lengths(call):
    focal = [100.0, 300.0, 600.0]
    projections = np.asarray(call("project_focal_lengths", _cube(), focal), dtype=float)
    return [Panel(f"f = {f:g}", points={"projection": p}) for f, p in zip(focal, projections)]


@figure("lab09.ex5", "project_onto_image(photo, P, points)")
def onto_image(call):
    from fixtures.lab09 import photo

    image = photo("astronaut", (320, 240))
    K = np.array([[300.0, 0, 160], [0, 300.0, 120], [0, 0, 1]])
    P = K @ np.hstack([np.eye(3), np.zeros((3, 1))])
    marked, _ = call("project_onto_image", image, P, _cube())
    return [Panel("input", image), Panel("project_onto_image", marked)]
