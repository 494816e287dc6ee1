"""The Design tab's friction law, Eq. (4): its four coefficients typed in (V_s, μ_s, A, B:
``ExplorerState`` inputs, carried by the URL), or fitted to a measured curve uploaded as a
CSV file (the file ``micropillar friction fit`` reads: ``v [unit],mu[,mu_err]``), the
fit's coefficients with their 95 % intervals and warnings, and Fig. 3 in physical units
(``app.figures.law``): the law in use, the fit's band and the measured points.

``FrictionLawView`` reads only the state and the results: a good file sets
``state.friction_curve`` (``app.law_results`` fits it and sets the inputs); a bad one
leaves everything unchanged and its note names the problem in the command line's words
(``model.lab.friction_curve.curve_from_text``).
"""
from __future__ import annotations

import math

import panel as pn
import param

from model.lab.friction_curve import CurveFileError, curve_from_text
from model.designs.units import to_si, ureg

from .. import figures as F
from ..figures.law import law_data, law_figure, set_axes
from ..results import SessionResults
from ..state import ExplorerState
from ..upload import upload_text
from ..defaults import DEFAULTS, DESIGN_INPUTS, LAW_INPUTS
from .access import LiveDescription, figure_classes
from .design_upload import plain
from .design_words import law_description
from .layout import INPUT_CSS
from .locked import locked
from .widgets import caption

#: The largest file read, and the most points fitted in the page (the fit of 1000 points
#: takes well under a second; the command line fits any number).
MAX_BYTES = 64 * 1024
MAX_POINTS = 1000
FORMAT = "CSV: header v [unit],mu (optionally ,mu_err)"
_NAMES = {"mu_s": "μ_s", "A": "A", "B": "B", "V_s": "V_s"}


def read_upload(data: bytes, filename: str = "", reader=curve_from_text,
                command: str = "micropillar friction fit FILE.csv"):
    """The ``FrictionCurve`` of an uploaded file's bytes read by ``reader`` (the command
    line's: ``curve_from_text``, or ``measured_from_text`` for the structured sample);
    ``ValueError`` naming what is wrong (empty, too large, not text, too many points, or
    the line the command line's reader refuses). ``command`` says what takes a larger file."""
    name = filename or "the uploaded file"
    text = upload_text(data, name, MAX_BYTES, f"upload a {FORMAT} file",
                       f"use the command line: {command}")
    try:
        curve = reader(text, name, source=name)
    except CurveFileError as error:
        raise ValueError(str(error)) from None
    if curve.n_points > MAX_POINTS:
        raise ValueError(f"{name} has {curve.n_points} points, at most {MAX_POINTS} are read "
                         f"here; use the command line: {command}")
    return curve


def curve_input(css_class: str, title: str, what: str = "") -> pn.widgets.FileInput:
    """A file input for a friction curve (``FORMAT``) with its visible ``title`` (its name
    for a screen reader too), ``what`` naming whose."""
    return pn.widgets.FileInput(**caption(title), accept=".csv,.txt,text/csv,text/plain",
                                width=300,
                                margin=(2, 5), css_classes=[css_class], stylesheets=[INPUT_CSS],
                                description=f"{what}{FORMAT}; at most {MAX_POINTS} points")


def take_upload(file: pn.widgets.FileInput, data: bytes, **read):
    """``(curve, "")`` of the bytes ``data`` just uploaded to ``file`` (``read_upload``
    with ``read``), or ``(None, the problem in Markdown)``; ``file`` is emptied, so choosing
    the same file again (edited) is read again."""
    name = file.filename or ""
    file.clear()
    try:
        return read_upload(data, name, **read), ""
    except ValueError as error:
        return None, f"**Not loaded:** {plain(str(error))}. Nothing was changed."


def _speed(values) -> tuple[float, str]:
    """The factor and unit (an SI prefix of m/s) that show the speeds ``values`` best."""
    finite = [abs(v) for v in values if math.isfinite(v) and v]
    unit = ureg.Quantity(max(finite, default=1.0), "m/s").to_compact().units
    return ureg.Quantity(1.0, "m/s").to(unit).magnitude, f"{unit:~P}"


def fit_markdown(fit, name: str, in_use: bool) -> str:
    """A fit's coefficients with their 95 % intervals, its residual and warnings."""
    if not fit.success:
        return (f"**The fit of {plain(name)} did not converge** ({plain(fit.message)}); "
                "the law was not changed.")
    parts = []
    for key in ("mu_s", "A", "B", "V_s"):
        value, (lo, hi) = fit.values[key], fit.ci95[key]
        factor, unit = _speed([value, lo, hi]) if key == "V_s" else (1.0, "")
        interval = (f"[{lo * factor:.4g}, {hi * factor:.4g}]"
                    if math.isfinite(lo) and math.isfinite(hi) else "(no interval)")
        parts.append(f"{_NAMES[key]} = {value * factor:.4g} {interval}{' ' + unit if unit else ''}")
    weighted = ", weighted by mu_err" if fit.weighted else ""
    lines = [f"**Fitted to {plain(name)}** ({fit.n_points} points{weighted}; rms residual "
             f"{fit.rms_residual:.3g}; 95 % intervals):", "; ".join(parts) + ".",
             "The design uses this fit." if in_use else
             "**The design uses the law typed above, not this fit.**"]
    lines += [f"⚠ {plain(w)}" for w in fit.warnings]
    return "  \n".join(lines)


class FrictionLawView(pn.viewable.Viewer):
    """The law's inputs, the upload, the fit's note and Fig. 3 (see the module docstring)."""

    state = param.ClassSelector(class_=ExplorerState, constant=True)
    results = param.ClassSelector(class_=SessionResults, constant=True)

    def __init__(self, **params):
        super().__init__(**params)
        s = self.state
        self.inputs = {name: pn.widgets.TextInput.from_param(
            s.param[name], **caption(DESIGN_INPUTS[name][2]), width=145, margin=(0, 3),
            css_classes=[f"ctl-{name}"], stylesheets=[INPUT_CSS]) for name in LAW_INPUTS}
        self.file = curve_input("design-friction-file", "Measured friction curve (CSV)")
        self.note = pn.pane.Markdown("", width=300, margin=(0, 5),
                                     styles={"font-size": "0.85em"},
                                     css_classes=["design-friction"])
        self.figure = law_figure()
        self._sources = F.sources(self.figure)
        self.pane = pn.pane.Bokeh(self.figure, margin=0)
        self.words = LiveDescription(width=0, height=0, margin=0, css_classes=["design-law-words"],
                                     describes=figure_classes(self.figure))
        self._problem = ""
        self.file.param.watch(self._on_file, "value")
        F.style(self.figure, s.projector)
        self._redraw()

    def _on_file(self, event) -> None:
        if event.new is None:
            return
        curve, self._problem = take_upload(self.file, event.new)
        if curve is None:
            self._redraw()
        else:
            self.state.friction_curve = curve

    @param.depends("results.friction_fit", *(f"state.{n}" for n in LAW_INPUTS),
                   "state.design_V0", watch=True)
    def _redraw(self) -> None:
        s, fit = self.state, self.results.friction_fit
        lines = [self._problem] if self._problem else []
        try:
            law, problem = s.friction_law, ""
        except ValueError as error:
            law, problem = None, f"**Friction law not usable:** {plain(str(error))}"
        try:
            V0 = to_si("V0", s.design_V0)
        except ValueError:
            V0 = None
        if fit is not None:
            lines.append(fit_markdown(fit, s.friction_curve.source or "the uploaded curve",
                                      self.results.fit_in_use))
        elif law is not None:
            paper = all(getattr(s, name) == DEFAULTS[name] for name in LAW_INPUTS
                        if name != "design_V_s")
            which = "the paper's μ_s, A, B" if paper else "μ_s, A, B as typed"
            lines.append(f"Law in use: {which}, V_s as typed. Or fit a measured curve: upload "
                         f"it ({FORMAT}).")
        if problem:
            lines.append(problem)
        self.note.object = "  \n".join(lines)
        curve = s.friction_curve if fit is not None else None
        data, speeds, mus = law_data(law, fit, curve, V0)
        self.words.text = law_description(law, fit, curve, V0, problem)

        def draw():
            F.update(self._sources, data)
            set_axes(self.figure, speeds, mus)
        locked(draw, self.figure)

    @param.depends("state.projector", watch=True)
    def _restyle(self) -> None:
        F.style(self.figure, self.state.projector)

    def __panel__(self):
        return pn.Column(pn.pane.Markdown("**Friction law**, Eq. (4): type it or fit it",
                                          margin=(4, 5, 0, 5)),
                         pn.GridBox(*self.inputs.values(), ncols=2, margin=0), self.file,
                         self.note,
                         self.pane, self.words, margin=0, css_classes=["design-law"])
