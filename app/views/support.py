"""The Support tab: one support of the fixed-orientation array at theta0 during one contact.

The scene (a top view: pivot, rest position, path coloured by tau, springs, the sliding
slab, arrows), the friction histories (Fig. 7), the friction law (Fig. 3) with the current
|v_R| and the live split of the slab work (Eq. 12 at every tau). A renderer of
``SessionResults.support``: a new result replaces the data of the figures' sources in
place (no new figures: nothing flickers).

The animation runs in the browser (``app.figures.player``): every frame's data is sent
once per result, and a browser-side timer draws the frames -- no server round trip per
frame, labelled play/pause, single steps, speed 0.1x-4x, loop and keyboard shortcuts,
and an optional sound of the motion (``app.figures.sound``, off by default).
"""
from __future__ import annotations

import collections
import contextlib
import logging
import time

import numpy as np
import panel as pn
import param

from model.contact.friction import mu0

from .. import figures as F
from ..figures.common import legend_above, source
from ..figures.live_energy import (energy_frames, energy_live_data, energy_live_range,
                                   live_energy_figure, support_frames_callback,
                                   support_frames_data)
from ..figures.pinned import add_pinned, forces_A, orbit_A, show_pinned
from ..figures.player import READY_DELAY_MS, browser_player
from ..figures.scene import view_box
from ..figures.sound import add_sound
from ..motion_words import plots_description
from ..results import SessionResults
from ..state import ExplorerState
from .access import LiveDescription, figure_classes
from .export import AnimationExport
from .layout import grid_css, mode_classes, projector_grid
from .shown import WhenShown


log = logging.getLogger(__name__)

#: Frames of the animation of one contact (the browser draws them at 30 per second at 1x).
N_FRAMES = 300
#: Projected, the top view and Fig. 7 take the window's height above the player (the top
#: view wider); Fig. 3 and the energy split go below the fold.
PROJECTED = projector_grid("minmax(0, 1fr) auto 380px", below=380,
                           columns="minmax(0, 3fr) minmax(0, 2fr)")


def _placeholder_energies(n: int) -> dict:
    return {k: np.zeros(n) for k in ("tau", "W", "D_x", "D_y", "U_el", "K")}


class SupportView(pn.viewable.Viewer):
    """Scene, Fig. 7, Fig. 3 and the live energy split for the current support; a player."""

    state = param.ClassSelector(class_=ExplorerState, constant=True)
    results = param.ClassSelector(class_=SessionResults, constant=True)

    def __init__(self, **params):
        super().__init__(**params)
        self._doc = pn.state.curdoc
        #: Off its tab, the view is redrawn when the tab is shown (not at every move).
        self.when_shown = WhenShown(self.state, "support")
        #: Server-side seconds from a control change to updated plot data (latest last).
        self.timings: collections.deque = collections.deque(maxlen=500)
        self.spinner = pn.indicators.LoadingSpinner(value=True, size=24, visible=False,
                                                    css_classes=["support-busy"])
        p = self.state.params
        self.player = browser_player(N_FRAMES, times=np.zeros(N_FRAMES), name="support_player",
                                     width=680, responsive=True, autoplay=self.state.play)
        # The player's frames (filled with the first trajectory) and the optional sound
        # (off until the reader switches it on): pitch from |v_R|, pan from the sideways
        # friction, worked out and played in the browser from these frames.
        self.frames = source("support_frames", {"v_R": np.zeros(0), "F_y": np.zeros(0)})
        self.sound_toggle = add_sound(self.player, self.frames)
        self.scene = F.scene_figure(None, p, 0, width=340, height=330)
        self.forces = F.forces_figure(None, p, 0, width=340, height=330)
        self._mu0_label = F.annotation(self.forces, "forces_mu0_label")  # at the range's end
        self.friction = F.friction_law_figure(None, p, 0, width=340, height=225)
        self.energy_frames = source("energy_live_frames", _placeholder_energies(N_FRAMES))
        self.energy_layout = live_energy_figure(_placeholder_energies(N_FRAMES), self.player,
                                                width=340, height=225,
                                                frames=self.energy_frames)
        self.energy = self.energy_layout.children[0]
        self.figures = [self.scene, self.forces, self.friction, self.energy]
        self._sources = {}
        for fig in self.figures:
            self._sources.update(F.sources(fig))
        # The player's drawing, made before the page's models join a document: attached
        # there, each callback added would send the page's graph of models again.
        self._frames_js = support_frames_callback(
            None, p, N_FRAMES, scene=self.scene, forces=self.forces, law=self.friction,
            frame=self.player.frame, frames_source=self.frames)
        self.player.on_frame(self._frames_js)
        self._frames_js.args["fp"].js_on_change("data", self._frames_js)
        self._layout = None  # the grid, made by __panel__
        self._framed = False  # whether the scene's frame sources hold a contact's frame
        self._pinned = {self.scene: add_pinned(self.scene, "scene", "orbit"),
                        self.forces: add_pinned(self.forces, "forces", "forces")}
        for fig in self._pinned:
            self._sources.update(F.sources(fig))
        legend_above(self.friction)
        for fig in self.figures:
            fig.sizing_mode = "stretch_both"
            F.style(fig, self.state.projector)
        self.energy_layout.sizing_mode = "stretch_both"
        self.energy_layout.min_height = self.energy.min_height = 200
        self.energy_layout.children[1].sizing_mode = "stretch_width"
        self._panes = [pn.pane.Bokeh(fig, margin=(0, 5), sizing_mode="stretch_both",
                                     css_classes=["figure", f"figure-{fig.name}"])
                       for fig in (self.scene, self.forces, self.friction, self.energy_layout)]
        self._player_pane = pn.pane.Bokeh(self.player.layout, margin=(0, 5),
                                          css_classes=["player"], sizing_mode="stretch_width")
        # The plots in words, for screen readers: written once per result, never per frame.
        self.description = LiveDescription(
            text=plots_description(None), width=0, height=0, margin=0,
            css_classes=["support-description"], label="Energy split during the contact",
            describes=figure_classes(self.scene, self.forces, self.friction,
                                     self.energy_layout))
        self.export = AnimationExport(state=self.state, results=self.results, what="support")
        if self._doc is not None:
            # Keyboard shortcuts (and autoplay) start with a change the page sees: made
            # once the page is up, after the models it changes were sent (app.opening).
            player, doc = self.player, self._doc
            pn.state.onload(lambda: pn.state.add_periodic_callback(
                player.ready, period=READY_DELAY_MS, count=1))
        self._draw()

    # ------------------------------------------------------------------ results
    @param.depends("results.support", watch=True)
    def _draw(self) -> None:
        self.when_shown.run(self._draw_support)

    def _draw_support(self) -> None:
        data = self.results.support
        if data is None or data.result is None or data.series is None:
            return
        s, p = data.series, data.params
        frames = support_frames_data(s, p, N_FRAMES)
        drawn = {**F.scene_data(s, p), **F.force_data(s)}
        if not self._framed:
            # The document's first contact: its first frame goes with it. Later contacts'
            # frames are drawn in the browser by the player's callback once the new
            # frames arrive (at the frame on show), so the server does not send them.
            drawn.update(F.scene_frame(s, p, 0))
            self._framed = True
        with self._hold():
            F.update(self._sources, drawn)
            self._fit_ranges(s, p)
            if getattr(s, "W", None) is not None:
                energies = energy_frames(s, N_FRAMES)
                self.energy_frames.data = energy_live_data(energies)["energy_live_frames"]
                self.energy.y_range.update(**dict(zip(("start", "end"),
                                                      energy_live_range(energies))))
            self.player.set_times(frames["support_frames"]["tau"])
            self._frames_js.args["data"].data = frames["support_frames"]
            self._frames_js.args["fp"].data = frames["support_frame_params"]
        self.description.text = plots_description(data)
        requested = self.results.slots["support"].requested_at
        if requested is not None:
            self.timings.append(time.perf_counter() - requested)
            log.debug("support update: %.2f ms (model %.2f ms)", 1e3 * self.timings[-1],
                      1e3 * data.seconds)

    def _fit_ranges(self, s, p) -> None:
        """Fixed ranges around everything each figure will draw (B's support and a pinned
        A's): the browser then need not recompute bounds while the markers move (the
        costliest part of a frame)."""
        shown = [(s, p)]
        a = self.results.support_A
        if a is not None and a.series is not None:
            shown.append((a.series, a.params))
        boxes = [view_box(*sp) for sp in shown]
        self.scene.x_range.update(start=min(b[0] for b in boxes), end=max(b[1] for b in boxes))
        self.scene.y_range.update(start=min(b[2] for b in boxes), end=max(b[3] for b in boxes))
        xs = [F.force_x_range(series) for series, _ in shown]
        ys = [F.force_y_range(series, mu0(params)) for series, params in shown]
        self.forces.x_range.update(start=min(x[0] for x in xs), end=max(x[1] for x in xs))
        self._mu0_label.x = self.forces.x_range.end
        self.forces.y_range.update(start=min(y[0] for y in ys), end=max(y[1] for y in ys))

    @param.depends("results.support_A", watch=True)
    def _draw_pinned(self) -> None:
        self.when_shown.run(self._draw_support_A)

    def _draw_support_A(self) -> None:
        """A pinned state's path and histories, muted under B's (``app.compare``)."""
        a = self.results.support_A
        on = a is not None and a.series is not None
        with self._hold():
            F.update(self._sources, {**orbit_A(a.series if on else None, a.params if on else None),
                                     **forces_A(a.series if on else None)})
            for fig, renderers in self._pinned.items():
                show_pinned(fig, renderers, on)
            b = self.results.support
            if b is not None and b.series is not None:
                self._fit_ranges(b.series, b.params)

    @param.depends("results.busy", watch=True)
    def _busy(self) -> None:
        """Show the spinner only for work that takes a noticeable time."""
        busy = "support" in self.results.busy
        if not busy:
            self.spinner.visible = False
        elif self._doc is not None:
            self._doc.add_timeout_callback(
                lambda: setattr(self.spinner, "visible", "support" in self.results.busy), 300)

    def _hold(self):
        return pn.io.hold(self._doc) if self._doc is not None else contextlib.nullcontext()

    @param.depends("state.projector", watch=True)
    def _restyle(self) -> None:
        projector = self.state.projector
        with self._hold():
            for fig in self.figures:
                F.style(fig, projector)
            if self._layout is not None:
                self._layout.css_classes = mode_classes(self._layout.css_classes, projector)

    def __panel__(self):
        scene, forces, friction, energy = self._panes
        # stretch_both as the figures inside are (Panel would otherwise override a
        # stretch_width container, with a warning, at every page build).
        player = pn.Row(self._player_pane, self.spinner, self.description,
                        css_classes=["player-row"],
                        sizing_mode="stretch_both", margin=0)
        self._layout = pn.Column(
            scene, forces, player, friction, energy,
            css_classes=mode_classes(["support-view"], self.state.projector),
            margin=0, sizing_mode="stretch_both",
            stylesheets=[grid_css("minmax(0, 1fr) minmax(0, 1fr)",
                                  "minmax(0, 3fr) auto minmax(0, 2fr)",
                                  {"player-row": "1 / span 2"}, projector=PROJECTED)])
        return self._layout

