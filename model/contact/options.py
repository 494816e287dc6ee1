"""Solver settings: tolerances, method choice and budgets (frozen, hashable)."""
from __future__ import annotations

from dataclasses import dataclass

from ..validation import Interval, choice, number, whole

__all__ = ["SolverOptions", "METHODS", "REFERENCE_METHODS", "ARRAY_METHODS", "array_method", "RTOL", "ATOL", "MAX_STEPS", "TAU_MAX", "RTOL_CHOICES"]

#: The scipy references (slow, independent of the kernel, for tests and benchmarks), each
#: with the ``solve_ivp`` method it runs: DOP853 (explicit, 8th order), and Radau
#: (implicit, 5th order) for the stiff contacts of large loads, where the explicit pair's
#: steps are bound by stability (k_r = k_theta = 0.01, F_N = 30: ~10x cheaper at 1e-12).
REFERENCE_METHODS = {"reference": "DOP853", "reference-radau": "Radau"}
#: ``auto`` switches between the explicit and implicit pair by stiffness detection.
METHODS = ("auto", "explicit", "implicit", *REFERENCE_METHODS)
#: Arrays integrate many contacts in one compiled batch; the scipy reference does one at a time.
ARRAY_METHODS = ("auto", "explicit", "implicit")
#: Accepted ranges: below rtol 1e-14 the steps drown in rounding, above 1e-2 the
#: results mean little; the budgets keep every run finite.
RTOL = Interval(1e-14, 1e-2)
ATOL = Interval(1e-16, 1e-2)
MAX_STEPS = Interval(10, 1e8)
TAU_MAX = Interval(1.0, 1e8)
#: The tolerances offered by the dashboard (its rtol selector and URL key).
RTOL_CHOICES = (1e-4, 1e-5, 1e-6, 1e-7, 1e-8)


@dataclass(frozen=True)
class SolverOptions:
    """How to integrate one contact.

    Parameters
    ----------
    rtol, atol : float
        Local error tolerances (per step, RMS norm over the motion and tau; the
        quadratures ride along and the energy residual checks them).
        ``atol=None`` means ``rtol / 100``.
    method : str
        One of ``METHODS``.
    max_steps : int
        Step budget (accepted + rejected); beyond it the run stops with
        ``success=False`` instead of hanging.
    tau_max : float
        Time budget in tau; a contact still running then is reported as not
        ended (``success=False``).
    """

    rtol: float = 1e-6
    atol: float | None = None
    method: str = "auto"
    max_steps: int = 1_000_000
    tau_max: float = 1e5

    def __post_init__(self):
        rtol = number("rtol", self.rtol, RTOL, "relative tolerance rtol")
        atol = rtol / 100 if self.atol is None else number("atol", self.atol, ATOL,
                                                           "absolute tolerance atol")
        choice("method", self.method, METHODS)
        max_steps = whole("max_steps", self.max_steps, *MAX_STEPS.bounds)
        tau_max = number("tau_max", self.tau_max, TAU_MAX, "time budget tau_max")
        object.__setattr__(self, "rtol", rtol)
        object.__setattr__(self, "atol", atol)
        object.__setattr__(self, "max_steps", max_steps)
        object.__setattr__(self, "tau_max", tau_max)


def array_method(method: str) -> str:
    """``method`` if arrays can use it, else a ValueError naming it and the choices."""
    if method in REFERENCE_METHODS:
        raise ValueError(f"method={method!r} is for single contacts (simulate_support); "
                         f"arrays take {', '.join(ARRAY_METHODS)}")
    return choice("method", method, ARRAY_METHODS)
