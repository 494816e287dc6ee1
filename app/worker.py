"""One support at theta0, as the dashboard shows it (Eqs. 5-6, 8-9, 12-13; Figs. 7, 9-11).

This module runs in the dashboard's worker processes as well as in the server, loaded
under one fixed name everywhere (``app.jobs.worker_module``), so its functions and
results pass between processes; it imports nothing from the rest of ``app``.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from model import (REGIMES, FixedArrayResult, Params, SupportResult, fixed_orientation,
                   simulate_support)

SAMPLES = 400


def warm() -> None:
    """Load the compiled kernel (the first call of a process)."""
    simulate_support(REGIMES["stiff"], samples=10)


@dataclass(frozen=True)
class SupportData:
    """One support at theta0 and its fixed-orientation array; ``error`` says what failed.

    ``result`` is None only when the model raised; a run that did not reach the end of
    its contact still has its (partial) ``result`` and an ``error``.
    """

    params: Params
    result: SupportResult | None
    fixed: FixedArrayResult | None
    error: str = ""
    seconds: float = 0.0

    @property
    def series(self):
        return None if self.result is None else self.result.series

    def energy_fractions(self) -> dict:
        """D_x, D_y, U_el, K as fractions of the slab work W (Eq. 12), and the residual."""
        r = self.result
        if r is None or not np.isfinite(r.W) or r.W == 0:
            return {k: math.nan for k in ("D_x", "D_y", "U_el", "K", "residual")}
        return {"D_x": r.D_x / r.W, "D_y": r.D_y / r.W, "U_el": r.U_el / r.W, "K": r.K / r.W,
                "residual": r.energy_residual / r.W}


def compute_support(params: Params, beta="self", rtol: float = 1e-6,
                    samples: int = SAMPLES) -> SupportData:
    """The fixed-orientation array at ``params.theta0`` (beta self-consistent or fixed) and
    the trajectory of its support, integrated with the array's beta, so the plotted motion
    is the one behind the readouts. Never raises: a failure is described in ``error``."""
    start = time.perf_counter()
    try:
        fixed = fixed_orientation(params, beta=beta, rtol=rtol)
        used = params.replace(beta=fixed.beta)
        result = simulate_support(used, rtol=rtol, samples=samples)
    except Exception as exc:  # shown on the page; the controls stay usable
        return _failed(params, exc, time.perf_counter() - start)
    return _assemble(used, fixed, result, time.perf_counter() - start)


def _failed(params, exc, seconds) -> SupportData:
    return SupportData(params, None, None, f"The model raised {type(exc).__name__}: {exc}",
                       seconds)


def _assemble(used, fixed, result, seconds) -> SupportData:
    problems = []
    if not result.success:
        problems.append(f"The contact did not reach its end (status {result.status}): "
                        f"{result.message}.")
    elif not result.accurate:
        problems.append(f"Inaccurate run: {result.message}.")
    if not fixed.success:
        problems.append(f"Fixed array at theta0: {fixed.message}.")
    if result.series is None:
        problems.append("No time series could be sampled for this run.")
    return SupportData(used, result, fixed, " ".join(problems), seconds)
