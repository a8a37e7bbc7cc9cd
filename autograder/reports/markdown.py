"""A student's Markdown (a lab report's explanation) as HTML that is safe to show the instructor.

The text is untrusted: :func:`render_markdown` renders it with markdown-it-py's
CommonMark rules and

- raw HTML off: ``<script>``, ``<img onerror=...>``, ``<iframe>`` are shown as text;
- no remote fetch: an image is shown only when it names one of the figures the
  grader made from the student's code (``figures/lab07.ex1.png`` -> ``lab07.ex1``,
  looked up by ``figure_url``); any other image is its alt text, so opening the page
  never asks another server for anything;
- links only to another machine's ``http:``/``https:`` address or to ``mailto:``
  (:func:`external_link`), each opening with ``rel="noopener noreferrer nofollow"``
  so the review's address (and its token) is never sent along; every other link is
  inert text followed by its target (``[link not followed: ../rubric]``): a relative,
  absolute-path, ``?query``, ``#fragment`` or ``//host`` link would open the page's
  own application (the student's text inside its chrome), a link to this machine
  (``localhost``, an IP address) would reach its servers; ``javascript:``, ``data:``,
  ``vbscript:`` and ``file:`` are not even parsed as links (:func:`safe_link`);
- bounded: at most :data:`MAX_MARKDOWN_CHARS` characters are rendered (the rest is
  cut, and the page says so), nesting at most :data:`MAX_NESTING` deep; control
  characters removed.
"""

from __future__ import annotations

import html
import re
import unicodedata
from pathlib import PurePosixPath
from typing import Callable
from urllib.parse import unquote

from markupsafe import Markup

from ..loading.text import printable

MAX_MARKDOWN_CHARS = 50_000
MAX_NESTING = 20
_SAFE_SCHEMES = ("http", "https", "mailto")
_SCHEME = re.compile(r"^([a-zA-Z][a-zA-Z0-9+.-]*):")
# This machine, or an IP literal: a browser takes a host whose last label is a number
# (decimal, octal, 0x hex: 127.1, 2130706433, 0x7f.1) as IPv4; IPv6 is in brackets.
_LOCAL_HOST = re.compile(r"localhost|.*\.localhost|\[.*\]|.*:.*|(?:.*\.)?(?:0x[0-9a-f]*|[0-9]+)")


def safe_link(url: str) -> bool:
    """Whether a link may be followed: http(s), mailto, or a relative/in-page address.

    Browsers ignore tabs, newlines and leading spaces in a scheme (``java\\tscript:``),
    and decode character references before the page is parsed: both are looked through,
    and percent-escapes too (to be on the safe side).
    """
    text = "".join(c for c in unquote(html.unescape(url)) if c not in "\t\n\r").strip()
    text = "".join(c for c in text if ord(c) > 32)
    match = _SCHEME.match(text)
    if match is None:
        return not text.startswith("//")   # a scheme-relative address is another server's
    return match[1].lower() in _SAFE_SCHEMES


def external_link(url: str) -> bool:
    """Whether a link may stay a link: ``mailto:``, or ``http(s)://`` naming another machine.

    Read as a browser reads an ``href``: C0 controls and spaces trimmed, tabs and newlines
    removed anywhere, ``\\`` as ``/`` and the host percent-decoded. Anything without a
    scheme (``../x``, ``/x``, ``?x``, ``#x``, ``//host``), ``http:x`` or ``http:/x`` (both
    resolve against the page's own address), a host that is this machine (``localhost``,
    ``*.localhost``) or any IP literal (``127.1``, ``0x7f.1``, ``[::1]``: the loopback has
    many spellings) is not.
    """
    text = "".join(c for c in str(url) if c not in "\t\n\r").strip("".join(map(chr, range(33))))
    match = _SCHEME.match(text)
    if match is None:
        return False
    scheme = match[1].lower()
    if scheme == "mailto":
        return True
    rest = text[match.end():].replace("\\", "/")
    if scheme not in ("http", "https") or not rest.startswith("//"):
        return False
    host = unquote(re.split(r"[/?#]", rest[2:], maxsplit=1)[0].rsplit("@", 1)[-1])
    # IDNA maps full-width letters and the ideographic full stops: ｌｏｃａｌｈｏｓｔ is localhost
    # (and markdown-it writes such a host as punycode, xn--...).
    host = ".".join(_punycode(label) for label in host.split("."))
    host = re.sub("[\u3002\uff0e\uff61]", ".", unicodedata.normalize("NFKC", host)).casefold()
    host = re.sub(r":\d*$", "", host).rstrip(".")
    return bool(host) and not _LOCAL_HOST.fullmatch(host)


def _punycode(label: str) -> str:
    if label[:4].lower() != "xn--":
        return label
    try:
        return label[4:].encode("ascii").decode("punycode")
    except (UnicodeError, ValueError):
        return label


def figure_name(src: str) -> str:
    """The figure an image names: ``figures/lab07.ex1.png`` -> ``lab07.ex1``."""
    name = PurePosixPath(src.replace("\\", "/").split("?")[0].split("#")[0]).name
    return name[:-4] if name.lower().endswith(".png") else name


def _parser():
    from markdown_it import MarkdownIt

    md = MarkdownIt("commonmark", {"html": False, "linkify": False, "typographer": False,
                                   "maxNesting": MAX_NESTING})
    md.validateLink = lambda url: safe_link(url)
    return md


_MD = None


def render_markdown(text: str, figure_url: Callable[[str], str | None] | None = None,
                    limit: int = MAX_MARKDOWN_CHARS) -> Markup:
    """``text`` (Markdown) as safe HTML (see the module docstring).

    ``figure_url(name)`` gives the address of the grader-made figure ``name``
    (``"lab07.ex1"``), or None when there is none; without it no image is shown.
    """
    global _MD
    if _MD is None:
        _MD = _parser()
    text = printable(text or "")
    cut = len(text) > limit
    text = text[:limit]
    tokens = _MD.parse(text)
    for token in tokens:
        inert = None   # the target of the link being made text (links do not nest)
        for child in token.children or ():
            if child.type == "image":
                _figure_or_alt(child, figure_url)
            elif child.type == "link_open" and external_link(str(child.attrs.get("href", ""))):
                child.attrs["rel"] = "noopener noreferrer nofollow"
                child.attrs["target"] = "_blank"
            elif child.type == "link_open":
                # An autolink's text is its target already; another link's text is followed by it.
                inert = "" if child.markup == "autolink" else f" [link not followed: {child.attrs.get('href', '')}]"
                _as_text(child, "")
            elif child.type == "link_close" and inert is not None:
                _as_text(child, inert)
                inert = None
    body = _MD.renderer.render(tokens, _MD.options, {})
    if cut:
        body += f'<p class="muted">(cut: only the first {limit:,} characters are shown)</p>'
    return Markup(body)


def _figure_or_alt(token, figure_url) -> None:
    """An image becomes the grader's figure it names, or its alt text (never a fetch)."""
    src = str(token.attrs.get("src", ""))
    url = figure_url(figure_name(src)) if figure_url and safe_link(src) and not _SCHEME.match(src.strip()) else None
    alt = "".join(c.content for c in token.children or () if c.type in ("text", "code_inline")) or token.content
    if url:
        token.attrs = {"src": url, "alt": alt}
        return
    _as_text(token, f"[image not shown: {alt or src}]")   # the alt, marked as an image not shown


def _as_text(token, content: str) -> None:
    """``token`` (a link's or an image's) rendered as ``content``, escaped like any text."""
    token.type, token.tag, token.nesting, token.children, token.attrs = "text", "", 0, None, {}
    token.content = content
