"""The structured surface's friction against sliding speed: a pillar design
(``model.designs.units.PillarDesign``) evaluated (``model.designs.design_point.evaluate``) at each speed V0
of a range, next to the flat material's mu(V0) of Eq. (4).

At each speed the apparent friction coefficient of the structured surface is
F_T,x/F_N = (F_T,x/(mu0 F_N)) mu0 (Eqs. 10, 11), with mu0 = mu(V0) the flat material's
coefficient at that speed (the rigid-contact limit; ``model.contact.friction.mu0``). Each point
carries the array's quadrature error (on F_T,x/F_N) and its integration error (the largest
relative energy-balance residual of its contacts); a speed the model cannot reach is a
point with its reason and no values, never a stop. The friction law needs its own V_s:
with V_s = V0/zeta it would move with the speed.
"""
from __future__ import annotations

import math
import re
import time
from dataclasses import dataclass

import numpy as np

from ..designs.si import to_si, ureg

__all__ = ["SpeedPoint", "SpeedCurve", "friction_velocity", "speed_point", "parse_speeds",
           "speed_range", "check_own_V_s", "check_speeds"]


@dataclass(frozen=True)
class SpeedPoint:
    """One sliding speed: the flat mu(V0), the structured surface's F_T,x/F_N with its
    errors, and the evaluation's status (``model.designs.design_point.POINT_STATUS``, or
    ``outside_range`` when the model cannot compute this speed)."""

    V0: float  # m/s
    mu_flat: float
    mu_apparent: float  # F_T,x / F_N
    quadrature_error: float  # on mu_apparent
    integration_error: float  # relative energy-balance residual
    success: bool
    status: str
    message: str


@dataclass(frozen=True)
class SpeedCurve:
    """The friction-velocity curve of a design (``points`` in increasing speed)."""

    law: dict  # the friction law's coefficients, V_s in m/s
    points: tuple
    seconds: float

    @property
    def success(self) -> bool:
        return all(p.success for p in self.points)

    def column(self, name: str) -> np.ndarray:
        return np.array([getattr(p, name) for p in self.points])

    def to_dict(self) -> dict:
        keys = ("V0", "mu_flat", "mu_apparent", "quadrature_error", "integration_error",
                "success", "status", "message")
        out = {("V0_m_per_s" if k == "V0" else k): [getattr(p, k) for p in self.points]
               for k in keys}
        return {"law": dict(self.law), **out, "all_success": self.success,
                "seconds": self.seconds}


def check_own_V_s(design) -> None:
    """``ValueError`` unless ``design``'s friction law has its own V_s (module doc)."""
    if design.V_s is None:
        raise ValueError("V_s=None: a friction-velocity curve needs the friction law's own "
                         "V_s (with V_s = V0/zeta the law would move with the speed); give V_s "
                         "or a fitted law")


def speed_point(design, V0: float, distribution=None, psi: float = 0.0, beta="self",
                tol: float = 1e-3, budget: float | None = None) -> SpeedPoint:
    """``design`` evaluated at the one sliding speed ``V0`` (m/s): the module doc. A speed
    the model cannot reach is a point with its reason; a bad ``tol``, ``beta``, ``budget``
    or ``psi`` raises ``ValueError``. The app computes its curve point by point with this."""
    from ..designs.design_point import evaluate, model_params
    from ..contact.friction import mu0
    check_own_V_s(design)
    V0 = float(V0)
    flat = float(design.friction_law.mu(V0))
    at_speed = design.replace(V0=ureg.Quantity(V0, "m/s"))
    try:
        r = evaluate(at_speed, distribution, psi=psi, beta=beta, tol=tol, budget=budget)
    except ValueError as error:
        if str(error).startswith(("tol=", "beta=", "budget=", "psi=")):
            raise
        return SpeedPoint(V0, flat, math.nan, math.nan, math.nan, False, "outside_range",
                          str(error))
    m0, a = mu0(model_params(at_speed)), r.array  # = mu(V0) of the design's law
    return SpeedPoint(V0, flat, float(a.FTx_over_mu0FN * m0),
                      float(a.quadrature_error["FTx_over_mu0FN"] * m0),
                      float(a.integration_error), r.success, r.status, a.message)


def _speed_task(task) -> SpeedPoint:
    """``speed_point`` of one task tuple (module level: sent to worker processes)."""
    design, V0, distribution, psi, beta, tol, budget = task
    return speed_point(design, V0, distribution, psi, beta, tol, budget)


def check_speeds(speeds) -> np.ndarray:
    """``speeds`` (m/s) sorted, as a 1-d array; ``ValueError`` unless finite and > 0."""
    values = np.asarray(speeds, dtype=float)
    if values.ndim != 1 or values.size == 0 or not np.all(np.isfinite(values) & (values > 0)):
        raise ValueError(f"speeds={speeds!r} must be finite speeds > 0 (m/s)")
    return np.sort(values)


def friction_velocity(design, speeds, distribution=None, psi: float = 0.0, beta="self",
                      tol: float = 1e-3, budget: float | None = None,
                      on_point=None, workers: int = 1) -> SpeedCurve:
    """``design`` at each of ``speeds`` (m/s): the module doc. ``budget`` (seconds) bounds
    each speed's evaluation; ``on_point(i, point)`` is called as each speed finishes (in
    the order they finish). ``workers`` > 1 computes the speeds on that many local
    processes (``model.runs.parallel.run_points``), the slowest (lowest) speeds handed out
    first; every point is the one ``workers=1`` gives (each speed is independent)."""
    from ..runs.parallel import run_points
    from ..validation import whole

    check_own_V_s(design)
    speeds = check_speeds(speeds)
    workers = whole("workers", workers, 1)
    tasks = [(design, float(V0), distribution, psi, beta, tol, budget) for V0 in speeds]
    start = time.perf_counter()
    workers = min(workers, len(tasks))
    points = run_points(_speed_task, tasks, workers=workers,
                        sizes=None if workers == 1 else [1] * len(tasks), on_row=on_point)
    return SpeedCurve(law=design.friction_law.to_dict(), points=tuple(points),
                      seconds=time.perf_counter() - start)


_RANGE = re.compile(r"^\s*(.+?)\s*\.\.\s*(.+?)\s*$")


def parse_speeds(text: str) -> tuple[float, float]:
    """``"0.1mm/s..1m/s"`` as (low, high) in m/s; ``ValueError`` naming the text."""
    match = _RANGE.match(text or "")
    if not match:
        raise ValueError(f"speeds={text!r} is not a range; write it like '0.1mm/s..1m/s'")
    try:
        lo, hi = (to_si("V0", part) for part in match.groups())
    except ValueError as error:
        raise ValueError(f"speeds={text!r}: {error}") from None
    if not lo < hi:
        raise ValueError(f"speeds={text!r}: the low speed must be below the high one")
    return lo, hi


def speed_range(lo: float, hi: float, n: int) -> np.ndarray:
    """``n`` speeds evenly spaced in log from ``lo`` to ``hi`` (m/s)."""
    if not (isinstance(n, int) and n >= 2):
        raise ValueError(f"n={n!r} must be a whole number >= 2")
    return np.geomspace(lo, hi, n)
