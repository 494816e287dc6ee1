"""Exports from the page: a GIF or MP4 of the animation on show for slides, made on the
server in the background (``SessionResults.prepare_animation``) and then offered for
download; the CSV of a result, offered once it is computed (``ResultDownload``); figures
saved as SVG in the browser (``svg_button``). The page never waits for any of them."""
from __future__ import annotations

import io

import panel as pn
import param

from ..results import SessionResults
from ..state import ExplorerState
from .browser import SVG_BUTTON_CLASS, SVG_EXPORTS
from .layout import BUTTON_CSS
from .widgets import caption, look


class AnimationExport(pn.viewable.Viewer):
    """Format choice, a "make" button, and the download once the file is ready."""

    state = param.ClassSelector(class_=ExplorerState, constant=True)
    results = param.ClassSelector(class_=SessionResults, constant=True)
    what = param.Selector(default="support", objects=["support", "array"], constant=True)

    def __init__(self, **params):
        super().__init__(**params)
        self.format = pn.widgets.RadioButtonGroup(options={"GIF": "gif", "MP4": "mp4"},
                                                  value="gif", margin=(4, 5),
                                                  stylesheets=[BUTTON_CSS],
                                                  css_classes=[f"export-{self.what}-format"])
        self.make = pn.widgets.Button(**caption("Make animation for slides"),
                                      **look("primary", "outline"), margin=(4, 5),
                                      stylesheets=[BUTTON_CSS],
                                      css_classes=[f"export-{self.what}-make"],
                                      description="renders the animation on the server "
                                                  "(about half a minute)")
        self.make.on_click(self._make)
        self.download = pn.widgets.FileDownload(
            callback=self._file, filename="animation.gif", label="Download", disabled=True,
            **look("success"), margin=(4, 5), css_classes=[f"export-{self.what}-download"],
            stylesheets=[BUTTON_CSS])
        self.status = pn.pane.Markdown("", margin=(0, 5), styles={"font-size": "0.85em"})

    def _make(self, _event=None) -> None:
        self.download.disabled = True
        self.status.object = "Rendering on the server …"
        self.results.prepare_animation(self.what, self.format.value)

    def _mine(self) -> bool:
        a = self.results.animation
        return a is not None and a.get("what") == self.what

    @param.depends("results.animation", "results.errors", watch=True)
    def _ready(self) -> None:
        error = self.results.errors.get("animation", "")
        if self._mine():
            a = self.results.animation
            s = self.state
            self.download.filename = (f"{self.what}_kr{s.k_r:.3g}_kt{s.k_theta:.3g}_"
                                      f"FN{s.F_N:.3g}_theta0_{s.theta0:g}.{a['format']}")
            self.download.disabled = False
            self.status.object = (f"Ready: {a['message']}, {len(a['bytes']) / 1e6:.1f} MB. "
                                  "Press Download.")
        elif error:
            self.status.object = error

    def _file(self):
        return io.BytesIO(self.results.animation["bytes"]) if self._mine() else io.BytesIO()

    def __panel__(self):
        return pn.FlexBox(self.format, self.make, self.download, self.status,
                          flex_wrap="wrap", css_classes=[f"export-{self.what}"],
                          sizing_mode="stretch_width")


class ResultDownload(pn.viewable.Viewer):
    """A CSV of one result (``SessionResults.<name>``), offered only once it is there:
    disabled and saying "computing…" while it is computed; for a result the tab does not
    compute by itself (the polar sweep off its tab), a button asks for it first. With a
    pinned state A, A's result is waited for too (``writer`` puts it beside B's)."""

    results = param.ClassSelector(class_=SessionResults, constant=True)
    name = param.String(constant=True)
    label = param.String(constant=True)

    def __init__(self, writer, filename: str, css: str, **params):
        super().__init__(**params)
        self._writer = writer
        # Long captions ("… computing…") wrap rather than being cut off.
        common = dict(sizing_mode="stretch_width", margin=(2, 3),
                      stylesheets=[BUTTON_CSS, ".bk-btn { white-space: normal; }"])
        self.download = pn.widgets.FileDownload(
            callback=self._file, filename=filename, label=self.label,
            css_classes=[f"download-{css}"], **look("light"), **common)
        self.compute = pn.widgets.Button(**caption(f"Compute {self.label[:1].lower()}{self.label[1:]}"), visible=False,
                                         css_classes=[f"download-{css}-compute"],
                                         **look("light", "outline"), **common)
        self.compute.on_click(self._request)
        state = self.results.state
        state.param.watch(self._update, list(self.results.slots[self.name].depends)
                          + ["pinned"])
        self.results.param.watch(self._update, [self.name, "busy", "errors"])
        self._update()

    def _slots(self) -> list:
        r = self.results
        return [s for s in (r.slots[self.name], r.pinned_slot(self.name)) if s is not None]

    @property
    def ready(self) -> bool:
        return getattr(self.results, self.name) is not None and all(
            s.current for s in self._slots())

    def _request(self, _event=None) -> None:
        for slot in self._slots():
            if not slot.current:
                slot.request()
        self._update()

    def _update(self, *_events) -> None:
        r = self.results
        busy = self.name in r.busy or (r.A is not None and self.name in r.A.busy)
        ready = self.ready and not busy
        error = r.errors.get(self.name, "")
        self.download.disabled = not ready
        self.download.label = self.label if ready else (
            f"{self.label}: failed" if error and not busy else f"{self.label}: computing…")
        # Not on its way (a result this tab does not compute): a button asks for it.
        waiting = not ready and not busy and not error and not r.slots[self.name].needed
        self.compute.visible = waiting
        self.download.visible = not waiting

    def _file(self):
        return io.StringIO(self._writer() if self.ready else "")

    def __panel__(self):
        return pn.Column(self.compute, self.download, sizing_mode="stretch_width", margin=0)


def svg_button(css: str, label: str = "Figure (SVG)"):
    """A button that saves the figures ``SVG_EXPORTS[css]`` that are on screen as
    ``<name>.svg``, in the browser: no server round trip.

    The click is answered by the page's own code (``app.views.browser.PageBehaviour``,
    which finds the button by its classes): a Panel ``js_on_click`` would register a
    Panel ``Callback``, and from then on every layout update of every page in the
    process walks the page's whole model graph looking for links (~10 % of a page's
    build, ``benchmarks/bench_page_steps.py``)."""
    if css not in SVG_EXPORTS:
        raise ValueError(f"css={css!r}: an SVG button is one of {sorted(SVG_EXPORTS)} "
                         "(add its figures to app.views.browser.SVG_EXPORTS)")
    return pn.widgets.Button(**caption(label), **look("light"), margin=(2, 3),
                             sizing_mode="stretch_width",
                             css_classes=[f"export-{css}", SVG_BUTTON_CLASS],
                             stylesheets=[BUTTON_CSS],
                             description="saves the figure as a vector graphic (SVG)")
