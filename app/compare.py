"""Compare two states: the pinned state "A" beside the controls, "B".

``ExplorerState.pinned`` holds A: the support's inputs and the Design tab's (in the URL as
``A=k_r:...,k_theta:...``, see ``app.pinned_state``). ``PinnedResults``, a base of
``SessionResults``, computes A's results with the very machinery of B's: a second
``SessionResults`` (made at the first pin) of a private state that takes A's values, whose
slots are needed only while something is pinned and only for what the visible tab shows
(``PINNED_RESULTS``; the Design tab's only while it is on screen). Its request keys are
B's, so the shared result cache makes A free wherever it equals a state computed before (B
at the moment of pinning). Views draw ``support_A``, ``polar_A``, ``uniform_A``,
``load_A`` and ``design_point_A``, ``design_array_A``, ``design_polar_A`` muted under B's;
nothing of A is computed or drawn while nothing is pinned.
"""
from __future__ import annotations

import param

from .pinned_state import complete
from .state import ExplorerState

#: The results computed for A: those the overlays and readouts draw.
PINNED_RESULTS = ("support", "polar", "uniform", "load", "design_point", "design_array",
                  "design_polar")
#: How A's errors are told apart from B's on the page.
PINNED_LABEL = "A (pinned)"


class PinnedResults(param.Parameterized):
    """The A side of a session's results (a base class of ``SessionResults``)."""

    support_A = param.Parameter(None, doc="the pinned state's support, a worker.SupportData")
    polar_A = param.Parameter(None, doc="the pinned state's orientation sweep (Fig. 11)")
    uniform_A = param.Dict(None, allow_None=True, doc="the pinned state's uniform array row")
    load_A = param.Dict(None, allow_None=True, doc=(
        "the pinned state's Fig. 6 curve, {F_N: uniform-array row}"))
    design_point_A = param.Dict(None, allow_None=True, doc=(
        "the pinned state's design point on the map (Design tab)"))
    design_array_A = param.Dict(None, allow_None=True, doc=(
        "the pinned state's design array for its distribution (Design tab)"))
    design_polar_A = param.Parameter(None, doc=(
        "the pinned state's Fig. 11a sweep at its design's springs (Design tab)"))

    def _init_pinned(self, side: str) -> None:
        """Set up the A side (``side`` "B": this is a page's results; "A": this is it).
        A's results object is made when a state is first pinned: none without a comparison."""
        self.A = None
        self._shown = set(PINNED_RESULTS)
        if side == "A":
            return
        self.state.param.watch(self._on_pinned, "pinned")
        if self.state.pinned is not None:
            self._make_pinned()

    def _make_pinned(self) -> None:
        self.A = type(self)(ExplorerState(**complete(self.state.pinned)), side="A")
        # One session for the pool's turns and budgets: A is part of this page.
        self.A.session_id, self.A.client = self.session_id, self.client
        self.A.started = self.started
        for slot in self.A.slots.values():
            slot.needed = False
        self.A.param.watch(self._from_pinned, [*PINNED_RESULTS, "errors"])

    @property
    def comparing(self) -> bool:
        """Whether a state is pinned (A shown beside B)."""
        return self.A is not None and self.state.pinned is not None

    def pinned_slot(self, name: str):
        """A's ``Slot`` of the result ``name`` while something is pinned, else None."""
        return self.A.slots[name] if self.comparing else None

    def _show_pinned(self, names) -> None:
        self._shown = set(names)
        self._need_pinned()

    def _start_pinned(self) -> None:
        if self.A is not None:
            self.A.started = True
            self._need_pinned()

    def _need_pinned(self) -> None:
        if self.A is None:
            return
        for name in PINNED_RESULTS:
            self.A.slots[name].set_needed(self.comparing and name in self._shown)

    def _on_pinned(self, event) -> None:
        if event.new is None:
            self._need_pinned()  # cancels A's work: late results are ignored
            self.param.update(**{f"{name}_A": None for name in PINNED_RESULTS})
            self._from_pinned_errors({})
            return
        if self.A is None:
            self._make_pinned()
        else:
            self.A.state.param.update(**complete(event.new))
        self._need_pinned()

    def _from_pinned(self, event) -> None:
        if event.name == "errors":
            self._from_pinned_errors(event.new)
        elif self.comparing:
            value = event.new
            if event.name == "load":
                value = (value or {}).get("current")
            setattr(self, f"{event.name}_A", value)

    def _from_pinned_errors(self, errors: dict) -> None:
        """A's errors on the page, each named as A's."""
        mine = {f"A:{name}": f"{PINNED_LABEL}: {message}" if message else ""
                for name, message in errors.items()}
        old = {k: v for k, v in self.errors.items() if not k.startswith("A:")}
        new = {**old, **mine}
        if new != self.errors:
            self.errors = new
