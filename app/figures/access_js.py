"""JavaScript shared by the served page (``app.views.access.PageAccess``) and the pages the
project writes (``app.figures.animation_page``): Bokeh and Panel draw each widget inside
its own shadow root, out of reach of the page's stylesheet and of ARIA attributes set from
Python, so a script walks the shadow roots, again whenever one of them changes.

* ``WATCH_ROOTS_JS`` defines ``watchRoots(tend, done)``: calls ``tend(root)`` for the
  document and every shadow root now and after each change (debounced, 100 ms), then
  ``done(roots)``; returns a function that stops watching. Changes inside an element of
  class ``LIVE_CLASS`` (a player's readouts, rewritten while it plays: plain text, no
  control) are not changes of the page's structure and start no walk;
* ``HANDLE_NAMES_JS`` defines ``nameHandles(root)``: names each slider handle
  (``role="slider"``) after its slider's visible title, so a screen reader says what it
  sets ("frame", "k_r radial stiffness (log)"; a range slider's two handles: "..., from",
  "..., to") -- WCAG 4.1.2.
"""
from __future__ import annotations

#: CSS class of the boxes of text that follow a playing animation (``app.figures.live_text``).
LIVE_CLASS = "mp-live-text"

WATCH_ROOTS_JS = f"""
const LIVE_CLASS = {LIVE_CLASS!r};
""" + """
function watchRoots(tend, done) {
  const watched = new WeakSet();
  let pending = null;
  // Inside a live text box (its shadow root's host has LIVE_CLASS): only text changes.
  const live = (record) => {
    const root = record.target.getRootNode && record.target.getRootNode();
    const host = root && root.host;
    return !!(host && host.classList && host.classList.contains(LIVE_CLASS));
  };
  const observer = new MutationObserver((records) => {
    if (pending === null && !records.every(live)) pending = setTimeout(scan, 100);
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

function nameHandles(root) {
  for (const handle of root.querySelectorAll(".noUi-handle")) {
    const name = handleName(root, handle);
    if (name && handle.getAttribute("aria-label") !== name)
      handle.setAttribute("aria-label", name);
  }
}
"""

#: A written page's script: its slider handles named, now and as BokehJS draws them.
PAGE_SCRIPT = ("<script>\n" + WATCH_ROOTS_JS + HANDLE_NAMES_JS
               + "window.addEventListener('load', () => watchRoots(nameHandles));\n</script>")
