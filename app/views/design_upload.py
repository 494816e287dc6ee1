"""The Design tab's histogram upload: a CSV file of orientations read into the
distribution editor (the ``histogram`` family), with a note on the histogram in use and
whether a shared link carries it.

``HistogramUpload`` reads only the state: a good file sets ``state.dist_hist`` and selects
the ``histogram`` family; a bad one (empty, too large, not CSV text, a non-numeric value, a
negative weight, too many bins) leaves the state unchanged and its note names the
problem (``app.histogram.read_upload``).
"""
from __future__ import annotations

import re

import panel as pn
import param

from ..histogram import MAX_UPLOAD_BYTES, describe, link_note, read_upload
from ..state import ExplorerState
from .layout import INPUT_CSS
from .widgets import caption

#: Markdown and HTML characters, escaped where a file's name or content is echoed.
_MARKUP = re.compile(r"([\\`*_{}\[\]()#!|<>&~])")
FORMAT = "CSV: header theta0_deg,weight (bin centres) or lower_deg,upper_deg,weight"


def plain(text: str) -> str:
    """``text`` from a file (its name, a problem with it) shown literally in Markdown."""
    return _MARKUP.sub(r"\\\1", text)


class HistogramUpload(pn.viewable.Viewer):
    """A file input for an orientation histogram and its note (see the module docstring)."""

    state = param.ClassSelector(class_=ExplorerState, constant=True)

    def __init__(self, **params):
        super().__init__(**params)
        self.file = pn.widgets.FileInput(**caption("Orientation histogram (CSV)"),
                                         accept=".csv,.txt,text/csv,text/plain", width=300,
                                         margin=(2, 5), css_classes=["design-histogram-file"],
                                         stylesheets=[INPUT_CSS],
                                         description=f"{FORMAT}; at most "
                                                     f"{MAX_UPLOAD_BYTES // 1024} kB")
        self.note = pn.pane.Markdown("", width=300, margin=(0, 5),
                                     styles={"font-size": "0.85em"},
                                     css_classes=["design-histogram"])
        self._problem = ""
        self._source = ""
        self.file.param.watch(self._on_file, "value")
        self._describe()

    def _on_file(self, event) -> None:
        if event.new is None:
            return
        name = self.file.filename or ""
        # Emptied in the browser, so choosing the same file again (edited) is read again.
        self.file.clear()
        try:
            hist = read_upload(event.new, name)
        except ValueError as error:
            self._problem = f"**Not loaded:** {plain(str(error))}. Nothing was changed."
            self._describe()
            return
        self._problem, self._source = "", name
        uses = {"dist_family": "histogram"}
        if self.state.mix_weight > 0 and self.state.dist2_family == "histogram":
            uses = {}  # already in use as the mixture's second component
        self.state.param.update(dist_hist=hist, **uses)
        self._describe()

    @param.depends("state.dist_hist", "state.dist_family", "state.dist2_family",
                   "state.mix_weight", watch=True)
    def _describe(self) -> None:
        s = self.state
        used = s.dist_family == "histogram" or (s.mix_weight > 0
                                                 and s.dist2_family == "histogram")
        lines = [self._problem] if self._problem else []
        if s.dist_hist:
            source = f" from {plain(repr(self._source))}" if self._source else ""
            lines.append(f"Histogram{source}: {describe(s.dist_hist)}"
                         + ("" if used else " (not used: choose the histogram family)") + ". "
                         + link_note(s.dist_hist))
        elif used:
            lines.append("**No histogram uploaded:** the uniform distribution is used until a "
                         f"file is ({FORMAT}).")
        else:
            lines.append(f"Orientations from a file: upload a histogram ({FORMAT}).")
        self.note.object = "  \n".join(lines)

    def __panel__(self):
        return pn.Column(self.file, self.note, margin=0, css_classes=["design-histogram-upload"])
