"""Score histograms as small inline SVG: crisp at any width, a few hundred bytes each.

Hand-made rather than Matplotlib's SVG (tens of kilobytes per chart once the
fonts are drawn as paths): a class page holds one per exercise.
"""

from __future__ import annotations

from markupsafe import Markup, escape

from .analysis import Distribution

WIDTH, HEIGHT = 320, 140
LEFT, RIGHT, TOP, BOTTOM = 6, 6, 16, 22
MEAN_COLOUR, MEDIAN_COLOUR = "#8250df", "#bc4c00"


def _num(x: float) -> str:
    return f"{x:.3g}" if abs(x) < 1000 else f"{x:.0f}"


def histogram_svg(distribution: Distribution, what: str, bins: int = 10) -> Markup:
    """An inline ``<svg>`` histogram of ``distribution``'s scores with mean and median marked.

    ``what`` names the scores for screen readers ("lab07.ex2 scores").
    """
    counts = distribution.histogram(bins)
    top = max(counts) or 1
    plot_w, plot_h = WIDTH - LEFT - RIGHT, HEIGHT - TOP - BOTTOM
    bar_w = plot_w / bins
    step = distribution.max_score / bins if distribution.max_score else 0.0
    description = ", ".join(
        f"{_num(i * step)} to {_num((i + 1) * step)}: {n}" for i, n in enumerate(counts))
    labels = []   # drawn last, over the mean and median lines
    parts = [f'<svg class="hist" viewBox="0 0 {WIDTH} {HEIGHT}" role="img" '
             f'aria-label="{escape(what)}: {escape(description)}" xmlns="http://www.w3.org/2000/svg">',
             f"<title>{escape(what)}</title>"]
    for i, n in enumerate(counts):
        x = LEFT + i * bar_w
        h = plot_h * n / top
        full = i == bins - 1
        parts.append(f'<rect x="{x + 1:.1f}" y="{TOP + plot_h - h:.1f}" width="{bar_w - 2:.1f}" '
                     f'height="{h:.1f}" fill="{"#1a7f37" if full else "#0969da"}"/>')
        if n:
            labels.append(f'<text x="{x + bar_w / 2:.1f}" y="{TOP + plot_h - h - 3:.1f}" text-anchor="middle" '
                          f'font-size="11" stroke="#fff" stroke-width="3" paint-order="stroke">{n}</text>')
    baseline = TOP + plot_h
    parts.append(f'<line x1="{LEFT}" y1="{baseline}" x2="{WIDTH - RIGHT}" y2="{baseline}" stroke="#57606a"/>')
    for value, anchor in ((0.0, "start"), (distribution.max_score / 2, "middle"), (distribution.max_score, "end")):
        x = LEFT + (plot_w * value / distribution.max_score if distribution.max_score else 0)
        parts.append(f'<text x="{x:.1f}" y="{HEIGHT - 6}" text-anchor="{anchor}" font-size="11" '
                     f'fill="#57606a">{_num(value)}</text>')
    for value, colour, dash in ((distribution.mean, MEAN_COLOUR, ' stroke-dasharray="4 3"'),
                                (distribution.median, MEDIAN_COLOUR, "")):
        if value is None or not distribution.max_score:
            continue
        x = LEFT + plot_w * min(max(value / distribution.max_score, 0.0), 1.0)
        parts.append(f'<line x1="{x:.1f}" y1="{TOP - 6}" x2="{x:.1f}" y2="{baseline}" stroke="{colour}" '
                     f'stroke-width="2"{dash}/>')
    parts += labels
    parts.append("</svg>")
    return Markup("".join(parts))
