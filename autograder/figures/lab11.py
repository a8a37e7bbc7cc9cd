"""Lab 11's figures: epipolar lines drawn on the second image."""

from . import Panel, figure


@figure("lab11.ex2", "draw_epipolar_lines(image 2, epipolar_lines(F, points of image 1))")
def epipolar(call):
    import cv2
    from fixtures import lab11 as truth
    from fixtures.images import photo

    views = truth.two_views(seed=6, n=40)
    inside = truth.inside(views.pts2, views.cam2, margin=3)
    pts1, pts2 = views.pts1[inside][:8], views.pts2[inside][:8]
    image = photo("coffee", (views.cam2.width, views.cam2.height))
    drawn = call("draw_epipolar_lines", image, call("epipolar_lines", views.F, pts1))
    if getattr(drawn, "ndim", 0) == 3:
        drawn = drawn.copy()
        for x, y in pts2:
            cv2.circle(drawn, (int(round(x)), int(round(y))), 4, (255, 255, 255), 1)
    return [Panel("image 2", image), Panel("your lines; white circles: the matches", drawn)]
