"""The ranges and defaults of the explorer's controls, defined once.

The ranges are those the paper's figures span: stiffnesses k_r, k_theta on
[0.01, 3] (Figs. 5, 8), loads F_N on [0.1, 10] (Fig. 6). The dashboard's sliders and
its URL parser read them from here, and so do the sweeps' default axes; what the model
accepts at all is wider (``model.contact.params.RANGES``).

The default view is the pendulum support of Fig. 7a: its springs (``REGIMES``), and the
load, orientation and tolerance that ``Params`` and ``SolverOptions`` default to.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from .contact.options import RTOL_CHOICES, SolverOptions
from .contact.params import REGIMES, Params
from .validation import BETA, Interval

__all__ = ["Control", "CONTROLS", "DEFAULT_REGIME", "STIFFNESS_RANGE", "LOAD_RANGE",
           "OBJECTIVES", "BOUND_RANGE", "MIX_WEIGHT", "DIST_FAMILIES", "KAPPA_RANGE",
           "PSI_RANGE"]

#: Both stiffness axes of Figs. 5 and 8 (sampled logarithmically).
STIFFNESS_RANGE = Interval(0.01, 3.0)
#: The loads of Fig. 6 (sampled logarithmically).
LOAD_RANGE = Interval(0.1, 10.0)
DEFAULT_REGIME = "pendulum"
#: What ``model.designs.design.optimise`` seeks: the least F_T,x/(mu0 F_N) (under a bound on
#: |F_T,y|/(mu0 F_N)), or the largest |F_T,y|/(mu0 F_N) (under a bound on F_T,x/(mu0 F_N)).
OBJECTIVES = ("min-FTx", "max-FTy")
#: The bound of the objective, a force over mu0 F_N: 0 (none sideways) up to 2 (above any
#: F_T,x/(mu0 F_N) of the model's arrays, which stay near 1).
BOUND_RANGE = Interval(0.0, 2.0)
#: The weight of a mixture's second component (0: no mixture, 1: the second alone).
MIX_WEIGHT = Interval(0.0, 1.0)
#: The orientation distributions a design edits (``model.designs.distributions.FAMILIES``' names;
#: a mixture is two of them, made with the mixture weight).
DIST_FAMILIES = ("fixed", "pair", "vonmises", "uniform", "histogram")
#: The von Mises concentration a design edits: 0 (uniform) up to 1e4 (a spread of ~0.6 deg,
#: narrower than a real array's; the model accepts up to ``distributions.KAPPA_MAX``).
KAPPA_RANGE = Interval(0.0, 1e4)
#: The sliding direction psi to the array [deg].
PSI_RANGE = Interval(-180.0, 180.0)
#: An angle in degrees, one turn.
_TURN_DEG = Interval(0.0, 360.0, hi_open=True)


@dataclass(frozen=True)
class Control:
    """One control: its accepted values (an interval, or ``choices``), default and scale."""

    meaning: str
    default: object
    interval: Interval | None = None
    choices: tuple = ()
    scale: str = "linear"  # or "log"

    @property
    def bounds(self) -> tuple[float, float]:
        return self.interval.bounds

    def expected(self) -> str:
        """What a valid value looks like, for messages: "a number in [0.01, 3]"."""
        if self.choices:
            return "one of " + ", ".join(f"{c:g}" if isinstance(c, float) else str(c)
                                         for c in self.choices)
        return f"a number in {self.interval}"


_PARAMS = Params(REGIMES[DEFAULT_REGIME].k_r, REGIMES[DEFAULT_REGIME].k_theta)

CONTROLS = {
    "k_r": Control("radial stiffness k_r (Eq. 5)", _PARAMS.k_r, STIFFNESS_RANGE, scale="log"),
    "k_theta": Control("torsional stiffness k_theta (Eq. 5)", _PARAMS.k_theta, STIFFNESS_RANGE,
                       scale="log"),
    "F_N": Control("normal load F_N", _PARAMS.F_N, LOAD_RANGE, scale="log"),
    "theta0_deg": Control("rest orientation theta0 [deg]", math.degrees(_PARAMS.theta0),
                          _TURN_DEG),
    "beta": Control("fixed load factor beta = N_c0/N_c", _PARAMS.beta, BETA),
    "beta_mode": Control("load factor: self-consistent or fixed", "self",
                         choices=("self", "fixed")),
    "rtol": Control("relative tolerance per contact", SolverOptions().rtol,
                    choices=RTOL_CHOICES),
    "objective": Control("optimisation objective: least F_T,x or largest |F_T,y|",
                         OBJECTIVES[0], choices=OBJECTIVES),
    "bound": Control("bound on |F_T,y|/(mu0 F_N) (min-FTx) or F_T,x/(mu0 F_N) (max-FTy); "
                     "none when not given", None, BOUND_RANGE),
    "mix_weight": Control("weight of the mixture's second component", 0.0, MIX_WEIGHT),
    # The orientation distribution of a design (a von Mises family about theta0 = 90 deg;
    # a mixture's second component starts as a fixed orientation at 0 deg).
    "dist_family": Control("orientation distribution", "vonmises", choices=DIST_FAMILIES),
    "dist_deg": Control("its angle: theta0 (fixed, pair) or the mean (von Mises) [deg]",
                        math.degrees(_PARAMS.theta0), _TURN_DEG),
    "kappa": Control("von Mises concentration kappa", 4.0, KAPPA_RANGE),
    "psi_deg": Control("sliding direction psi to the array [deg]", 0.0, PSI_RANGE),
    "dist2_family": Control("the mixture's second distribution", "fixed",
                            choices=DIST_FAMILIES),
    "dist2_deg": Control("its angle [deg]", 0.0, _TURN_DEG),
}
