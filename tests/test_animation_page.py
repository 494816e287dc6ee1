"""The standalone animation pages (``app.figures.animation_page``) are self-contained: a
saved file loads nothing from beside it or from the network, even when the dashboard's
Panel models are imported in the same process (Bokeh then lists their external files).
The browser plays them in tests/browser/test_animation_page.py."""
import re

import app.views  # noqa: F401  (registers Panel's models, as a served process does)
from app.figures.animation_page import page_html, support_document
from model import REGIMES


def test_a_saved_page_refers_to_no_file_outside_itself():
    doc, _, _ = support_document(REGIMES["pendulum"])
    html = page_html(doc)
    assert re.findall(r'<script[^>]+src="', html) == []
    links = re.findall(r'<link[^>]+href="([^"]*)"', html)
    assert links and all(href.startswith("data:") for href in links), links
    assert "BEGIN bokeh.min.js" in html  # Bokeh inline
