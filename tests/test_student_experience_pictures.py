"""Pictures that tell the truth on a page that stays small, and a page that fits a phone."""

import base64
import re
from html import escape
import shutil
import subprocess

import cv2
import numpy as np
import pytest
import skimage.data

from autograder.engine import pictures
from autograder.reports import html
from autograder.engine.results import Artifact, CheckResult, ExerciseResult, GradingResult
from autograder.engine.runner import grade
from conftest import REFERENCE, mutant

MODULE = "lab07_transformations"


def drawn(page: str) -> dict:
    """label -> (CSS width, size label) of every picture drawn on the page."""
    found = re.findall(r'<figure style="width: (\d+)px">\s*<svg class="pic"[^>]*aria-label="([^"]*)".*?'
                       r'<span class="size">([^<]*)</span>', page, re.S)
    return {label: (int(width), size) for width, label, size in found}


def page_of(artifacts) -> str:
    check = CheckResult("a check", 0.0, 1.0, "failed", "wrong", artifacts=artifacts)
    return html.render(GradingResult("s", "h", "0", [ExerciseResult("lab07.ex1", "T", [], [check])]))


def test_a_wrongly_sized_result_is_drawn_smaller_and_without_a_difference_map(tmp_path):
    result = grade(mutant(tmp_path, MODULE, """
        _translate = translate
        def translate(image, tx=100, ty=50):
            return _translate(image, tx, ty)[:80, :90]
        """), ["lab07.ex1"])
    page = html.render(result)
    sizes = drawn(page)
    assert sizes["yours"][1] == "90 × 80"
    assert sizes["yours"][0] < sizes["expected"][0], "the smaller image must look smaller"
    assert "difference" not in sizes
    # one sentence: no caption about a difference map run together with "no difference map"
    assert " — no difference map: your image is 90 × 80 pixels" in page
    assert "the difference map is grey" not in page


def test_a_difference_map_has_its_colour_scale(tmp_path):
    page = html.render(grade(REFERENCE, ["lab07.ex1"]))
    assert "difference" in drawn(page)
    assert 'class="scale" style="background: linear-gradient(to right, rgb(' in page
    assert "64+ grey levels" in page


def test_photos_become_jpeg_drawings_stay_png_and_each_picture_is_embedded_once():
    photo = skimage.data.astronaut()[:, :, ::-1]
    drawing = np.zeros((240, 320, 3), np.uint8)
    cv2.line(drawing, (0, 0), (319, 239), (0, 255, 0), 1)
    page = page_of([Artifact("images", "first", [pictures.picture_item("photo", photo),
                                                 pictures.picture_item("drawing", drawing)]),
                    Artifact("images", "again", [pictures.picture_item("photo", photo)])])
    assert page.count("data:image/jpeg;base64,") == 1 and page.count("data:image/png;base64,") == 1
    assert page.count('<use href="#pic0"/>') == 2
    [jpeg] = re.findall(r"data:image/jpeg;base64,([^\"]+)", page)
    decoded = cv2.imdecode(np.frombuffer(base64.b64decode(jpeg), np.uint8), cv2.IMREAD_COLOR)
    assert max(decoded.shape[:2]) <= 360, "encoded at about twice the drawn size, not 512 px"
    assert len(jpeg) < len(pictures.png_base64(photo)) / 5
    assert drawn(page)["photo"][1] == "512 × 512"


def test_a_side_by_side_pair_is_drawn_wide_enough_to_read():
    pair = np.zeros((480, 1284, 3), np.uint8)
    single = np.zeros((480, 640, 3), np.uint8)
    page = page_of([Artifact("images", "pair", [pictures.picture_item("pair", pair)]),
                    Artifact("images", "one", [pictures.picture_item("one", single)])])
    sizes = drawn(page)
    assert sizes["pair"][0] >= 600
    assert sizes["one"][0] < sizes["pair"][0] / 2


CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")
# Appended to a copy of the page: says whether anything is wider than the window. The page
# sits in an iframe of the width wanted (headless Chromium's windows are 500 px at least).
LAYOUT_PROBE = """<script>
  const tooWide = [...document.querySelectorAll('main *')].filter(
      e => e.getBoundingClientRect().right > window.innerWidth + 1).map(e => e.tagName);
  const pictures = [...document.querySelectorAll('svg.pic')].map(e => e.getBoundingClientRect().width);
  parent.document.body.insertAdjacentHTML('beforeend', '<p id="probe">' + JSON.stringify(
      {width: window.innerWidth, tooWide: tooWide, pictures: pictures}) + '</p>');
</script>"""


@pytest.mark.slow
@pytest.mark.skipif(CHROMIUM is None, reason="needs a headless Chromium")
@pytest.mark.parametrize("width", [390, 1280])
def test_the_page_fits_a_phone_and_a_laptop(tmp_path, width):
    import json

    result = grade(mutant(tmp_path, MODULE, """
        def rotate(image, angle_deg=45):
            return image[::2, ::2].copy()
        """), ["lab07.ex1", "lab07.ex2"])
    probed = (html.render(result).replace("<details>", "<details open>")
              .replace("</body>", LAYOUT_PROBE + "</body>"))
    page = tmp_path / "page.html"
    page.write_text(f'<!doctype html><body style="margin:0"><iframe width="{width}" height="900" '
                    f'style="border:0" srcdoc="{escape(probed, quote=True)}"></iframe></body>')
    run = subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
                          f"--window-size={max(width, 500) + 20},1000", "--virtual-time-budget=5000", "--dump-dom",
                          page.as_uri()], capture_output=True, text=True, timeout=120)
    probe = json.loads(re.search(r'<p id="probe">(.*?)</p>', run.stdout).group(1))
    assert probe["width"] == width
    assert probe["tooWide"] == [], f"wider than a {width} px window: {probe['tooWide'][:5]}"
    assert probe["pictures"] and min(probe["pictures"]) > 40
