"""The exporter of a lesson's page: nbconvert's HTML exporter, less two passes that change
nothing in a lesson's page and took two thirds of its time (:mod:`sandbox.course.page`).

- **Sanitizing the highlighted code.** The ``lab`` template passes every code cell, once
  highlighted by pygments, through ``clean_html`` (bleach), whatever the exporter's
  ``sanitize_html`` says: a guard against notebooks from elsewhere. A lesson's code is the
  course's own, and pygments escapes it already; here the filter keeps the text as it is.
- **Reparsing the page.** nbconvert reads the whole page back (BeautifulSoup) to give images
  without one an ``alt`` text and to make input and output areas focusable (``tabindex="0"``).
  A lesson's images always have their ``alt`` (the page's template writes it); the two
  attributes are written here into the page's text directly (:func:`finished`).

Measured on the 19 lessons' executed notebooks, one process: 9.2 s for their pages with
nbconvert's exporter, 2.9 s with this one; the pages are the same once both are read as HTML
(``tests/test_lessons.py`` compares lessons' pages, ``tests/test_course.py`` a small notebook's).
With an nbconvert whose pieces moved, the page is nbconvert's own export.
"""

from __future__ import annotations

import re

from nbconvert import HTMLExporter
from nbconvert.exporters.templateexporter import TemplateExporter

try:  # the pieces of nbconvert 7's HTMLExporter.from_notebook_node
    from nbconvert.filters.highlight import Highlight2HTML
    from nbconvert.filters.widgetsdatatypefilter import WidgetsDataTypeFilter
except ImportError:  # another nbconvert: its own export, reparse included (slower, same page)
    Highlight2HTML = WidgetsDataTypeFilter = None

# the opening tags nbconvert makes focusable: a cell's input wrapper and every output area
_FOCUSABLE = re.compile(
    r'<div class="(?:[^"]* )?(?:jp-Cell-inputWrapper|jp-OutputArea-output)(?: [^"]*)?"[^>]*'
)
_IMAGE_WITHOUT_ALT = re.compile(r"<img(?![^>]*\balt=)")
NO_ALT = "No description has been provided for this image"  # nbconvert's words


def finished(page: str) -> str:
    """``page`` with what nbconvert's reparse adds: ``tabindex="0"`` on each input wrapper and
    output area (a keyboard reaches every cell's code and output), and an ``alt`` text on an
    image without one (a lesson's figures have their own)."""
    page = _FOCUSABLE.sub(lambda tag: tag[0] + ' tabindex="0"', page)
    return _IMAGE_WITHOUT_ALT.sub(f'<img alt="{NO_ALT}"', page)


def keep(text: str) -> str:
    """The ``clean_html`` filter for the course's own pages: the text as it is."""
    return text


class LessonPageExporter(HTMLExporter):
    """nbconvert's :class:`~nbconvert.HTMLExporter` without the sanitizing of highlighted code
    and without reparsing the page (see the module)."""

    def default_filters(self):
        for name, function in super().default_filters():
            yield name, keep if name == "clean_html" else function

    def from_notebook_node(self, nb, resources=None, **kw):
        if WidgetsDataTypeFilter is None or not hasattr(self, "_init_resources"):
            return super().from_notebook_node(nb, resources, **kw)
        # HTMLExporter.from_notebook_node, up to its reparse of the page
        language = nb.metadata.get("language_info", {})
        lexer = language.get("pygments_lexer", language.get("name", None))
        highlight = self.filters.get(
            "highlight_code", Highlight2HTML(pygments_lexer=lexer, parent=self)
        )
        resources = self._init_resources(resources)
        data_types = WidgetsDataTypeFilter(
            notebook_metadata=self._nb_metadata, parent=self, resources=resources
        )
        self.register_filter("highlight_code", highlight)
        self.register_filter("filter_data_type", data_types)
        page, resources = TemplateExporter.from_notebook_node(self, nb, resources, **kw)
        return finished(page), resources
