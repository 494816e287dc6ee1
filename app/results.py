"""The results of one session: controls -> ``SessionResults`` -> views.

``SessionResults`` watches the session's ``ExplorerState`` and owns every computation of
the page; each result is a parameter of it, so views declare what they draw from
(``@param.depends("results.support", watch=True)``) and never read one another. One
lifecycle serves every result (``app.slot.Slot``): stale -> needed? -> request -> newest
wins -> applied, or its error shown while the last good result stays.
"""
from __future__ import annotations

import json
import logging
import time

import panel as pn
import param

from . import worker
from .compare import PinnedResults
from .jobs import work_pool
from .law_results import LawResults
from .slot import Request, Slot, client_address
from .speed_results import SpeedResults
from .state import DESIGN_KEYS, DIST_KEYS, OPTIMUM_KEYS, ExplorerState

log = logging.getLogger(__name__)

#: The Design tab's results computed while the tab is on screen (``SessionResults.show``).
DESIGN_RESULTS = ("design_point", "design_array", "design_polar")
#: What the headline above every tab reads (``app.views.readouts.HeadlineView``): needed
#: whichever tab is on screen, though a tab's own list may leave them out.
HEADLINE_RESULTS = ("support", "uniform")


def optimum_family(state) -> str:
    """The family Optimise searches for ``state``'s editor (uniform has nothing to tune:
    the pair instead, or a fixed orientation for the largest |F_T,y|, a pair having none)."""
    family, sideways = state.dist_family, state.opt_objective == "max-FTy"
    if state.mix_weight > 0:
        return "mixture"
    if sideways and family in ("pair", "uniform"):
        return "fixed"
    return family if family in ("fixed", "pair", "vonmises") else "pair"


LOAD_REGIMES = worker.LOAD_REGIMES  # the Fig. 6 curves of the paper's regimes


class SessionResults(PinnedResults, LawResults, SpeedResults):
    """Every result one session shows, computed from its ``ExplorerState``.

    Views depend on these parameters; the page sets what is ``needed`` (on screen). With a
    pinned state, ``A`` holds its results (``app.compare``); ``side`` is "A" for that one.
    The Design tab's fitted law and speed curve: ``app.law_results``, ``app.speed_results``."""

    support = param.ClassSelector(class_=worker.SupportData, allow_None=True, doc=(
        "the support at theta0 during one contact and its fixed array (Support tab)"))
    polar = param.Parameter(None, doc="fixed arrays over theta0, a SweepResult (Fig. 11)")
    uniform = param.Dict(None, allow_None=True, doc="the uniform array's row (readouts, Fig. 6)")
    load = param.Dict(None, allow_None=True, doc=(
        "Fig. 6 curves: {'current': {F_N: row}, regime: {F_N: row}, ...}"))
    regime_map = param.Parameter(None, doc="the regime map shown on the Map tab (Fig. 5)")
    array = param.Parameter(None, doc="the array under the slab, frame by frame (Array tab)")
    animation = param.Dict(None, allow_None=True, doc=(
        "an animation file for slides, made on request: bytes, mime, message, what, format"))
    errors = param.Dict({}, doc="result name -> what went wrong with its latest request")
    busy = param.List([], doc="names of the results being computed")

    LABELS = {"support": "The computation", "polar": "Orientation sweep",
              "uniform": "Uniform array", "load": "Load curve",
              "load_regimes": "Load curves of the regimes", "regime_map": "Regime map",
              "array": "The array under the slab", "animation": "The animation file"}
    #: Seconds of one worker each result may take (``app.jobs``: past it, it is stopped).
    #: The hardest single support in the controls' ranges takes ~3 s on a busy server; a
    #: regime map at an unshipped load (36, then 144 arrays) is shared through the caches.
    BUDGET_S = {"support": 4.0, "polar": 6.0, "uniform": 5.0, "load": 15.0,
                "load_regimes": 30.0, "regime_map": 20.0, "regime_map_fine": 60.0,
                "array": 8.0, "animation": 120.0}
    #: The uniform arrays wait until the controls have rested this long.
    DEBOUNCE_MS = 200

    def __init__(self, state: ExplorerState, side: str = "B", **params):
        super().__init__(**params)
        self.state = state
        self.session_id = work_pool().session_id()
        self.client = client_address()
        self.started = False  # see start()
        s = state
        self.slots = {
            "support": Slot(self, "support", self._support_request, self._set("support"),
                            ("k_r", "k_theta", "F_N", "theta0", "rtol", "beta_mode", "beta")),
            "polar": Slot(self, "polar", self._polar_request, self._set("polar"),
                          ("k_r", "k_theta", "F_N", "rtol", "beta_mode", "beta"),
                          needed=False),
            "uniform": Slot(self, "uniform", self._uniform_request, self._set("uniform"),
                            ("k_r", "k_theta", "F_N", "beta_mode", "beta"),
                            delay_ms=self.DEBOUNCE_MS),
            "load": Slot(self, "load", self._load_request, self._set_load,
                         ("k_r", "k_theta", "beta_mode", "beta"), needed=False),
            "load_regimes": Slot(self, "load_regimes", self._load_regimes_request,
                                 self._set_load_regimes, ("beta_mode", "beta"), needed=False),
            "regime_map": Slot(self, "regime_map", self._map_request, self._set("regime_map"),
                               ("F_N", "beta_mode", "beta"), needed=False),
            "array": Slot(self, "array", self._array_request, self._set("array"),
                          ("k_r", "k_theta", "F_N", "theta0", "orientation"), needed=False),
            # Made only when asked for (``prepare_animation``), never on a control change.
            "animation": Slot(self, "animation", self._animation_request,
                              self._set("animation"), (), needed=False),
        }
        self._animation_kind = ("support", "gif")
        self.slots.update(self._design_slots())
        for slot in self.slots.values():
            s.param.watch(slot.invalidate, list(slot.depends))
        self._curves = {}
        self._init_pinned(side)
        self._init_law()
        self._init_speeds()

    # ================================================================== Design tab
    # A pillar array in physical units (``state.design_*``) -> its dimensionless point
    # (``design_point``), its array for the edited distribution (``design_array``), the
    # Fig. 11a curve of its springs (``design_polar``) and, on request only, the best
    # distribution (``design_optimum``: ``optimise`` / ``cancel_optimum``).
    design_point = param.Dict(None, allow_None=True, doc=(
        "the design's dimensionless point, status, regime and speed line (Design tab)"))
    design_array = param.Dict(None, allow_None=True, doc=(
        "the design's array for the edited distribution, dimensionless and physical"))
    design_polar = param.Parameter(None, doc=(
        "fixed arrays over theta0 at the design's springs and load, a SweepResult"))
    design_optimum = param.Dict(None, allow_None=True, doc=(
        "the optimum distribution of the design's springs (``optimise``), when asked for"))
    optimum_note = param.String("", doc="what the optimisation is doing, or did")
    optimum_started = param.Number(None, allow_None=True, doc=(
        "time.monotonic() when the running optimisation was requested"))

    LABELS = {**LABELS, "design_point": "The design's point", "design_array": "The design's array",
              "design_polar": "The design's orientation sweep",
              "design_optimum": "The optimisation"}
    #: Seconds of a worker: the design's springs may lie far outside the paper's map
    #: (k~ up to 1e6), where one contact costs ~L0 sqrt(k~) steps.
    BUDGET_S = {**BUDGET_S, "design_point": 4.0, "design_array": 30.0, "design_polar": 30.0,
                "design_optimum": 30.0}

    def _design_slots(self) -> dict:
        array_keys = (*DESIGN_KEYS, *DIST_KEYS, "beta_mode", "beta")
        self.state.param.watch(self._forget_optimum, [*DESIGN_KEYS, *OPTIMUM_KEYS])
        return {
            "design_point": Slot(self, "design_point", self._design_point_request,
                                 self._set_design_point, DESIGN_KEYS, needed=False),
            "design_array": Slot(self, "design_array", self._design_array_request,
                                 self._set("design_array"), array_keys,
                                 delay_ms=self.DEBOUNCE_MS, needed=False),
            "design_polar": Slot(self, "design_polar", self._design_polar_request,
                                 self._set("design_polar"), (*DESIGN_KEYS, "beta_mode", "beta"),
                                 needed=False),
            # Only on request (``optimise``); a change of the design drops it.
            "design_optimum": Slot(self, "design_optimum", self._design_optimum_request,
                                   self._set_design_optimum, DESIGN_KEYS, needed=False),
        }

    def _design(self):
        """The state's ``PillarDesign``; ``ValueError`` naming an unusable input."""
        return worker.design_of(self.state.design_inputs)

    def _design_params(self):
        """The model's ``Params`` of the design, or None when the design is unusable (the
        point's slot says why): the dependent results are then cleared, not computed."""
        try:
            return worker.design_model_params(self._design())
        except ValueError:
            return None

    def _design_point_request(self) -> Request:
        try:
            design = self._design()
        except ValueError:
            self.design_point = None  # the last point is not this design's
            raise
        return Request("interactive", ("design_point", design), worker.compute_design_point,
                       (design,), self.BUDGET_S["design_point"])

    def _design_array_request(self) -> Request | None:
        s = self.state
        if self._design_params() is None:
            self._clear_design("design_array")
            return None
        design = self._design()
        args = (design, s.distribution, float(s.dist_psi), s.array_beta)
        # The distribution's text as its key: a mixture's dict holds lists (unhashable).
        key = ("design_array", design, json.dumps(s.distribution, sort_keys=True), *args[2:])
        return Request("background", key,
                       worker.compute_design_array, args, self.BUDGET_S["design_array"])

    def _design_polar_request(self) -> Request | None:
        p = self._design_params()
        if p is None:
            self._clear_design("design_polar")
            return None
        s = self.state
        return Request("background", ("polar", p, s.array_beta, 1e-6), worker.compute_polar,
                       (p, s.array_beta, 1e-6), self.BUDGET_S["design_polar"])

    def _design_optimum_request(self) -> Request | None:
        p = self._design_params()
        if p is None:
            return None
        s = self.state
        args = (p, optimum_family(s), s.array_beta, s.opt_objective, s.opt_bound)
        return Request("background", ("design_optimum", *args),
                       worker.compute_design_optimum, args,
                       self.BUDGET_S["design_optimum"])

    def _clear_design(self, name: str) -> None:
        setattr(self, name, None)
        self._set_error(name, "")

    def _set_design_point(self, value: dict) -> None:
        self.design_point = value
        self._set_error("design_point", value.get("error", ""))

    def _set_design_optimum(self, value: dict) -> None:
        self.optimum_started = None
        self.design_optimum = value
        self.optimum_note = (f"Done in {value['seconds']:.1f} s ({value['evaluations']} model "
                             f"evaluations): {value['message']}.")
        self.state.set_distribution(value["distribution"])

    def _forget_optimum(self, *_events) -> None:
        self.design_optimum = None
        if self.optimum_started is not None:
            self.optimum_started = None
            self.optimum_note = "The design changed: its optimisation was dropped."
        else:  # a finished search's note answered the former question
            self.optimum_note = ""

    def optimise(self) -> None:
        """Search the best distribution of the edited family (min F_T,x) in the background."""
        slot = self.slots["design_optimum"]
        self._set_error("design_optimum", "")
        self.optimum_started = time.monotonic()
        self.optimum_note = (f"Optimising over the {optimum_family(self.state)} "
                             f"family (at most {self.BUDGET_S['design_optimum']:g} s) …")
        slot.request()
        if "design_optimum" not in self.busy and self.optimum_started is not None:
            # Refused at once (unusable design, busy server) or done synchronously.
            self.optimum_started = None
            if self.errors.get("design_optimum"):
                self.optimum_note = ""

    def cancel_optimum(self) -> None:
        """Drop the optimisation: a queued job never runs; a running one finishes in its
        worker and its result is ignored here."""
        slot = self.slots["design_optimum"]
        running = "design_optimum" in self.busy
        slot.cancel()
        if slot._future is not None:
            slot._future.cancel()
        self.optimum_started = None
        self.optimum_note = ("Cancelled. If the search had already started in a worker, it "
                             "finishes there and its result is ignored." if running
                             else "Nothing to cancel.")

    # ------------------------------------------------------------------ requests
    def _support_request(self) -> Request:
        s = self.state
        p = s.params
        return Request("interactive", ("support", p, s.array_beta, s.rtol),
                       worker.compute_support, (p, s.array_beta, s.rtol),
                       self.BUDGET_S["support"])

    def _polar_request(self) -> Request:
        s = self.state
        p = s.support
        return Request("background", ("polar", p, s.array_beta, s.rtol), worker.compute_polar,
                       (p, s.array_beta, s.rtol), self.BUDGET_S["polar"])

    def _uniform_request(self) -> Request:
        s = self.state
        key = (float(s.k_r), float(s.k_theta), float(s.F_N), s.array_beta)
        return Request("background", ("uniform", *key), worker.compute_uniform, key,
                       self.BUDGET_S["uniform"])

    def _load_request(self) -> Request:
        s = self.state
        key = (float(s.k_r), float(s.k_theta), s.array_beta)
        return Request("background", ("load", *key), worker.compute_load, key,
                       self.BUDGET_S["load"])

    def _map_request(self) -> Request:
        """The regime map at the current load and beta: the shipped one at once where it
        exists, else a coarse map first and then a finer one."""
        s = self.state
        F_N, beta = float(s.F_N), s.array_beta
        if beta == "self" and worker.shipped_load(F_N) is not None:
            return Request("background", ("map", F_N, beta, "shipped"), worker.compute_map,
                           (F_N, beta), self.BUDGET_S["regime_map"])
        fine = Request("background", ("map", F_N, beta, worker.MAP_FINE_N), worker.compute_map,
                       (F_N, beta, worker.MAP_FINE_N), self.BUDGET_S["regime_map_fine"])
        return Request("background", ("map", F_N, beta, worker.MAP_COARSE_N),
                       worker.compute_map, (F_N, beta, worker.MAP_COARSE_N),
                       self.BUDGET_S["regime_map"], then=fine)

    def _array_request(self) -> Request:
        s, p = self.state, worker.array_params(self.state)
        return Request("background", ("array", p, s.orientation), worker.compute_array_motion,
                       (p, s.orientation), self.BUDGET_S["array"])

    def _animation_request(self) -> Request:
        s = self.state
        what, fmt = self._animation_kind
        if what == "array":
            p = self._array_request().args[0]
        elif self.support is not None and self.support.result is not None:
            p = self.support.params  # the support as shown (with its array's beta)
        else:
            p = s.params
        return Request("background", ("animation", what, fmt, p, s.orientation),
                       worker.compute_animation, (what, fmt, p, s.orientation),
                       self.BUDGET_S["animation"])

    def prepare_animation(self, what: str, fmt: str) -> None:
        """Make the animation file of ``what`` (support, array) as ``fmt`` (gif, mp4)."""
        if what not in ("support", "array") or fmt not in ("gif", "mp4"):
            raise ValueError(f"what={what!r}, fmt={fmt!r}: choose support or array, gif or mp4")
        self._animation_kind = (what, fmt)
        self.animation = None
        self.slots["animation"].request()

    def _load_regimes_request(self) -> Request:
        beta = self.state.array_beta
        return Request("background", ("load_regimes", beta), worker.compute_load_regimes,
                       (beta,), self.BUDGET_S["load_regimes"])

    # ------------------------------------------------------------------ results
    def _set(self, name: str):
        def apply(value):
            if name == "support":  # the model raised: say so, keep the last good plots
                self._set_error(name, value.error)
                if value.result is None:
                    return
            setattr(self, name, value)
        return apply

    def _set_load(self, curve: dict) -> None:
        self._curves["current"] = curve
        self._publish_load()

    def _set_load_regimes(self, curves: dict) -> None:
        self._curves.update(curves)
        self._publish_load()

    def _publish_load(self) -> None:
        self.load = {"current": {}, **{r: {} for r in LOAD_REGIMES}, **self._curves}

    def _set_error(self, name: str, message: str) -> None:
        if self.errors.get(name, "") != message:
            self.errors = {**self.errors, name: message}

    def _set_busy(self, name: str, flag: bool) -> None:
        busy = [n for n in self.busy if n != name] + ([name] if flag else [])
        if busy != self.busy:
            self.busy = busy

    # ------------------------------------------------------------------ control
    def show(self, names) -> None:
        """Compute the results in ``names`` (on screen) and the headline's, no other."""
        names = set(names) | set(HEADLINE_RESULTS)
        for name in ("polar", "load", "load_regimes", "uniform", "regime_map", "array",
                     *DESIGN_RESULTS):
            self.slots[name].set_needed(name in names)
        self._show_pinned(names)

    def start(self) -> None:
        """First requests of a new page: whatever is needed and not computed yet.

        In a served page they are sent once the browser has the page (Panel's ``onload``:
        the page's ``document_ready``), not while the page is built: a page requested but
        never opened -- a script fetching URLs, the copy Panel's liveness endpoint builds
        -- costs no worker time, and the page build never waits for a result.
        """
        if pn.state.curdoc is None:
            self._start_now()
        else:
            pn.state.onload(self._start_now)

    def _start_now(self) -> None:
        self.started = True
        for slot in self.slots.values():
            if slot.needed and slot.stale:
                slot.request()
        self._start_pinned()

    def clear_errors(self) -> None:
        self.errors = {}

    @property
    def error_messages(self) -> list[str]:
        return [m for m in self.errors.values() if m]
