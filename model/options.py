"""Solver settings: tolerances, method choice and budgets (frozen, hashable)."""
from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["SolverOptions", "METHODS"]

#: ``auto`` switches between the explicit and implicit pair by stiffness detection;
#: ``reference`` is scipy's DOP853 (slow, independent, for tests and benchmarks).
METHODS = ("auto", "explicit", "implicit", "reference")


@dataclass(frozen=True)
class SolverOptions:
    """How to integrate one contact.

    rtol, atol : local error tolerances (per step, RMS norm over all states).
        ``atol=None`` means ``rtol / 100``.
    method : one of ``METHODS``.
    max_steps : step budget (accepted + rejected); beyond it the run stops with
        ``success=False`` instead of hanging.
    tau_max : time budget in tau; a contact still running then is reported as not
        ended (``success=False``).
    """

    rtol: float = 1e-6
    atol: float | None = None
    method: str = "auto"
    max_steps: int = 1_000_000
    tau_max: float = 1e5

    def __post_init__(self):
        rtol = _finite("rtol", self.rtol, 1e-14, 1e-2)
        atol = rtol / 100 if self.atol is None else _finite("atol", self.atol, 1e-16, 1e-2)
        if self.method not in METHODS:
            raise ValueError(f"method={self.method!r} is unknown; choose one of {', '.join(METHODS)}")
        max_steps = _finite("max_steps", self.max_steps, 10, 1e8)
        if not max_steps.is_integer():
            raise ValueError(f"max_steps={self.max_steps!r} must be a whole number in [10, 1e8]")
        max_steps = int(max_steps)
        tau_max = _finite("tau_max", self.tau_max, 1.0, 1e8)
        object.__setattr__(self, "rtol", rtol)
        object.__setattr__(self, "atol", atol)
        object.__setattr__(self, "max_steps", max_steps)
        object.__setattr__(self, "tau_max", tau_max)


def _finite(name, value, lo, hi) -> float:
    try:
        if isinstance(value, (bool, str, bytes)):  # float() would accept these
            raise TypeError
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value!r} is not a number; it must be in [{lo:g}, {hi:g}]") from None
    except OverflowError:  # an int beyond the float range
        x = math.inf
    if not (math.isfinite(x) and lo <= x <= hi):
        raise ValueError(f"{name}={value!r} is outside the sane range [{lo:g}, {hi:g}]")
    return x
