"""The global search behind ``model.designs.design.optimise``: a scan of the family on a theta0
grid (the fixed-orientation arrays in one batched call), then the best few candidates
refined with scipy.optimize on the full model (``distribution_array``)."""
from __future__ import annotations

import math
import time

import numpy as np
from scipy.optimize import minimize, minimize_scalar

from ..arrays.fixed import orientation_sweep
from .design_result import DesignResult, OptimisationCancelled
from .distribution_array import distribution_array
from .distributions import Fixed, Mixture, Pair, Uniform, VonMises

#: Concentrations searched for von Mises, as log10(kappa).
LOG_KAPPA = (-2.0, 4.0)
#: Penalty per unit of bound violation in the refinement (an exact penalty: larger
#: than the trade-off F_T,x/F_T,y along the bound anywhere on the paper's map).
PENALTY = 100.0


class Search:
    def __init__(self, params, family, objective, bound, beta, tol, n_scan, candidates,
                 max_evaluations, progress, cancel):
        self.params, self.family, self.objective, self.bound = params, family, objective, bound
        self.beta, self.tol, self.n_scan, self.n_candidates = beta, tol, n_scan, candidates
        self.max_evaluations, self.progress, self.cancel = max_evaluations, progress, cancel
        self.evaluations = 0
        self.memo = {}

    # ------------------------------------------------------------------ model evaluations
    def array(self, dist):
        if dist in self.memo:
            return self.memo[dist]
        if self.cancel is not None and self.cancel.is_set():
            raise OptimisationCancelled(self.evaluations)
        a = distribution_array(self.params, dist, beta=self.beta, tol=self.tol)
        self.evaluations += 1
        self.memo[dist] = a
        if self.progress is not None:
            self.progress(self.evaluations, self.max_evaluations)
        return a

    def value(self, fx, fy):
        """(objective to minimise, bound violation) from the two forces."""
        if self.objective == "min-FTx":
            v, c = fx, np.abs(fy)
        else:
            v, c = -np.abs(fy), fx
        excess = 0.0 if self.bound is None else np.maximum(0.0, c - self.bound)
        return v, excess

    def penalised(self, dist):
        if dist not in self.memo and self.evaluations >= self.max_evaluations:
            raise _Budget
        a = self.array(dist)
        v, excess = self.value(a.FTx_over_mu0FN, a.FTy_over_mu0FN)
        return float(v + PENALTY * excess)

    # ------------------------------------------------------------------ scan
    def scan(self):
        n = self.n_scan
        # Cell midpoints, off the exact axis, plus points next to it: there F_T,y -> 0,
        # so a bound on |F_T,y| is often met only in a sliver near 0 or pi.
        theta = np.concatenate([[_EDGE], (np.arange(n) + 0.5) * math.pi / n, [math.pi - _EDGE]])
        s = orientation_sweep(self.params, theta, beta=self.beta, rtol=min(1e-6, self.tol / 100))
        fx, fy = np.asarray(s.FTx_over_mu0FN), np.asarray(s.FTy_over_mu0FN)
        ok = np.asarray(s.success)
        # Mirror symmetry: F_x even, F_y odd in theta0; the grid on the whole circle.
        full = np.concatenate([-theta[::-1], theta])
        FX = np.concatenate([fx[::-1], fx])
        FY = np.concatenate([-fy[::-1], fy])
        OK = np.concatenate([ok[::-1], ok])
        self.grid = dict(theta=full, FTx=FX, FTy=FY, ok=OK)
        return getattr(self, f"scan_{self.family}")(full, FX, FY, OK)

    def ranked(self, points, fx, fy, ok):
        v, excess = self.value(fx, fy)
        score = np.where(ok, v + PENALTY * excess, np.inf)
        order = np.argsort(score, kind="stable")
        return [points[i] for i in order if np.isfinite(score[i])], score[order[0]]

    def scan_fixed(self, theta, fx, fy, ok):
        return self.ranked(list(theta), fx, fy, ok)

    def scan_pair(self, theta, fx, fy, ok):
        half = theta > 0
        return self.ranked(list(theta[half]), fx[half], np.zeros(half.sum()), ok[half])

    def scan_vonmises(self, theta, fx, fy, ok):
        means = theta[::2]
        spacing = math.pi / self.n_scan
        # Narrower than ~2 grid cells the grid sum no longer stands for the density.
        top = min(LOG_KAPPA[1], math.log10(1.0 / (2 * spacing) ** 2))
        kappas = np.logspace(LOG_KAPPA[0], top, 9)
        pts, FX, FY = [], [], []
        # Each grid point stands for the arc between its neighbours' midpoints.
        ends = np.concatenate([[-math.pi], 0.5 * (theta[1:] + theta[:-1]), [math.pi]])
        w_ok = ok * np.diff(ends)
        for k in kappas:
            dens = np.exp(k * (np.cos(theta[None, :] - means[:, None]) - 1.0)) * w_ok
            dens /= dens.sum(axis=1, keepdims=True)
            FX.append(dens @ np.where(ok, fx, 0.0))
            FY.append(dens @ np.where(ok, fy, 0.0))
            pts += [(m, math.log10(k)) for m in means]
        # The most concentrated end stands for the fixed array at its mean, which the
        # grid gives exactly (the surrogate above cannot resolve it).
        pts += [(m, LOG_KAPPA[1]) for m in theta]
        FX.append(np.where(ok, fx, np.nan))
        FY.append(np.where(ok, fy, np.nan))
        FX, FY = np.concatenate(FX), np.concatenate(FY)
        return self.ranked(pts, FX, FY, np.isfinite(FX))

    def scan_mixture(self, theta, fx, fy, ok):
        # Every other orientation of the half circle and its mirror image, so that the
        # grid holds exact pairs +-theta0 (F_T,y = 0 at w = 1/2).
        half = np.flatnonzero((theta > 0) & ok)[::2]
        idx = np.concatenate([theta.size - 1 - half[::-1], half])
        th, FX, FY = theta[idx], fx[idx], fy[idx]
        i, j = np.triu_indices(th.size, k=1)
        # Linear in w on each pair: the best w is at an end of its feasible interval.
        ws = np.linspace(0.0, 1.0, 21)
        W = ws[None, :]
        mx = W * FX[i, None] + (1 - W) * FX[j, None]
        my = W * FY[i, None] + (1 - W) * FY[j, None]
        v, excess = self.value(mx, my)
        score = v + PENALTY * excess
        best = np.argmin(score, axis=1)
        pts = [(th[a], th[b], ws[k]) for a, b, k in zip(i, j, best)]
        sc = score[np.arange(i.size), best]
        order = np.argsort(sc, kind="stable")
        return [pts[q] for q in order], sc[order[0]]

    # ------------------------------------------------------------------ refinement
    def dist(self, x):
        if self.family == "fixed":
            return Fixed(float(x[0]))
        if self.family == "pair":
            return Pair(float(x[0]))
        if self.family == "vonmises":
            return VonMises(float(x[0]), 10.0 ** float(np.clip(x[1], *LOG_KAPPA)))
        w = float(np.clip(x[2], 0.0, 1.0))
        return Mixture((Fixed(float(x[0])), Fixed(float(x[1]))), (w, 1.0 - w))

    def refine(self, start):
        x0 = np.atleast_1d(np.asarray(start, dtype=float))
        f = lambda x: self.penalised(self.dist(np.atleast_1d(x)))  # noqa: E731
        if self.family in ("fixed", "pair"):
            step = math.pi / self.n_scan  # one scan cell on either side
            lo, hi = x0[0] - step, x0[0] + step
            if self.family == "pair":
                lo, hi = max(lo, 1e-6), min(hi, math.pi - 1e-6)
            r = minimize_scalar(lambda t: f([t]), bounds=(lo, hi), method="bounded",
                                options={"xatol": 1e-4})
            return np.array([r.x])
        simplex_scale = {"vonmises": [0.1, -0.5], "mixture": [0.05, 0.05, 0.1]}[self.family]
        simplex = np.vstack([x0] + [x0 + np.eye(x0.size)[k] * simplex_scale[k]
                                    for k in range(x0.size)])
        r = minimize(f, x0, method="Nelder-Mead",
                     options={"initial_simplex": simplex, "xatol": 1e-4, "fatol": self.tol / 10,
                              "maxfev": max(10, self.max_evaluations // self.n_candidates)})
        return r.x

    def boundary(self):
        """Where the bound is active: the crossings of the scan's grid, solved on the model
        (a constrained optimum of a 1-D family often lies on the bound). Between grid
        points where F_T,y changes sign, |F_T,y| <= bound holds in a window around the
        root even when both grid points miss it."""
        if self.bound is None or self.family != "fixed":
            return
        from scipy.optimize import brentq

        g = self.grid
        v, excess = self.value(g["FTx"], g["FTy"])
        feasible = (excess == 0) & g["ok"]
        cross = feasible[1:] != feasible[:-1]
        if self.objective == "min-FTx":
            cross |= np.sign(g["FTy"][1:]) * np.sign(g["FTy"][:-1]) < 0
        cross &= g["ok"][1:] & g["ok"][:-1]
        idx = np.flatnonzero(cross)
        # Most promising first: the better objective at either end.
        order = np.argsort(np.minimum(v[idx], v[idx + 1]))
        for i in idx[order][: 2 * self.n_candidates]:
            self.solve_bound(brentq, g["theta"][i], g["theta"][i + 1])

    def forces(self, t):
        self.penalised(Fixed(float(t)))
        a = self.memo[Fixed(float(t))]
        return a.FTx_over_mu0FN, a.FTy_over_mu0FN

    def solve_bound(self, brentq, a, b):
        def c(t):
            fx, fy = self.forces(t)
            return (abs(fy) if self.objective == "min-FTx" else fx) - self.bound

        def root(f, lo, hi):
            try:
                return brentq(f, lo, hi, xtol=1e-7)
            except ValueError:  # no sign change on the model: the grid's was noise
                return None

        if self.objective == "min-FTx" and np.sign(self.forces(a)[1]) != np.sign(self.forces(b)[1]):
            zero = root(lambda t: self.forces(t)[1], a, b)
            if zero is not None:  # the window |F_T,y| <= bound on both sides of the root
                for lo, hi in ((a, zero), (zero, b)):
                    root(c, lo, hi)
                return
        root(c, a, b)

    def run(self) -> DesignResult:
        start = time.perf_counter()
        points, scan_best = self.scan()
        chosen = _distinct(points, self.n_candidates, self.family)
        out_of_budget = False
        try:
            for p in chosen:
                self.refine(p)
            self.boundary()
        except _Budget:
            out_of_budget = True
        # Every distribution evaluated so far competes, refined or not.
        evaluated = [(d, a) for d, a in self.memo.items()]
        if not evaluated:  # budget smaller than one refinement: evaluate the scan's best
            d = self.dist(np.atleast_1d(np.asarray(chosen[0], dtype=float)))
            evaluated = [(d, self.array(d))]

        def key(item):
            v, excess = self.value(item[1].FTx_over_mu0FN, item[1].FTy_over_mu0FN)
            return (excess > 0, v + PENALTY * excess)

        best_dist, coarse = min(evaluated, key=key)
        # The optimum again at a ten times tighter tolerance: its difference from the
        # search's value is the error estimate (the search favours values that err low).
        best = distribution_array(self.params, best_dist, beta=self.beta, tol=self.tol / 10)
        uniform = distribution_array(self.params, Uniform(), beta=self.beta, tol=self.tol)
        _, excess = self.value(best.FTx_over_mu0FN, best.FTy_over_mu0FN)
        q = best.quadrature_error
        if self.objective == "min-FTx":
            err_key, value, old = "FTx_over_mu0FN", best.FTx_over_mu0FN, coarse.FTx_over_mu0FN
        else:
            err_key, value, old = "FTy_over_mu0FN", best.FTy_over_mu0FN, coarse.FTy_over_mu0FN
        error = q[err_key] + abs(value - old) + abs(value) * best.integration_error
        other = "FTy_over_mu0FN" if self.objective == "min-FTx" else "FTx_over_mu0FN"
        bound_err = q[other] + abs(getattr(best, other) - getattr(coarse, other))
        feasible = bool(excess <= bound_err + 1e-12)
        message = "ok" if feasible else "no distribution of the family met the bound"
        if out_of_budget:
            message += f"; refinement stopped at max_evaluations = {self.max_evaluations}"
        if not best.success:
            message += f"; the optimum's array: {best.message}"
        return DesignResult(
            params=self.params, family=self.family, objective=self.objective, bound=self.bound,
            distribution=best_dist, array=best, FTx_over_mu0FN=best.FTx_over_mu0FN,
            FTy_over_mu0FN=best.FTy_over_mu0FN, error_estimate=float(error),
            uniform_FTx_over_mu0FN=uniform.FTx_over_mu0FN,
            gain=1.0 - best.FTx_over_mu0FN / uniform.FTx_over_mu0FN, feasible=feasible,
            scan_best=float(scan_best), evaluations=self.evaluations,
            success=bool(feasible and best.success and uniform.success), message=message,
            seconds=time.perf_counter() - start,
            scan={k: np.asarray(v) for k, v in self.grid.items()})


#: Distance from the axis of the scan's first and last orientations (radians).
_EDGE = 1e-3


class _Budget(Exception):
    """max_evaluations reached inside a refinement."""


def _distinct(points, n, family):
    """The first ``n`` scan points at least a few grid cells apart (distinct minima)."""
    chosen = []
    for p in points:
        x = np.atleast_1d(np.asarray(p, dtype=float))
        if all(np.max(np.abs(_angle_diff(x, np.atleast_1d(np.asarray(c, dtype=float)),
                                         family))) > 0.15 for c in chosen):
            chosen.append(p)
        if len(chosen) == n:
            break
    return chosen or points[:1]


def _angle_diff(a, b, family):
    d = a - b
    if family == "mixture":
        d[:2] = np.angle(np.exp(1j * d[:2]))
    else:
        d[0] = np.angle(np.exp(1j * d[0]))
    return d
