"""Reference solution with scipy's ``solve_ivp`` (DOP853 or Radau), independent of the kernel.

Written directly from Eqs. (3)-(6) with numpy so that it shares no code with the
compiled kernel beyond the friction law of ``model.contact.friction``. Slow (~10 us of
overhead per right-hand-side call); used by tests and benchmarks.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

from .._kernel import slots
from .friction import mu_over_s
from .options import REFERENCE_METHODS, SolverOptions
from .params import Params

__all__ = ["reference_rhs", "integrate_reference"]


def reference_rhs(params: Params):
    """du/dtau for the state (x, y, v_x, v_y, theta, W, I_y, D_x, D_y, S_theta, S_r)."""
    k_r, k_th, th0, lam, f_N = params.k_r, params.k_theta, params.theta0, params.lam, params.f_N

    def fun(t, u):
        x, y, vx, vy, th = u[:5]
        r = math.hypot(x, y)
        e_r = np.array([x, y]) / r if r > 0 else np.zeros(2)
        e_th = np.array([-y, x]) / r if r > 0 else np.zeros(2)
        phi = math.exp(-r / lam) / (2 * lam)
        v_R = np.array([vx - 1.0, vy])
        F = -f_N * float(mu_over_s(np.hypot(*v_R), params)) * v_R  # Eq. (4) friction
        a = -(k_r * (r - 1) - phi) * e_r - (k_th / r if r > 0 else 0.0) * (th - th0) * e_th + F
        dth = (x * vy - y * vx) / r**2 if r > 0 else 0.0  # Eq. (6)
        return np.array([vx, vy, a[0], a[1], dth, F[0], F[1], -F[0] * v_R[0], -F[1] * v_R[1],
                         (th - th0) ** 2, (r - 1) ** 2])

    return fun


class _Budget(Exception):
    pass


def integrate_reference(params: Params, options: SolverOptions, dense: bool = False):
    """Integrate one contact with scipy until s(tau) = L0 (Eq. 9): DOP853, or Radau for
    ``options.method == "reference-radau"`` (``REFERENCE_METHODS``).

    Returns (status, t_out, y_out, stats, r_min, r_max, sol) with the status codes of
    ``model.contact.results.Status``; ``sol`` is scipy's dense output (or None).
    """
    fun = reference_rhs(params)
    budget = 13 * options.max_steps  # DOP853 uses ~12 evaluations per step, Radau fewer
    calls = [0]

    def counted(t, u):
        calls[0] += 1
        if calls[0] > budget:
            raise _Budget
        return fun(t, u)

    x0, y0 = params.rest_position

    def exit_event(t, u):
        return t - (u[0] - x0) - params.L0

    exit_event.terminal = True
    exit_event.direction = 1
    u0 = np.zeros(11)
    u0[:5] = [x0, y0, 0.0, 0.0, params.theta0]
    try:
        sol = solve_ivp(counted, (0.0, options.tau_max), u0,
                        method=REFERENCE_METHODS[options.method], rtol=options.rtol,
                        atol=options.atol, events=exit_event, dense_output=dense)
    except _Budget:
        return (slots.STEP_BUDGET, math.nan, np.full(11, np.nan), {"n_rhs": calls[0]}, math.nan,
                math.nan, None)
    stats = {"n_steps": int(sol.t.size - 1), "n_rhs": int(sol.nfev)}
    r = np.hypot(sol.y[0], sol.y[1])
    r_min, r_max = float(np.min(r)), float(np.max(r))
    if sol.status == 1:
        return slots.OK, float(sol.t_events[0][0]), sol.y_events[0][0], stats, r_min, r_max, sol.sol
    status = slots.TIME_BUDGET if sol.status == 0 else slots.STEP_UNDERFLOW
    return status, float(sol.t[-1]), sol.y[:, -1], stats, r_min, r_max, sol.sol
