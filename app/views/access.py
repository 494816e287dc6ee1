"""What the page does for keyboard, screen-reader and low-vision users (WCAG 2.1 AA).

Bokeh and Panel draw every widget inside its own shadow root, where the page's
stylesheet does not reach and where Panel 1.9 gives no way to set an ARIA attribute.
``PageAccess``, an invisible ``JSComponent`` placed once in the page, walks the page's
shadow roots (again whenever one of them changes, debounced) and:

* gives every root ``ACCESS_CSS`` (``app.views.layout``): a visible focus ring on every
  focusable control and text colours with a contrast of at least 4.5:1 where Bokeh's and
  Panel's defaults fall short;
* names each slider handle (``role="slider"``) after its visible title, so a screen
  reader says "k_r radial stiffness (log), 0.48" (a range slider's two handles: "from",
  "to");
* hides typeset equations' SVG from screen readers: each equation's text is written
  beside it (``EquationsView``), in a visually hidden paragraph;
* lets the keyboard reach a region that scrolls sideways (a long equation on a phone).

``LiveDescription`` is a polite live region (``role="status"``): a short description of
what a view's plots show, written by the server from the computed result (never per
animation frame); a screen reader announces it once a change has settled. It is visually
hidden (``SR_ONLY_CSS``).
"""
from __future__ import annotations

import param
from panel.custom import JSComponent

from .layout import ACCESS_CSS, SR_ONLY_CSS


class PageAccess(JSComponent):
    """Focus rings, contrast and accessible names for the whole page (see the module)."""

    css = param.String(default=ACCESS_CSS, doc="stylesheet given to every shadow root")

    _esm = """
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

    function tend(root, sheet) {
      if (root !== document && !root.adoptedStyleSheets.includes(sheet))
        root.adoptedStyleSheets = [...root.adoptedStyleSheets, sheet];
      for (const handle of root.querySelectorAll(".noUi-handle")) {
        const name = handleName(root, handle);
        if (name && handle.getAttribute("aria-label") !== name)
          handle.setAttribute("aria-label", name);
      }
      for (const svg of root.querySelectorAll("mjx-container svg")) {
        if (svg.getAttribute("aria-hidden") !== "true") svg.setAttribute("aria-hidden", "true");
      }
      for (const el of root.querySelectorAll(".scroll-x")) {
        if (el.scrollWidth > el.clientWidth + 1) el.setAttribute("tabindex", "0");
        else el.removeAttribute("tabindex");
      }
    }

    export function render({ model, el }) {
      el.style.display = "none";
      const sheet = new CSSStyleSheet();
      sheet.replaceSync(model.css);
      document.adoptedStyleSheets = [...document.adoptedStyleSheets, sheet];
      const watched = new WeakSet();
      let pending = null;
      const observer = new MutationObserver(() => {
        if (pending === null) pending = setTimeout(scan, 100);
      });
      const scan = () => {
        pending = null;
        const visit = (root) => {
          if (!watched.has(root)) {
            watched.add(root);
            observer.observe(root, {childList: true, subtree: true});
          }
          tend(root, sheet);
          for (const host of root.querySelectorAll("*")) {
            if (host.shadowRoot) visit(host.shadowRoot);
          }
        };
        visit(document);
      };
      scan();
      model.on("remove", () => {
        observer.disconnect();
        if (pending !== null) clearTimeout(pending);
      });
    }
    """


class LiveDescription(JSComponent):
    """A visually hidden, polite live region whose text is ``text`` (set by the server)."""

    text = param.String(default="", doc="what the view's plots show now, in words")

    _esm = """
    export function render({ model, el }) {
      const region = document.createElement("p");
      region.className = "sr-only live-description";
      region.setAttribute("role", "status");
      region.setAttribute("aria-live", "polite");
      region.textContent = model.text;
      model.on("text", () => { region.textContent = model.text; });
      el.appendChild(region);
    }
    """

    _stylesheets = [SR_ONLY_CSS]
