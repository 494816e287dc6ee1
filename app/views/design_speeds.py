"""The Design tab's friction against sliding speed: the structured surface's predicted
F_T,x/F_N over a range of speeds beside the flat material's mu(V0), computed in the
background point by point (``app.speed_results``), and the structured sample's measured
curve uploaded as a CSV file (the file ``micropillar pillar --compare`` reads) drawn over
it, with the difference, its RMS and the speeds where they disagree beyond the model's
error (``app.figures.speeds``).

``FrictionSpeedsView`` reads only the state and the results: its inputs set
``state.speeds_range`` and ``speeds_n``, Predict and Cancel call the results, a good file
sets ``state.structured_curve``; a bad one leaves everything unchanged and its note names
the problem in the command line's words (``model.lab.friction_compare.measured_from_text``).
"""
from __future__ import annotations

import panel as pn
import param

from model.lab.friction_compare import measured_from_text

from .. import figures as F
from ..figures.speeds import (difference_data, difference_figure, set_speed_axis, speeds_data,
                              speeds_figure)
from ..results import SessionResults
from ..speed_results import speed_words
from ..state import ExplorerState
from .design_law import FORMAT, curve_input, take_upload
from .access import LiveDescription, figure_classes
from .design_upload import plain
from .design_words import speeds_description
from .layout import FIT_TEXT_CSS, INPUT_CSS
from .locked import locked
from .widgets import caption, look

COMMAND = "micropillar pillar ... --compare FILE.csv"


def comparison_markdown(c, name: str) -> str:
    """The comparison in words: its RMS and the speeds where it disagrees."""
    where = "mu_err" if c.mu_err_given else "an assumed mu_err"
    lines = [f"**Measured ({plain(name)}) − predicted:** RMS **{c.rms:.3g}** over "
             f"{c.n_compared} speeds."]
    if c.disagree:
        lines.append(f"**They disagree beyond the model's error** (+ {c.n_sigma:g} × {where}) "
                     f"at {speed_words(c.disagree)}.")
    else:
        lines.append(f"They agree within the model's error (+ {c.n_sigma:g} × {where}) at "
                     f"every measured speed.")
    if not c.success:
        lines.append(plain(c.message))
    return "  \n".join(lines)


class FrictionSpeedsView(pn.viewable.Viewer):
    """The speeds' inputs, Predict/Cancel, progress, the upload and the two figures."""

    state = param.ClassSelector(class_=ExplorerState, constant=True)
    results = param.ClassSelector(class_=SessionResults, constant=True)

    def __init__(self, **params):
        super().__init__(**params)
        s = self.state
        self.range = pn.widgets.TextInput.from_param(
            s.param.speeds_range, **caption("speeds V₀, LO..HI"), width=170, margin=(0, 3),
            css_classes=["ctl-speeds_range"], stylesheets=[INPUT_CSS])
        self.n = pn.widgets.IntInput.from_param(
            s.param.speeds_n, **caption("how many"), width=80, margin=(0, 3),
            css_classes=["ctl-speeds_n"], stylesheets=[INPUT_CSS])
        self.predict = pn.widgets.Button(**caption("Predict"), **look("primary"), width=90,
                                         css_classes=["design-speeds-predict"],
                                         stylesheets=[INPUT_CSS, FIT_TEXT_CSS])
        self.cancel = pn.widgets.Button(**caption("Cancel"), **look("light"), width=70,
                                        disabled=True, css_classes=["design-speeds-cancel"],
                                        stylesheets=[INPUT_CSS, FIT_TEXT_CSS])
        self.predict.on_click(lambda _e: self.results.predict_speeds())
        self.cancel.on_click(lambda _e: self.results.cancel_speeds())
        self.progress = pn.indicators.Progress(value=0, max=1, width=160, margin=(8, 5),
                                               visible=False, bar_color="primary",
                                               css_classes=["design-speeds-progress"])
        self.note = pn.pane.Markdown("", width=300, margin=(0, 5),
                                     styles={"font-size": "0.85em"},
                                     css_classes=["design-speeds"])
        self.file = curve_input("design-structured-file",
                                "Structured sample's measured curve (CSV)",
                                "the structured sample: ")
        self.compare = pn.pane.Markdown("", width=300, margin=(0, 5),
                                        styles={"font-size": "0.85em"},
                                        css_classes=["design-speeds-compare"])
        self.figure, self.difference = speeds_figure(), difference_figure()
        self._sources = {**F.sources(self.figure), **F.sources(self.difference)}
        self.words = LiveDescription(width=0, height=0, margin=0,
                                     css_classes=["design-speeds-words"],
                                     describes=figure_classes(self.figure, self.difference))
        self._problem = ""
        self.file.param.watch(self._on_file, "value")
        for fig in (self.figure, self.difference):
            F.style(fig, s.projector)
        self._redraw()

    def _on_file(self, event) -> None:
        if event.new is None:
            return
        curve, self._problem = take_upload(self.file, event.new, reader=measured_from_text,
                                           command=COMMAND)
        if curve is None:
            self._redraw()
        else:
            self.state.structured_curve = curve

    @param.depends("results.speed_points", "results.speed_running", "results.speed_note",
                   "results.speed_comparison", "results.speed_compare_note",
                   "state.structured_curve", watch=True)
    def _redraw(self) -> None:
        s, r = self.state, self.results
        points, measured = r.speed_points, s.structured_curve
        done = sum(p is not None for p in points)
        self.predict.disabled, self.cancel.disabled = r.speed_running, not r.speed_running
        self.progress.visible = r.speed_running
        self.progress.max, self.progress.value = max(len(points), 1), done
        note = r.speed_note or ("**Predict** computes the structured surface's F_T,x/F_N at "
                                "each speed (in the background; needs the law's own V_s).")
        self.note.object = note
        lines = [self._problem] if self._problem else []
        c = r.speed_comparison
        name = (measured.source if measured is not None else "") or "the uploaded curve"
        if c is not None:
            lines.append(comparison_markdown(c, name))
        elif measured is not None:
            lines.append(f"Measured curve {plain(name)}: {measured.n_points} points. "
                         + r.speed_compare_note)
        else:
            lines.append(f"Compare with the structured sample's measured curve: upload it "
                         f"({FORMAT}).")
        self.compare.object = "  \n".join(lines)
        law = r.speed_law if points else _law_or_none(s)
        data, xr, yr = speeds_data(points, law, measured)
        diff, dr = difference_data(c)
        self.words.text = speeds_description(points, law, measured, c, r.speed_running)

        def draw():
            F.update(self._sources, {**data, **diff})
            for fig in (self.figure, self.difference):
                set_speed_axis(fig, *xr)
            self.figure.y_range.update(start=yr[0], end=yr[1])
            self.difference.y_range.update(start=dr[0], end=dr[1])
        locked(draw, self.figure)
        self.difference.visible = c is not None

    @param.depends("state.projector", watch=True)
    def _restyle(self) -> None:
        for fig in (self.figure, self.difference):
            F.style(fig, self.state.projector)

    def __panel__(self):
        return pn.Column(
            pn.pane.Markdown("**Friction against sliding speed**: the pillars predicted, "
                             "beside the flat material", margin=(4, 5, 0, 5)),
            pn.Row(self.range, self.n, margin=0),
            pn.Row(self.predict, self.cancel, self.progress, margin=0), self.note,
            pn.pane.Bokeh(self.figure, margin=0), self.file, self.compare,
            pn.pane.Bokeh(self.difference, margin=0), self.words, margin=0, css_classes=["design-speeds-box"])


def _law_or_none(state):
    try:
        return state.friction_law
    except ValueError:
        return None
