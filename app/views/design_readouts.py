"""The Design tab's readouts: a one-sentence headline, the array's table (dimensionless and
in physical units, every value with the error bar it carries: ``model.designs.design_table``) and
its CSV download.

While a new array is computed the table keeps the previous inputs' numbers, greyed and
struck through under a banner that says so with the seconds elapsed and the most the
computation may take; a result that did not converge says what is known instead of an
error bar (bounds, or none).
"""
from __future__ import annotations

import io
import time

import panel as pn
import param

from model.designs.design_table import headline, rows, table_csv

from ..results import SessionResults
from ..state import ExplorerState
from .layout import BUTTON_CSS
from .widgets import look

#: A table of numbers that belong to the previous inputs.
STALE_CSS = """
:host(.stale) table { opacity: 0.45; text-decoration: line-through; }
:host(.stale) .design-headline-text { opacity: 0.45; }
"""
#: The banner's box is drawn on the pane's content, whose width is the pane's: a padding or
#: border on the pane itself would push the content past the column's edge.
BANNER_CSS = """
:host > div { background: #fff3cd; border: 1px solid #e0a800; padding: 2px 6px;
              border-radius: 4px; box-sizing: border-box; }
"""


def readouts_markdown(record: dict) -> str:
    """The headline and the table of a ``DesignPoint.to_dict`` record, as Markdown."""
    table = "| the array | value |\n|:--|--:|\n" + "\n".join(
        f"| {r['what']} | {r['text']} |" for r in rows(record))
    note = "" if record["success"] else f"\n\n**Not converged:** {record['message']}"
    return (f'<span class="design-headline-text">**{headline(record)}**</span>\n\n'
            + table + note)


class DesignReadouts(pn.viewable.Viewer):
    """Headline, table and CSV download of the design's array (see the module docstring)."""

    state = param.ClassSelector(class_=ExplorerState, constant=True)
    results = param.ClassSelector(class_=SessionResults, constant=True)

    def __init__(self, **params):
        super().__init__(**params)
        self.banner = pn.pane.Markdown("", width=340, margin=(0, 5), visible=False,
                                       styles={"font-size": "0.88em"}, stylesheets=[BANNER_CSS],
                                       css_classes=["design-updating"])
        self.table = pn.pane.Markdown("", width=340, margin=(0, 5),
                                      styles={"font-size": "0.88em"},
                                      stylesheets=[STALE_CSS], css_classes=["design-readouts"])
        self.download = pn.widgets.FileDownload(
            callback=self._csv, filename="design_table.csv", label="Design table CSV",
            **look("light"), width=160, margin=(2, 5), disabled=True,
            css_classes=["download-design-table"], stylesheets=[BUTTON_CSS])
        self._since = None
        self._ticker = None
        self._on_array()

    @param.depends("results.design_array", "results.busy", "results.errors", watch=True)
    def _on_array(self) -> None:
        r = self.results
        a, busy = r.design_array, "design_array" in r.busy
        error = r.errors.get("design_array", "")
        if busy and self._since is None:
            self._since = time.monotonic()
        elif not busy:
            self._since = None
        self._tick(busy)
        self.download.disabled = a is None or busy
        stale = busy and a is not None
        self.table.css_classes = ["design-readouts"] + (["stale"] if stale else [])
        self._banner(busy, a is not None)
        if a is None:
            self.table.object = error or ("Computing the array …" if busy else
                                          "The array is computed for a usable design.")
            return
        self.table.object = readouts_markdown(a) + ("" if busy or not error else
                                                    f"\n\n{error}")

    def _banner(self, busy: bool, shown: bool) -> None:
        self.banner.visible = busy
        if not busy:
            return
        seconds = 0 if self._since is None else time.monotonic() - self._since
        most = self.results.BUDGET_S["design_array"]
        what = ("**Updating:** the numbers below are for the previous inputs. "
                if shown else "**Computing the array** ")
        self.banner.object = (f"{what}Computing the new result: {seconds:.0f} s so far (the "
                              f"server gives it up to {most:.0f} s of computing, once a "
                              f"worker is free).")

    def _tick(self, busy: bool) -> None:
        """Refresh the banner's seconds once a second while the array is computed."""
        doc = pn.state.curdoc
        if busy and self._ticker is None and doc is not None and doc.session_context is not None:
            self._ticker = pn.state.add_periodic_callback(
                lambda: self._banner("design_array" in self.results.busy,
                                     self.results.design_array is not None), period=1000)
        elif not busy and self._ticker is not None:
            self._ticker.stop()
            self._ticker = None

    def _csv(self):
        a = self.results.design_array
        if a is None or "design_array" in self.results.busy:
            return io.StringIO("# the design's array is being computed: download it once "
                               "the table is up to date\n")
        return io.StringIO(table_csv(a))

    def __panel__(self):
        return pn.Column(self.banner, self.table, self.download, margin=0)
