"""A student's Markdown is rendered inert: no script, no remote fetch, no javascript: link, bounded."""

from __future__ import annotations

import re
import time

import pytest
from hypothesis import given, strategies as st

from autograder.reports.markdown import MAX_MARKDOWN_CHARS, render_markdown, safe_link

FIGURES = {"lab07.ex1": "/r/TOKEN/figure/ada/lab07.ex1"}


def render(text: str) -> str:
    return str(render_markdown(text, figure_url=FIGURES.get))


def tags(page: str) -> list[str]:
    return re.findall(r"<\s*([a-zA-Z0-9]+)", page)


def test_markdown_is_rendered():
    page = render("# Title\n\nThe **warp** leaves *black* corners:\n\n- one\n- two\n\n`code`\n\n> quote")
    assert "<h1>Title</h1>" in page and "<strong>warp</strong>" in page and "<li>one</li>" in page
    assert "<code>code</code>" in page and "<blockquote>" in page


@pytest.mark.parametrize("attack", [
    "<script>alert(1)</script>",
    "<img src=x onerror=alert(1)>",
    '<a href="javascript:alert(1)">x</a>',
    "<iframe src=https://evil.example></iframe>",
    "<svg onload=alert(1)>",
    "<style>body{display:none}</style>",
    '<div style="background:url(https://evil.example/x)">',
    "<!-- comment --><object data=x>",
])
def test_raw_html_is_shown_as_text(attack):
    page = render(f"Before {attack} after\n\n{attack}")
    assert set(tags(page)) <= {"p"}, page
    assert "&lt;" in page


@pytest.mark.parametrize("link", [
    "javascript:alert(1)", "JAVASCRIPT:alert(1)", "java\tscript:alert(1)", "java&#x09;script:alert(1)",
    "&#106;avascript:alert(1)", "%6Aavascript:alert(1)", " javascript:alert(1)", "data:text/html,<script>1</script>",
    "vbscript:msgbox(1)", "file:///etc/passwd", "//evil.example/x",
])
def test_dangerous_links_are_not_links(link):
    for text in (f"[click]({link})", f"<{link}>", f"[click][r]\n\n[r]: {link}"):
        page = render(text)
        assert "<a " not in page, (text, page)


def test_safe_links_never_send_the_page_address_along():
    page = render("[lab sheet](https://example.org/lab) and <mailto:ta@example.org> and [top](#top)")
    assert page.count("<a ") == 2, "another machine's address and mailto: stay links"
    assert page.count('rel="noopener noreferrer nofollow"') == 2
    assert "top [link not followed: #top]" in page
    assert safe_link("https://example.org") and not safe_link("javascript:x")


# Every link that resolves against the page's own address (the review application: its rubric page
# showed a student's words in its error panel) or reaches this machine, and every dangerous scheme.
INERT_LINKS = ["rubric?error=You+passed", "../rubric?error=x", "../../t0ken/rubric", "/t0ken/review/1", "/review/0",
               "?error=x", "#frag", "#", "//evil.example/x", "///evil.example", "\\\\evil.example/x",
               "http:rubric", "http:/t0ken/rubric", "HTTP:%2F%2Fevil.example", "http://localhost:5000/t0ken/",
               "http://LOCALHOST./", "http://a.localhost/", "http://127.0.0.1:8123/t0ken/rubric", "http://127.1/",
               "http://2130706433/", "http://0x7f.0.0.1/", "http://0177.0.0.1/", "http://[::1]:8123/",
               "http://user@127.0.0.1/", "https://%6c%6f%63%61%6c%68%6f%73%74/", "https://ｌｏｃａｌｈｏｓｔ/",
               "http://10.0.0.1/", "javascript:alert(1)", "data:text/html,x", "file:///etc/passwd",
               "vbscript:x", "ftp://example.org/x"]


@pytest.mark.parametrize("link", INERT_LINKS)
def test_a_link_to_the_page_itself_or_this_machine_is_inert_text(link):
    for text in (f"see [the rubric]({link}) now", f"see [the rubric][r] now\n\n[r]: {link}", f"see <{link}> now"):
        page = render(text)
        assert "<a " not in page and "href" not in page, (text, page)
        assert "see " in page and " now" in page, "the text around it is kept"
    page = render(f"see [the rubric]({link}) now")
    assert "the rubric" in page, "the link's text is kept, as text"


@pytest.mark.parametrize("link", ["https://example.org/x", "http://docs.opencv.org/4.x/", "HTTPS://Example.ORG",
                                  "https://example.org:8443/a?b#c", "mailto:ta@example.org",
                                  "https://127.0.0.1.example/"])
def test_another_machines_address_stays_a_link_that_sends_no_referrer(link):
    page = render(f"[there]({link})")
    assert page.count("<a ") == 1 and 'rel="noopener noreferrer nofollow"' in page and 'target="_blank"' in page


def test_images_are_only_the_graders_own_figures_never_a_remote_fetch():
    page = render("![mine](figures/lab07.ex1.png) ![remote](https://evil.example/track.png) "
                  "![other](figures/lab07.ex2.png) ![proto](//evil.example/x.png) ![d](data:image/png;base64,AAAA) "
                  "![abs](https://evil.example/figures/lab07.ex1.png)")
    assert re.findall(r'<img src="([^"]*)"', page) == [FIGURES["lab07.ex1"]]
    assert not re.search(r'(src|href)="[^"]*evil', page), "nothing to fetch from elsewhere (text only)"
    assert "[image not shown: remote]" in page and "[image not shown: other]" in page
    assert "<img" not in str(render_markdown("![mine](figures/lab07.ex1.png)")), "no figures given: none shown"


def test_huge_and_deeply_nested_input_is_bounded():
    for text in ("x" * 10 * MAX_MARKDOWN_CHARS, ">" * 200_000, "[" * 100_000 + "]" * 100_000,
                 "*a" * 100_000, "- " * 50_000 + "x", "`" * 100_000, "\x00\x1b[31m\u202e\x9b" * 1000):
        start = time.process_time()
        page = render(text)
        assert len(page) < 3 * MAX_MARKDOWN_CHARS + 1000
        assert not {"\x00", "\x1b", "\u202e", "\x9b"} & set(page), "control and bidi characters removed"
        assert time.process_time() - start < 20, "bounded work (not a timing claim: a hang guard)"
    assert "cut: only the first" in render("y" * (MAX_MARKDOWN_CHARS + 1))


@given(st.text(alphabet=st.sampled_from(list("<>[]()!`*_#:/\\\"'&;=\n jJaAvVsScCrRiIpPtTdD0123456789%")),
               max_size=200))
def test_any_text_renders_without_a_script_handler_or_dangerous_link(text):
    page = render(text)
    for tag in re.findall(r"<[a-zA-Z][^>]*>", page):
        name = re.match(r"<([a-zA-Z0-9]+)", tag)[1].lower()
        assert name in {"p", "a", "img", "em", "strong", "code", "pre", "h1", "h2", "h3", "h4", "h5", "h6", "ul",
                        "ol", "li", "blockquote", "hr", "br"}, tag
        assert not re.search(r"\son[a-z]+\s*=", tag), tag
        for url in re.findall(r'(?:href|src)="([^"]*)"', tag):
            assert safe_link(url) and not url.lower().lstrip().startswith(("javascript", "data", "vbscript")), tag
