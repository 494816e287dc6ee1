"""One support dragged by the slab: ``simulate_support`` (Eqs. 5-6, 8, 9, 12, 13)."""
from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

import numpy as np
from scipy.interpolate import CubicHermiteSpline

from .contacts import STAT_NAMES, Contacts, exit_quantities, run_contacts
from .friction import mu_over_s
from .options import SolverOptions
from .params import Params
from .reference import integrate_reference
from .results import ACCURACY_FACTOR, STATUS, SupportResult, TimeSeries

__all__ = ["simulate_support"]


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
    if not (isinstance(samples, (int, float, np.integer, np.floating))
            and not isinstance(samples, bool) and 0 <= samples <= 10**6
            and float(samples).is_integer()):
        raise ValueError(f"samples={samples!r} must be a whole number in [0, 1e6]")
    options = SolverOptions(rtol=rtol, atol=atol, method=method, max_steps=max_steps,
                            tau_max=tau_max)
    return _simulate(params, options, int(samples))


@lru_cache(maxsize=1024)
def _simulate(params: Params, options: SolverOptions, samples: int) -> SupportResult:
    if options.method == "reference":
        status, t, y, stats, r_min, sol = integrate_reference(params, options, dense=samples > 0)
        stats["method"] = "reference (scipy DOP853)"
        row = exit_quantities(params, options, np.array([params.theta0]), [status], [t], [y],
                              np.zeros((1, len(STAT_NAMES)), np.int64), [r_min])
        series = _series_from_dense(params, sol, t, samples) if samples and status == 0 else None
    else:
        row, nodes = run_contacts(params, params.theta0, options, record=samples > 0)
        stats = {k: int(v) for k, v in zip(STAT_NAMES, row.stats[0])}
        stats["method"] = _method_used(options.method, stats)
        series = _series_from_nodes(params, nodes, samples) if samples else None
    return _assemble(row, stats, series)


def _method_used(method: str, stats: dict) -> str:
    if method != "auto":
        return method
    used = [name for name, key in (("explicit", "n_steps_explicit"), ("implicit", "n_steps_implicit"))
            if stats[key]]
    return "auto (" + " + ".join(used) + f", {stats['n_switches']} switches)"


def _assemble(row: Contacts, stats: dict, series) -> SupportResult:
    """The one-contact result from a one-row ``Contacts``."""
    status = int(row.status[0])
    r_min = float(row.r_min[0])
    approach = bool(row.pivot_approach[0])
    state_out = row.state_out[0].copy()
    F_mean = np.array([row.F_x[0], row.F_y[0]])
    for a in (F_mean, state_out):
        a.flags.writeable = False
    result = SupportResult(
        params=row.params, options=row.options, success=status == 0, status=status,
        message=_message(status, float(row.t_out[0]), r_min, approach, row.pivot_radius,
                         row.options),
        t_out=float(row.t_out[0]), state_out=state_out, F_mean=F_mean,
        W=float(row.W[0]), D_x=float(row.D_x[0]), D_y=float(row.D_y[0]),
        U_el=float(row.U_el[0]), K=float(row.K[0]),
        energy_residual=float(row.energy_residual[0]),
        dtheta_rms=float(row.dtheta_rms[0]), dr_rms=float(row.dr_rms[0]),
        r_min=r_min, pivot_approach=approach, pivot_radius=row.pivot_radius,
        stats=stats, series=series)
    if result.success and not result.accurate:
        warning = (f"; warning: the energy balance misses by {result.relative_energy_residual:.1e}"
                   f" of W, more than {ACCURACY_FACTOR:g} rtol: the result is inaccurate; "
                   + ("tighten rtol" if result.options.method == "auto"
                      else "tighten rtol or use method='auto'"))
        result = replace(result, message=result.message + warning)
    return result


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
    # tau is non-decreasing but can stall at rounding level where the mass passes its
    # pivot (dtau/ds = w ~ 0): keep the nodes that advance it.
    tau = nodes[:, 0]
    keep = np.concatenate(([True], tau[1:] > np.maximum.accumulate(tau)[:-1]))
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
