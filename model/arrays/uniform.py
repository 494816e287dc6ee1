"""Uniform-orientation arrays (Figs. 5, 6, 8): theta0 uniform on [0, 2 pi).

The paper averages n = 200 random supports (Eq. 10); here the average over theta0 is
a deterministic adaptive Gauss-Kronrod quadrature with an error estimate. Mirror
symmetry (y -> -y) makes F_x even and F_y odd in theta0, so only [0, pi] is
integrated and F_T,y = 0 (``full_circle=True`` integrates [0, 2 pi) as a check).
Two averages of the same trajectories (docs/model.md, "Arrays"):

* paper (Eq. 10, default): mean over supports of F_x/f_N;
* duration-weighted: sum of int F_f,x dtau over f_N sum tau_out, the steady force
  on the slab when contacts last different times.

Energy ratios are ratios of ensemble sums. The load factor beta = L0/<tau_out>(beta)
is solved self-consistently by default (``model.arrays.beta``), coarse to fine: first on one
15-node interval, then the quadrature refines its partition at that beta, then a Newton
step (the slope of G from a neighbouring sweep point) and secant steps start from the
residual G(beta) that the quadrature yields for free; each step is the quadrature at
the new beta, refining on from the last partition, until |G| <= tol beta^2/10
(``BETA_GTOL``: N_c/N_c0 then moves by at most tol/10; docs/model.md, "Contact count
and the load factor β"). Every member is integrated once per (beta, theta0) and reused
(the last beta evaluated is the one the quadrature uses).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from ..contact.friction import mu0
from ..contact.options import SolverOptions
from ..contact.params import Params, check_array_params
from ..contact.results import ACCURACY_FACTOR, ArrayResult
from ..validation import Interval, instance, load_factor, number, whole
from .beta import solve_beta_secant
from .contacts import run_contacts
from .quadrature import W_K, integrate

__all__ = ["UniformArrayResult", "uniform_array", "TOL"]

#: Quadrature tolerance on F_T,x/(mu0 F_N) and N_c/N_c0 a uniform array accepts.
TOL = Interval(1e-8, 0.5)
#: The self-consistent beta is accepted when |G(beta)| <= BETA_GTOL * tol * beta**2.
BETA_GTOL = 0.1

# Integrand components per orientation; the last three are diagnostics, not averaged.
QUANTITIES = ("F_x", "F_y", "t_out", "W", "D_x", "D_y", "U_el", "K", "dtheta_rms", "dr_rms")
DIAGNOSTICS = ("pivot", "relative_residual", "failed")
_FX, _FY, _T = 0, 1, 2


def COARSE_PARTITIONS(span):
    """Partitions on which beta is solved before the quadrature refines (coarse first)."""
    return (np.array([0.0, span]),)


@dataclass(frozen=True)
class UniformArrayResult(ArrayResult):
    """A uniform-orientation array; every ``*_error`` is the quadrature error estimate.

    ``params`` holds the beta used; ``FTx_over_mu0FN`` is the paper average (Eq. 10).
    """

    FTx_over_mu0FN_duration: float  # duration-weighted average
    quadrature_error: dict
    integration_error: float  # largest |energy residual| / W over the members
    beta_iterations: int
    n_members: int
    n_failed: int
    n_pivot: int
    failed_theta0: tuple
    success: bool
    message: str
    seconds: float
    stats: dict = field(default_factory=dict)


def uniform_array(params: Params, beta="self", tol: float = 1e-3, rtol: float | None = None,
                  atol: float | None = None, method: str = "auto", max_intervals: int = 256,
                  full_circle: bool = False, *, beta_guess=None,
                  guess_is_close: bool = False) -> UniformArrayResult:
    """Uniform-orientation array for the springs and load of ``params`` (Figs. 5, 6, 8).

    theta0 uniform on [0, 2 pi): the average over theta0 is an adaptive Gauss-Kronrod
    (7, 15) quadrature on [0, pi] (mirror symmetry makes F_x even and F_y odd, so
    F_T,y = 0).

    Parameters
    ----------
    params : Params
        The springs, load and friction law. The array covers every theta0, so
        ``params.theta0`` must be left at its default; its load factor is the ``beta``
        argument, so ``params.beta`` must be 1 or equal ``beta`` (``ValueError``
        otherwise: nothing in ``params`` is silently ignored).
    beta : "self" or float, default "self"
        ``"self"`` solves beta = L0/<tau_out>(beta); a number fixes it.
    tol : float, default 1e-3
        Bound on the quadrature error estimates of F_T,x/(mu0 F_N) and N_c/N_c0;
        intervals of theta0 are bisected where the integrand is rough until it is met.
    rtol : float, optional
        ``None`` integrates each member at tol/100 (at most 1e-5), so the integration
        error stays well below the quadrature tolerance.
    atol, method
        Solver settings of each member, as in ``simulate_support``.
    max_intervals : int, default 256
        Most intervals of theta0 the quadrature may bisect into.
    full_circle : bool, default False
        Integrate over [0, 2 pi) instead of [0, pi] (a check of the symmetry).
    beta_guess : float or tuple, optional
        A number, or (beta, slope of G) from ``UniformArrayResult.stats`` of a
        neighbouring array: starts the self-consistent solve near its root (continuation
        across a sweep); the result is the same to within the tolerance.
    guess_is_close : bool, default False
        Start the quadrature at ``beta_guess`` itself, without the one-interval solve (for
        a guess extrapolated from two neighbours, closer to the root than that solve gets).

    Returns
    -------
    UniformArrayResult
        Both averages of F_T,x/(mu0 F_N) (the paper's Eq. 10 and the duration-weighted
        one), D_y/D_x, N_c/N_c0, the work split, beta, and their error estimates
        (``quadrature_error``, ``integration_error``).

    Examples
    --------
    >>> from model import REGIMES, uniform_array
    >>> array = uniform_array(REGIMES["stiff"], tol=1e-3)
    >>> round(float(array.FTx_over_mu0FN), 4), float(array.FTy_over_mu0FN), array.success
    (0.9987, 0.0, True)
    >>> bool(array.quadrature_error["FTx_over_mu0FN"] < 1e-3)
    True
    """
    instance("params", params, Params)
    tol = number("tol", tol, TOL, "quadrature tolerance tol")
    max_intervals = whole("max_intervals", max_intervals, 1)
    beta = load_factor("beta", beta)
    check_array_params(params, "uniform_array", beta, uses_theta0=False)
    if rtol is None:
        rtol = min(1e-5, max(1e-10, tol / 100))
    options = SolverOptions(rtol=rtol, atol=atol, method=method)
    if not isinstance(beta, str):
        params = params.replace(beta=beta)
    guess, slope = _guess(beta_guess)
    return _uniform(params.replace(theta0=0.0), beta == "self", float(tol), options,
                    int(max_intervals), bool(full_circle), guess, slope,
                    bool(guess_is_close) and guess is not None)


def _guess(beta_guess):
    """(beta, slope) from ``beta_guess``: None, a number, or a (beta, slope) pair."""
    if beta_guess is None:
        return None, None
    beta, slope = (beta_guess, None) if np.ndim(beta_guess) == 0 else beta_guess
    beta = float(beta)
    if not (math.isfinite(beta) and 0.0 < beta <= 1.0):
        raise ValueError(f"beta_guess={beta_guess!r} must be a number in (0, 1] "
                         "or a (beta, slope) pair")
    slope = float(slope) if slope is not None and math.isfinite(float(slope)) else None
    return beta, slope


@lru_cache(maxsize=256)
def _uniform(params, self_consistent, tol, options, max_intervals, full_circle,
             guess=None, slope=None, close=False):
    start = time.perf_counter()
    span = 2 * math.pi if full_circle else math.pi
    counter = {"trajectories": 0, "n_rhs": 0}
    integrand = _Members(params, options, counter)
    m0 = mu0(params)
    # Error targets on the integrals of F_x/f_N and tau_out for tol on the means.
    targets = np.array([tol * m0 * span, tol * params.L0 * span])
    beta = params.beta
    beta_iter, beta_res = 0, 0.0
    edges = np.linspace(0.0, span, 5)
    # The slope of G on the quadrature's partition: a neighbour's (continuation), else
    # the coarse rule's. The coarse G can jump where one of its 15 members does (its
    # slope is then no guide), while G on the refined partition is smooth.
    fine_slope = slope if slope is not None and slope > 0 else None
    if self_consistent and close:
        beta = guess
    elif self_consistent:
        # Coarse to fine: beta on one 15-node interval first. Its root is only a start:
        # the one-interval rule moves the root by up to ~1e-2, so xtol = tol suffices.
        for edges in COARSE_PARTITIONS(span):
            sol = solve_beta_secant(lambda b: _mean(edges, integrand(_nodes(edges), b)[:, _T], span),
                                    params.L0, xtol=tol / 100 if edges.size > 2 else tol,
                                    guess=guess, slope=slope)
            beta_iter += sol.iterations
            beta, guess = sol.beta, sol.beta
            slope = sol.slope if math.isfinite(sol.slope) else slope
    fine_slope = fine_slope or slope
    edges = np.linspace(0.0, span, 5)
    # beta is converged when |G| <= gtol = BETA_GTOL tol beta^2 on the quadrature's own
    # partition: then beta moves N_c/N_c0 = 1/(beta - G) by at most BETA_GTOL tol and, with
    # |d(F_T,x/(mu0 F_N))/dbeta| <= 1 and a slope of G >= 1 (docs/model.md, "Contact
    # count and the load factor"), F_T,x/(mu0 F_N) by less: a tenth of the tolerance.
    quad = integrate(lambda x: integrand(x, beta), 0.0, span, targets, control=[_FX, _T],
                     edges=edges, max_intervals=max_intervals)
    last = {"beta": beta, "quad": quad}

    def mean_tau(b):
        """<tau_out> at b from the quadrature refined on from the last partition."""
        last["beta"], last["quad"] = b, integrate(
            lambda x: integrand(x, b), 0.0, span, targets, control=[_FX, _T],
            edges=last["quad"].edges, max_intervals=max_intervals)
        return last["quad"].integral[_T] / span

    for _ in range(6 if self_consistent else 0):
        # G(beta) on the refined partition comes free with the quadrature.
        beta_res = beta - params.L0 * span / quad.integral[_T]
        gtol = BETA_GTOL * tol * beta ** 2
        if abs(beta_res) <= gtol:
            break
        # Newton's step from the free residual with the slope of the last solve, then
        # secant steps; each evaluation is the quadrature at that beta, refining on.
        s = fine_slope if fine_slope and fine_slope > 0 else 1.0
        sol = solve_beta_secant(mean_tau, params.L0, xtol=gtol / beta, guess=beta - beta_res / s,
                                slope=s, gtol=gtol, known=(beta, beta_res))
        beta_iter += sol.iterations
        beta = sol.beta
        if last["beta"] != beta:  # the solver returns its last point: never, but be sure
            mean_tau(beta)
        quad = last["quad"]
        fine_slope = sol.slope if math.isfinite(sol.slope) and sol.slope > 0 else fine_slope
    if fine_slope is not None and math.isfinite(fine_slope):  # to continue a sweep from
        counter["beta_slope"] = float(fine_slope)
    return _result(params.replace(beta=beta), quad, span, m0, counter,
                   beta_iter, beta_res, options, time.perf_counter() - start)


class _Members:
    """Integrand of the orientation average: each member's quantities at a load factor.

    Every member computed is kept by (beta, theta0), so the beta iterations and the
    quadrature at the solved beta never integrate the same contact twice.
    """

    def __init__(self, params, options, counter):
        self.params, self.options, self.counter = params, options, counter
        self.rows: dict = {}

    def __call__(self, theta0, beta):
        theta0 = np.asarray(theta0, dtype=float)
        keys = [(beta, t) for t in theta0.tolist()]
        missing = [i for i, k in enumerate(keys) if k not in self.rows]
        if missing:
            c = run_contacts(self.params, theta0[missing], self.options,
                             beta=np.full(len(missing), beta))[0]
            self.counter["trajectories"] += len(missing)
            self.counter["n_rhs"] += c.n_rhs
            vals = np.column_stack([getattr(c, q) for q in QUANTITIES])
            vals[~c.ok] = np.nan
            with np.errstate(divide="ignore", invalid="ignore"):
                relres = np.abs(c.energy_residual / c.W)
            new = np.column_stack([vals, c.pivot_approach, relres, ~c.ok])
            for i, row in zip(missing, new):
                self.rows[keys[i]] = row
        out = np.array([self.rows[k] for k in keys])
        out[:, :len(QUANTITIES)] = _repair(out[:, :len(QUANTITIES)])
        return out


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
