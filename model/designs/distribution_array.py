"""Arrays whose orientations follow a distribution p(theta0) (``model.designs.distributions``).

The paper's averages (Eq. 10) become p-weighted averages: F_T,x/(mu0 F_N) = <F_x/f_N>_p/mu0
and F_T,y likewise; the duration-weighted force sum int F_f,x dtau / (f_N sum tau_out) and
the energy ratios D_y/D_x, U_el/W are ratios of p-weighted sums; N_c/N_c0 = <tau_out>_p/L0;
the load factor beta = L0/<tau_out>_p(beta) is solved self-consistently or fixed.

Mirror symmetry (y -> -y) makes F_x, tau_out and the energies even and F_y odd in theta0,
so the circle folds onto [0, pi]: the continuous part is integrated there with the weights
p(theta) + p(-theta) (even quantities) and p(theta) - p(-theta) (F_y), by the adaptive
Gauss-Kronrod rule of ``model.arrays.quadrature`` with its error estimate; point masses are
integrated exactly as single trajectories (``model.designs.distribution_nodes``). Nodes where the
density vanishes cost no trajectory, and every member is integrated once per (beta, theta0)
and reused: the beta iterations and the quadrature at the solved beta share them.

A time ``budget`` is honoured inside the contacts too: each batch of members gets a step
budget from the seconds left and the step rate measured so far, so a stiff design whose
contacts ring for millions of steps ends on time, with its outcome (``OUTCOMES``) saying
which members were cut short and what to change.
"""
from __future__ import annotations

import dataclasses
import math
import time
from functools import lru_cache

import numpy as np

from ..arrays.beta import solve_beta_secant
from ..arrays.contacts import run_contacts
from .distribution_nodes import (EMPTY, density_grid, fold_atoms, folded, initial_edges,
                                 kronrod, nodes, quantile_nodes, repair)
from .distribution_result import (FILLED, OUTCOMES, QUANTITIES, DistributionArrayResult,
                                  assemble, filled_columns)
from .._kernel.slots import ST_ACC, ST_REJ
from ..arrays.quadrature import integrate
from ..arrays.uniform import TOL
from ..contact.friction import mu0
from ..contact.options import SolverOptions, array_method
from ..contact.params import Params, check_array_params
from ..contact.results import Status
from ..validation import Interval, instance, load_factor, number, whole
from .distributions import Distribution, Uniform, rotated

__all__ = ["DistributionArrayResult", "distribution_array", "OUTCOMES"]

_FX, _FY, _T = 0, 1, 2
#: Under a time budget no member gets fewer steps than this (a smooth contact needs a
#: few hundred), so the cheap members always finish and only the ringing ones are cut.
MIN_STEPS = 2000
#: Steps per second assumed before any has been measured (a conservative kernel rate).
GUESS_STEP_RATE = 5e5


def distribution_array(params: Params, distribution: Distribution | None = None,
                       psi: float = 0.0, beta="self", tol: float = 1e-3,
                       rtol: float | None = None, atol: float | None = None,
                       method: str = "auto", max_intervals: int = 256,
                       max_steps: int = 1_000_000,
                       budget: float | None = None) -> DistributionArrayResult:
    """The array of supports with the springs and load of ``params`` and orientations
    drawn from ``distribution`` (default ``Uniform()``), seen by a slab sliding at ``psi``.

    ``tol`` bounds the quadrature error estimates of F_T,x/(mu0 F_N), F_T,y/(mu0 F_N) and
    N_c/N_c0 (point masses have none). ``beta="self"`` solves beta = L0/<tau_out>_p(beta);
    a number fixes it. ``rtol=None`` integrates each contact at tol/100 (at most 1e-5).
    ``max_steps`` is each contact's step budget (a contact that exhausts it is reported).
    ``budget`` (seconds) bounds the work beyond a minimum (an 8-orientation first beta and
    two evaluations of the first partition): the beta iteration stops at the best beta so
    far, refinement where the time measured says the next round would overrun; the
    result then says so (``success=False``, finite values and estimates).
    """
    instance("params", params, Params)
    distribution = Uniform() if distribution is None else distribution
    instance("distribution", distribution, Distribution)
    tol = number("tol", tol, TOL, "quadrature tolerance tol")
    max_intervals = whole("max_intervals", max_intervals, 1)
    beta = load_factor("beta", beta)
    check_array_params(params, "distribution_array", beta, uses_theta0=False)
    psi = number("psi", psi, Interval(-math.inf, math.inf), "the sliding angle psi [rad]")
    if budget is not None:
        budget = number("budget", budget, Interval(0.0, math.inf, lo_open=True),
                        "the time budget [s]")
    array_method(method)
    if rtol is None:
        rtol = min(1e-5, max(1e-10, tol / 100))
    options = SolverOptions(rtol=rtol, atol=atol, method=method, max_steps=max_steps)
    if not isinstance(beta, str):
        params = params.replace(beta=beta)
    args = (params.replace(theta0=0.0), distribution, psi, beta == "self", float(tol), options,
            int(max_intervals))
    if budget is None:
        return _cached_array(*args, None)
    # A budgeted result depends on the machine's speed: computed afresh, never cached.
    return _array(*args, float(budget))


def _array(params, distribution, psi, self_consistent, tol, options, max_intervals, budget):
    start = time.perf_counter()
    dist = rotated(distribution, psi)
    counter = {"trajectories": 0, "n_rhs": 0}
    members = _Members(params, options, counter, start, budget)
    state = {"beta": params.beta}
    m0 = mu0(params)
    atoms = fold_atoms(dist.atoms())
    mass_c = dist.continuous_mass
    # Nodes whose weight is below this carry no mass worth a trajectory.
    floor = EMPTY * max(float(np.max(folded(dist, density_grid(dist))[0])), 1e-300)

    def over() -> bool:
        return budget is not None and time.perf_counter() - start > budget

    def weighted(theta, beta):
        """Integrand on [0, pi]: folded weights times the per-orientation quantities."""
        even, odd = folded(dist, theta)
        busy = (even > floor) | (np.abs(odd) > floor)
        vals = np.zeros((theta.size, len(QUANTITIES)))
        diag = np.zeros((theta.size, 3))
        if np.any(busy):
            v, d = members(theta[busy], beta)
            vals[busy], diag[busy] = repair(v), d
        w = np.repeat(even[:, None], len(QUANTITIES), axis=1)
        w[:, _FY] = odd
        return np.column_stack([w * vals, diag, filled_columns(w * vals, even, odd, diag)])

    def atom_values(beta, filled=False):
        """The point masses' weighted sums and diagnostics (with ``filled``, also the sums
        of ``filled_columns``)."""
        if not atoms:
            out = np.zeros(len(QUANTITIES)), np.zeros((0, 3))
            return (*out, np.zeros(len(FILLED))) if filled else out
        v, d = members(np.array([t for t, _, _ in atoms]), beta)
        even, odd = np.array([e for _, e, _ in atoms]), np.array([o for _, _, o in atoms])
        w = np.repeat(even[:, None], len(QUANTITIES), axis=1)
        w[:, _FY] = odd
        wv = w * repair(v)
        if filled:
            return np.sum(wv, axis=0), d, np.sum(filled_columns(wv, even, odd, d), axis=0)
        return np.sum(wv, axis=0), d

    closest = {}  # the beta with the smallest |G| so far, for a budget that runs out

    def mean_tau_on(edges):
        def mean_tau(beta):
            if closest and over():
                raise _OutOfTime
            total = atom_values(beta)[0][_T]
            if edges is not None:
                total += kronrod(edges, weighted(nodes(edges), beta))[_T]
            _some_contact(total)
            g = abs(beta - params.L0 / total)
            if g < closest.get("g", math.inf):
                closest.update(g=g, beta=beta)
            return total
        return mean_tau

    def quadrature(edges, allowed):
        return integrate(lambda x: weighted(x, state["beta"]), 0.0, math.pi, targets,
                         control=[_FX, _FY, _T], edges=edges, max_intervals=allowed)

    edges = initial_edges(dist) if mass_c > 1e-15 else None
    targets = np.array([tol * m0, tol * m0, tol * params.L0])
    quad, quad_beta, beta_iter, beta_res = None, None, 0, 0.0
    slope, beta_cut, out_of_time = None, False, False
    if self_consistent:
        # A first beta, and the slope of G(beta) = beta - L0/<tau_out>(beta): from 8
        # equal-mass orientations when there is a continuous part (then Newton steps on
        # the full partition start close), else exactly on the point masses.
        try:
            if edges is not None:
                first = solve_beta_secant(_proxy(dist, members, atom_values, mass_c),
                                          params.L0, xtol=tol / 10)
            else:
                first = solve_beta_secant(mean_tau_on(None), params.L0, xtol=tol / 100)
                beta_iter += first.iterations
            if math.isfinite(first.beta) and 0.0 < first.beta <= 1.0:
                state["beta"] = first.beta
            if math.isfinite(first.slope) and first.slope > 0:
                slope = first.slope
        except _Unsolvable:
            state["beta"], beta_cut = closest.get("beta", state["beta"]), True
    gtol = tol / 10
    for _ in range(6):
        if edges is None or beta_cut:
            break
        allowed = max_intervals
        if budget is not None and counter["trajectories"]:
            # Seconds per interval so far (15 nodes each) -> intervals the rest can afford.
            per_interval = 15 * (time.perf_counter() - start) / counter["trajectories"]
            left = budget - (time.perf_counter() - start)
            affordable = edges.size - 1 + max(0, int(left / per_interval / 2))
            out_of_time = affordable < max_intervals
            allowed = max(edges.size - 1, min(max_intervals, affordable))
        quad, quad_beta = quadrature(edges, allowed), state["beta"]
        if not self_consistent:
            break
        # G(beta) on the refined partition comes free with the quadrature.
        tau = atom_values(state["beta"])[0][_T] + quad.integral[_T]
        if not tau > 0:  # every member failed: nothing to solve beta on
            beta_cut = True
            break
        beta_res = state["beta"] - params.L0 / tau
        if abs(beta_res) <= gtol:
            break
        if over():
            beta_cut = out_of_time = True
            break
        edges = quad.edges
        try:
            # Started at the quadrature's beta, whose members are all computed: G there
            # is free, and the second point gives the secant the full partition's slope.
            sol = solve_beta_secant(mean_tau_on(edges), params.L0, xtol=tol / 100,
                                    slope=slope, gtol=gtol, guess=state["beta"])
            beta_iter += sol.iterations
            state["beta"] = sol.beta
            if math.isfinite(sol.slope) and sol.slope > 0:
                slope = sol.slope
        except _Unsolvable:  # the best beta so far, on the current partition
            state["beta"], beta_cut = closest.get("beta", state["beta"]), True
    if edges is not None and quad_beta != state["beta"]:
        # The values at the final beta on the last partition, without refining further
        # (its nodes are mostly computed already by the beta iteration).
        quad = quadrature(edges, edges.size - 1)
    atom_sum, atom_diag, atom_filled = atom_values(state["beta"], filled=True)
    if self_consistent:
        tau = atom_sum[_T] + (quad.integral[_T] if quad is not None else 0.0)
        beta_res = state["beta"] - params.L0 / tau if tau > 0 else math.nan
    return assemble(params.replace(beta=state["beta"]), distribution, psi, atom_sum, atom_diag,
                    atoms, quad, m0, counter, beta_iter, beta_res, options,
                    time.perf_counter() - start, budget if (out_of_time or beta_cut) else None,
                    beta_cut, atom_filled, self_consistent)


#: Arrays without a time budget, by their arguments (the cache the dashboard's sessions
#: share in a process; ``_cached_array.cache_clear()`` empties it).
_cached_array = lru_cache(maxsize=512)(_array)


class _Unsolvable(Exception):
    """beta cannot be solved further: the time budget ran out, or no member finished."""


class _OutOfTime(_Unsolvable):
    """The time budget ran out while solving for beta."""


def _some_contact(total: float) -> float:
    """<tau_out>_p, which is 0 only when every member failed (then G is undefined)."""
    if not total > 0:
        raise _Unsolvable
    return total


def _proxy(dist, members, atom_values, mass_c):
    """<tau_out>_p(beta) estimated from 8 equal-mass orientations (and the point masses)."""
    theta = quantile_nodes(dist, 8)

    def tau(beta):
        values = repair(members(theta, beta)[0])
        return _some_contact(atom_values(beta)[0][_T] + mass_c * float(np.mean(values[:, _T])))
    return tau


class _Members:
    """Each member's quantities and diagnostics (pivot, |energy residual|/W, failed) at a
    load factor, kept by (beta, theta0) so no contact is integrated twice.

    Under a time budget each batch gets the steps its share of the seconds left can pay
    for at the step rate measured so far (at least ``MIN_STEPS``), the members cut short
    then share what is left; one still cut short is marked failed with code 2 (1: its
    own step budget or an error).
    """

    def __init__(self, params, options, counter, start, budget):
        self.params, self.options, self.counter = params, options, counter
        self.start, self.budget = start, budget
        self.rows: dict = {}
        self.rate = 0.0  # steps per second of the last batch that took measurable time

    def _cap(self, n: int) -> int:
        """Steps per member that ``n`` members can afford in the seconds left."""
        if self.budget is None:
            return self.options.max_steps
        left = max(0.0, self.budget - (time.perf_counter() - self.start))
        rate = self.rate if self.rate > 0 else GUESS_STEP_RATE
        # A ringing member's steps cost more than a smooth one's: a margin for that.
        return int(min(self.options.max_steps, max(MIN_STEPS, 0.8 * left * rate / n)))

    def _run(self, theta, beta, cap):
        options = self.options if cap >= self.options.max_steps else dataclasses.replace(
            self.options, max_steps=cap)
        t0 = time.perf_counter()
        c = run_contacts(self.params, theta, options, beta=np.full(theta.size, beta))[0]
        seconds = time.perf_counter() - t0
        steps = int(c.stats[:, ST_ACC].sum() + c.stats[:, ST_REJ].sum())
        if seconds > 0.02:
            self.rate = steps / seconds
        self.counter["trajectories"] += theta.size
        self.counter["n_rhs"] += c.n_rhs
        cut = (c.status == Status.STEP_BUDGET) & (cap < self.options.max_steps)
        return c, cut

    def _rows(self, c, cut):
        vals = np.column_stack([getattr(c, q) for q in QUANTITIES])
        vals[~c.ok] = np.nan
        with np.errstate(divide="ignore", invalid="ignore"):
            relres = np.abs(c.energy_residual / c.W)
        failed = np.where(cut, 2.0, (~c.ok).astype(float))
        return np.column_stack([vals, c.pivot_approach, relres, failed])

    def __call__(self, theta, beta):
        theta = np.asarray(theta, dtype=float)
        keys = [(beta, t) for t in theta.tolist()]
        missing = [i for i, k in enumerate(keys) if k not in self.rows]
        todo = np.array(missing, dtype=int)
        cap = self._cap(todo.size) if todo.size else 0
        while todo.size:
            # An equal share of the time first; the few members that ring for long then
            # share what the quick ones left (each pass at least doubles their steps).
            c, cut = self._run(theta[todo], beta, cap)
            for i, row in zip(todo, self._rows(c, cut)):
                self.rows[keys[i]] = row
            todo, previous = todo[cut], cap
            cap = self._cap(todo.size) if todo.size else 0
            if cap < 2 * previous:
                break
        out = np.array([self.rows[k] for k in keys])
        n = len(QUANTITIES)
        return out[:, :n], out[:, n:]
