"""Uniform-orientation arrays: the Regime map tab (Fig. 5a/5b; a click sets k_r and
k_theta) and the Load tab (Fig. 6: the paper's four regimes and the current springs).

Renderers of ``SessionResults.regime_map`` and ``SessionResults.load`` (with
``.uniform`` marking the current load on Fig. 6).
"""
from __future__ import annotations

import panel as pn
import param
from bokeh.events import Tap
from bokeh.palettes import Cividis256, Viridis256

from .. import figures as F
from ..figures.arrays import AVERAGE_COLUMNS, map_title
from ..figures.pinned import add_pinned, load_curve_A, show_pinned
from ..results import SessionResults
from ..state import ExplorerState
from ..export import load_csv, map_csv
from ..plot_words import load_description, map_description
from ..worker import LOAD_F_N, UNIFORM_TOL
from .access import LiveDescription, figure_classes
from .click_keys import map_cell, map_steps
from .data_table import DataTable
from .export import ResultDownload, svg_button
from .layout import BUTTON_CSS, grid_css

#: One figure beside a column of text (narrower in projector mode): the figure takes what
#: the window leaves.
FIGURE_AND_TEXT = grid_css("minmax(0, 1fr) var(--mp-text-width, 330px)", "minmax(0, 1fr)",
                           phone_height=420)


class RegimeMapView(pn.viewable.Viewer):
    """Fig. 5a (F_T,x/(mu0 F_N)) or 5b (D_y/D_x) over (k_r, k_theta); click to choose."""

    state = param.ClassSelector(class_=ExplorerState, constant=True)
    results = param.ClassSelector(class_=SessionResults, constant=True)

    def __init__(self, **params):
        super().__init__(**params)
        state = self.state
        self.map = self.results.regime_map
        self.figure = F.regime_map_figure(self.map, state.map_quantity, state.average,
                                          current=(state.k_r, state.k_theta), width=600,
                                          height=500)
        self.figure.sizing_mode = "stretch_both"
        self._sources = F.sources(self.figure)
        self._mapper = F.annotation(self.figure, "regime_map_colorbar").color_mapper
        self.figure.on_event(Tap, self._on_tap)
        self.toggle = pn.widgets.RadioButtonGroup.from_param(
            state.param.map_quantity, css_classes=["ctl-map_quantity"],
            stylesheets=[BUTTON_CSS],
            options={"5a: friction F_T,x/(μ₀F_N)": "5a", "5b: D_y/D_x": "5b"}, orientation="vertical",
            sizing_mode="stretch_width", description=None)
        F.style(self.figure, state.projector)
        self.info = pn.pane.Markdown("", sizing_mode="stretch_width",
                                     styles={"font-size": "0.92em"}, css_classes=["map-info"])
        self.csv = ResultDownload(lambda: map_csv(self.results.regime_map), "regime_map.csv",
                                  "map", results=self.results, name="regime_map",
                                  label="Map CSV")
        self.svg = svg_button("map-svg")
        # The map in words (with the current springs' cell) and in numbers.
        self.description = LiveDescription(width=0, height=0, margin=0,
                                           css_classes=["map-description"],
                                           describes=figure_classes(self.figure))
        self.table = DataTable(lambda: map_csv(self.results.regime_map),
                               "Uniform arrays over k_r and k_θ (Fig. 5)", "map-table")
        self.keys = map_steps(state, lambda: map_cell(self.results.regime_map))
        self._describe()
        self._words()

    def _on_tap(self, event) -> None:
        if event.x is not None and event.y is not None and event.x > 0 and event.y > 0:
            self.state.set_stiffness(event.x, event.y)

    @param.depends("state.k_r", "state.k_theta", watch=True)
    def _on_stiffness(self) -> None:
        F.update(self._sources, F.map_now(self.state.k_r, self.state.k_theta))

    @param.depends("state.k_r", "state.k_theta", "state.map_quantity", "state.average",
                   "results.regime_map", watch=True)
    def _words(self) -> None:
        s = self.state
        self.description.text = map_description(self.results.regime_map, s.map_quantity,
                                                s.average, s.k_r, s.k_theta)
        self.table.refresh()

    @param.depends("results.regime_map", "results.busy", "results.errors", watch=True)
    def _describe(self) -> None:
        """Which map is on show (load, beta, grid, how it was made), and what is coming."""
        m, busy = self.results.regime_map, "regime_map" in self.results.busy
        error = self.results.errors.get("regime_map", "")
        if m is None:
            head = error or "Computing the regime map for this load …"
        else:
            meta = m.metadata
            n = meta.get("grid", {}).get("n", m.k_r.size)
            made = ("precomputed" if meta.get("computed") != "on this server"
                    else f"computed here in {meta.get('seconds', float('nan')):.1f} s")
            head = (f"Uniform arrays on a {n}×{n} log grid at F_N = {meta.get('F_N', 1.0):g}, "
                    f"β {meta.get('beta', 'self')}, quadrature tolerance "
                    f"{meta.get('tol', 1e-3):g} (largest error "
                    f"{meta.get('max_quadrature_error', float('nan')):.1e}); {made}.")
            if busy:
                head += " **Refining …**"
            elif error:
                head += f" {error}"
        self.info.object = (
            f"{head} The map follows the F_N slider and the β option: loads "
            "0.1, 0.3, 1, 3 and 10 are shipped, others are computed here (a coarse map "
            "first). **Click the map to choose k_r, k_θ** (or, from the keyboard, the "
            "buttons below). Dashed lines: where the regime "
            "text switches; the four labelled points are the paper's regimes; the current "
            "springs are marked ⊕.")

    @param.depends("state.map_quantity", "state.average", "results.regime_map", watch=True)
    def _on_quantity(self) -> None:
        q = self.state.map_quantity
        self.map = self.results.regime_map
        data = F.map_data(self.map, q, self.state.average)
        F.update(self._sources, data)
        lo, hi = F.value_range(data["regime_map"]["value"])
        self._mapper.update(low=lo, high=hi, palette=Viridis256 if q == "5a" else Cividis256)
        self.figure.title.text = map_title(q, self.map, self.state.average)

    @param.depends("state.projector", watch=True)
    def _restyle(self) -> None:
        F.style(self.figure, self.state.projector)

    def __panel__(self):
        return pn.Column(
            pn.pane.Bokeh(self.figure, sizing_mode="stretch_both",
                          css_classes=["figure", "figure-regime_map"]),
            pn.Column(self.toggle, self.info, self.keys, pn.Row(self.csv, self.svg, margin=0,
                                                     sizing_mode="stretch_width"),
                      self.table, self.description, css_classes=["side-column"], margin=0),
            css_classes=["map-view"], margin=0, sizing_mode="stretch_both",
            stylesheets=[FIGURE_AND_TEXT])


class LoadView(pn.viewable.Viewer):
    """Fig. 6 for the current (k_r, k_theta) and the paper's four regimes."""

    state = param.ClassSelector(class_=ExplorerState, constant=True)
    results = param.ClassSelector(class_=SessionResults, constant=True)

    def __init__(self, **params):
        super().__init__(**params)
        self.figure = F.load_figure(width=620, height=440)
        self.figure.sizing_mode = "stretch_both"
        self._pinned = add_pinned(self.figure, "load", "load_curve")
        self._sources = F.sources(self.figure)
        self.status = pn.pane.Markdown("", sizing_mode="stretch_width",
                                       styles={"font-size": "0.92em"},
                                       css_classes=["load-status"])
        self.pane = pn.pane.Bokeh(self.figure, sizing_mode="stretch_both",
                                  css_classes=["figure", "figure-load"])
        F.style(self.figure, self.state.projector)
        self.csv = ResultDownload(lambda: load_csv(self.results.load), "load_curves.csv",
                                  "load", results=self.results, name="load",
                                  label="Load curves CSV")
        self.svg = svg_button("load-svg")
        self.description = LiveDescription(width=0, height=0, margin=0,
                                           css_classes=["load-description"],
                                           describes=figure_classes(self.figure))
        self.table = DataTable(lambda: load_csv(self.results.load),
                               "Uniform arrays against the load (Fig. 6)", "load-table")
        self._redraw()

    @property
    def curves(self) -> dict:
        return self.results.load or {}

    @property
    def points(self) -> dict:
        """The current springs' curve: {F_N: uniform-array row}."""
        return self.curves.get("current", {})

    @param.depends("results.load", "state.average", watch=True)
    def _redraw(self) -> None:
        avg = self.state.average
        regimes = {name: c for name, c in self.curves.items() if name != "current"}
        F.update(self._sources, {**F.load_curve_data(self.points, avg),
                                 **F.load_regimes_data(regimes, avg)})
        self._mark()
        self._on_busy()
        self._draw_pinned()

    @param.depends("results.load_A", watch=True)
    def _draw_pinned(self) -> None:
        """A pinned state's curve, muted (``app.compare``)."""
        points = self.results.load_A
        F.update(self._sources, load_curve_A(points, AVERAGE_COLUMNS[self.state.average]))
        show_pinned(self.figure, self._pinned, bool(points))

    @param.depends("results.uniform", "state.F_N", watch=True)
    def _mark(self) -> None:
        row = self.results.uniform
        col = AVERAGE_COLUMNS[self.state.average]
        F.update(self._sources, F.load_now(self.state.F_N, row[col] if row else None))
        self.description.text = load_description(self.results.load, self.state.F_N,
                                                 self.state.average, row)
        self.table.refresh()

    @param.depends("results.busy", "results.errors", watch=True)
    def _on_busy(self) -> None:
        busy = {"load", "load_regimes"} & set(self.results.busy)
        error = self.results.errors.get("load") or self.results.errors.get("load_regimes")
        self.pane.loading = bool(busy) and not self.points
        done = sum(len(c) for c in self.curves.values())
        if error:
            self.status.object = error
        elif busy:
            self.status.object = "Computing the load curves (uniform arrays) …"
        elif done:
            self.status.object = (f"{done} uniform arrays (quadrature tolerance "
                                  f"{UNIFORM_TOL:g}), β {self.state.array_beta}.")

    @param.depends("state.projector", watch=True)
    def _restyle(self) -> None:
        F.style(self.figure, self.state.projector)

    def __panel__(self):
        return pn.Column(self.pane, pn.Column(self.status, pn.pane.Markdown(
            "Uniform arrays (θ₀ uniform on [0°, 360°)) against the normal load (Fig. 6), "
            f"at F_N = {', '.join(f'{f:.2g}' for f in LOAD_F_N)}. "
            "Coloured lines: the paper's four regimes; black: the current k_r, k_θ; the "
            "marker: the current F_N. The curves show the average chosen under "
            "Advanced options (the headline gives the duration-weighted one, the force the "
            "slab feels).",
            sizing_mode="stretch_width", styles={"font-size": "0.92em"}),
            pn.Row(self.csv, self.svg, margin=0, sizing_mode="stretch_width"),
            self.table, self.description, css_classes=["side-column"], margin=0),
            css_classes=["load-view"], margin=0, sizing_mode="stretch_both",
            stylesheets=[FIGURE_AND_TEXT])
