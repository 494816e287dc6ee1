"""The Support tab: one support of the fixed-orientation array at theta0 during one contact.

The scene (pivot, rest position, path coloured by tau, springs, slab), the friction
histories (Fig. 7), the friction law (Fig. 3) with the current |v_R| and the split of the
slab work (Eq. 12). A player animates the contact. New results replace the data of the
figures' sources in place (no new figures: zoom is kept, nothing flickers).
"""
from __future__ import annotations

import collections
import concurrent.futures as cf
import contextlib
import logging
import time

import panel as pn
import param

from .. import figures as F
from ..compute import SAMPLES, SupportData, support_future
from ..jobs import LatestOnly
from ..state import SUPPORT_KEYS, ExplorerState
from .widgets import caption

log = logging.getLogger(__name__)


class SupportView(pn.viewable.Viewer):
    """Scene, Fig. 7, Fig. 3 and the energy split for the current support; a player."""

    data = param.ClassSelector(class_=SupportData, doc="the latest single-support result")
    error = param.String("", doc="what went wrong with the latest request, if anything")
    busy = param.Boolean(False, doc="a computation is under way")

    def __init__(self, state: ExplorerState, **params):
        super().__init__(**params)
        self.state = state
        self._doc = pn.state.curdoc
        #: Server-side seconds from a control change to updated plot data (latest last).
        self.timings: collections.deque = collections.deque(maxlen=500)
        self._requested = None
        self.spinner = pn.indicators.LoadingSpinner(value=True, size=24, visible=False,
                                                    css_classes=["support-busy"])
        data, first = _first(state)
        self.player = pn.widgets.Player(
            **caption("Animation"), start=0, end=SAMPLES - 1, value=0, step=2, interval=50,
            loop_policy="loop", show_loop_controls=False, show_value=False, width=330,
            scale_buttons=0.8, css_classes=["player"], margin=(0, 5),
            visible_buttons=["slower", "first", "previous", "reverse", "pause", "play",
                             "next", "last", "faster"])
        series, p, i = data.series, data.params, 0
        self.scene = F.scene_figure(series, p, i, width=340, height=330)
        self.forces = F.forces_figure(series, p, i, width=340, height=330)
        self.friction = F.friction_law_figure(series, p, i, width=340, height=225)
        self.energy = F.energy_figure(data.energy_fractions(), width=340, height=225)
        self.figures = [self.scene, self.forces, self.friction, self.energy]
        self._sources = {}
        for fig in self.figures:
            self._sources.update(F.sources(fig))
        self._time_label = F.annotation(self.scene, "scene_time")
        self._time_span = F.annotation(self.forces, "forces_time")
        self.data, self.error = data, data.error
        self.runner = LatestOnly(self._apply, busy=self._busy)
        if data.result is None and not data.error:  # fill the plots when it arrives
            self.runner.submit(lambda: first)
        state.param.watch(self._request, list(SUPPORT_KEYS))
        state.param.watch(self._restyle, "projector")
        for fig in self.figures:
            F.style(fig, state.projector)
        self.player.param.watch(self._on_frame, "value")
        self._panes = [pn.pane.Bokeh(fig, margin=(0, 5)) for fig in self.figures]
        self.hint = pn.pane.Markdown(
            "▶ animates the contact: the slab (blue band) slides over the support; its "
            "trailing edge reaches the mass at τ_out.", width=300, margin=(0, 5),
            styles={"font-size": "0.85em"}, visible=not state.projector)

    # ------------------------------------------------------------------ compute
    def _request(self, *_events) -> None:
        self._requested = time.perf_counter()
        try:
            params = self.state.params
        except ValueError as exc:
            self.error = f"Invalid parameters: {exc}"
            return
        args = (params, self.state.array_beta, self.state.rtol)
        self.runner.submit(lambda: support_future(*args))

    def _apply(self, data: SupportData | None, error) -> None:
        if error is not None or data is None:
            self.error = f"The computation failed: {type(error).__name__}: {error}"
            return

        self.error = data.error
        if data.result is None:  # the model raised: keep the last good plots
            return
        with self._hold():
            self.data = data
            s, p = data.series, data.params
            F.update(self._sources, {**F.scene_data(s, p), **F.force_data(s),
                                     **F.energy_data(data.energy_fractions())})
            self._draw_frame(self.player.value)
        if self._requested is not None:
            self.timings.append(time.perf_counter() - self._requested)
            log.debug("support update: %.2f ms (model %.2f ms)", 1e3 * self.timings[-1],
                      1e3 * data.seconds)

    def _busy(self, flag: bool) -> None:
        """Show the spinner only for work that takes a noticeable time."""
        self.busy = flag
        if not flag:
            self.spinner.visible = False
        elif self._doc is not None:
            self._doc.add_timeout_callback(
                lambda: setattr(self.spinner, "visible", self.busy), 300)

    def _hold(self):
        return pn.io.hold(self._doc) if self._doc is not None else contextlib.nullcontext()

    # ------------------------------------------------------------------ animation
    def _on_frame(self, event) -> None:
        with self._hold():
            self._draw_frame(event.new)

    def _draw_frame(self, i: int) -> None:
        s, p = self.data.series, self.data.params
        F.update(self._sources, {**F.scene_frame(s, p, i), **F.force_now(s, i),
                                 **F.friction_now(s, i, p)})
        now = self._sources["forces_now"].data["tau"]
        self._time_span.location = float(now[0]) if len(now) else 0.0
        self._time_label.text = F.time_text(s, i)

    def _restyle(self, event) -> None:
        self.hint.visible = not event.new
        with self._hold():
            for fig in self.figures:
                F.style(fig, event.new)

    def __panel__(self):
        scene, forces, friction, energy = self._panes
        return pn.Column(pn.Row(scene, forces), pn.Row(self.player, self.spinner, self.hint),
                         pn.Row(friction, energy), css_classes=["support-view"])


def _first(state: ExplorerState, wait: float = 1.0):
    """The first result of a session and its future: waited for briefly so the page opens
    with data; a slow one (a hard case in the URL) starts with empty plots."""
    future = support_future(state.params, state.array_beta, state.rtol)
    try:
        return future.result(timeout=wait), future
    except cf.TimeoutError:
        return SupportData(state.params, None, None, ""), future
    except Exception as exc:  # a worker that could not start: say so, keep the page
        return SupportData(state.params, None, None,
                           f"The computation failed: {type(exc).__name__}: {exc}"), future
