"""Standalone HTML (BokehJS inlined: opens offline) and PNG, SVG and PDF pictures of the
figures.

All pictures are made from the HTML by headless Chromium through Playwright (Bokeh's own
``export_png``/``export_svg`` need Selenium and a driver; Playwright drives Debian's
``chromium``): PNGs are screenshots; SVGs are drawn by BokehJS itself into an SVG context
(``view.export("svg")``, what ``bokeh.io.export_svg`` runs), so lines, markers and text
stay vectors; PDFs are Chromium's print of that SVG (vector too), one page the size of
the figure. Every picture carries the package version (SVG ``<metadata>``, PNG text
chunks, PDF via its SVG's title), as the CSVs do in their header.
"""
from __future__ import annotations

import os
import shutil
from pathlib import Path

from bokeh.io import save
from bokeh.resources import INLINE

from ..about import PAPER_DOI, version_text

#: Picture formats the browser makes (HTML is always written).
FORMATS = ("png", "svg", "pdf")

CHROMIUM_FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking",
                  "--disable-component-update", "--no-first-run", "--disable-sync",
                  "--disable-dev-shm-usage"]


#: Right and bottom edges of everything drawn on the page.
_EXTENT = """() => { let w = 0, h = 0;
  for (const el of document.querySelectorAll('body *')) {
    const r = el.getBoundingClientRect();
    if (r.width > 0 && r.height > 0) { w = Math.max(w, r.right); h = Math.max(h, r.bottom); }
  } return [w, h]; }"""


def save_html(model, path: Path, title: str) -> Path:
    save(model, filename=str(path), resources=INLINE, title=f"{title} ({version_text()})")
    return path


def chromium() -> str | None:
    """The Chromium executable to use, or None: ``$MICROPILLAR_CHROMIUM``, else Debian's."""
    for candidate in (os.environ.get("MICROPILLAR_CHROMIUM"), "/usr/bin/chromium",
                      shutil.which("chromium")):
        if candidate and os.access(candidate, os.X_OK):
            return candidate
    return None


def browser_problem() -> str | None:
    """Why PNGs cannot be made here (None when they can)."""
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        return "Playwright is not installed (pip install '.[test]')"
    if chromium() is None:
        return "no Chromium found (apt-get install chromium)"
    return None


#: Every root of the page's document exported by BokehJS as one SVG document (a row of
#: plots becomes one SVG); the page's other views (notifications) are not roots.
_SVG_EXPORT = """() => { const roots = new Set(Bokeh.documents[0].roots().map(r => r.id));
  const out = [];
  for (const view of Bokeh.index) {
    if (roots.has(view.model.id)) { const {ctx} = view.export("svg");
                                    out.push(ctx.get_serialized_svg(true)); }
  } return out; }"""


def _escape(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def with_metadata(svg: str, title: str) -> str:
    """``svg`` with a ``<title>``, a ``<desc>`` and a ``<metadata>`` naming the figure, the
    package version and the paper, right after the opening ``<svg>`` tag."""
    import json

    meta = {"software": version_text(), "figure": title, "paper_doi": PAPER_DOI}
    head_end = svg.index(">", svg.index("<svg")) + 1
    return (svg[:head_end] + f"<title>{_escape(title)}</title>"
            f"<desc>{_escape(title)}; drawn by {_escape(version_text())}</desc>"
            f"<metadata>{_escape(json.dumps(meta, ensure_ascii=False))}</metadata>"
            + svg[head_end:])


def _png_metadata(path: Path, title: str) -> None:
    """Write the version and the figure's title into the PNG's text chunks."""
    from PIL import Image
    from PIL.PngImagePlugin import PngInfo

    info = PngInfo()
    info.add_text("Software", version_text())
    info.add_itxt("Title", title)
    with Image.open(path) as image:
        image.load()
        image.save(path, pnginfo=info)


def _open(page, html) -> None:
    page.goto(Path(html).resolve().as_uri())
    # BokehJS calls its document idle once every root's view has been laid out and painted.
    page.wait_for_function("() => window.Bokeh && Bokeh.documents.length > 0 && "
                           "document.querySelector('.bk-Figure, .bk-Row, "
                           ".bk-Column, .bk-GridPlot') !== null && "
                           "Bokeh.documents[0].is_idle", timeout=30_000)


def _settled_extent(page, timeout_ms: int = 10_000) -> tuple[float, float]:
    """The content's extent once BokehJS has finished laying it out (two readings 200 ms
    apart agree): on a busy machine the first layout pass can still be under way."""
    last, waited = None, 0
    while waited < timeout_ms:
        now = tuple(page.evaluate(_EXTENT))
        if now == last:
            return now
        last = now
        page.wait_for_timeout(200)
        waited += 200
    return last


def _screenshot(page, png: Path) -> None:
    """The page in a viewport as wide as its content, captured whole."""
    w, h = _settled_extent(page)
    page.set_viewport_size({"width": max(400, int(w) + 24), "height": max(300, int(h) + 24)})
    page.wait_for_timeout(100)
    w, h = page.evaluate(_EXTENT)
    page.screenshot(path=str(png), clip={"x": 0, "y": 0, "width": int(w) + 8,
                                         "height": int(h) + 8})


def _svg_size(svg: str) -> tuple[int, int]:
    import xml.etree.ElementTree as ET

    root = ET.fromstring(svg)
    return int(float(root.get("width"))), int(float(root.get("height")))


def pictures(jobs: list, progress=None) -> list:
    """Make pictures in one browser session. ``jobs``: ``(html, title, {format: path})``
    with formats among ``FORMATS``; returns the paths written, per job."""
    from playwright.sync_api import sync_playwright

    done = []
    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=chromium(), args=CHROMIUM_FLAGS)
        try:
            page = browser.new_page(viewport={"width": 800, "height": 600})
            for i, (html, title, targets) in enumerate(jobs):
                _open(page, html)
                written = {}
                if "png" in targets:
                    _screenshot(page, targets["png"])
                    _png_metadata(targets["png"], title)
                    written["png"] = Path(targets["png"])
                if "svg" in targets or "pdf" in targets:
                    svgs = page.evaluate(_SVG_EXPORT)
                    if len(svgs) != 1:
                        raise RuntimeError(f"{html}: {len(svgs)} figures to export, not one")
                    svg = with_metadata(svgs[0], title)
                    svg_path = Path(targets.get("svg") or Path(targets["pdf"]).with_suffix(
                        ".pdf.svg"))
                    svg_path.write_text(svg, encoding="utf-8")
                    if "svg" in targets:
                        written["svg"] = svg_path
                    if "pdf" in targets:
                        w, h = _svg_size(svg)
                        page.goto(svg_path.resolve().as_uri())
                        # The SVG's <title> becomes the PDF's: name the version there too.
                        page.evaluate("t => { document.title = t; }",
                                      f"{title} ({version_text()})")
                        page.pdf(path=str(targets["pdf"]), width=f"{w}px", height=f"{h}px",
                                 print_background=True, page_ranges="1")
                        written["pdf"] = Path(targets["pdf"])
                        if "svg" not in targets:
                            svg_path.unlink()
                done.append(written)
                if progress is not None:
                    progress(i + 1, len(jobs))
        finally:
            browser.close()
    return done


def html_to_png(pages: list, progress=None) -> list:
    """Screenshot each ``(html, png)`` pair in one browser session; returns the PNG paths."""
    jobs = [(html, Path(html).stem, {"png": png}) for html, png in pages]
    return [w["png"] for w in pictures(jobs, progress)]
