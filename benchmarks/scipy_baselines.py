"""scipy solve_ivp baselines for the support benchmark, with a wall-time budget."""
from __future__ import annotations

import math
import statistics
import time

import numpy as np
from scipy.integrate import solve_ivp

from model import Params, SolverOptions
from model.energy import elastic_energy, kinetic_energy
from model.reference import reference_rhs

TAU_MAX = SolverOptions().tau_max


def score(row: dict, t_out: float, state, ref: dict) -> dict:
    """Add the errors against the reference to a successful run's row."""
    row["error"] = float(np.max(np.abs(np.asarray(state[:5]) - ref["state_out"])))
    row["t_error"] = abs(t_out - ref["t_out"])
    return row


class OverBudget(Exception):
    """A scipy run went past its time limit."""


def solve_scipy(params: Params, method: str, rtol: float, limit: float):
    """solve_ivp on the reference right-hand side with the exit event of Eq. (9)."""
    fun = reference_rhs(params)
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


def timed_scipy(params, method, rtol, left, repeats):
    """(solution, times of the completed runs, seconds spent); runs over 0.25 s are not repeated.

    The solution is None when the first run went over the `left` seconds.
    """
    sol, done, spent = None, [], 0.0
    while len(done) < repeats and (not done or done[-1] < 0.25):
        start = time.perf_counter()
        try:
            sol = solve_scipy(params, method, rtol, left - spent)
        except OverBudget:
            spent += time.perf_counter() - start
            break
        done.append(time.perf_counter() - start)
        spent += done[-1]
    return sol, done, spent


def sweep_scipy(params, method, rtols, ref, budget, repeats) -> list:
    """The rtol sweep of one scipy method, within `budget` seconds of wall time.

    A run is aborted when it would exceed what is left of the budget, and a tolerance
    is skipped once the previous run took longer than what is left (a tighter
    tolerance takes no less time).
    """
    rows, spent, last = [], 0.0, 0.0
    for rtol in rtols:
        row = {"method": method, "rtol": rtol, "success": False}
        rows.append(row)
        if last > budget - spent:
            row["status"] = "skipped: over time budget"
            continue
        sol, times, used = timed_scipy(params, method, rtol, budget - spent, repeats)
        spent += used
        last = times[-1] if times else math.inf
        if not times:
            row.update(status=f"aborted: over time budget ({budget:g} s per sweep)", elapsed=used)
        elif sol.status != 1:
            row["status"] = f"no exit: {sol.message}"
        else:
            u = sol.y_events[0][0]
            row.update(success=True, status="ok", seconds=statistics.median(times),
                       n_rhs=int(sol.nfev), rel_energy=relative_energy(params, u))
            score(row, float(sol.t_events[0][0]), u, ref)
    return rows
