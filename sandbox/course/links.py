"""Checking the course book offline: every local link and image must resolve, and nothing may be
loaded from the network (no remote script, style sheet, font or image)."""

from __future__ import annotations

import re
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

# (tag, attribute) pairs whose target a browser loads by itself, rather than on a click
LOADED = {("link", "href")} | {
    (tag, "src") for tag in ("img", "script", "iframe", "source", "video", "audio", "embed")
}
CSS_URL = re.compile(r"""url\(\s*['"]?([^'")\s]+)|@import\s+['"]([^'"]+)""")
# a span with a class and nothing else, or a span's end: no link, image or style in it, and most
# of a page's tags (the highlighted code): left out before parsing, which they slowed fivefold
PLAIN_SPAN = re.compile(r'<span class="[^"<>]*">|</span>')


class _References(HTMLParser):
    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.found: list[tuple[str, str, str]] = []  # (tag, attribute, value)
        self._style = False
        self.css: list[str] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        for name, value in attrs:
            if value is not None and name in ("href", "src"):
                self.found.append((tag, name, value))
            if name == "style" and value:
                self.css.append(value)
        self._style = tag == "style"

    def handle_endtag(self, tag: str) -> None:
        self._style = False

    def handle_data(self, data: str) -> None:
        if self._style:
            self.css.append(data)


def references(text: str) -> tuple[list[tuple[str, str, str]], list[str]]:
    """``(tag, attribute, value)`` of every href and src in an HTML text, and the URLs its CSS
    loads (``url(...)``, ``@import``)."""
    parser = _References()
    parser.feed(PLAIN_SPAN.sub("", text))
    css = [a or b for chunk in parser.css for a, b in CSS_URL.findall(chunk)]
    return parser.found, css


def _remote(value: str) -> bool:
    parts = urlsplit(value)
    return bool(parts.scheme and parts.scheme not in ("data", "file")) or value.startswith("//")


def page_problems(page: Path) -> list[str]:
    """What is wrong with one page: local links or images that do not resolve, and anything
    the browser would fetch from the network. Empty when the page works from a USB stick."""
    text = page.read_text(encoding="utf-8")
    found, css = references(text)
    problems = [f"{page.name}: loads {url} from the network" for url in css if _remote(url)]
    for tag, attr, value in found:
        if _remote(value):
            if (tag, attr) in LOADED:
                problems.append(f"{page.name}: <{tag} {attr}> loads {value} from the network")
            continue  # a hyperlink to a web page is fine: nothing is fetched until clicked
        parts = urlsplit(value)
        if parts.scheme == "data" or not parts.path:
            continue  # embedded, or an anchor in this page
        if not (page.parent / unquote(parts.path)).exists():
            problems.append(f"{page.name}: <{tag} {attr}={value!r}> does not resolve")
    return problems


def book_problems(index: Path) -> list[str]:
    """:func:`page_problems` of the course book and of every local HTML page it links to."""
    problems = page_problems(index)
    found, _ = references(index.read_text(encoding="utf-8"))
    pages = {
        index.parent / unquote(urlsplit(value).path)
        for _, _, value in found
        if not _remote(value) and urlsplit(value).path.endswith(".html")
    }
    for page in sorted(pages):
        if page.exists():
            problems += page_problems(page)
    return problems
