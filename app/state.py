"""Per-session state of the dashboard: every control, and the ``model.Params`` they make.

``ExplorerState`` holds what the user set: the springs k_r, k_theta and the load F_N
(Eq. 5), the rest orientation theta0 (in degrees, as on the slider), the solver
tolerance, the load factor beta = N_c0/N_c (self-consistent or fixed), which uniform
average is shown (paper, Eq. 10, or duration-weighted), the regime-map quantity
(Fig. 5a or 5b), the visible tab and projector mode. Views read it and never own it;
the URL mirrors it (``app.urlstate``).
"""
from __future__ import annotations

import math

import param

from model import REGIMES, Params

from .urlstate import (AVERAGES, DEFAULTS, F_N_BOUNDS, K_BOUNDS, MAP_QUANTITIES, RTOLS, TABS,
                       parse, serialize, to_search)

#: Preset buttons: regime -> (k_r, k_theta) (Fig. 6 caption).
PRESETS = {name: (p.k_r, p.k_theta) for name, p in REGIMES.items()}

#: Boundary between "stiff" and "compliant" springs: the log-midpoint of [0.01, 3].
K_MID = math.sqrt(K_BOUNDS[0] * K_BOUNDS[1])

#: Parameters that change a single support (and so the Support tab).
SUPPORT_KEYS = ("k_r", "k_theta", "F_N", "theta0", "rtol", "beta_mode", "beta")
#: Parameters that change the fixed-orientation sweeps (Fig. 11): not theta0.
SWEEP_KEYS = ("k_r", "k_theta", "F_N", "rtol", "beta_mode", "beta")
#: Parameters that change the uniform arrays (Figs. 5, 6).
ARRAY_KEYS = ("k_r", "k_theta", "F_N", "beta_mode", "beta")
#: Parameters carried by the URL.
URL_KEYS = tuple(DEFAULTS)


def classify(k_r: float, k_theta: float) -> str:
    """The regime of Fig. 5a a pair of stiffnesses falls in (quadrants about ``K_MID``)."""
    stiff_r, stiff_t = k_r >= K_MID, k_theta >= K_MID
    return {(True, True): "stiff", (True, False): "pendulum",
            (False, True): "slider", (False, False): "soft"}[(stiff_r, stiff_t)]


def clamp(value: float, bounds: tuple[float, float]) -> float:
    """``value`` moved into the closed interval ``bounds`` (rounding off log sliders)."""
    return min(max(float(value), bounds[0]), bounds[1])


class ExplorerState(param.Parameterized):
    """The controls of one browser session (the issue's list "What users see and do", 1)."""

    k_r = param.Number(DEFAULTS["k_r"], bounds=K_BOUNDS, doc="radial stiffness k~_r (Eq. 5)")
    k_theta = param.Number(DEFAULTS["k_theta"], bounds=K_BOUNDS,
                           doc="torsional stiffness k~_theta (Eq. 5)")
    F_N = param.Number(DEFAULTS["F_N"], bounds=F_N_BOUNDS, doc="normal load F~_N on the slab")
    theta0 = param.Number(DEFAULTS["theta0"], bounds=(0.0, 360.0),
                          inclusive_bounds=(True, False),
                          doc="rest orientation theta0 in degrees from the sliding direction +x")
    rtol = param.Selector(default=DEFAULTS["rtol"], objects=list(RTOLS),
                          doc="relative tolerance of the single-support integration")
    beta_mode = param.Selector(default=DEFAULTS["beta_mode"], objects=["self", "fixed"],
                               doc="load factor beta = N_c0/N_c: self-consistent or fixed")
    beta = param.Number(DEFAULTS["beta"], bounds=(0.0, 1.0), inclusive_bounds=(False, True),
                        doc="the fixed load factor (used when beta_mode is 'fixed')")
    average = param.Selector(default=DEFAULTS["average"], objects=list(AVERAGES),
                             doc="uniform-array average: paper (Eq. 10) or duration-weighted")
    map_quantity = param.Selector(default=DEFAULTS["map_quantity"], objects=list(MAP_QUANTITIES),
                                  doc="regime map of F_T,x/(mu0 F_N) (Fig. 5a) or D_y/D_x (5b)")
    tab = param.Selector(default=DEFAULTS["tab"], objects=list(TABS), doc="the visible tab")
    projector = param.Boolean(DEFAULTS["projector"],
                              doc="large fonts, thick lines, high contrast for projection")
    notice = param.String("", doc="a message for the page (unusable URL values)")

    # ------------------------------------------------------------------ model inputs
    @property
    def params(self) -> Params:
        """The ``model.Params`` of the current controls (theta0 in radians).

        ``beta`` is the fixed load factor in the fixed mode; in the self-consistent mode it
        is 1 here and the array functions solve it (``array_beta`` is then ``"self"``).
        """
        beta = self.beta if self.beta_mode == "fixed" else 1.0
        return Params(k_r=self.k_r, k_theta=self.k_theta, F_N=self.F_N,
                      theta0=math.radians(self.theta0), beta=beta)

    @property
    def array_beta(self):
        """The ``beta`` argument of the array functions: ``"self"`` or the fixed value."""
        return "self" if self.beta_mode == "self" else float(self.beta)

    @property
    def regime(self) -> str:
        """The regime (pendulum, slider, stiff, soft) of the current springs."""
        return classify(self.k_r, self.k_theta)

    def values(self) -> dict:
        """The current value of every URL-carried parameter."""
        return {name: getattr(self, name) for name in URL_KEYS}

    # ------------------------------------------------------------------ actions
    def apply_preset(self, name: str) -> None:
        """Set k_r, k_theta to a regime of the paper (pendulum, slider, stiff, soft)."""
        if name not in PRESETS:
            raise ValueError(f"preset={name!r} is unknown; choose one of {sorted(PRESETS)}")
        k_r, k_theta = PRESETS[name]
        self.param.update(k_r=k_r, k_theta=k_theta)

    def set_stiffness(self, k_r: float, k_theta: float) -> None:
        """Set both stiffnesses (clamped into range), e.g. from a click on the regime map."""
        self.param.update(k_r=clamp(k_r, K_BOUNDS), k_theta=clamp(k_theta, K_BOUNDS))

    def set_theta0(self, degrees: float) -> None:
        """Set theta0 from any angle in degrees (wrapped into [0, 360), whole degrees)."""
        self.theta0 = float(round(float(degrees)) % 360)

    def reset(self) -> None:
        """Every control back to its default (the tab stays where it is)."""
        self.param.update(**{k: v for k, v in DEFAULTS.items() if k != "tab"}, notice="")

    # ------------------------------------------------------------------ URL
    def to_query(self) -> dict[str, str]:
        """URL query parameters of the current state (``app.urlstate.serialize``)."""
        return serialize(self.values())

    def to_search(self) -> str:
        """The URL search string of the current state, ``?k_r=...``."""
        return to_search(self.values())

    def load_query(self, query) -> list[str]:
        """Apply URL ``query`` (mapping or search string); unusable values keep defaults.

        Returns the notices, which are also shown on the page through ``notice``.
        """
        values, notices = parse(query)
        self.param.update(**values, notice=" ".join(notices))
        return notices
