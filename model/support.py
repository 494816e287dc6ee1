"""One support dragged by the slab: ``simulate_support`` (Eqs. 5-6, 8, 9, 12, 13)."""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from scipy.interpolate import CubicHermiteSpline

from . import _kernel
from .energy import elastic_energy, kinetic_energy
from .friction import mu_over_s
from .options import SolverOptions
from .params import Params
from .reference import integrate_reference
from .results import STATUS, SupportResult, TimeSeries

__all__ = ["simulate_support", "PIVOT_RADIUS_OVER_LAMBDA"]

#: A trajectory "approaches its pivot" when r < PIVOT_RADIUS_OVER_LAMBDA * lambda
#: (0.01 at the default lambda = 0.05): there the repulsion of Eq. (3) dominates and
#: the terms k_theta (theta - theta0)/r and theta' = (x v_y - y v_x)/r^2 grow without bound.
PIVOT_RADIUS_OVER_LAMBDA = 0.2
_STAT_NAMES = ("n_steps", "n_rejected", "n_rhs", "n_jac", "n_lu", "n_switches",
               "n_steps_explicit", "n_steps_implicit")


def simulate_support(params: Params, rtol: float = 1e-6, atol: float | None = None,
                     method: str = "auto", samples: int = 0, max_steps: int = 1_000_000,
                     tau_max: float = 1e5) -> SupportResult:
    """Integrate one contact of a support with the slab, from rest until exit (Eq. 9).

    Parameters
    ----------
    params : the support and load (``Params``).
    rtol, atol : local error tolerances (``atol=None`` means rtol/100).
    method : ``"auto"`` (default: explicit Dormand-Prince 5(4), switching to the
        L-stable Rosenbrock Rodas4 where stiffness is detected), ``"explicit"``,
        ``"implicit"`` or ``"reference"`` (scipy DOP853, slow).
    samples : number of uniformly spaced points of the time histories to return
        in ``result.series`` (0: none, the fastest).
    max_steps, tau_max : budgets; when one runs out the result has ``success=False``.

    Returns
    -------
    SupportResult; call ``.check()`` to raise ``IntegrationError`` on failure.
    Results are cached (LRU) by parameters and settings; arrays are read-only.
    """
    if not isinstance(params, Params):
        raise TypeError(f"params must be a model.Params, not {type(params).__name__}")
    if isinstance(samples, bool) or not float(samples).is_integer() or not 0 <= samples <= 10**6:
        raise ValueError(f"samples={samples!r} must be a whole number in [0, 1e6]")
    options = SolverOptions(rtol=rtol, atol=atol, method=method, max_steps=max_steps,
                            tau_max=tau_max)
    return _simulate(params, options, int(samples))


@lru_cache(maxsize=1024)
def _simulate(params: Params, options: SolverOptions, samples: int) -> SupportResult:
    if options.method == "reference":
        status, t, y, stats, r_min, sol = integrate_reference(params, options, dense=samples > 0)
        stats["method"] = "reference (scipy DOP853)"
        series = _series_from_dense(params, sol, t, samples) if samples and status == 0 else None
    else:
        status, t, y, st, r_min, nodes, n_nodes = _kernel.integrate(
            _kernel.initial_state(params), _kernel.pack(params), options.rtol, options.atol,
            _kernel.METHOD_CODES[options.method], options.max_steps, options.tau_max, samples > 0)
        stats = {k: int(v) for k, v in zip(_STAT_NAMES, st)}
        stats["method"] = _method_used(options.method, stats)
        series = _series_from_nodes(params, nodes[:n_nodes], samples) if samples else None
    return _assemble(params, options, int(status), float(t), np.asarray(y, dtype=float),
                     stats, float(r_min), series)


def _method_used(method: str, stats: dict) -> str:
    if method != "auto":
        return method
    used = [name for name, key in (("explicit", "n_steps_explicit"), ("implicit", "n_steps_implicit"))
            if stats[key]]
    return "auto (" + " + ".join(used) + f", {stats['n_switches']} switches)"


def _assemble(params, options, status, t, y, stats, r_min, series) -> SupportResult:
    """Quantities of Eqs. (8), (12), (13) from the exit state and the quadratures."""
    x, yy, vx, vy, th, W, Iy, Dx, Dy, S_th, S_r = (float(v) for v in y)
    r = math.hypot(x, yy)
    U_el = float(elastic_energy(params, r, th))
    K = float(kinetic_energy(vx, vy))
    fN = params.f_N
    F_mean = np.array([W, Iy]) / (t * fN) if t > 0 else np.full(2, np.nan)
    pivot_radius = PIVOT_RADIUS_OVER_LAMBDA * params.lam
    r_min = min(r_min, r) if math.isfinite(r) else r_min
    approach = bool(r_min < pivot_radius)
    state_out = np.array([x, yy, vx, vy, th])
    for a in (F_mean, state_out):
        a.flags.writeable = False
    return SupportResult(
        params=params, options=options, success=status == 0, status=status,
        message=_message(status, t, r_min, approach, pivot_radius, options),
        t_out=t, state_out=state_out, F_mean=F_mean, W=W, D_x=Dx, D_y=Dy, U_el=U_el, K=K,
        energy_residual=W - (Dx + Dy + U_el + K),
        dtheta_rms=math.sqrt(max(S_th, 0.0) / t) if t > 0 else math.nan,
        dr_rms=math.sqrt(max(S_r, 0.0) / t) if t > 0 else math.nan,
        r_min=r_min, pivot_approach=approach, pivot_radius=pivot_radius,
        stats=stats, series=series)


def _message(status, t, r_min, approach, pivot_radius, options) -> str:
    text = STATUS.get(status, f"unknown status {status}")
    if status == 0:
        text += f" at tau_out = {t:.6g}"
    elif status == 1:
        text += f" (max_steps = {options.max_steps}, tau = {t:.6g}); raise max_steps or loosen rtol"
    elif status == 2:
        text += f" (tau_max = {options.tau_max:g}); raise tau_max"
    elif status in (3, 4):
        text += f" at tau = {t:.6g}; try method='implicit' or a looser rtol"
    if approach:
        text += (f"; the mass was driven into the region of its pivot (r_min = {r_min:.3g} "
                 f"< {pivot_radius:.3g})")
    return text


def _series(params, tau, x, y, vx, vy, theta) -> TimeSeries:
    vrx = vx - 1.0
    m = mu_over_s(np.hypot(vrx, vy), params)
    Fx, Fy = -m * vrx, -m * vy
    arrays = dict(tau=tau, x=x, y=y, v_x=vx, v_y=vy, theta=theta, r=np.hypot(x, y),
                  F_x=Fx, F_y=Fy, F_abs=np.hypot(Fx, Fy))
    for a in arrays.values():
        a.flags.writeable = False
    return TimeSeries(**arrays)


def _series_from_nodes(params, nodes, samples) -> TimeSeries | None:
    """Uniform samples by cubic Hermite interpolation of the accepted steps."""
    keep = np.concatenate(([True], np.diff(nodes[:, 0]) > 0))
    nodes = nodes[keep]
    if nodes.shape[0] < 2:
        return None
    tau = np.linspace(0.0, nodes[-1, 0], samples)
    u = CubicHermiteSpline(nodes[:, 0], nodes[:, 1:6], nodes[:, 6:11])(tau)
    return _series(params, tau, *u.T)


def _series_from_dense(params, sol, t_out, samples) -> TimeSeries | None:
    if sol is None:
        return None
    tau = np.linspace(0.0, t_out, samples)
    return _series(params, tau, *sol(tau)[:5])
