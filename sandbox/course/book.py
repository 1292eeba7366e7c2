"""The course book: ``outputs/index.html``, one card per lesson with its title, its opening
paragraph, a thumbnail and links to its page, its notebook, its tables and each figure and
animation it made. Plain HTML and CSS with relative links only: it opens from a USB stick, with
no network, in any browser.
"""

from __future__ import annotations

import html
from collections.abc import Sequence
from pathlib import Path
from urllib.parse import quote

from sandbox.course.catalogue import Lesson
from sandbox.course.markup import inline_html

FIGURES = (".png", ".gif")

STYLE = """
body { font: 15px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; margin: 0;
  color: #1d2430; background: #f4f6f9; }
header { padding: 20px 32px 8px; }
header h1 { margin: 0 0 6px; font-size: 26px; }
header p { margin: 4px 0; color: #4a5565; max-width: 70em; }
main { display: grid; grid-template-columns: repeat(auto-fill, minmax(340px, 1fr)); gap: 18px;
  padding: 16px 32px 40px; }
article { background: #fff; border: 1px solid #d8dde5; border-radius: 8px; padding: 14px 16px;
  display: flex; flex-direction: column; }
article h2 { font-size: 18px; margin: 10px 0 4px; }
article p { margin: 4px 0; }
a { color: #1f5fbf; text-decoration: none; }
a:hover { text-decoration: underline; }
.thumb { display: block; height: 190px; background: #fafbfc; border: 1px solid #eceff3;
  border-radius: 4px; overflow: hidden; }
.thumb img { width: 100%; height: 100%; object-fit: contain; }
.thumb span { display: block; padding: 80px 0; text-align: center; color: #8a94a3; }
.opening { color: #3b4555; font-size: 14px; }
.links { margin-top: 8px; font-weight: 600; }
.links a { margin-right: 14px; }
.files { margin: 8px 0 0; padding: 0; font-size: 13px; list-style: none; display: flex;
  flex-wrap: wrap; gap: 2px 16px; }
.missing { color: #8a94a3; font-size: 13px; }
math { font-size: 105%; }
"""


def made_files(folder: Path) -> list[Path]:
    """The figures and animations in a lesson's folder (and its subfolders), in the order made."""
    if not folder.is_dir():
        return []
    found = [p for p in folder.rglob("*") if p.is_file() and p.suffix.lower() in FIGURES]
    return sorted(found, key=lambda p: (p.stat().st_mtime_ns, p.as_posix()))


def href(path: Path, root: Path) -> str:
    """``path`` as a relative, URL-quoted link from ``root``."""
    return quote(path.relative_to(root).as_posix())


def card(lesson: Lesson, outputs: Path) -> str:
    """One lesson's card (HTML)."""
    folder = outputs / lesson.stem
    title = html.escape(lesson.title)
    page = folder / f"{lesson.stem}.html"
    notebook = folder / f"{lesson.stem}.ipynb"
    tables = folder / "tables.md"
    files = made_files(folder)
    pngs = [p for p in files if p.suffix.lower() == ".png"]
    pictures = [p for p in pngs if p.parent == folder] + [p for p in pngs if p.parent != folder]
    main = page if page.exists() else (pictures[0] if pictures else None)
    if pictures:
        thumb = f'<img src="{href(pictures[0], outputs)}" alt="{title}: {pictures[0].stem}">'
    else:
        thumb = "<span>no figure yet</span>"
    parts = [f'<article id="{html.escape(lesson.stem)}">']
    if main is not None:
        parts.append(f'<a class="thumb" href="{href(main, outputs)}">{thumb}</a>')
        parts.append(f'<h2><a href="{href(main, outputs)}">{title}</a></h2>')
    else:
        parts.append(f'<div class="thumb">{thumb}</div><h2>{title}</h2>')
    parts.append(f'<p class="opening">{inline_html(lesson.opening)}</p>')
    links = [
        f'<a href="{href(p, outputs)}">{text}</a>'
        for text, p in (("page", page), ("notebook", notebook), ("tables", tables))
        if p.exists()
    ]
    if links:
        parts.append(f'<p class="links">{"".join(links)}</p>')
    if not files and not links:
        command = f"sandbox lessons {lesson.number:02d}"
        parts.append(f'<p class="missing">not made yet: <code>{command}</code></p>')
    if files:
        items = "".join(
            f'<li><a href="{href(p, outputs)}">{html.escape(p.relative_to(folder).as_posix())}</a>'
            f"{' (animation)' if p.suffix.lower() == '.gif' else ''}</li>"
            for p in files
        )
        parts.append(f'<ul class="files">{items}</ul>')
    parts.append("</article>")
    return "\n".join(parts)


def book_html(lessons: Sequence[Lesson], outputs: Path, note: str = "") -> str:
    """The whole course book page."""
    cards = "\n".join(card(lesson, outputs) for lesson in lessons)
    extra = f"<p>{html.escape(note)}</p>" if note else ""
    return f"""<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>Physics sandbox: the course</title>
<style>{STYLE}</style>
</head>
<body>
<header>
<h1>Physics sandbox: the course</h1>
<p>{len(lessons)} lessons on physics-based animation. Each card opens the lesson's page: the
lesson run as a notebook, its explanations, code, printed tables, figures and animations.
The notebook itself opens in JupyterLab, where the explorer cells have live sliders.</p>
{extra}
</header>
<main>
{cards}
</main>
</body>
</html>
"""


def write_book(lessons: Sequence[Lesson], outputs: Path, note: str = "") -> Path:
    """Write ``outputs/index.html`` (whole or not at all) and return its path."""
    from sandbox.atomic import atomic_write_text

    path = outputs / "index.html"
    atomic_write_text(path, book_html(lessons, outputs, note))
    return path
