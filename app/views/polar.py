"""The Polar tab (Fig. 11a-c): fixed-orientation arrays against theta0 for the current
springs and load, as polar diagrams; a click on a diagram sets theta0.

The sweep (``POLAR_N`` orientations, self-consistent or fixed beta) runs in a worker
process, only while the tab is visible; a newer request supersedes an older one.
"""
from __future__ import annotations

import contextlib
import math

import numpy as np
import panel as pn
import param
from bokeh.events import Tap

from .. import figures as F
from ..compute import POLAR_N, polar_cached, polar_future
from ..jobs import LatestOnly
from ..state import SWEEP_KEYS, ExplorerState
from .support import SupportView

KEYS = ("FTx", "DyDx", "FTy")


class PolarView(pn.viewable.Viewer):
    """Three polar diagrams of the fixed arrays (Fig. 11a-c), the current theta0 marked."""

    active = param.Boolean(False, doc="whether the tab is visible (compute only then)")
    sweep = param.Parameter(None, doc="the latest orientation sweep (a SweepResult)")
    error = param.String("")

    def __init__(self, state: ExplorerState, support: SupportView, **params):
        super().__init__(**params)
        self.state, self.support = state, support
        self._doc = pn.state.curdoc
        self._stale = True
        self._axes = {}
        self.figures = {k: F.polar_figure(k, width=325, height=340) for k in KEYS}
        self._sources = {}
        for key, fig in self.figures.items():
            self._sources.update(F.sources(fig))
            fig.on_event(Tap, self._on_tap)
            self._axes[key] = F.polar_data(key, [], [])[1]
        self.status = pn.pane.Markdown("", css_classes=["polar-status"],
                                       styles={"font-size": "0.92em"}, margin=(0, 10))
        self.row = pn.Row(*(pn.pane.Bokeh(f, margin=(0, 4)) for f in self.figures.values()),
                          css_classes=["polar-view"])
        self.runner = LatestOnly(self._apply, busy=self._busy)
        state.param.watch(self._invalidate, list(SWEEP_KEYS))
        state.param.watch(self._restyle, "projector")
        for fig in self.figures.values():
            F.style(fig, state.projector)
        support.param.watch(self._mark, "data")
        self.param.watch(self._on_active, "active")
        cached = polar_cached(state.params, state.array_beta, state.rtol)
        if cached is not None:
            self._apply(cached, None)

    # ------------------------------------------------------------------ compute
    def _invalidate(self, *_events) -> None:
        self._stale = True
        if self.active:
            self._request()
        else:
            self.runner.cancel()

    def _on_active(self, event) -> None:
        if event.new and self._stale:
            self._request()

    def _request(self) -> None:
        s = self.state
        self._stale = False
        self.status.object = (f"Computing {POLAR_N} fixed-orientation arrays "
                              f"(θ₀ in (0°, 180°), mirrored) …")
        self.runner.submit(lambda: polar_future(s.params, s.array_beta, s.rtol))

    def _busy(self, flag: bool) -> None:
        self.row.loading = flag

    def _apply(self, sweep, error) -> None:
        if error is not None:
            self.error = f"Orientation sweep failed: {type(error).__name__}: {error}"
            self.status.object = self.error
            return
        self.error = ""
        cols = sweep.columns
        with self._hold():
            self.sweep = sweep
            for key in KEYS:
                column = F.POLAR_QUANTITIES[key][0]
                data, self._axes[key] = F.polar_data(key, cols["theta0"], cols[column])
                F.update(self._sources, data)
                F.set_extent(self.figures[key], self._axes[key])
            self._mark()
        bad = int(np.sum(~np.asarray(cols["success"], bool)))
        pivot = int(np.sum(np.asarray(cols["pivot_approach"], bool)))
        settings = sweep.settings
        self.status.object = (
            f"{len(cols['theta0'])} orientations in {sweep.seconds:.2f} s; "
            f"k_r = {settings['k_r']:.3g}, k_θ = {settings['k_theta']:.3g}, "
            f"F_N = {settings['F_N']:.3g}, β {settings['beta']}. "
            + (f"⚠ {bad} orientations did not succeed. " if bad else "")
            + (f"{pivot} driven into their pivot region. " if pivot else "")
            + "Click a diagram to set θ₀.")

    def _hold(self):
        return pn.io.hold(self._doc) if self._doc is not None else contextlib.nullcontext()

    # ------------------------------------------------------------------ current theta0
    def _mark(self, *_events) -> None:
        data = self.support.data
        theta0 = math.radians(self.state.theta0)
        values = {"FTx": None, "DyDx": None, "FTy": None}
        if data is not None and data.fixed is not None:
            f = data.fixed
            values = {"FTx": f.FTx_over_mu0FN, "DyDx": f.Dy_over_Dx, "FTy": f.FTy_over_mu0FN}
        for key in KEYS:
            F.update(self._sources, F.polar_now(key, theta0, values[key], self._axes[key]))

    def _on_tap(self, event) -> None:
        if event.x is None or event.y is None or (event.x == 0 and event.y == 0):
            return
        self.state.set_theta0(math.degrees(math.atan2(event.y, event.x)))

    def _restyle(self, event) -> None:
        for fig in self.figures.values():
            F.style(fig, event.new)

    def __panel__(self):
        return pn.Column(self.row, self.status, pn.pane.Markdown(
            "Fixed-orientation arrays: every support shares θ₀ (Fig. 9). The radius is the "
            "quantity, the angle is θ₀ (0° = sliding direction +x). F_T,x and D_y/D_x are even "
            "in θ₀, F_T,y is odd; F_T,y is drawn about the bold zero ring.",
            styles={"font-size": "0.92em"}, margin=(0, 10), width=900))

