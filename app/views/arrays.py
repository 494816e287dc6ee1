"""Uniform-orientation arrays: the Regime map tab (Fig. 5a/5b, from the shipped map; a
click sets k_r and k_theta) and the Load tab (Fig. 6: the paper's four regimes and the
current springs, computed point by point in a worker process while the tab is visible).
"""
from __future__ import annotations

import functools

import panel as pn
import param
from bokeh.events import Tap
from bokeh.palettes import Cividis256, Viridis256

from model import REGIMES
from model.shipped_map import load_regime_map

from .. import figures as F
from ..compute import LOAD_F_N, sweep_row, uniform_future
from ..figures.arrays import MAP_QUANTITIES
from ..jobs import LatestOnly
from ..state import ExplorerState
from .readouts import ReadoutsView


@functools.lru_cache(maxsize=1)
def shipped_map():
    """The precomputed 24 x 24 regime map (F_N = 1), read once per server process."""
    return load_regime_map()


class RegimeMapView(pn.viewable.Viewer):
    """Fig. 5a (F_T,x/(mu0 F_N)) or 5b (D_y/D_x) over (k_r, k_theta); click to choose."""

    def __init__(self, state: ExplorerState, **params):
        super().__init__(**params)
        self.state = state
        self.map = shipped_map()
        self.figure = F.regime_map_figure(self.map, state.map_quantity, state.average,
                                          current=(state.k_r, state.k_theta), width=600,
                                          height=500)
        self._sources = F.sources(self.figure)
        self._mapper = F.annotation(self.figure, "regime_map_colorbar").color_mapper
        self.figure.on_event(Tap, self._on_tap)
        self.toggle = pn.widgets.RadioButtonGroup.from_param(
            state.param.map_quantity, css_classes=["ctl-map_quantity"],
            options={"5a: F_T,x/(μ₀F_N)": "5a", "5b: D_y/D_x": "5b"}, width=300,
            description=None)
        state.param.watch(self._on_stiffness, ["k_r", "k_theta"])
        state.param.watch(self._on_quantity, ["map_quantity", "average"])
        state.param.watch(lambda e: F.style(self.figure, e.new), "projector")
        F.style(self.figure, state.projector)
        meta = self.map.metadata
        self.info = pn.pane.Markdown(
            f"Uniform arrays on a {meta.get('grid', {}).get('n', 24)}² log grid at F_N = 1 "
            f"(self-consistent β, quadrature tolerance {meta.get('tol', 1e-3):g}, largest "
            f"error {meta.get('max_quadrature_error', float('nan')):.1e}); precomputed, so it "
            "does not follow the F_N slider or the β option. **Click the map to choose k_r, "
            "k_θ.** The four labelled points are the paper's regimes; the current springs are "
            "marked ⊕.", width=330, styles={"font-size": "0.92em"}, css_classes=["map-info"])

    def _on_tap(self, event) -> None:
        if event.x is not None and event.y is not None and event.x > 0 and event.y > 0:
            self.state.set_stiffness(event.x, event.y)

    def _on_stiffness(self, *_events) -> None:
        F.update(self._sources, F.map_now(self.state.k_r, self.state.k_theta))

    def _on_quantity(self, *_events) -> None:
        q = self.state.map_quantity
        data = F.map_data(self.map, q, self.state.average)
        F.update(self._sources, data)
        lo, hi = F.value_range(data["regime_map"]["value"])
        self._mapper.update(low=lo, high=hi, palette=Viridis256 if q == "5a" else Cividis256)
        self.figure.title.text = MAP_QUANTITIES[q][1]

    def __panel__(self):
        return pn.Row(pn.pane.Bokeh(self.figure), pn.Column(self.toggle, self.info),
                      css_classes=["map-view"])


class LoadView(pn.viewable.Viewer):
    """Fig. 6 for the current (k_r, k_theta) and the paper's four regimes, one uniform
    array at a time (current springs first), while the tab is visible."""

    active = param.Boolean(False, doc="whether the tab is visible (compute only then)")
    error = param.String("")

    def __init__(self, state: ExplorerState, readouts: ReadoutsView, **params):
        super().__init__(**params)
        self.state, self.readouts = state, readouts
        self.figure = F.load_figure(width=620, height=440)
        self._sources = F.sources(self.figure)
        self.curves: dict = {"current": {}, **{r: {} for r in REGIMES}}
        self._springs = self._beta = None
        self._pending = None
        self._stale = True
        self.status = pn.pane.Markdown("", width=300, styles={"font-size": "0.92em"},
                                       css_classes=["load-status"])
        self.pane = pn.pane.Bokeh(self.figure)
        self.runner = LatestOnly(self._apply, busy=self._busy)
        state.param.watch(self._invalidate, ["k_r", "k_theta", "beta_mode", "beta"])
        state.param.watch(self._redraw, "average")
        state.param.watch(lambda e: F.style(self.figure, e.new), "projector")
        F.style(self.figure, state.projector)
        readouts.param.watch(self._mark, "uniform")
        self.param.watch(self._on_active, "active")

    @property
    def points(self) -> dict:
        """The current springs' curve: {F_N: uniform-array row}."""
        return self.curves["current"]

    def _invalidate(self, *_events) -> None:
        self._stale = True
        self.runner.cancel()
        if self.active:
            self._start()

    def _on_active(self, event) -> None:
        if event.new and self._stale:
            self._start()

    def _start(self) -> None:
        s = self.state
        self._stale = False
        if self._beta != s.array_beta:
            self.curves = {name: {} for name in self.curves}
        self.curves["current"] = {}
        self._springs, self._beta = (s.k_r, s.k_theta), s.array_beta
        self._redraw()
        self._next()

    def _todo(self):
        for name, curve in self.curves.items():
            k = self._springs if name == "current" else (REGIMES[name].k_r, REGIMES[name].k_theta)
            for F_N in LOAD_F_N:
                if F_N not in curve:
                    return name, k, F_N
        return None

    def _next(self) -> None:
        todo = self._todo()
        done = sum(len(c) for c in self.curves.values())
        total = len(LOAD_F_N) * len(self.curves)
        if todo is None:
            self._pending = None
            self.status.object = (f"{done} uniform arrays (quadrature tolerance 1e-3), "
                                  f"β {self._beta}.")
            return
        self._pending = todo
        name, (k_r, k_theta), F_N = todo
        beta = self._beta
        self.status.object = f"Computing {name}, F_N = {F_N:.3g} ({done + 1}/{total}) …"
        self.runner.submit(lambda: uniform_future(k_r, k_theta, F_N, beta))

    def _busy(self, flag: bool) -> None:
        self.pane.loading = flag and not self.points

    def _apply(self, sweep, error) -> None:
        if self._pending is None:
            return
        name, _, F_N = self._pending
        if error is not None:
            self.error = f"Fig. 6 point failed: {type(error).__name__}: {error}"
            self.status.object = self.error
            return
        self.curves[name][F_N] = sweep_row(sweep)
        self._redraw()
        self._next()

    def _redraw(self, *_events) -> None:
        avg = self.state.average
        regimes = {name: c for name, c in self.curves.items() if name != "current"}
        F.update(self._sources, {**F.load_curve_data(self.points, avg),
                                 **F.load_regimes_data(regimes, avg)})
        self._mark()

    def _mark(self, *_events) -> None:
        row = self.readouts.uniform
        col = "FTx_over_mu0FN" if self.state.average == "paper" else "FTx_over_mu0FN_duration"
        F.update(self._sources, F.load_now(self.state.F_N, row[col] if row else None))

    def __panel__(self):
        return pn.Row(self.pane, pn.Column(self.status, pn.pane.Markdown(
            "Uniform arrays (θ₀ uniform on [0°, 360°)) against the normal load (Fig. 6). "
            "Thin lines: the paper's four regimes; black: the current k_r, k_θ; red: the "
            "current F_N (the readout of the Support tab).", width=300,
            styles={"font-size": "0.92em"})), css_classes=["load-view"])
