"""The served page's HTML head: ``<meta name="viewport">``, so that a phone lays the page
out at its own width.

Without it a phone lays every page out 980 px wide and then scales it down (to ~0.4 on a
390-px phone: text ~5 px, buttons 13 px tall); with it the page's phone layout
(``app.views.layout``, below ``NARROW_PX``) is what a phone shows.

Panel renders a served page from the document's template (Bokeh's ``Document.template``),
a Jinja2 template that may extend Panel's own page (``{% extends base %}``, the variable
Panel and Bokeh pass to it): ``PAGE_TEMPLATE`` keeps that page and adds the meta tag to
its head (the ``postamble`` block of Panel's ``_templates/base.html``).
"""
from __future__ import annotations

#: The meta tag a phone needs to lay the page out at its own width.
VIEWPORT_META = '<meta name="viewport" content="width=device-width, initial-scale=1">'

#: Panel's page with the meta tag in its head (a string: Panel extends ``base`` with it).
PAGE_TEMPLATE = "{% block postamble %}{{ super() }}\n" + VIEWPORT_META + "\n{% endblock %}"


def use_page_template(doc) -> None:
    """Serve ``doc`` (the page's Bokeh document; None outside a server) with
    ``PAGE_TEMPLATE``."""
    if doc is not None:
        doc.template = PAGE_TEMPLATE
