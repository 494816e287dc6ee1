"""BokehJS: every paint of a figure rewrites its renderers' ``<style>`` elements with the
text they already have, and each rewrite makes the next ``getComputedStyle`` (text and
fill colours are read from CSS at paint time) recalculate the figure's styles.

Bokeh 3.9.2. ``RendererView.paint`` calls ``update_position`` at every paint, which calls
``InlineStyleSheet.replace`` -> ``_update``: ``this.el.textContent = css``, unconditionally
(``core/dom``). A figure with a line, a legend and its axes repainted with new data: each
repaint rewrites ~9 ``<style>`` elements, 7 of them with their own text.
Expected: an unchanged stylesheet is not written again (``if (this.el.textContent !== css)``).

Run: ``python docs/upstream/bokehjs_style_rewrite.py``: a standalone page (``file_html``,
BokehJS inlined) in headless Chromium; ``REPAINTS`` new data; prints the rewrites per
repaint with the same text and with another, BokehJS's own method and with the one-line
change. Here (2026-11-28, Chromium, Bokeh 3.9.2): reproduced, per repaint 7.4 rewrites with the
same text and 1.4 with another; with the one-line change 0.0 and 1.4.
The workaround in this project: ``app/offline/bokeh_fix.js`` (the offline explorer only,
guarded by the BokehJS version; a key press there: 35 identical rewrites per press
removed, the press's paint ~20-25 % shorter, docs/performance-record.md).
"""
import tempfile
from pathlib import Path

from bokeh.embed import file_html
from bokeh.plotting import figure
from bokeh.resources import INLINE

from harness import CHROMIUM, CHROMIUM_FLAGS

REPAINTS = 10

COUNT = """async ([repaints, fixed]) => {
  const proto = Bokeh.require("core/dom").InlineStyleSheet.prototype, own = proto._update;
  if (fixed) proto._update = function (css) { if (this.el.textContent !== css) own.call(this, css); };
  const writes = {same: 0, changed: 0};
  const seen = (records) => records.forEach((r) => {
    if (r.type !== "childList" || r.target.tagName !== "STYLE") return;
    const old = [...r.removedNodes].map((n) => n.textContent).join("");
    const now = [...r.addedNodes].map((n) => n.textContent).join("");
    writes[old === now ? "same" : "changed"] += 1;
  });
  const watch = (root) => {
    new MutationObserver(seen).observe(root, {childList: true, subtree: true});
    root.querySelectorAll("*").forEach((el) => { if (el.shadowRoot) watch(el.shadowRoot); });
  };
  watch(document);
  const source = Bokeh.documents[0].get_model_by_name("line");
  for (let i = 0; i < repaints; i++) {
    source.data = {x: [0, 1, 2], y: [0, Math.sin(i), 1]};
    await new Promise((done) => requestAnimationFrame(() => setTimeout(done, 30)));
  }
  proto._update = own;
  return writes;
}"""


def main() -> None:
    from playwright.sync_api import sync_playwright

    p = figure(width=400, height=300, title="a figure repainted with new data")
    p.line(x=[0, 1, 2], y=[0, 0.5, 1], legend_label="a line", name="line_renderer")
    p.renderers[-1].data_source.name = "line"
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "page.html"
        path.write_text(file_html(p, resources=INLINE, title="repaint"), encoding="utf-8")
        with sync_playwright() as play:
            browser = play.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_FLAGS)
            for fixed in (False, True):
                page = browser.new_page()
                page.goto(path.as_uri())
                page.wait_for_function("Bokeh.documents.length > 0 && "
                                       "document.querySelector('.bk-Figure') !== null")
                page.wait_for_timeout(500)
                got = page.evaluate(COUNT, [REPAINTS, fixed])
                label = "with the one-line change" if fixed else "BokehJS's own _update"
                print(f"{label}: per repaint {got['same'] / REPAINTS:.1f} rewrites with the "
                      f"same text, {got['changed'] / REPAINTS:.1f} with another")
                page.close()
            browser.close()


if __name__ == "__main__":
    main()
