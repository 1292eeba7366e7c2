"""The generated parts of the user reference (Markdown), built from the same descriptions the
validator and the parser use, so the docs cannot drift from them.

- :func:`scene_reference`: every object and field of a scene file (type, unit, default, range)
- :func:`cli_reference`: every command and option of ``sandbox`` with its help and default
- :func:`lesson_list`: one line per lesson, from each lesson's title and opening sentence

The docs' MkDocs hook (``docs/hooks.py``) puts them into the pages at build time.
"""

from __future__ import annotations

import argparse
import re
import textwrap
from pathlib import Path

from sandbox.fieldspec import Field
from sandbox.scene_spec import OBJECTS, UNIONS

__all__ = ["cli_reference", "lesson_list", "scene_reference"]

_TYPES = {
    "number": "number",
    "integer": "integer",
    "vector": "[x, y]",
    "boolean": "boolean",
    "string": "string",
    "choice": "string",
    "version": "integer",
    "vertices": "[[x, y], ...]",
    "limits": "[lo, hi]",
    "body": "body name",
    "bodies": "[body name, ...]",
}
_PLURAL = {"body": "bodies"}
_SECTIONS = (
    ("The file", ("scene",)),
    ("Settings", ("settings",)),
    ("Bodies", ("body",)),
    ("Shapes", UNIONS["shape"]),
    ("Joints", (*UNIONS["joint"], "motor")),
    ("Forces", UNIONS["force"]),
)


def _type(field: Field) -> str:
    if field.kind == "list":
        return f"list of {_PLURAL.get(field.item, field.item + 's')}"
    if field.kind == "object":
        return f"{field.item} object"
    text = _TYPES[field.kind]
    return f"{text} or null" if field.nullable else text


def _cell(text: str) -> str:
    return text.replace("|", "\\|")


def _row(field: Field) -> str:
    valid = field.range_text() or ("`1`" if field.kind == "version" else "-")
    if field.kind == "choice":
        valid = ", ".join(f"`{c}`" for c in field.choices)
    unit = field.unit or "-"
    default = field.describe_default()
    default = default if default == "required" else f"`{default}`"
    cells = (f"`{field.name}`", _type(field), unit, default, valid, field.doc)
    return "| " + " | ".join(_cell(c) for c in cells) + " |"


def object_table(name: str) -> str:
    """The Markdown table of one object of the format."""
    spec = OBJECTS[name]
    head = "| field | type | unit | default | valid values | meaning |\n|---|---|---|---|---|---|"
    rows = [_row(f) for f in spec.fields]
    return f"{head}\n" + "\n".join(rows)


def scene_reference() -> str:
    """Every object of the scene format with a table of its fields (Markdown)."""
    parts = []
    for title, names in _SECTIONS:
        parts.append(f"## {title}\n")
        for name in names:
            spec = OBJECTS[name]
            if len(names) > 1:
                parts.append(f"### `{name}`\n")
            parts.append(f"{spec.doc[:1].upper()}{spec.doc[1:]}.\n")
            parts.append(object_table(name) + "\n")
    return "\n".join(parts)


def _subcommands(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return dict(action.choices)
    return {}


def _option_row(action: argparse.Action, formatter: argparse.HelpFormatter) -> str:
    names = ", ".join(action.option_strings) or action.metavar or action.dest
    if action.option_strings and action.nargs != 0:
        metavar = action.metavar or action.dest.upper()
        if action.choices:
            metavar = "{" + ",".join(map(str, action.choices)) + "}"
        names += f" {metavar}"
    text = formatter._get_help_string(action) % vars(action) if action.help else ""
    return f"| `{_cell(names)}` | {_cell(text)} |"


def cli_reference() -> str:
    """Every command of ``sandbox`` with its options, their help and defaults, and examples."""
    from sandbox.cli import build_parser

    parser = build_parser()
    formatter = parser._get_formatter()
    parts = ["```text\n" + parser.format_usage().strip() + "\n```\n"]
    for name, sub in _subcommands(parser).items():
        parts.append(f"## `sandbox {name}`\n")
        parts.append((sub.description or "").replace("\n", " ") + "\n")
        parts.append("```text\n" + sub.format_usage().strip() + "\n```\n")
        shown = [a for a in sub._actions if a.dest != "help" and a.help != argparse.SUPPRESS]
        rows = [_option_row(a, formatter) for a in shown]  # not the hidden ones
        if rows:
            parts.append("| argument | what it does |\n|---|---|\n" + "\n".join(rows) + "\n")
        if sub.epilog:
            examples = textwrap.dedent(sub.epilog.replace("examples:\n", "")).rstrip()
            parts.append("**Examples**\n\n```sh\n" + examples + "\n```\n")
    return "\n".join(parts)


_TITLE = re.compile(r"^# # (.+)$", re.M)


def lesson_list(folder: Path) -> str:
    """One Markdown list item per lesson in ``folder``: number, title and opening sentence."""
    items = []
    for path in sorted(folder.glob("[0-9][0-9]_*.py")):
        text = path.read_text(encoding="utf-8")
        title = _TITLE.search(text)
        heading = title.group(1).strip() if title else path.stem
        after = text[title.end() :] if title else ""
        para = []
        for line in after.splitlines()[1:]:
            line = line.removeprefix("#").strip()
            if not line:
                if para:
                    break
                continue
            para.append(line)
        sentence = _first_sentence(" ".join(para))
        items.append(f"- **{heading}** (`lessons/{path.name}`): {sentence}")
    return "\n".join(items)


_SENTENCE_END = re.compile(r"(?<!e\.g)(?<!i\.e)\.\s+(?=[A-Z])")


def _first_sentence(text: str, limit: int = 170) -> str:
    """The first sentence of ``text``, cut at a clause boundary when longer than ``limit``."""
    sentence = _SENTENCE_END.split(text, maxsplit=1)[0].rstrip(".")
    if "$" in sentence:  # no formulas in a one-line summary: stop before the first
        limit = min(limit, sentence.index("$"))
    if len(sentence) > limit:
        cut = max(sentence.rfind(";", 0, limit), sentence.rfind(",", 0, limit))
        sentence = sentence[: cut if cut > 40 else limit].rstrip() + " ..."
        return sentence
    return sentence + "."
