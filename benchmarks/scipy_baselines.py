"""scipy solve_ivp baselines for the support benchmark, under a wall-time cap.

Two right-hand sides of the same model, Eqs. (3)-(6), both with the exit event of Eq. (9):

* ``lean`` (methods named ``"RK45-lean"``, ...): what a researcher would write: the five
  motion states as scalars with ``math`` functions and the six quadratures as extra
  states, returning a list (no numpy arrays inside the right-hand side);
* the 11-state numpy form of ``model.contact.reference`` (methods ``"RK45"``, ...), about four
  times slower per call, kept for comparison with earlier reports.
"""
from __future__ import annotations

import math
import time

import numpy as np
from scipy.integrate import solve_ivp

from model import Params, SolverOptions
from model.contact.energy import elastic_energy, kinetic_energy
from model.contact.friction import SERIES_BELOW, series_coefficients
from model.contact.reference import reference_rhs

from spread import repeats_for, spread

CUT = ("aborted:", "skipped:")  # statuses of runs left out by the time cap

TAU_MAX = SolverOptions().tau_max


def score(row: dict, t_out: float, state, ref: dict) -> dict:
    """Add the errors against the reference to a successful run's row."""
    row["error"] = float(np.max(np.abs(np.asarray(state[:5]) - ref["state_out"])))
    row["t_error"] = abs(t_out - ref["t_out"])
    return row


class OverBudget(Exception):
    """A scipy run went past its time limit."""


def lean_rhs(params: Params):
    """du/dtau with scalar arithmetic: (x, y, v_x, v_y, theta) and the quadratures
    W, I_y, D_x, D_y, int (theta - theta0)^2, int (r - 1)^2 (Eqs. 3-6, 12, 13)."""
    k_r, k_th, th0, lam, f_N = params.k_r, params.k_theta, params.theta0, params.lam, params.f_N
    mu_s, A, B, zeta = params.mu_s, params.A, params.B, params.zeta
    c0, c2, c4, c6 = series_coefficients(A, B)
    sqrt, exp, atan, sin = math.sqrt, math.exp, math.atan, math.sin

    def fun(t, u):
        x, y, vx, vy, th = u[0], u[1], u[2], u[3], u[4]
        r = sqrt(x * x + y * y)
        vrx = vx - 1.0
        s = sqrt(vrx * vrx + vy * vy)
        z = zeta * s
        if z < SERIES_BELOW:  # mu(s)/s by its series near s = 0 (Eq. 4)
            z2 = z * z
            m = mu_s * zeta * (c0 + z2 * (c2 + z2 * (c4 + z2 * c6)))
        else:
            m = mu_s * sin(A * atan(z - B * (z - atan(z)))) / s
        Fx, Fy = -f_N * m * vrx, -f_N * m * vy
        dth = th - th0
        if r > 0.0:
            q = (-k_r * (r - 1.0) + exp(-r / lam) / (2.0 * lam)) / r
            p = -k_th * dth / (r * r)
            ax, ay, om = q * x - p * y + Fx, q * y + p * x + Fy, (x * vy - y * vx) / (r * r)
        else:
            ax, ay, om = Fx, Fy, 0.0
        return [vx, vy, ax, ay, om, Fx, Fy, -Fx * vrx, -Fy * vy, dth * dth, (r - 1.0) ** 2]

    return fun


def solve_scipy(params: Params, method: str, rtol: float, limit: float):
    """solve_ivp with the exit event of Eq. (9); ``"<method>-lean"`` uses ``lean_rhs``,
    a plain method name the 11-state numpy right-hand side of ``model.contact.reference``."""
    lean = method.endswith("-lean")
    method = method.removesuffix("-lean")
    fun = lean_rhs(params) if lean else reference_rhs(params)
    deadline = time.perf_counter() + limit

    def budgeted(t, u):
        if time.perf_counter() > deadline:
            raise OverBudget
        return fun(t, u)

    x0 = math.cos(params.theta0)

    def exit_event(t, u):
        return t - (u[0] - x0) - params.L0

    exit_event.terminal = True
    exit_event.direction = 1
    u0 = np.zeros(11)
    u0[:5] = [x0, math.sin(params.theta0), 0.0, 0.0, params.theta0]
    return solve_ivp(budgeted, (0.0, TAU_MAX), u0, method=method, rtol=rtol, atol=rtol / 100,
                     events=exit_event)


def relative_energy(params: Params, u) -> float:
    """|W - (D_x + D_y + U_el + K)| / |W| at the exit state u (11 components)."""
    U = float(elastic_energy(params, math.hypot(u[0], u[1]), u[4]))
    K = float(kinetic_energy(u[2], u[3]))
    return abs(u[5] - (u[7] + u[8] + U + K)) / max(abs(u[5]), 1e-300)


def timed_scipy(params, method, rtol, abort, cap, min_total):
    """(solution, seconds of the completed runs); the solution is None when the first run
    went over `abort` seconds.

    A run is repeated until about `min_total` seconds in all, at least 3 times, unless
    it took more than `cap` seconds (it then ends its sweep and is not repeated).
    """
    sol, done = None, []
    while True:
        start = time.perf_counter()
        try:
            sol = solve_scipy(params, method, rtol, abort)
        except OverBudget:
            if not done:
                return None, [time.perf_counter() - start]
            break  # a repeat slowed down by other load: keep the completed runs
        done.append(time.perf_counter() - start)
        if done[0] > cap or len(done) >= repeats_for(done[0], min_total):
            return sol, done
    return sol, done


def sweep_scipy(params, method, rtols, ref, cap, abort, min_total) -> list:
    """The rtol sweep of one scipy method, loosest rtol first, under a time cap.

    A run is aborted after `abort` seconds; once a run was aborted or took more than
    `cap` seconds, the tighter tolerances are skipped (a tighter tolerance takes no less
    time). Such rows get the status "aborted: > A s at rtol R" or "skipped: > X s at
    rtol R".
    """
    rows, stop = [], None
    for rtol in rtols:
        row = {"method": method, "rtol": rtol, "success": False}
        rows.append(row)
        if stop:
            row["status"] = stop
            continue
        sol, times = timed_scipy(params, method, rtol, abort, cap, min_total)
        if sol is None:
            row.update(status=f"aborted: > {abort:g} s at rtol {rtol:g}", elapsed=times[0])
            stop = f"skipped: > {abort:g} s at rtol {rtol:g}"
            continue
        if times[0] > cap:
            stop = f"skipped: > {cap:g} s at rtol {rtol:g}"
        if sol.status != 1:
            row["status"] = f"no exit: {sol.message}"
        else:
            u = sol.y_events[0][0]
            t = spread(times)
            row.update(success=True, status="ok", seconds=t["median"], min_s=t["min"],
                       max_s=t["max"], n_runs=t["n"], n_rhs=int(sol.nfev),
                       rel_energy=relative_energy(params, u))
            score(row, float(sol.t_events[0][0]), u, ref)
    return rows
