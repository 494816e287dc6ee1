"""scipy solve_ivp baselines for the support benchmark, under a wall-time cap."""
from __future__ import annotations

import math
import time

import numpy as np
from scipy.integrate import solve_ivp

from model import Params, SolverOptions
from model.energy import elastic_energy, kinetic_energy
from model.reference import reference_rhs

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
