"""JavaScript shared by the served page (``app.views.access.PageAccess``) and the pages the
project writes (``app.figures.animation_page``): Bokeh and Panel draw each widget inside
its own shadow root, out of reach of the page's stylesheet and of ARIA attributes set from
Python, so a script walks the shadow roots, again whenever one of them changes.

* ``WATCH_ROOTS_JS`` defines ``watchRoots(tend, done, wide)``: calls ``tend(root)`` for
  the document and every shadow root now and after each change (debounced, 100 ms), then
  ``done(roots)``; returns a function that stops watching. A change inside one root that
  adds no shadow root (a slider's value, a label's text) tends that root alone, at once,
  unless it is inside an element matching the CSS selector ``wide``. Changes inside an element of
  class ``LIVE_CLASS`` (a player's readouts, rewritten while it plays: plain text, no
  control) are not changes of the page's structure and start no walk;
* ``HANDLE_NAMES_JS`` defines ``nameHandles(root)``: names each slider handle
  (``role="slider"``) after its slider's visible title, so a screen reader says what it
  sets ("frame", "k_r radial stiffness (log)"; a range slider's two handles: "..., from",
  "..., to"), and gives it the value the slider shows as its ``aria-valuetext`` ("0.1",
  not the log slider's position "-1.0") -- WCAG 4.1.2;
* ``FIGURE_NAMES_JS`` defines ``nameFigures(roots)``: gives each drawn Bokeh plot marked
  by ``figure_classes`` (``mark_figures``) ``role="figure"``, its title as its name and,
  when the page defines
  ``window.describeFigure(name)``, that text as its description (WCAG 1.1.1) -- for the
  pages the project writes; the served page's figures are described by
  ``app.views.access``.
"""
from __future__ import annotations

#: CSS class of the boxes of text that follow a playing animation (``app.figures.live_text``).
LIVE_CLASS = "mp-live-text"

WATCH_ROOTS_JS = f"""
const LIVE_CLASS = {LIVE_CLASS!r};
""" + """
function watchRoots(tend, done, wide) {
  const watched = new WeakSet();
  let pending = null;
  // Not a change of the page's structure: inside a live text box (its shadow root's host
  // has LIVE_CLASS: only text changes), or a stylesheet's text (BokehJS writes each
  // renderer's position as a <style>'s text whenever it paints it).
  const still = (record) => {
    if (record.target.nodeName === "STYLE") return true;
    const root = record.target.getRootNode && record.target.getRootNode();
    const host = root && root.host;
    return !!(host && host.classList && host.classList.contains(LIVE_CLASS));
  };
  // A change inside one root that adds no shadow root (a slider's value, its tooltip, a
  // label's text) needs only that root tended, not the page walked (a walk costs a frame
  // of a playing animation); a change inside an element matching ``wide`` concerns the
  // whole page (a description of figures elsewhere).
  const hosts = (node) => node.nodeType === 1 && (node.shadowRoot !== null ||
    [...node.querySelectorAll("*")].some((el) => el.shadowRoot !== null));
  const local = (record) => {
    if (wide && record.target.closest && record.target.closest(wide)) return false;
    return ![...record.addedNodes].some(hosts);
  };
  const observer = new MutationObserver((records) => {
    const changed = records.filter((r) => !still(r));
    if (pending !== null || changed.length === 0) return;
    if (!changed.every(local)) { pending = setTimeout(scan, 100); return; }
    for (const root of new Set(changed.map((r) => r.target.getRootNode()))) tend(root);
  });
  function scan() {
    pending = null;
    const roots = [];
    const visit = (root) => {
      if (!watched.has(root)) {
        watched.add(root);
        observer.observe(root, {childList: true, subtree: true});
      }
      roots.push(root);
      tend(root);
      for (const host of root.querySelectorAll("*")) {
        if (host.shadowRoot) visit(host.shadowRoot);
      }
    };
    visit(document);
    if (done) done(roots);
  }
  scan();
  return () => { observer.disconnect(); if (pending !== null) clearTimeout(pending); };
}
"""

HANDLE_NAMES_JS = """
function handleName(root, handle) {
  const title = root.querySelector(".bk-slider-title");
  if (!title) return null;
  const words = [...title.childNodes]
    .filter((n) => !(n.classList && n.classList.contains("bk-slider-value")))
    .map((n) => n.textContent).join("").replace(/:\\s*$/, "").replace(/\\s+/g, " ").trim();
  if (!words) return null;
  const handles = root.querySelectorAll(".noUi-handle");
  if (handles.length < 2) return words;
  return words + (handle.getAttribute("data-handle") === "0" ? ", from" : ", to");
}

// The value as the slider shows it ("0.1" on a log slider whose position is -1), or, for
// a range slider's handle, its end of the shown range ("0.1 .. 3").
function handleValue(root, handle) {
  const shown = root.querySelector(".bk-slider-value");
  const text = shown && shown.textContent.trim();
  if (!text) return null;
  if (root.querySelectorAll(".noUi-handle").length < 2) return text;
  const ends = text.split(/\\s*\\.\\.\\s*/);
  return ends.length === 2 ? ends[handle.getAttribute("data-handle") === "0" ? 0 : 1] : text;
}

function nameHandles(root) {
  for (const handle of root.querySelectorAll(".noUi-handle")) {
    const name = handleName(root, handle);
    if (name && handle.getAttribute("aria-label") !== name)
      handle.setAttribute("aria-label", name);
    const value = handleValue(root, handle);
    if (value && handle.getAttribute("aria-valuetext") !== value)
      handle.setAttribute("aria-valuetext", value);
  }
}
"""

#: ``figureName(title)``: a figure's accessible name, its title's text on one line (a
#: title of two lines is one name).
FIGURE_NAME_JS = """
function figureName(title) { return title.text.replace(/\\s+/g, " "); }
"""

FIGURE_NAMES_JS = FIGURE_NAME_JS + """
function nameFigures(roots) {
  if (!window.Bokeh) return;
  const hosts = [];
  for (const root of roots) hosts.push(...root.querySelectorAll("[class*='figure-']"));
  for (const doc of Bokeh.documents) {
    for (const m of doc.all_models) {
      if (!m.name || !m.title || typeof m.title.text !== "string" || !m.title.text) continue;
      const words = window.describeFigure ? window.describeFigure(m.name) : null;
      const name = figureName(m.title);
      for (const el of hosts.filter((h) => h.classList.contains("figure-" + m.name))) {
        if (el.getAttribute("role") !== "figure") el.setAttribute("role", "figure");
        if (el.getAttribute("aria-label") !== name) el.setAttribute("aria-label", name);
        if (words && el.getAttribute("aria-description") !== words)
          el.setAttribute("aria-description", words);
      }
    }
  }
}
"""


def figure_classes(*figures) -> list[str]:
    """Mark Bokeh ``figures`` (or layouts) with the class ``figure-<name>`` by which the
    page's script finds their drawn element (``nameFigures``; in the served page
    ``app.views.access``); returns those classes."""
    classes = []
    for fig in figures:
        cls = f"figure-{fig.name}"
        if cls not in fig.css_classes:
            fig.css_classes = [*fig.css_classes, cls]
        classes.append(cls)
    return classes


def mark_figures(doc) -> None:
    """``figure_classes`` for every named plot with a title in the Bokeh document ``doc``
    (a page the project writes, named and described by ``PAGE_SCRIPT``)."""
    from bokeh.models import Plot
    plots = {m for root in doc.roots for m in root.references()
             if isinstance(m, Plot) and m.name and m.title is not None and m.title.text}
    figure_classes(*sorted(plots, key=lambda m: m.name))


#: A written page's script: its slider handles and figures named, now and as BokehJS draws
#: them (and again after each change of the page).
PAGE_SCRIPT = ("<script>\n" + WATCH_ROOTS_JS + HANDLE_NAMES_JS + FIGURE_NAMES_JS
               + "window.addEventListener('load', () => watchRoots(nameHandles, nameFigures));"
               "\n</script>")
