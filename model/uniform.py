"""Uniform-orientation arrays (Figs. 5, 6, 8): theta0 uniform on [0, 2 pi).

The paper averages n = 200 random supports (Eq. 10); here the average over theta0 is
a deterministic adaptive Gauss-Kronrod quadrature with an error estimate. Mirror
symmetry (y -> -y) makes F_x even and F_y odd in theta0, so only [0, pi] is
integrated and F_T,y = 0 (``full_circle=True`` integrates [0, 2 pi) as a check).
Two averages of the same trajectories (MODEL.md):

* paper (Eq. 10, default): mean over supports of F_x/f_N;
* duration-weighted: sum of int F_f,x dtau over f_N sum tau_out, the steady force
  on the slab when contacts last different times.

Energy ratios are ratios of ensemble sums. The load factor beta = L0/<tau_out>(beta)
is solved self-consistently by default (``model.beta``).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from .beta import solve_beta_scalar
from .contacts import run_contacts
from .friction import mu0
from .options import SolverOptions
from .params import Params
from .quadrature import W_K, integrate
from .results import ACCURACY_FACTOR

__all__ = ["UniformArrayResult", "uniform_array"]

# Integrand components per orientation; the last three are diagnostics, not averaged.
QUANTITIES = ("F_x", "F_y", "t_out", "W", "D_x", "D_y", "U_el", "K", "dtheta_rms", "dr_rms")
DIAGNOSTICS = ("pivot", "relative_residual", "failed")
_FX, _FY, _T = 0, 1, 2


@dataclass(frozen=True)
class UniformArrayResult:
    """A uniform-orientation array; every ``*_error`` is the quadrature error estimate."""

    params: Params  # with the beta used
    FTx_over_mu0FN: float  # paper average, Eq. (10)
    FTx_over_mu0FN_duration: float  # duration-weighted average
    FTy_over_mu0FN: float
    Dy_over_Dx: float
    Nc_over_Nc0: float
    beta: float
    work_split: dict
    dtheta_rms: float
    dr_rms: float
    quadrature_error: dict
    integration_error: float  # largest |energy residual| / W over the members
    beta_iterations: int
    beta_residual: float
    n_members: int
    n_failed: int
    n_pivot: int
    failed_theta0: tuple
    success: bool
    message: str
    seconds: float
    stats: dict = field(default_factory=dict)

    def to_dict(self) -> dict:
        d = {k: getattr(self, k) for k in self.__dataclass_fields__ if k != "params"}
        d["failed_theta0"] = list(self.failed_theta0)
        d["params"] = self.params.as_dict()
        return d


def uniform_array(params: Params, beta="self", tol: float = 1e-3, rtol: float | None = None,
                  atol: float | None = None, method: str = "auto", max_intervals: int = 256,
                  full_circle: bool = False) -> UniformArrayResult:
    """Uniform-orientation array for the springs and load of ``params`` (theta0 ignored).

    ``tol`` bounds the quadrature error estimates of F_T,x/(mu0 F_N) and N_c/N_c0;
    intervals of theta0 are bisected where the integrand is rough until it is met.
    ``beta="self"`` solves beta = L0/<tau_out>(beta); a number fixes it.
    ``rtol=None`` integrates each member at tol/100 (at most 1e-5), so the integration
    error stays well below the quadrature tolerance.
    """
    if not isinstance(params, Params):
        raise TypeError(f"params must be a model.Params, not {type(params).__name__}")
    if not (isinstance(tol, (int, float)) and 1e-8 <= tol <= 0.5):
        raise ValueError(f"tol={tol!r} must be in [1e-8, 0.5]")
    if isinstance(max_intervals, bool) or not isinstance(max_intervals, (int, np.integer)) \
            or max_intervals < 1:
        raise ValueError(f"max_intervals={max_intervals!r} must be a whole number >= 1")
    if isinstance(beta, str) and beta != "self":
        raise ValueError(f"beta={beta!r} must be 'self' or a number in (0, 1]")
    if rtol is None and isinstance(tol, (int, float)):
        rtol = min(1e-5, max(1e-10, tol / 100))
    options = SolverOptions(rtol=rtol, atol=atol, method=method)
    if not isinstance(beta, str):
        params = params.replace(beta=beta)
    return _uniform(params.replace(theta0=0.0), beta == "self", float(tol), options,
                    int(max_intervals), bool(full_circle))


@lru_cache(maxsize=256)
def _uniform(params, self_consistent, tol, options, max_intervals, full_circle):
    start = time.perf_counter()
    span = 2 * math.pi if full_circle else math.pi
    counter = {"trajectories": 0, "n_rhs": 0}
    state = {"beta": params.beta}

    def integrand(theta0, beta=None):
        c = run_contacts(params, theta0, options, beta=np.full(theta0.size, beta or state["beta"]))[0]
        counter["trajectories"] += theta0.size
        counter["n_rhs"] += c.n_rhs
        vals = np.column_stack([getattr(c, q) for q in QUANTITIES])
        vals[~c.ok] = np.nan
        with np.errstate(divide="ignore", invalid="ignore"):
            relres = np.abs(c.energy_residual / c.W)
        return np.column_stack([_repair(vals), c.pivot_approach, relres, ~c.ok]), c

    m0 = mu0(params)
    f = lambda x: integrand(x)[0]  # noqa: E731
    # Error targets on the integrals of F_x/f_N and tau_out for tol on the means.
    targets = np.array([tol * m0 * span, tol * params.L0 * span])
    edges = np.linspace(0.0, span, 5)
    beta_iter, beta_res, guess = 0, 0.0, None
    for _ in range(4 if self_consistent else 1):
        if self_consistent:
            # beta on the current partition, then refine the partition at that beta.
            sol = solve_beta_scalar(lambda b: _mean(edges, integrand(_nodes(edges), b)[0][:, _T], span),
                                    params.L0, xtol=tol / 100, guess=guess, width=0.01)
            beta_iter += sol.iterations
            state["beta"] = guess = sol.beta
        quad = integrate(f, 0.0, span, targets, control=[_FX, _T], edges=edges,
                         max_intervals=max_intervals)
        # G(beta) on the refined partition comes free with the quadrature.
        beta_res = state["beta"] - params.L0 * span / quad.integral[_T] if self_consistent else 0.0
        if quad.edges.size == edges.size or abs(beta_res) <= tol / 10:
            break
        edges = quad.edges
    return _result(params.replace(beta=state["beta"]), quad, span, m0, counter,
                   beta_iter, beta_res, options, time.perf_counter() - start)


def _repair(vals):
    """Fill failed members (NaN rows) with the nearest successful member's values."""
    bad = np.isnan(vals[:, 0])
    if not np.any(bad) or np.all(bad):
        return vals
    good = np.flatnonzero(~bad)
    nearest = good[np.abs(np.flatnonzero(bad)[:, None] - good[None, :]).argmin(axis=1)]
    vals = vals.copy()
    vals[bad] = vals[nearest]
    return vals


def _nodes(edges):
    from .quadrature import NODES

    mid, half = 0.5 * (edges[1:] + edges[:-1]), 0.5 * np.diff(edges)
    return (mid[:, None] + half[:, None] * NODES[None, :]).ravel()


def _mean(edges, values, span):
    """Kronrod mean of one quantity on the partition ``edges`` (values at ``_nodes``)."""
    widths = np.diff(edges)
    return float(np.sum(0.5 * widths * (W_K @ values.reshape(-1, 15).T))) / span


def _result(params, quad, span, m0, counter, beta_iter, beta_res, options, seconds):
    mean = dict(zip(QUANTITIES, quad.integral / span))
    err = dict(zip(QUANTITIES, quad.error / span))
    pivot, relres, failed = quad.values[:, len(QUANTITIES):].T
    fN = params.f_N

    def ratio(a, b):
        value = mean[a] / mean[b]
        return value, abs(value) * (err[a] / abs(mean[a]) + err[b] / abs(mean[b]))

    Dy_Dx, Dy_Dx_err = ratio("D_y", "D_x")
    split = {k: ratio(k, "W") for k in ("D_x", "D_y", "U_el", "K")}
    duration = mean["W"] / (fN * mean["t_out"]) / m0
    n_failed = int(np.sum(failed > 0))
    failed = tuple(quad.nodes[failed > 0].tolist())
    message = "ok" if quad.converged else "quadrature tolerance not met within max_intervals"
    if n_failed:
        message += (f"; {n_failed} of {quad.nodes.size} members did not finish their contact "
                    f"and took the values of their nearest neighbour in theta0")
    n_pivot = int(np.sum(pivot > 0))
    n_inaccurate = int(np.sum(relres > ACCURACY_FACTOR * options.rtol))
    if n_inaccurate:
        message += (f"; {n_inaccurate} members miss the energy balance by more than "
                    f"{ACCURACY_FACTOR:g} rtol (largest {np.nanmax(relres):.1e} of W)")
    if n_pivot:
        message += f"; {n_pivot} members were driven into the region of their pivot"
    integ = float(np.nanmax(relres))
    return UniformArrayResult(
        params=params, FTx_over_mu0FN=mean["F_x"] / m0, FTx_over_mu0FN_duration=duration,
        FTy_over_mu0FN=mean["F_y"] / m0 if span > math.pi else 0.0,
        Dy_over_Dx=Dy_Dx, Nc_over_Nc0=mean["t_out"] / params.L0, beta=params.beta,
        work_split={k: v for k, (v, _) in split.items()},
        dtheta_rms=mean["dtheta_rms"], dr_rms=mean["dr_rms"],
        quadrature_error={
            "FTx_over_mu0FN": err["F_x"] / m0,
            "FTx_over_mu0FN_duration": duration * (err["W"] / abs(mean["W"]) + err["t_out"] / mean["t_out"]),
            # Zero by mirror symmetry on the half range: exact, no quadrature error.
            "FTy_over_mu0FN": err["F_y"] / m0 if span > math.pi else 0.0,
            "Dy_over_Dx": Dy_Dx_err,
            "Nc_over_Nc0": err["t_out"] / params.L0,
            **{f"work_split.{k}": e for k, (_, e) in split.items()}},
        integration_error=integ, beta_iterations=beta_iter, beta_residual=beta_res,
        n_members=int(quad.nodes.size), n_failed=n_failed, n_pivot=n_pivot, failed_theta0=failed,
        success=bool(quad.converged and n_failed == 0), message=message, seconds=seconds,
        stats={**counter, "intervals": int(quad.edges.size - 1), "rounds": quad.rounds,
               "rtol": options.rtol, "method": options.method})
