"""The Polar tab (Fig. 11a-c): fixed-orientation arrays against theta0 for the current
springs and load, as polar diagrams; a click on a diagram sets theta0.

A renderer of ``SessionResults.polar`` (the sweep, computed only while this tab is
visible) and ``SessionResults.support`` (the current theta0's values, marked).
"""
from __future__ import annotations

import contextlib
import math

import numpy as np
import panel as pn
import param
from bokeh.events import Tap

from .. import figures as F
from ..export import sweep_csv
from ..figures.pinned import add_pinned, polar_A, show_pinned
from ..plot_words import polar_description
from ..results import SessionResults
from ..state import ExplorerState
from ..worker import POLAR_N
from .access import LiveDescription, figure_classes
from .click_keys import theta_steps
from .data_table import DataTable
from .layout import grid_css
from .shown import WhenShown

KEYS = ("FTx", "DyDx", "FTy")


class PolarView(pn.viewable.Viewer):
    """Three polar diagrams of the fixed arrays (Fig. 11a-c), the current theta0 marked."""

    state = param.ClassSelector(class_=ExplorerState, constant=True)
    results = param.ClassSelector(class_=SessionResults, constant=True)

    def __init__(self, **params):
        super().__init__(**params)
        self._doc = pn.state.curdoc
        self.when_shown = WhenShown(self.state, "polar")  # the marks wait off the tab
        self._axes = {}
        self.figures = {k: F.polar_figure(k, width=325, height=340) for k in KEYS}
        for fig in self.figures.values():  # fill the window; match_aspect keeps them round
            fig.update(frame_width=None, frame_height=None, sizing_mode="stretch_both")
        self._sources = {}
        for key, fig in self.figures.items():
            self._sources.update(F.sources(fig))
            fig.on_event(Tap, self._on_tap)
            self._axes[key] = F.polar_data(key, [], [])[1]
        # A pinned state's curves (``app.compare``), under B's; hidden until one is pinned.
        self._pinned = {fig: add_pinned(fig, "polar", f"polar_{key}" + (
            "_pos" if F.POLAR_QUANTITIES[key][2] == "odd" else ""), key)
                        for key, fig in self.figures.items()}
        for fig in self.figures.values():
            self._sources.update(F.sources(fig))
            F.style(fig, self.state.projector)
        self.status = pn.pane.Markdown("", css_classes=["polar-status"],
                                       styles={"font-size": "0.92em"}, margin=(0, 10))
        self.caption = self._caption()
        # The diagrams in words and in numbers, once per result.
        self.description = LiveDescription(text=polar_description(None), width=0, height=0,
                                           margin=0, css_classes=["polar-description"],
                                           describes=figure_classes(*self.figures.values()))
        r = self.results
        self.table = DataTable(lambda: sweep_csv(r.polar, pinned=r.polar_A,
                                                 comparing=r.comparing),
                               "Fixed arrays against θ₀ (Fig. 11)", "polar-table")
        self.panes = [pn.pane.Bokeh(f, margin=(0, 4), sizing_mode="stretch_both",
                                    css_classes=["figure", f"figure-{f.name}"])
                      for f in self.figures.values()]
        self._draw()
        self._on_busy()

    # ------------------------------------------------------------------ results
    @param.depends("results.polar", "results.polar_A", watch=True)
    def _draw(self) -> None:
        sweep, pinned = self.results.polar, self.results.polar_A
        if sweep is None:
            return
        cols = sweep.columns
        a = pinned.columns if pinned is not None else None
        with self._hold():
            for key in KEYS:
                column, _, parity = F.POLAR_QUANTITIES[key]
                data, self._axes[key] = F.polar_data(key, cols["theta0"], cols[column],
                                                     a[column] if a is not None else ())
                F.update(self._sources, {**data, **polar_A(
                    key, a["theta0"] if a is not None else None,
                    a[column] if a is not None else None, parity, self._axes[key])})
                F.set_extent(self.figures[key], self._axes[key])
                show_pinned(self.figures[key], self._pinned[self.figures[key]], a is not None)
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
            + "Click a diagram to set θ₀ (or, from the keyboard, the buttons below).")
        self.table.refresh()

    @param.depends("results.busy", "results.errors", watch=True)
    def _on_busy(self) -> None:
        busy = "polar" in self.results.busy
        for pane in self.panes:
            pane.loading = busy
        error = self.results.errors.get("polar", "")
        if error:
            self.status.object = error
        elif busy:
            self.status.object = (f"Computing {POLAR_N} fixed-orientation arrays "
                                  f"(θ₀ in (0°, 180°), mirrored) …")

    def _hold(self):
        return pn.io.hold(self._doc) if self._doc is not None else contextlib.nullcontext()

    # ------------------------------------------------------------------ current theta0
    @param.depends("results.support", watch=True)
    def _mark(self) -> None:
        self.when_shown.run(self._mark_theta0)

    def _mark_theta0(self) -> None:
        data = self.results.support
        values = {"FTx": None, "DyDx": None, "FTy": None}
        theta0 = math.radians(self.state.theta0)
        if data is not None and data.fixed is not None:
            f = data.fixed
            theta0 = data.params.theta0
            values = {"FTx": f.FTx_over_mu0FN, "DyDx": f.Dy_over_Dx, "FTy": f.FTy_over_mu0FN}
        for key in KEYS:
            F.update(self._sources, F.polar_now(key, theta0, values[key], self._axes[key]))
        self.description.text = polar_description(self.results.polar, data)

    def _on_tap(self, event) -> None:
        if event.x is None or event.y is None or (event.x == 0 and event.y == 0):
            return
        self.state.set_theta0(math.degrees(math.atan2(event.y, event.x)))

    @param.depends("state.projector", watch=True)
    def _restyle(self) -> None:
        # Projected, the diagrams take the room (their legends say how to read F_T,y).
        self.caption.visible = not self.state.projector
        for fig in self.figures.values():
            F.style(fig, self.state.projector)

    def __panel__(self):
        notes = pn.Column(self.status, theta_steps(self.state), self.caption, self.table,
                          self.description,
                          css_classes=["polar-notes"],
                          sizing_mode="stretch_width", margin=0)
        return pn.Column(
            *self.panes, notes, css_classes=["polar-view"], margin=0,
            sizing_mode="stretch_both",
            stylesheets=[grid_css("repeat(3, minmax(0, 1fr))", "minmax(0, 1fr) auto",
                                  {"polar-notes": "1 / span 3"}, phone_height=400)])

    def _caption(self):
        return pn.pane.Markdown(
            "Fixed-orientation arrays: every support shares θ₀ (Fig. 9). The radius is the "
            "quantity, the angle is θ₀ (0° = sliding direction +x). F_T,x and D_y/D_x are even "
            "in θ₀, F_T,y is odd. **Reading the F_T,y diagram:** its radius counts from the "
            "bold zero ring, so a point outside the ring (blue) pushes the slab sideways "
            "towards +y and a point inside it (orange) towards −y; at θ₀ = 0° and 180° the "
            "curve crosses the ring (no sideways force).",
            styles={"font-size": "0.92em"}, margin=(0, 10), sizing_mode="stretch_width",
            css_classes=["polar-caption"], visible=not self.state.projector)
