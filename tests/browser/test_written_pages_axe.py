"""The pages the project writes pass axe-core's WCAG 2.1 A/AA rules too: the reproduction's
``index.html`` and its figures' HTML (``python -m app.reproduce``, a coarse run without
pictures), the exported animation pages (``app.figures.animation_page``) and the server's
busy page (``app/static/busy.html``), each opened from its file in headless Chromium."""
from __future__ import annotations

import pytest

from app.figures.animation_page import array_document, page_html, support_document
from app.opening import BUSY_FILE
from app.reproduce import reproduce
from model import REGIMES

from . import axe_tools
from .conftest import unavailable
from .serving import VIEWPORT

pytestmark = [pytest.mark.browser, pytest.mark.timeout(600)]


@pytest.fixture(scope="module")
def written(tmp_path_factory) -> list:
    """Every HTML file a coarse reproduction and the animation export write."""
    if not axe_tools.AXE_JS.exists():
        unavailable(f"axe-core is not installed at {axe_tools.AXE_JS} "
                    f"({axe_tools.INSTALL_HINT})")
    out = tmp_path_factory.mktemp("written")
    reproduce(out / "reproduction", resolution="coarse", png=False)
    for name, document in (("array", array_document), ("support", support_document)):
        doc = document(REGIMES["soft"])[0]
        (out / f"animation-{name}.html").write_text(page_html(doc), encoding="utf-8")
    return sorted(out.glob("**/*.html")) + [BUSY_FILE]


def test_the_written_pages_have_no_wcag_violation(browser, written):
    assert any(p.name == "index.html" for p in written) and len(written) >= 16, written
    context = browser.new_context(viewport=VIEWPORT)
    found = {}
    try:
        page = context.new_page()
        for path in written:
            page.goto(path.as_uri())
            page.wait_for_load_state("load")
            page.wait_for_timeout(300)  # BokehJS draws the document after the load
            violations = axe_tools.violations(page)
            if violations:
                found[path.name] = axe_tools.describe(violations)
    finally:
        context.close()
    assert not found, "axe-core's WCAG 2.1 A/AA violations:\n" + "\n".join(
        f"[{name}]\n{text}" for name, text in found.items())
