"""One support dragged by the slab: ``simulate_support`` (Eqs. 5-6, 8, 9, 12, 13)."""
from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

import numpy as np
from scipy.interpolate import CubicHermiteSpline

from .. import _kernel
from .._kernel import N_REC
from ..arrays.contacts import PIVOT_RADIUS_OVER_LAMBDA, STAT_NAMES, exit_quantities
from ..validation import instance, whole
from .energy import elastic_energy, kinetic_energy
from .friction import mu_over_s
from .options import REFERENCE_METHODS, SolverOptions
from .params import Params
from .reference import integrate_reference
from .results import ACCURACY_FACTOR, Status, SupportResult, TimeSeries

__all__ = ["simulate_support"]


def simulate_support(params: Params, rtol: float = 1e-6, atol: float | None = None,
                     method: str = "auto", samples: int = 0, max_steps: int = 1_000_000,
                     tau_max: float = 1e5, cache: bool = True) -> SupportResult:
    """Integrate one contact of a support with the slab, from rest until exit (Eq. 9).

    The motion (Eqs. 5-6) and the quadratures of the slab work, the dissipations and the
    fluctuations (Eqs. 8, 12, 13) are integrated under one error control, from the rest
    position until the slab has slid L0 over the support.

    Parameters
    ----------
    params : Params
        The support and load.
    rtol : float, default 1e-6
        Local relative error tolerance.
    atol : float, optional
        Local absolute error tolerance; ``None`` means ``rtol / 100``.
    method : {"auto", "explicit", "implicit", "reference", "reference-radau"}, default "auto"
        ``"auto"``: the explicit Dormand-Prince pair chosen by rtol (DOP853 at
        rtol <= 1e-6, 5(4) above), switching to the L-stable Rosenbrock Rodas4 where
        stiffness is detected; ``"explicit"``, ``"implicit"`` (Rodas4), ``"reference"``
        (scipy's DOP853, slow) or ``"reference-radau"`` (scipy's Radau, for stiff contacts).
        See the Solvers page of the documentation.
    samples : int, default 0
        Number of uniformly spaced points of the time histories to return in
        ``result.series`` (0: none, the fastest).
    max_steps : int, default 1_000_000
        Step budget (accepted and rejected steps).
    tau_max : float, default 1e5
        Time budget in tau. When a budget runs out the result has ``success=False``.
    cache : bool, default True
        Reuse the result of an identical earlier call (an LRU cache of 1024 results, by
        parameters and settings). ``False`` integrates afresh and leaves the cache as it
        was: what a benchmark times.

    Returns
    -------
    SupportResult
        Contact duration, mean friction over f_N, energies in m V0^2 and the energy
        residual; call ``.check()`` to raise ``IntegrationError`` on failure. Its arrays
        are read-only (a cached result is shared).

    See Also
    --------
    fixed_orientation : the array in which every support shares this orientation.

    Examples
    --------
    >>> from model import REGIMES, simulate_support
    >>> result = simulate_support(REGIMES["pendulum"])
    >>> result.success, round(result.t_out, 3)      # contact duration tau_out (Eq. 9)
    (True, 11.122)
    >>> result.F_mean.round(3)                      # mean friction over f_N (Eq. 8)
    array([0.951, 0.13 ])
    >>> parts = result.D_x + result.D_y + result.U_el + result.K
    >>> abs(result.W - parts) < 1e-6                # energy balance, Eq. (12)
    True
    >>> simulate_support(REGIMES["pendulum"], samples=50).series.tau.shape
    (50,)
    >>> simulate_support(REGIMES["pendulum"], cache=False) is result  # computed afresh
    False
    """
    instance("params", params, Params)
    if not isinstance(cache, bool):
        raise TypeError(f"cache must be True or False, not {cache!r}")
    samples = whole("samples", samples, 0, 10**6)
    options = SolverOptions(rtol=rtol, atol=atol, method=method, max_steps=max_steps,
                            tau_max=tau_max)
    return (_simulate if cache else _integrate)(params, options, int(samples))


def _integrate(params: Params, options: SolverOptions, samples: int) -> SupportResult:
    """The contact's result, computed (``_simulate``: the same, cached)."""
    if options.method in REFERENCE_METHODS:
        status, t, y, stats, r_min, r_max, sol = integrate_reference(params, options,
                                                                     dense=samples > 0)
        stats["method"] = f"reference (scipy {REFERENCE_METHODS[options.method]})"
        c = exit_quantities(params, options, np.array([params.theta0]), [status], [t], [y],
                            np.zeros((1, len(STAT_NAMES)), np.int64), [r_min], r_max=[r_max])
        series = _series_from_dense(params, sol, t, samples) if samples and status == 0 else None
        return _assemble(params, options, int(c.status[0]), float(c.t_out[0]), c.state_out[0],
                         c.F_x[0], c.F_y[0], c.W[0], c.D_x[0], c.D_y[0], c.U_el[0], c.K[0],
                         c.energy_residual[0], c.dtheta_rms[0], c.dr_rms[0], c.r_min[0],
                         c.r_max[0], stats, series)
    # One row straight through the kernel: the per-call cost of a single contact is
    # mostly Python (a few us per array built), so the ``Contacts`` table is skipped.
    Y0, P = _start(params)
    status, t, Y, D, st, r_min, r_max, nodes, n_nodes = _kernel.integrate_batch(
        Y0, P, options.rtol, options.atol, _kernel.METHOD_CODES[options.method],
        options.max_steps, options.tau_max, samples > 0)
    stats = dict(zip(STAT_NAMES, st[0].tolist()))
    stats["method"] = _method_used(options.method, stats)
    series = _series_from_nodes(params, nodes[:n_nodes], samples) if samples else None
    y, (F_x, F_y, U_el, K, residual, dtheta_rms, dr_rms, r_out) = Y[0], D[0].tolist()
    S = _kernel.slots
    return _assemble(params, options, int(status[0]), float(t[0]), y[:S.N_MOTION], F_x, F_y,
                     float(y[S.W]), float(y[S.D_X]), float(y[S.D_Y]), U_el, K, residual,
                     dtheta_rms, dr_rms, min(float(r_min[0]), r_out), max(float(r_max[0]), r_out),
                     stats, series)


_simulate = lru_cache(maxsize=1024)(_integrate)


@lru_cache(maxsize=1024)
def _start(params: Params):
    """Kernel start row and parameter row of ``params`` (private: never written to)."""
    return _kernel.initial_state(params)[None], _kernel.pack(params)[None]


def _method_used(method: str, stats: dict) -> str:
    if method != "auto":
        return method
    used = [name for name, key in (("explicit", "n_steps_explicit"), ("implicit", "n_steps_implicit"))
            if stats[key]]
    return "auto (" + " + ".join(used) + f", {stats['n_switches']} switches)"


def _assemble(params, options, status, t_out, state_out, F_x, F_y, W, D_x, D_y, U_el, K,
              residual, dtheta_rms, dr_rms, r_min, r_max, stats, series) -> SupportResult:
    """The one-contact result from its exit quantities."""
    pivot_radius = PIVOT_RADIUS_OVER_LAMBDA * params.lam
    approach = bool(r_min < pivot_radius)
    state_out = np.array(state_out, dtype=float)
    F_mean = np.array([F_x, F_y], dtype=float)
    for a in (F_mean, state_out):
        a.flags.writeable = False
    result = SupportResult(
        params=params, options=options, success=status == Status.OK, status=status,
        message=_message(status, t_out, r_min, approach, pivot_radius, options),
        t_out=t_out, state_out=state_out, F_mean=F_mean, W=float(W), D_x=float(D_x),
        D_y=float(D_y), U_el=float(U_el), K=float(K), energy_residual=float(residual),
        dtheta_rms=float(dtheta_rms), dr_rms=float(dr_rms), r_min=float(r_min),
        r_max=float(r_max), pivot_approach=approach, pivot_radius=pivot_radius,
        stats=stats, series=series)
    if result.success and not result.accurate:
        warning = (f"; warning: the energy balance misses by {result.relative_energy_residual:.1e}"
                   f" of W, more than {ACCURACY_FACTOR:g} rtol: the result is inaccurate; "
                   + ("tighten rtol" if result.options.method == "auto"
                      else "tighten rtol or use method='auto'"))
        result = replace(result, message=result.message + warning)
    return result


def _message(status, t, r_min, approach, pivot_radius, options) -> str:
    """The status's message with where it happened and its remedy (``Status``)."""
    try:
        code = Status(status)
    except ValueError:
        return f"unknown status {status}"
    text = code.message + {
        Status.OK: f" at tau_out = {t:.6g}",
        Status.STEP_BUDGET: f" (max_steps = {options.max_steps}, tau = {t:.6g})",
        Status.TIME_BUDGET: f" (tau_max = {options.tau_max:g})",
    }.get(code, f" at tau = {t:.6g}")
    if code.remedy:
        text += "; " + code.remedy
    if approach:
        text += (f"; the mass was driven into the region of its pivot (r_min = {r_min:.3g} "
                 f"< {pivot_radius:.3g})")
    return text


def _series(params, tau, x, y, vx, vy, theta, W, D_x, D_y) -> TimeSeries:
    """Histories from the sampled motion and cumulative quadratures (Eqs. 4, 12, 13)."""
    vrx = vx - 1.0
    m = mu_over_s(np.hypot(vrx, vy), params)
    Fx, Fy = -m * vrx, -m * vy
    r = np.hypot(x, y)
    arrays = dict(tau=tau, x=x, y=y, v_x=vx, v_y=vy, theta=theta, r=r,
                  F_x=Fx, F_y=Fy, F_abs=np.hypot(Fx, Fy), W=W, D_x=D_x, D_y=D_y,
                  U_el=elastic_energy(params, r, theta), K=kinetic_energy(vx, vy))
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
    n = N_REC  # recorded: x, y, v_x, v_y, theta, W, D_x, D_y (``_kernel.REC_SLOTS``)
    u = CubicHermiteSpline(nodes[:, 0], nodes[:, 1:1 + n], nodes[:, 1 + n:1 + 2 * n])(tau)
    return _series(params, tau, *u.T)


def _series_from_dense(params, sol, t_out, samples) -> TimeSeries | None:
    if sol is None:
        return None
    tau = np.linspace(0.0, t_out, samples)
    x, y, vx, vy, theta, W, _, D_x, D_y = sol(tau)[:9]
    return _series(params, tau, x, y, vx, vy, theta, W, D_x, D_y)
