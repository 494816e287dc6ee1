"""The ranges and defaults of the explorer's controls, defined once.

The ranges are those the paper's figures span: stiffnesses k_r, k_theta on
[0.01, 3] (Figs. 5, 8), loads F_N on [0.1, 10] (Fig. 6). The dashboard's sliders and
its URL parser read them from here, and so do the sweeps' default axes; what the model
accepts at all is wider (``model.params.RANGES``).

The default view is the pendulum support of Fig. 7a: its springs (``REGIMES``), and the
load, orientation and tolerance that ``Params`` and ``SolverOptions`` default to.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from .options import RTOL_CHOICES, SolverOptions
from .params import REGIMES, Params
from .validation import BETA, Interval

__all__ = ["Control", "CONTROLS", "DEFAULT_REGIME", "STIFFNESS_RANGE", "LOAD_RANGE",
           "OBJECTIVES", "BOUND_RANGE", "MIX_WEIGHT"]

#: Both stiffness axes of Figs. 5 and 8 (sampled logarithmically).
STIFFNESS_RANGE = Interval(0.01, 3.0)
#: The loads of Fig. 6 (sampled logarithmically).
LOAD_RANGE = Interval(0.1, 10.0)
DEFAULT_REGIME = "pendulum"
#: What ``model.design.optimise`` seeks: the least F_T,x/(mu0 F_N) (under a bound on
#: |F_T,y|/(mu0 F_N)), or the largest |F_T,y|/(mu0 F_N) (under a bound on F_T,x/(mu0 F_N)).
OBJECTIVES = ("min-FTx", "max-FTy")
#: The bound of the objective, a force over mu0 F_N: 0 (none sideways) up to 2 (above any
#: F_T,x/(mu0 F_N) of the model's arrays, which stay near 1).
BOUND_RANGE = Interval(0.0, 2.0)
#: The weight of a mixture's second component (0: no mixture, 1: the second alone).
MIX_WEIGHT = Interval(0.0, 1.0)


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
                          Interval(0.0, 360.0, hi_open=True)),
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
}
