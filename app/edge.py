"""The serving edge: what the lab's server needs that Panel, Bokeh and Tornado do not offer
through a public hook, in one place, each installed only on the tested stack (``TESTED``).

On another version of Panel, Bokeh or Tornado the server says so in one line at start-up
(``install``) and runs on public behaviour alone: the page still works, without the
guards below. ``tests/test_edge.py`` fails the day one of the internals they use changes.
Each guard has a reproducer with plain Panel in ``docs/upstream/``. (Panel's reader of the
page address, which raises on a 4301-digit value (``docs/upstream/parse_query_digits.py``),
needs no guard: the page is served without Panel's ``Location``, ``app/main.py``. The busy
page a client without room gets before any session is made needs none either: Panel's
``authorize_callback`` sends it there, ``app.opening.admit_or_busy``.)

The touches, and what each buys:

1. **Response headers** (``SECURITY_HEADERS``; ``add_security_headers``): Tornado's hook
   for default headers (``RequestHandler.set_default_headers``), meant for subclasses, set
   on the base class so Bokeh's and Panel's handlers get it too: no other site may frame
   the dashboard, browsers take each file as the type the server declares. There it also
   drops a ``bokeh-session-id`` Bokeh would read as empty (Bokeh answers 500,
   ``docs/upstream/empty_session_id.py``) or cannot decode (Tornado answers 400).
2. **Panel's text views drawn late** (``MARKUP_GUARD_JS``, in the page): a change of
   ``visible`` reaching a markup view built but not yet drawn throws in Panel's view
   (``docs/upstream/markup_visible_before_drawn.py``); likewise a change of ``disabled``
   reaching a control (a FileDownload on a tab not drawn yet) threw "Cannot read
   properties of undefined (reading 'removeAttribute')": its undrawn elements are skipped.
   The same page code gives the "Figure (SVG)" buttons ``window.mp_export_svg``: BokehJS
   offers a figure's SVG only through its drawn view (what the toolbar's save tool does
   for a figure drawn in SVG); on another stack the buttons point to the save tool.
   The same page code applies the offline page's BokehJS fix (``app/offline/bokeh_fix.js``,
   one file for both pages; ``page_js``): each paint of a figure rewrote its renderers'
   ``<style>`` elements with their own text, and the styles were recalculated for each
   (``docs/upstream/bokehjs_style_rewrite.py``). The browser's work per key press, with
   the fix and without: ``benchmarks/bench_style_fix.py``.
3. **Changes queued while the websocket is busy** (``keep_queued_writes``): Panel queues a
   change it cannot write at once and a task writes the queue; a change queued as the
   previous write ends waited for the page's next change, because the previous write's
   task had cleared the queue's flag and the new task, finding it cleared, returned
   (``docs/upstream/write_queue_strands_last_change.py``). Under a class's load the last
   position of about one θ₀ drag in 500 was never shown. Panel's writing task is wrapped: it
   writes what it finds queued.
"""
from __future__ import annotations

import functools
import json
import logging
import re
from pathlib import Path

log = logging.getLogger(__name__)

#: The versions the guards were written and tested against (``tests/test_edge.py``).
TESTED = {"panel": "1.9.4", "bokeh": "3.9.2", "tornado": "6.6.1"}

#: Headers added to every HTTP response of the server (pages, scripts, websocket upgrades,
#: the liveness endpoint, errors).
SECURITY_HEADERS = {
    "X-Frame-Options": "SAMEORIGIN",
    "Content-Security-Policy": "frame-ancestors 'self'",
    "X-Content-Type-Options": "nosniff",
    "Referrer-Policy": "same-origin",
}

#: Control characters Tornado's ``get_argument`` turns into spaces (as Tornado 6.6 does).
CONTROL_CHARS = re.compile(r"[\x00-\x08\x0e-\x1f]")


def versions() -> dict:
    import bokeh
    import panel
    import tornado

    return {"panel": panel.__version__, "bokeh": bokeh.__version__, "tornado": tornado.version}


def on_tested_stack() -> bool:
    return versions() == TESTED


def untested_note() -> str | None:
    """The one line the server logs at start-up on an untested stack, else None."""
    found = versions()
    if found == TESTED:
        return None
    return (f"panel/bokeh/tornado {found['panel']}/{found['bokeh']}/{found['tornado']} are not "
            f"the tested {TESTED['panel']}/{TESTED['bokeh']}/{TESTED['tornado']}: the server "
            "runs without its guards (security headers, text-view guard, queued writes); "
            "see app/edge.py")


def install() -> bool:
    """Install the server guards 1 and 3 (once per process) on the tested stack; elsewhere
    log ``untested_note()`` once. Returns whether they are installed. (Guard 2 is page
    code: ``guard_markup_views``.)"""
    note = untested_note()
    if note is not None:
        log.warning(note)
        return False
    add_security_headers()
    keep_queued_writes()
    return True


# ---------------------------------------------------------------------- 1. headers
def add_security_headers() -> None:
    from tornado.web import RequestHandler

    if getattr(RequestHandler.set_default_headers, "_security_headers", False):
        return
    default = RequestHandler.set_default_headers

    def set_default_headers(self):
        default(self)
        for name, value in SECURITY_HEADERS.items():
            self.set_header(name, value)
        drop_unreadable_session_id(getattr(self, "request", None))

    set_default_headers._security_headers = True
    RequestHandler.set_default_headers = set_default_headers


def drop_unreadable_session_id(request) -> None:
    """Without a ``bokeh-session-id`` Bokeh cannot read -- empty (control characters made
    spaces, then stripped: ``?bokeh-session-id=%00`` is empty too; Bokeh answers 500) or
    not UTF-8 (``%ED%A0%80``; Tornado answers 400) -- the page gets a new session, as for
    any address without one."""
    for args in (getattr(request, "query_arguments", None), getattr(request, "arguments", None)):
        values = args.get("bokeh-session-id") if args is not None else None
        if not values:
            continue
        last = values[-1]
        if isinstance(last, bytes):
            try:
                last = last.decode("utf-8")
            except UnicodeDecodeError:
                last = ""
        if not CONTROL_CHARS.sub(" ", last).strip():
            del args["bokeh-session-id"]


# ---------------------------------------------------------------------- 2. text views
#: Panel's text views (``PanelMarkupView``: HTML, Markdown, alerts) make their
#: ``container`` when first drawn, and their handler of ``visible`` uses it at once: a page
#: sent in a patch has views BokehJS builds at once but draws over later turns, so a change
#: of ``visible`` in between threw "Cannot read properties of undefined (reading 'style')"
#: and stopped the rest of that message. Until a view is drawn its ``container`` is a
#: detached stand-in (the drawing reads the model's state anew). It relies on Panel's
#: bundle defining ``container`` as a plain property (no class field).
MARKUP_GUARD_JS = """
// The prototype of the view BokehJS makes for the model named ``name``, or null.
const viewOf = (name) => {
  try { return Bokeh.Models.get(name)?.prototype?.default_view?.prototype ?? null; }
  catch (e) { return null; }
};
const markup = viewOf("panel.models.markup.HTML");
const base = markup == null ? null : Object.getPrototypeOf(markup);
if (base != null && Object.getOwnPropertyDescriptor(base, "container") == null) {
  Object.defineProperty(base, "container", {
    configurable: true,
    get() { return this._drawn_container ?? document.createElement("div"); },
    set(value) { this._drawn_container = value; },
  });
}
// Likewise a control's ``disabled`` handler reaches its elements (``controls()``: for
// Panel's FileDownload its anchor and button) before the view has drawn them: until then
// the undrawn ones are skipped (the drawing reads ``disabled`` from the model).
for (const name of Bokeh.Models.names ?? []) {
  const proto = viewOf(name);
  if (proto == null || !Object.prototype.hasOwnProperty.call(proto, "controls")
      || proto.controls.mp_guarded) continue;
  const controls = proto.controls;
  const drawn = function* () { for (const el of controls.call(this)) if (el != null) yield el; };
  drawn.mp_guarded = true;
  proto.controls = drawn;
}
// Panel's FileDownload updates its label, file name and style on its drawn anchor: until
// the view is drawn those updates wait for the drawing, which reads the model anew.
const dl = viewOf("panel.models.widgets.FileDownload");
for (const method of ["_update_label", "_update_download", "_update_href",
                      "_update_button_style", "_handle_click"]) {
  const original = dl == null ? null : dl[method];
  if (typeof original !== "function" || original.mp_guarded) continue;
  const guarded = function (...args) {
    if (this.anchor_el == null || this.label_el == null) return undefined;
    return original.apply(this, args);
  };
  guarded.mp_guarded = true;
  dl[method] = guarded;
}
// The page's "Figure (SVG)" buttons (app/views/export.py) call this: each figure named
// (none named: every figure on screen) is exported by its own drawn view, as the
// toolbar's save tool does for a figure drawn in SVG, whatever backend draws it here.
window.mp_export_svg = function (names, prefix) {
  const wanted = new Set(names);  // empty: every figure on screen
  for (const doc of Bokeh.documents) {
    for (const model of doc.all_models) {
      if (typeof model.output_backend !== "string" || model.name == null) continue;
      if (wanted.size > 0 && !wanted.has(model.name)) continue;
      const view = Bokeh.index.find_one(model);
      // Drawn and on screen (a hidden tab's figures have no boxes).
      if (view == null || !view.el.isConnected || view.el.getClientRects().length === 0
          || view.bbox.width === 0) continue;
      view.export("svg").to_blob().then((blob) => {
        const link = document.createElement("a");
        link.href = URL.createObjectURL(blob);
        link.download = `${prefix}${model.name}.svg`;
        document.body.appendChild(link);
        link.click();
        link.remove();
      });
    }
  }
};
"""


#: BokehJS's rewrite of unchanged ``<style>`` elements: the offline page's fix, the same file.
BOKEH_FIX_JS = Path(__file__).parent / "offline" / "bokeh_fix.js"


@functools.cache
def page_js() -> str:
    """The page's code on the tested stack: ``MARKUP_GUARD_JS``, then ``BOKEH_FIX_JS``
    applied to the BokehJS version tested (``window.MicropillarBokehFix`` says whether it
    was and why not). Read once per process."""
    fix = BOKEH_FIX_JS.read_text(encoding="utf-8")
    return (f"{MARKUP_GUARD_JS}\n(function () {{\n{fix}\n}}).call(window);\n"
            f"MicropillarBokehFix.apply(Bokeh, {json.dumps(TESTED['bokeh'])});\n")


def guard_markup_views(doc) -> None:
    """Install ``page_js()`` in ``doc``'s page when it is ready (tested stack only)."""
    if doc is None or not on_tested_stack():
        return
    from bokeh.models import CustomJS

    doc.js_on_event("document_ready", CustomJS(code=page_js()))


# ---------------------------------------------------------------------- 3. queued writes
def keep_queued_writes() -> None:
    """Panel writes a page's change it could not write at once from a queue
    (``schedule_write_events``), by a task (``_dispatch_msgs``) that returns without writing
    when the queue's flag (``_WRITE_BLOCK``) is cleared. A change queued in the turn in
    which the previous write ended had its flag cleared by that write's task before its own
    task ran, and stayed queued until the page's next change. Wrapped: a task that finds
    changes queued and the flag cleared sets the flag and writes them."""
    from panel.io import document

    dispatch = document._dispatch_msgs
    if getattr(dispatch, "_keeps_queue", False):
        return

    async def dispatch_msgs(doc):
        if doc not in document._WRITE_BLOCK and document._WRITE_MSGS.get(doc):
            document._WRITE_BLOCK[doc] = True
        await dispatch(doc)

    dispatch_msgs._keeps_queue = True
    dispatch_msgs.__wrapped__ = dispatch
    document._dispatch_msgs = dispatch_msgs
