"""The Design tab's friction against sliding speed: the structured surface's F_T,x/F_N at
each speed of a range (``model.lab.speed_curve``) beside the flat material's mu(V0) of Eq. (4),
and its comparison with the structured sample's measured curve
(``model.lab.friction_compare.compare_friction``).

Controls (``ExplorerState.speeds_range``, ``speeds_n``, ``structured_curve`` and the
design's inputs) -> ``SpeedResults`` -> the views. ``predict_speeds`` hands each speed to
the work pool's background lane as a job of its own (``worker.compute_speed_point``, with
its own budget ``worker.SPEED_POINT_S``), so points arrive one by one, in the order they
finish, and are applied with the session's document locked; ``cancel_speeds`` drops the
jobs not started (a running one finishes in its worker and is ignored). A change of the
design, its law or its orientations drops the curve: it no longer describes the inputs.
"""
from __future__ import annotations

import asyncio
import json
import logging
import math
import time

import numpy as np
import panel as pn
import param

from model.lab.friction_compare import compare_friction
from model.lab.speed_curve import SpeedCurve, SpeedPoint, check_own_V_s, parse_speeds, speed_range

from . import worker
from .jobs import work_pool
from .state import DESIGN_KEYS, DIST_KEYS

log = logging.getLogger(__name__)

#: Seconds a speed's job may hold its worker before the pool stops it (the model's own
#: budget, ``worker.SPEED_POINT_S``, ends the refinement well before).
SPEED_JOB_S = 2 * worker.SPEED_POINT_S
#: Inputs whose change drops the curve (it was computed for others).
SPEED_INPUTS = (*DESIGN_KEYS, *DIST_KEYS, "beta_mode", "beta", "speeds_range", "speeds_n")


class SpeedResults(param.Parameterized):
    """The friction-velocity curve and its comparison (module doc); a base of
    ``app.results.SessionResults``, which gives ``state``, ``session_id`` and ``client``."""

    speed_points = param.List([], doc=(
        "Design tab: one model.lab.speed_curve.SpeedPoint per speed in increasing speed, None "
        "where it has not arrived"))
    speed_running = param.Boolean(False, doc="whether the curve's speeds are being computed")
    speed_note = param.String("", doc="what the curve's computation is doing, or did")
    speed_comparison = param.Parameter(None, doc=(
        "Design tab: the measured structured curve against the prediction "
        "(model.FrictionComparison), or None"))
    speed_compare_note = param.String("", doc="why there is no comparison, if there is none")

    def _init_speeds(self) -> None:
        self._speed_generation = 0
        self._speed_futures = []
        self._speed_started = None
        self._speed_doc = None
        self._speed_law = None
        self.state.param.watch(self._drop_speeds, list(SPEED_INPUTS))
        self.state.param.watch(self._compare_speeds, ["structured_curve"])

    # ------------------------------------------------------------------ requests
    def speed_request(self):
        """(design, speeds in m/s) of the state; ``ValueError`` naming an unusable input."""
        s = self.state
        design = worker.design_of(s.design_inputs)
        check_own_V_s(design)
        lo, hi = parse_speeds(s.speeds_range)
        return design, speed_range(lo, hi, int(s.speeds_n))

    def predict_speeds(self) -> None:
        """Compute the curve in the background, speed by speed (module doc)."""
        self.cancel_speeds(quiet=True)
        try:
            design, speeds = self.speed_request()
        except ValueError as error:
            self.speed_points, self.speed_comparison = [], None
            self.speed_note = f"**Not computed:** {error}"
            return
        s, generation = self.state, self._speed_generation
        self.speed_points = [None] * len(speeds)
        self.speed_comparison, self.speed_compare_note = None, ""
        self.speed_running, self._speed_started = True, time.monotonic()
        self._set_busy("speed_curve", True)
        self.speed_note = f"Computing {len(speeds)} speeds in the background …"
        pool, distribution = work_pool(), s.distribution
        self._speed_law = design.friction_law
        self._speed_futures = [pool.submit(
            "background", ("speed_point", design, float(V0), json.dumps(distribution, sort_keys=True),
                           float(s.dist_psi), s.array_beta),
            worker.compute_speed_point, design, float(V0), distribution, float(s.dist_psi),
            s.array_beta, session=self.session_id, client=getattr(self, "client", None),
            budget_s=SPEED_JOB_S) for V0 in speeds]
        self._collect(generation, list(zip(speeds, self._speed_futures)))

    def cancel_speeds(self, quiet: bool = False) -> None:
        """Drop the speeds not computed yet (queued jobs never run)."""
        self._close_speeds()
        if self.speed_running and not quiet:
            done = sum(p is not None for p in self.speed_points)
            self.speed_note = (f"Cancelled after {done} of {len(self.speed_points)} speeds; "
                               "a speed already running finishes in its worker, ignored.")
        self.speed_running = False
        self._set_busy("speed_curve", False)

    def _close_speeds(self, *_session_context) -> None:
        """The session ended: queued speeds never run, late ones are ignored; nothing on
        the page is touched."""
        self._speed_generation += 1
        for future in self._speed_futures:
            future.cancel()
        self._speed_futures = []

    def _drop_speeds(self, *_events) -> None:
        if not self.speed_points and not self.speed_running:
            return
        running = self.speed_running
        self.cancel_speeds(quiet=True)
        self.speed_points, self.speed_comparison, self.speed_compare_note = [], None, ""
        self.speed_note = ("The design changed: its friction-velocity curve was dropped"
                           + (" while computing" if running else "") + "; predict again.")

    # ------------------------------------------------------------------ arrivals
    def _collect(self, generation: int, jobs) -> None:
        """Apply each speed as it finishes: at once without a server session (tests,
        notebooks), else on the session's document, locked, as each future resolves."""
        doc = self._speed_doc or pn.state.curdoc  # once bound, this session's (app.slot)
        if doc is None or doc.session_context is None:
            for i, (V0, future) in enumerate(jobs):
                self._arrive(generation, i, V0, future)
            return
        if doc is not self._speed_doc:
            self._speed_doc = doc
            doc.on_session_destroyed(self._close_speeds)

        async def one(i, V0, future):
            try:
                await asyncio.wrap_future(future)
            except BaseException:  # noqa: BLE001 - read from the future in _arrive
                pass
            return i, V0, future

        async def collect():
            for next_one in asyncio.as_completed([one(i, V0, f)
                                                  for i, (V0, f) in enumerate(jobs)]):
                i, V0, future = await next_one
                if generation != self._speed_generation:
                    return
                doc.add_next_tick_callback(lambda i=i, V0=V0, future=future: self._locked(
                    doc, self._arrive, generation, i, V0, future))
        pn.state.execute(collect)

    @staticmethod
    def _locked(doc, fn, *args) -> None:
        try:
            with pn.io.hold(doc):
                fn(*args)
        except Exception:
            log.exception("friction-velocity update failed")

    def _arrive(self, generation: int, i: int, V0: float, future) -> None:
        if generation != self._speed_generation or future.cancelled():
            return
        try:
            point = future.result()
        except Exception as error:  # noqa: BLE001 - the pool's words: stopped, busy
            point = SpeedPoint(float(V0), float(self._speed_law.mu(V0)), math.nan, math.nan,
                               math.nan, False, "not_computed", f"{error}")
        points = list(self.speed_points)
        points[i] = point
        done = sum(p is not None for p in points)
        if done == len(points):
            self.speed_running = False
            self._set_busy("speed_curve", False)
            self.speed_note = finished_note(points, time.monotonic() - self._speed_started)
        else:
            self.speed_note = f"{done} of {len(points)} speeds computed …"
        self.speed_points = points
        if done == len(points):
            self._compare_speeds()

    # ------------------------------------------------------------------ comparison
    @property
    def speed_law(self):
        """The friction law (``FrictionLaw``) the curve on show was requested with."""
        return self._speed_law

    @property
    def speed_curve(self) -> SpeedCurve | None:
        """The finished curve (every speed arrived), or None."""
        points = self.speed_points
        if not points or any(p is None for p in points):
            return None
        return SpeedCurve(law=self._speed_law.to_dict(), points=tuple(points), seconds=0.0)

    def _compare_speeds(self, *_events) -> None:
        measured, curve = self.state.structured_curve, self.speed_curve
        self.speed_comparison, self.speed_compare_note = None, ""
        if measured is None:
            return
        if curve is None:
            self.speed_compare_note = ("Predict the curve over speeds that cover the "
                                       "measurement to compare with it.")
            return
        try:
            self.speed_comparison = compare_friction(curve, measured)
        except ValueError as error:
            self.speed_compare_note = f"**Not compared:** {error}"


def finished_note(points, seconds: float) -> str:
    """How the curve's computation ended: time, successes, and the speeds whose budget ran
    out or that the model could not compute, with the first one's reason."""
    failed = [p for p in points if not p.success]
    text = (f"Done in {seconds:.1f} s: {len(points) - len(failed)} of {len(points)} speeds "
            f"computed to their error bars.")
    budget = [p for p in failed if "time budget" in p.message or "was stopped" in p.message]
    if budget:
        text += (f" The budget of {worker.SPEED_POINT_S:g} s per speed ran out at "
                 f"{speed_words([p.V0 for p in budget])} (their error bars say how far they "
                 f"got).")
    other = [p for p in failed if p not in budget]
    if other:
        text += (f" Not computed at {speed_words([p.V0 for p in other])}: "
                 f"{other[0].message}.")
    return text


def speed_words(speeds) -> str:
    """Speeds (m/s) in words: '0.1, 0.2 and 1 m/s'."""
    values = [f"{v:.3g}" for v in np.asarray(speeds, dtype=float)]
    if len(values) > 1:
        return f"{', '.join(values[:-1])} and {values[-1]} m/s"
    return f"{values[0]} m/s" if values else "no speed"
