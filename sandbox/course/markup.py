"""The little Markdown and TeX the course pages need, turned into HTML that works offline.

Formulas (``$...$`` inline, ``$$...$$`` displayed) become MathML, which browsers draw without any
script or web font. ``latex2mathml`` (in the ``notebook`` extra) converts them; without it, or for
a formula it cannot read, the TeX source is shown as code.
"""

from __future__ import annotations

import html
import re

# $$display$$ first, then $inline$ (no space just inside the dollars, no $ within)
MATH = re.compile(
    r"\$\$(.+?)\$\$|(?<![\\$])\$(?![\s$])((?:[^$\\\n]|\\.|\n(?!\s*\n))+?)(?<!\s)\$", re.S
)
CODE = re.compile(r"(```.*?```|(`+).+?\2)", re.S)
TOKEN = "sbxmath{}x"  # survives Markdown untouched: letters and digits only


def tex_to_html(tex: str, display: bool = False) -> str:
    """MathML for one formula; its TeX as ``<code>`` when it cannot be converted."""
    try:
        from latex2mathml.converter import convert

        return convert(tex.strip(), display="block" if display else "inline")
    except Exception:  # not installed, or TeX it does not read: show the source
        shown = html.escape(tex.strip())
        return (
            f'<code class="tex">{"$$" if display else "$"}{shown}{"$$" if display else "$"}</code>'
        )


def protect_math(markdown: str, fragments: list[str] | None = None) -> tuple[str, list[str]]:
    """Replace each formula outside code by a token; returns the text and the formulas' HTML
    (token ``i`` stands for ``fragments[i]``; pass ``fragments`` to go on numbering a list)."""
    fragments = [] if fragments is None else fragments

    def swap(match: re.Match) -> str:
        display = match.group(1) is not None
        fragments.append(tex_to_html(match.group(1) if display else match.group(2), display))
        return TOKEN.format(len(fragments) - 1)

    pieces = CODE.split(markdown)
    out = []
    # re.split with two groups yields: text, whole code, inner backticks, text, ...
    for i in range(0, len(pieces), 3):
        out.append(MATH.sub(swap, pieces[i]))
        if i + 1 < len(pieces):
            out.append(pieces[i + 1])
    return "".join(out), fragments


def restore_math(text: str, fragments: list[str]) -> str:
    """Put the formulas' HTML back in place of their tokens (a token that ended up inside a
    tag, e.g. in a heading's ``id``, is dropped there)."""
    if not fragments:
        return text
    token = re.compile(r"sbxmath(\d+)x")
    text = re.sub(r"<[^<>]*>", lambda tag: token.sub("", tag.group(0)), text)
    return token.sub(lambda m: fragments[int(m.group(1))], text)


def inline_html(markdown: str) -> str:
    """HTML for one paragraph of Markdown: code spans, **bold**, *italic*, links, formulas."""
    text, fragments = protect_math(markdown)
    parts = CODE.split(text)
    out = []
    for i in range(0, len(parts), 3):
        piece = html.escape(parts[i], quote=False)
        piece = re.sub(r"\*\*(.+?)\*\*", r"<strong>\1</strong>", piece)
        piece = re.sub(r"(?<![\w*])\*(?!\s)(.+?)(?<!\s)\*(?![\w*])", r"<em>\1</em>", piece)
        piece = re.sub(r"\[([^\]]+)\]\(([^)\s]+)\)", _link, piece)
        out.append(piece)
        if i + 1 < len(parts):
            out.append(f"<code>{html.escape(parts[i + 1].strip('`'))}</code>")
    return restore_math("".join(out), fragments)


def _link(match: re.Match) -> str:
    return f'<a href="{html.escape(match.group(2), quote=True)}">{match.group(1)}</a>'
