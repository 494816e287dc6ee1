"""What the page does for keyboard, screen-reader and low-vision users (WCAG 2.1 AA).

Bokeh and Panel draw every widget inside its own shadow root, where the page's
stylesheet does not reach and where Panel 1.9 gives no way to set an ARIA attribute.
``PageAccess``, an invisible ``JSComponent`` placed once in the page, walks the page's
shadow roots (again whenever one of them changes, debounced) and:

* gives every root ``ACCESS_CSS`` (``app.views.layout``): a visible focus ring on every
  focusable control and text colours with a contrast of at least 4.5:1 where Bokeh's and
  Panel's defaults fall short;
* names each slider handle (``role="slider"``) after its visible title, so a screen
  reader says "k_r radial stiffness (log), 3" -- the value the slider shows, not its log
  position (a range slider's two handles: "from", "to");
* hides typeset equations' SVG from screen readers: each equation's text is written
  beside it (``EquationsView``), in a visually hidden paragraph;
* lets the keyboard reach a region that scrolls sideways (a long equation on a phone);
* names a card's fold button after its title ("Data as a table") and a number field's
  spin buttons after their field ("increase κ");

``LiveDescription`` is a polite live region (``role="status"``): a short description of
what a view's plots show, written by the server from the computed result (never per
animation frame); a screen reader announces it once a change has settled. It is visually
hidden (``SR_ONLY_CSS``). ``PageAccess`` also gives the figures it ``describes`` (their
holders' CSS classes) ``role="figure"``, the figure's title as their name and the
region's text as their description, so a reader who moves onto a plot hears what it shows.
"""
from __future__ import annotations

import param
from panel.custom import JSComponent

from ..figures.access_js import (FIGURE_NAME_JS, HANDLE_NAMES_JS, WATCH_ROOTS_JS,
                                 figure_classes)
from .layout import ACCESS_CSS, SR_ONLY_CSS

__all__ = ["PageAccess", "LiveDescription", "figure_classes"]


class PageAccess(JSComponent):
    """Focus rings, contrast and accessible names for the whole page (see the module)."""

    css = param.String(default=ACCESS_CSS, doc="stylesheet given to every shadow root")

    _esm = WATCH_ROOTS_JS + HANDLE_NAMES_JS + FIGURE_NAME_JS + """
    // Bokeh figures' titles by name (a figure's holder has the class "figure-<name>").
    function titles() {
      const out = {};
      for (const doc of (window.Bokeh ? Bokeh.documents : []))
        for (const m of doc.all_models)
          if (m.name && m.title && typeof m.title.text === "string")
            out[m.name] = figureName(m.title);
      return out;
    }

    // The figures a live description describes: named by their title, described by it.
    function describe(roots) {
      const regions = [], hosts = [];
      for (const root of roots) {
        regions.push(...root.querySelectorAll(".live-description[data-describes]"));
        for (const el of root.querySelectorAll("*")) if (el.classList.length) hosts.push(el);
      }
      if (!regions.length) return;
      const named = titles();
      for (const region of regions) {
        const words = region.textContent;
        for (const cls of region.dataset.describes.split(" ")) {
          for (const host of hosts.filter((h) => h.classList.contains(cls))) {
            const name = named[cls.replace(/^figure-/, "")] || region.dataset.label;
            if (host.getAttribute("role") !== "figure") host.setAttribute("role", "figure");
            if (host.getAttribute("aria-label") !== name) host.setAttribute("aria-label", name);
            if (host.getAttribute("aria-description") !== words)
              host.setAttribute("aria-description", words);
          }
        }
      }
    }

    function tend(root, sheet) {
      if (root !== document && !root.adoptedStyleSheets.includes(sheet))
        root.adoptedStyleSheets = [...root.adoptedStyleSheets, sheet];
      nameHandles(root);
      // A button whose widget carries data-aria-label (the player's sound toggle) is
      // named by it: Bokeh puts html_attributes on the widget, not on its button.
      const label = root.host && root.host.getAttribute && root.host.getAttribute("data-aria-label");
      if (label) {
        for (const button of root.querySelectorAll("button")) {
          if (button.getAttribute("aria-label") !== label) button.setAttribute("aria-label", label);
          // A toggle's pressed state is its active class, also on a button drawn again.
          const pressed = String(button.classList.contains("bk-active"));
          if (button.getAttribute("aria-pressed") !== pressed)
            button.setAttribute("aria-pressed", pressed);
        }
      }
      // A number field's spin buttons: "increase"/"decrease" and the field's title.
      const spins = root.querySelectorAll("button.bk-spin-btn");
      if (spins.length) {
        const title = root.querySelector("label");
        const what = title ? title.textContent.replace(/\\s+/g, " ").trim() : "";
        for (const button of spins) {
          const name = (button.classList.contains("bk-spin-btn-up") ? "increase" : "decrease")
            + (what ? " " + what : "");
          if (button.getAttribute("aria-label") !== name) button.setAttribute("aria-label", name);
        }
      }
      // A card's fold button is named by its title, also where the title is clipped.
      for (const button of root.querySelectorAll("button.card-header")) {
        const name = button.textContent.replace(/\\s+/g, " ").trim();
        if (name && button.getAttribute("aria-label") !== name)
          button.setAttribute("aria-label", name);
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
      // A live description's new text describes figures elsewhere: the page is walked.
      const stop = watchRoots((root) => tend(root, sheet), describe, ".live-description");
      model.on("remove", stop);
    }
    """


class LiveDescription(JSComponent):
    """A visually hidden, polite live region whose text is ``text`` (set by the server)."""

    text = param.String(default="", doc="what the view's plots show now, in words")
    describes = param.List(default=[], item_type=str,
                           doc="CSS classes of the holders of the figures it describes")
    label = param.String(default="plot", doc="their name where a figure has no title")

    _esm = """
    export function render({ model, el }) {
      const region = document.createElement("p");
      region.className = "sr-only live-description";
      region.setAttribute("role", "status");
      region.setAttribute("aria-live", "polite");
      region.textContent = model.text;
      if (model.describes.length) {
        region.dataset.describes = model.describes.join(" ");
        region.dataset.label = model.label;
      }
      model.on("text", () => { region.textContent = model.text; });
      el.appendChild(region);
    }
    """

    _stylesheets = [SR_ONLY_CSS]
