"""An executed lesson notebook as one HTML page that works offline (from a USB stick).

nbconvert's ``lab`` template, without anything it would fetch from the network: no require.js,
no MathJax (formulas become MathML, :mod:`sandbox.course.markup`), no mermaid, no widget
manager (an explorer cell shows its figure instead). Figures and animations that sit beside the
page are linked by relative path; anything else is embedded. GIF animations play.
"""

from __future__ import annotations

import copy
import html
import threading
from pathlib import Path

from sandbox.course.markup import protect_math, restore_math
from sandbox.notebook import FILE_KEY

WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"
IMAGES = ("image/png", "image/gif")

TEMPLATE = r"""
{%- extends 'index.html.j2' -%}
{%- block html_head_js_requirejs -%}{%- endblock html_head_js_requirejs -%}
{%- block jupyter_widgets -%}{%- endblock jupyter_widgets -%}
{%- block html_head_js_mathjax -%}{%- endblock html_head_js_mathjax -%}
{%- block html_head_js_mermaidjs -%}{%- endblock html_head_js_mermaidjs -%}
{% block extra_css %}
<style type="text/css">
nav.sandbox { font: 14px system-ui, sans-serif; padding: 8px 16px; background: #f3f5f8;
  border-bottom: 1px solid #d5dae1; position: sticky; top: 0; z-index: 10; }
nav.sandbox a { margin-right: 18px; }
math[display="block"] { margin: 0.6em 0; }
code.tex { color: #555; }
</style>
{% endblock extra_css %}
{%- block body_header -%}
{{ super() }}
<nav class="sandbox">{{ resources.sandbox_nav }}</nav>
{%- endblock body_header -%}
{% macro image(output, mime, kind) -%}
<div class="jp-RenderedImage jp-OutputArea-output">
{%- set linked = output.metadata.get('filenames', {}).get(mime) %}
<img alt="{{ (output.metadata.get('sandbox_file') or kind) | escape_html }}" src="
{%- if linked %}{{ linked | posix_path | escape_html }}
{%- else %}data:{{ mime }};base64,{{ output.data[mime] | escape_html }}{% endif %}">
</div>
{%- endmacro %}
{% block data_png scoped %}{{ image(output, 'image/png', 'figure') }}{% endblock data_png %}
{% block data_other scoped %}
{%- if 'image/gif' in output.data %}{{ image(output, 'image/gif', 'animation') }}{% endif -%}
{% endblock data_other %}
"""

PRIORITY = [
    "text/html",
    "text/markdown",
    "image/svg+xml",
    "text/latex",
    "image/gif",
    "image/png",
    "image/jpeg",
    "text/plain",
]


_exporters = threading.local()  # each thread's exporter: its templates are compiled once


def page_exporter():
    """This thread's :class:`~sandbox.course.exporter.LessonPageExporter` with the page's
    template, made once (for each exporter class): compiling the templates took 0.13 s of each
    page's 0.15 s. One per thread, as lessons run side by side and the exporter keeps each
    export's filters."""
    from sandbox.course.exporter import LessonPageExporter

    if not hasattr(_exporters, "made"):
        _exporters.made = {}  # exporter class -> its exporter, in this thread
    made = _exporters.made
    exporter = made.get(LessonPageExporter)
    if exporter is None:
        from jinja2 import DictLoader
        from traitlets.config import Config

        exporter = made[LessonPageExporter] = LessonPageExporter(
            config=Config({"NbConvertBase": {"display_data_priority": PRIORITY}}),
            template_name="lab",
            extra_loaders=[DictLoader({"sandbox_page.html.j2": TEMPLATE})],
            template_file="sandbox_page.html.j2",
        )
    return exporter


def render_page(nb, folder: Path, title: str, nav: dict[str, str] | None = None) -> str:
    """The HTML page of an executed notebook ``nb`` to be written into ``folder``.

    ``nav`` maps link texts to relative addresses for the bar at the top of the page.
    """
    nb = copy.deepcopy(nb)
    nb.metadata.pop("widgets", None)
    nb.metadata["title"] = title
    fragments: list[str] = []
    for cell in nb.cells:
        if cell.cell_type == "markdown":
            cell.source, _ = protect_math(cell.source, fragments)
        for output in cell.get("outputs", []):
            _offline_output(output, folder)
    exporter = page_exporter()
    links = " ".join(
        f'<a href="{html.escape(href, quote=True)}">{html.escape(text)}</a>'
        for text, href in (nav or {}).items()
    )
    body, _ = exporter.from_notebook_node(
        nb, resources={"metadata": {"name": title}, "sandbox_nav": links}
    )
    return restore_math(body, fragments)


def _offline_output(output, folder: Path) -> None:
    """Drop an explorer's live widget (its figure stays) and link images that sit beside the
    page instead of embedding them."""
    data = output.get("data")
    if not data:
        return
    data.pop(WIDGET_VIEW, None)
    name = output.get("metadata", {}).get(FILE_KEY)
    if not name or not (folder / name).is_file():
        return
    for mime in IMAGES:
        if mime in data:
            output.metadata.setdefault("filenames", {})[mime] = name
