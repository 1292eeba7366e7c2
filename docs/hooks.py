"""MkDocs hook: put the generated reference (scene format, command line, lessons) into pages.

A page holds a marker such as ``<!-- generated: scene-reference -->``; at build time it is
replaced by the Markdown that :mod:`sandbox.reference` makes from the validator's and the
parser's own descriptions, so the reference cannot drift from the code.
"""

from __future__ import annotations

from pathlib import Path

from sandbox.reference import cli_reference, lesson_list, scene_reference

ROOT = Path(__file__).resolve().parent.parent
GENERATORS = {
    "scene-reference": scene_reference,
    "cli-reference": cli_reference,
    "lesson-list": lambda: lesson_list(ROOT / "lessons"),
}


def on_page_markdown(markdown: str, page, config, files) -> str:
    for name, make in GENERATORS.items():
        marker = f"<!-- generated: {name} -->"
        if marker in markdown:
            markdown = markdown.replace(marker, make())
    return markdown
