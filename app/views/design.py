"""The Design tab: a real micropillar array in physical units, where it sits on the regime
map, an orientation distribution over the Fig. 11a curve of its springs, the array's
readouts (dimensionless and physical) and the best distribution on request.

Renderer of ``SessionResults.design_point``, ``.design_array``, ``.design_polar`` and
``.design_optimum``; the inputs and the distribution are ``ExplorerState`` parameters
(so a shared link restores them). With a pinned state A (``app.compare``) its point is
marked muted on the map, its Fig. 11a curve and distribution are drawn muted under B's,
and the readouts give A's array, B's and B − A (``.design_point_A``, ``.design_array_A``,
``.design_polar_A``).
"""
from __future__ import annotations

import math
import time

import panel as pn
import param

from model.runs.shipped_map import load_regime_map

from .. import figures as F
from ..figures.design import (design_map_data, design_map_figure, design_polar_data,
                              design_polar_figure)
from ..figures.pinned import add_pinned, design_point_A, design_polar_A, show_pinned
from ..figures.polar import set_extent
from ..pinned_state import complete
from ..results import SessionResults, optimum_family
from ..state import ExplorerState, distribution_of
from ..defaults import DESIGN_INPUTS, LAW_INPUTS
from ..export import sweep_csv
from .access import LiveDescription, figure_classes
from .compare_tables import design_compare_markdown, distribution_words
from .data_table import DataTable
from .design_law import FrictionLawView
from .design_readouts import DesignReadouts
from .design_speeds import FrictionSpeedsView
from .design_upload import HistogramUpload
from .design_words import STATUS_WORDS, design_map_description, design_polar_description
from .layout import (FIT_TEXT_CSS, INPUT_CSS, PHONE, TOP, WIDE, grid_css, mode_classes,
                     projector_grid)
from .locked import locked as _locked
from .widgets import caption, look

#: Inputs, figures, readouts side by side (the figures take the width left); on a phone
#: one below the other.
DESIGN_ROW_CSS = f"""
:host {{ width: 100% !important; }}
.design-figures {{ flex: 1 1 0 !important; min-width: 280px; }}
/* Projected: the figures take the window's width and height; the inputs and readouts
   follow below the fold, side by side (their larger text fits there). */
{WIDE} {{
  :host(.projector) {{ flex-wrap: wrap !important; height: auto !important;
                      align-content: flex-start; }}
  :host(.projector) .design-figures {{ order: -1; flex: 0 0 100% !important;
    width: 100% !important; height: calc(100vh - {TOP}) !important; }}
  :host(.projector) .design-inputs, :host(.projector) .design-side {{
    height: auto !important; flex: 1 1 0 !important; min-width: 420px;
    width: auto !important; }}
}}
{PHONE} {{
  :host {{ flex-direction: column !important; min-width: 0 !important; max-width: 100vw;
           height: auto !important; flex: 0 0 auto !important; }}
  .design-figures {{ min-width: 0 !important; max-width: calc(100vw - 8px);
                     width: calc(100vw - 8px) !important; }}
  /* As tall as their content, so the figures below never cover an input. */
  .design-inputs, .design-side {{ height: auto !important; flex: 0 0 auto !important;
                                  max-width: calc(100vw - 8px); }}
}}
"""

#: A row of the distribution editor's fields: projected, their captions are larger than
#: the fields' normal widths, so each field grows to its caption and the row wraps.
FIELDS_CSS = """
:host { flex-wrap: wrap !important; row-gap: 4px; }
:host(.projector) > :not(style):not(link) { width: auto !important; min-width: 150px; }
"""

#: Projected, the map and the distribution side by side over the window's height.
PROJECTED = projector_grid("minmax(0, 1fr)", below=0, columns="minmax(0, 1fr) minmax(0, 1fr)")

FAMILY_LABELS = {"von Mises": "vonmises", "pair ±θ₀": "pair", "fixed θ₀": "fixed",
                 "uniform": "uniform", "histogram (CSV)": "histogram"}
OBJECTIVE_LABELS = {"least F_T,x": "min-FTx", "largest |F_T,y|": "max-FTy"}
#: What the bound of each objective limits (a force over μ₀F_N).
BOUND_OF = {"min-FTx": "|F_T,y|", "max-FTy": "F_T,x"}
def _g(x, digits: int = 3) -> str:
    return "–" if x is None or not math.isfinite(x) else f"{x:.{digits}g}"


def _speeds(interval) -> str:
    if interval is None:
        return "out of reach"
    lo, hi = interval
    if lo <= 0:
        return f"V₀ < {_g(hi)} m/s"
    if not math.isfinite(hi):
        return f"V₀ > {_g(lo)} m/s"
    return f"{_g(lo)} – {_g(hi)} m/s"


class DesignView(pn.viewable.Viewer):
    """Physical inputs -> the point on the map, the distribution editor, readouts, optimum."""

    state = param.ClassSelector(class_=ExplorerState, constant=True)
    results = param.ClassSelector(class_=SessionResults, constant=True)

    def __init__(self, **params):
        super().__init__(**params)
        s = self.state
        self.law = FrictionLawView(state=s, results=self.results)
        self.speeds = FrictionSpeedsView(state=s, results=self.results)
        self.inputs = {name: pn.widgets.TextInput.from_param(
            s.param[name], **caption(label), width=94, margin=(0, 3),
            css_classes=[f"ctl-{name}"]) for name, (_, _, label, _) in DESIGN_INPUTS.items()
            if name not in LAW_INPUTS}  # the law's: ``self.law``
        self.family = pn.widgets.Select.from_param(
            s.param.dist_family, options=FAMILY_LABELS, **caption("Orientations"), width=96,
            margin=(0, 3), css_classes=["ctl-dist_family"])
        self.angle = pn.widgets.FloatInput.from_param(
            s.param.dist_deg, **caption("θ₀, mean [°]"), step=5, width=92, margin=(0, 3),
            css_classes=["ctl-dist_deg"])
        self.kappa = pn.widgets.FloatInput.from_param(
            s.param.dist_kappa, **caption("κ"), step=0.5, width=58, margin=(0, 3),
            css_classes=["ctl-dist_kappa"])
        self.psi = pn.widgets.FloatInput.from_param(
            s.param.dist_psi, **caption("ψ [°]"), step=5, width=58, margin=(0, 3),
            css_classes=["ctl-dist_psi"])
        # A second component, mixed in with weight w (0: none).
        self.mix = pn.widgets.FloatInput.from_param(
            s.param.mix_weight, **caption("weight w"), step=0.1, width=74, margin=(0, 3),
            css_classes=["ctl-mix_weight"])
        self.family2 = pn.widgets.Select.from_param(
            s.param.dist2_family, options=FAMILY_LABELS, **caption("mixed with"), width=96,
            margin=(0, 3), css_classes=["ctl-dist2_family"])
        self.angle2 = pn.widgets.FloatInput.from_param(
            s.param.dist2_deg, **caption("θ₀, mean [°]"), step=5, width=92, margin=(0, 3),
            css_classes=["ctl-dist2_deg"])
        self.kappa2 = pn.widgets.FloatInput.from_param(
            s.param.dist2_kappa, **caption("κ"), step=0.5, width=58, margin=(0, 3),
            css_classes=["ctl-dist2_kappa"])
        self.objective = pn.widgets.Select.from_param(
            s.param.opt_objective, options=OBJECTIVE_LABELS, **caption("Optimise for"),
            width=120, margin=(0, 3), css_classes=["ctl-opt_objective"])
        self.bound = pn.widgets.FloatInput.from_param(
            s.param.opt_bound, **caption(""), step=0.01, width=110, margin=(0, 3),
            placeholder="none", css_classes=["ctl-opt_bound"])
        self.optimise_button = pn.widgets.Button(**caption("Optimise"), **look("primary"),
                                                 width=90, css_classes=["design-optimise"])
        self.cancel_button = pn.widgets.Button(**caption("Cancel"), **look("light"), width=70,
                                               disabled=True, css_classes=["design-cancel"])
        for widget in (*self.inputs.values(), self.family, self.angle, self.kappa, self.psi,
                       self.mix, self.family2, self.angle2, self.kappa2, self.objective,
                       self.bound, self.optimise_button, self.cancel_button):
            widget.stylesheets = [*widget.stylesheets, INPUT_CSS]  # touch-sized on a phone
        for button in (self.optimise_button, self.cancel_button):
            button.stylesheets = [*button.stylesheets, FIT_TEXT_CSS]
        self.upload = HistogramUpload(state=s)
        self.optimise_button.on_click(lambda _e: self.results.optimise())
        self.cancel_button.on_click(lambda _e: self.results.cancel_optimum())
        self.point_text = pn.pane.Markdown("", width=310, margin=(0, 5),
                                           styles={"font-size": "0.88em"},
                                           css_classes=["design-point"])
        self.table = DesignReadouts(state=s, results=self.results)
        self.readouts = self.table.table
        self.compare = pn.pane.Markdown("", width=340, margin=(0, 5), visible=False,
                                        styles={"font-size": "0.88em"},
                                        css_classes=["design-compare"])
        self.optimum_text = pn.pane.Markdown("", width=340, margin=(0, 5),
                                             styles={"font-size": "0.88em"},
                                             css_classes=["design-optimum"])
        try:
            shipped = load_regime_map()
        except (OSError, ValueError):
            shipped = None
        self.map_figure = design_map_figure(shipped, self.results.design_point)
        self.polar_figure = design_polar_figure(None, s.distribution, s.dist_psi)
        # A pinned state's point, curve and distribution, under B's; hidden until one is pinned.
        self._pinned = {self.map_figure: add_pinned(self.map_figure, "design_map",
                                                    "design_point"),
                        self.polar_figure: add_pinned(self.polar_figure, "design_polar",
                                                      "design_density")}
        self._map_sources = F.sources(self.map_figure)
        self._polar_sources = F.sources(self.polar_figure)
        # The figures fill the window's height beside the two columns of inputs and
        # readouts (as the other tabs' grids do); on a phone they stack below the inputs.
        for fig in (self.map_figure, self.polar_figure):
            fig.update(frame_width=None, frame_height=None, sizing_mode="stretch_both")
        self.map_pane = pn.pane.Bokeh(self.map_figure, margin=0, sizing_mode="stretch_both")
        self.polar_pane = pn.pane.Bokeh(self.polar_figure, margin=0, sizing_mode="stretch_both")
        self._ticker = None
        self._layouts = []  # made by __panel__
        # The figures in words (once per result) and the curve's numbers as a table.
        self.map_words, self.polar_words = (
            LiveDescription(width=0, height=0, margin=0, css_classes=[f"design-{what}-words"],
                            describes=figure_classes(fig))
            for what, fig in (("map", self.map_figure), ("polar", self.polar_figure)))
        self.polar_table = DataTable(lambda: sweep_csv(self.results.design_polar),
                                     "Fixed arrays of the design's springs against θ₀ "
                                     "(Fig. 11a)", "design-polar-table")
        for fig in (self.map_figure, self.polar_figure):
            F.style(fig, s.projector)
        self._on_point()
        self._on_polar()
        self._on_array()
        self._on_optimum()
        self._words()

    @property
    def _a(self) -> dict | None:
        """The pinned state A (every key), or None."""
        return None if self.state.pinned is None else complete(self.state.pinned)

    # ------------------------------------------------------------------ the point
    @param.depends("results.design_point", "results.errors", "results.design_point_A",
                   "state.pinned", watch=True)
    def _on_point(self) -> None:
        pt = self.results.design_point
        error = self.results.errors.get("design_point", "")
        a = self.results.design_point_A if self._a is not None else None
        data, xr, yr = design_map_data(pt, a)
        data.update(design_point_A(a))

        def draw():
            F.update(self._map_sources, data)
            self.map_figure.x_range.update(start=xr[0], end=xr[1])
            self.map_figure.y_range.update(start=yr[0], end=yr[1])
            show_pinned(self.map_figure, self._pinned[self.map_figure], a is not None)
        _locked(draw, self.map_figure)
        if error and (pt is None or error != pt.get("error")):
            self.point_text.object = f"**Not computed:** {error}"
            return
        if pt is None:
            self.point_text.object = "Computing the design's point …"
            return
        p, c = pt["point"], pt["computed"]
        lines = [f"**k̃_r = {_g(p['k_r'])}, k̃_θ = {_g(p['k_theta'])}, "
                 f"F̃_N = {_g(p['F_N'])}, ζ = {_g(p['zeta'])}, L₀ = {_g(p['L0'])}**",
                 f"Regime: **{pt['regime']}**; {STATUS_WORDS[pt['status']]}."]
        if pt["status"] == "scaled" and c is not None:
            lines.append(f"Computed at k̃_r = {_g(c['k_r'])}, k̃_θ = {_g(c['k_theta'])}, "
                         f"F̃_N = {_g(c['F_N'])} (×{_g(c['scale'])}, as at V₀ = "
                         f"{_g(pt['V0_m_per_s'] / math.sqrt(c['scale']))} m/s): the "
                         "quasi-static limit of these stiff pillars.")
        if pt["error"]:
            lines.append(f"**Not computable:** {pt['error']}")
        speeds = pt["intervals"]["V0_m_per_s"]
        reach = "; ".join(f"{r}: {_speeds(speeds[r])}" for r in
                          ("stiff", "pendulum", "slider", "soft"))
        lines.append(f"Regimes by speed — {reach}; the paper's map: "
                     f"{_speeds(pt['intervals']['V0_in_explored_map_m_per_s'])}.")
        lines.append("On the map: ★ this design, dashed: its path as V₀ changes"
                     + (", ■ the point computed" if pt["status"] == "scaled" else "")
                     + (", grey ★ the pinned A." if a is not None else "."))
        if a is not None:
            q = a["point"]
            lines.append(f"A (pinned): k̃_r = {_g(q['k_r'])}, k̃_θ = {_g(q['k_theta'])}, "
                         f"F̃_N = {_g(q['F_N'])}, regime **{a['regime']}**.")
        self.point_text.object = "  \n".join(lines)

    # ------------------------------------------------------------------ the polar curve
    @param.depends("results.design_polar", "state.dist_family", "state.dist_deg",
                   "state.dist_kappa", "state.dist_psi", "state.mix_weight",
                   "state.dist2_family", "state.dist2_deg", "state.dist2_kappa",
                   "state.dist_hist", "results.design_polar_A", "state.pinned", watch=True)
    def _on_polar(self) -> None:
        s, a = self.state, self._a
        sweep_A = self.results.design_polar_A if a is not None else None
        data, axis = design_polar_data(self.results.design_polar, s.distribution, s.dist_psi,
                                       sweep_A)
        if a is not None:
            data.update(design_polar_A(sweep_A, distribution_of(a),
                                       a["dist_psi"], axis))
        else:
            data.update(design_polar_A(None, None, 0.0, axis))

        def draw():
            F.update(self._polar_sources, {k: v for k, v in data.items()
                                           if k in self._polar_sources})
            set_extent(self.polar_figure, axis)
            show_pinned(self.polar_figure, self._pinned[self.polar_figure], a is not None)
        _locked(draw, self.polar_figure)
        self.kappa.disabled = s.dist_family != "vonmises"
        self.angle.disabled = s.dist_family in ("uniform", "histogram")
        second = s.mix_weight > 0
        self.family2.disabled = not second
        self.kappa2.disabled = not second or s.dist2_family != "vonmises"
        self.angle2.disabled = not second or s.dist2_family in ("uniform", "histogram")

    # ------------------------------------------------------------------ in words
    @param.depends("results.design_point", "results.design_array", "results.design_polar",
                   "results.busy", "state.dist_family", "state.dist_deg", "state.dist_kappa",
                   "state.dist_psi", "state.mix_weight", "state.dist2_family",
                   "state.dist2_deg", "state.dist2_kappa", "state.dist_hist", watch=True)
    def _words(self) -> None:
        """The map's and the polar diagram's words; the array's friction only once it is
        the current inputs' (not while a new one is computed)."""
        r, s = self.results, self.state
        array = None if "design_array" in r.busy else r.design_array
        point = None if "design_point" in r.busy else r.design_point
        self.map_words.text = design_map_description(point, array)
        polar = None if "design_polar" in r.busy else r.design_polar
        self.polar_words.text = design_polar_description(polar, s.distribution, s.dist_psi,
                                                         array)
        self.polar_table.refresh()

    # ------------------------------------------------------------------ readouts
    @param.depends("results.design_array", "results.design_array_A", "state.pinned",
                   watch=True)
    def _on_array(self) -> None:
        """A beside B, with B − A, when a state is pinned (B's own table: ``self.table``)."""
        r = self.results
        a = r.design_array
        pinned = self._a
        self.compare.visible = pinned is not None
        if pinned is not None:  # A beside B, with B − A
            s = self.state
            self.compare.object = design_compare_markdown(
                r.design_array_A, a,
                distribution_words(distribution_of(pinned), pinned["dist_psi"]),
                distribution_words(s.distribution, s.dist_psi))

    # ------------------------------------------------------------------ the optimum
    @param.depends("results.design_optimum", "results.optimum_note", "results.busy",
                   "results.errors", "state.dist_family", "state.mix_weight",
                   "state.opt_objective", watch=True)
    def _on_optimum(self) -> None:
        r = self.results
        running = "design_optimum" in r.busy and r.optimum_started is not None
        self.optimise_button.disabled = running
        self.cancel_button.disabled = not running
        self._tick(running)
        text = r.optimum_note
        if running and r.optimum_started is not None:
            text += f" {time.monotonic() - r.optimum_started:.0f} s so far."
        error = r.errors.get("design_optimum", "")
        if error and not running:
            text = error
        o = r.design_optimum
        if o is not None and not running:
            text += (f"  \nOptimum ({o['family']}): F_T,x/(μ₀F_N) = {o['FTx_over_mu0FN']:.4f}, "
                     f"F_T,y/(μ₀F_N) = {o['FTy_over_mu0FN']:.4f} (± {o['error_estimate']:.1e});"
                     f" uniform array {o['uniform_FTx_over_mu0FN']:.4f}: "
                     f"**{100 * o['gain']:.1f} % less friction**"
                     + ("" if o["feasible"] else " — **the bound could not be met**") + ".")
        self.bound.name = f"bound on {BOUND_OF[self.state.opt_objective]}/(μ₀F_N)"
        if not text:
            family = optimum_family(self.state)
            names = {v: k for k, v in FAMILY_LABELS.items()}
            what = ("the least F_T,x" if self.state.opt_objective == "min-FTx"
                    else "the largest |F_T,y|")
            text = (f"**Optimise** searches the {names.get(family, family)} family for {what}"
                    " (in the background; the editor is then set to the optimum).")
        self.optimum_text.object = text

    def _tick(self, running: bool) -> None:
        """Refresh the elapsed time once a second while the search runs (with a server)."""
        if running and self._ticker is None and pn.state.curdoc is not None \
                and pn.state.curdoc.session_context is not None:
            self._ticker = pn.state.add_periodic_callback(self._on_optimum, period=1000)
        elif not running and self._ticker is not None:
            self._ticker.stop()
            self._ticker = None

    @param.depends("state.projector", watch=True)
    def _restyle(self) -> None:
        for fig in (self.map_figure, self.polar_figure):
            F.style(fig, self.state.projector)
        for layout in self._layouts:
            layout.css_classes = mode_classes(layout.css_classes, self.state.projector)

    def __panel__(self):
        grid = pn.GridBox(*self.inputs.values(), ncols=3, margin=(0, 0))
        left = pn.Column(pn.pane.Markdown("**Pillar array** (values with units)",
                                          margin=(0, 5)), grid, self.point_text, self.law,
                         self.speeds, self.map_words, self.polar_words,
                         width=315,
                         css_classes=["design-inputs"])
        projector = self.state.projector
        fields = [pn.Row(*row, margin=0, stylesheets=[FIELDS_CSS],
                         css_classes=mode_classes(["design-fields"], projector))
                  for row in ((self.family, self.angle, self.kappa, self.psi),
                              (self.family2, self.angle2, self.kappa2, self.mix))]
        right = pn.Column(
            *fields, self.upload,
            self.table, self.polar_table, self.compare,
            pn.Row(self.objective, self.bound, margin=0),
            pn.Row(self.optimise_button, self.cancel_button, margin=0),
            self.optimum_text, width=345, css_classes=["design-side"])
        figures = pn.Column(self.map_pane, self.polar_pane, margin=0,
                            sizing_mode="stretch_both",
                            css_classes=mode_classes(["design-figures"], projector),
                            stylesheets=[grid_css("minmax(0, 1fr)",
                                                  "minmax(0, 1fr) minmax(0, 1fr)",
                                                  phone_height=360, min_height=600,
                                                  projector=PROJECTED)])
        row = pn.Row(left, figures, right, css_classes=mode_classes(["design-view"], projector),
                     sizing_mode="stretch_both", stylesheets=[DESIGN_ROW_CSS])
        self._layouts = [figures, row, *fields]
        return row
