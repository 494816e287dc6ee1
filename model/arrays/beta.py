"""The self-consistent load factor beta = N_c0 / N_c (docs/model.md, "Contact count and the load factor β").

Supports dragged beyond L0 stay in contact longer, so more of them share the load:
N_c/N_c0 = <tau_out>/L0 and each carries f_N = beta F_N with beta = L0/<tau_out>(beta).
The map beta -> L0/<tau_out>(beta) can be steep (slope ~ -60), so plain fixed-point
iteration falls into a 2-cycle; here the root of G(beta) = beta - L0/<tau_out>(beta)
is bracketed in [BETA_MIN, 1] and found by the Illinois (modified regula falsi)
method, vectorised so that many independent problems share each kernel call
(``solve_beta``: fixed arrays). A uniform array is one problem whose every evaluation
integrates the whole array: ``solve_beta_secant`` starts from a guess (a neighbour's
beta and slope in a sweep) and needs two or three evaluations where a bracket from
scratch needs eight to ten.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["BetaSolution", "solve_beta", "ScalarBeta", "solve_beta_scalar", "solve_beta_secant",
           "BETA_MIN"]

BETA_MIN = 1e-3


@dataclass(frozen=True)
class BetaSolution:
    """beta per problem with its residual G(beta) = beta - L0/<tau_out>(beta)."""

    beta: np.ndarray
    residual: np.ndarray
    iterations: int
    evaluations: int
    converged: np.ndarray  # bracket shrunk to xtol with a sign change inside
    capped: np.ndarray  # no root below 1: contacts shorter than L0 at beta = 1
    jump: np.ndarray  # G changes sign across a discontinuity: no exact root


def solve_beta(mean_tau, L0: float, size: int, xtol: float = 1e-8, max_iter: int = 100):
    """Solve beta = L0 / mean_tau(beta) for ``size`` independent problems at once.

    ``mean_tau(beta, rows) -> tau`` evaluates the problems numbered ``rows`` (an int
    array) at the loads ``beta`` (same length).
    """
    every = np.arange(size)
    hi = np.ones(size)
    tau_hi = mean_tau(hi, every)
    g_hi = hi - L0 / tau_hi
    # Where tau_out grows with the load, beta* = L0/tau(beta*) >= L0/tau(1): a much
    # tighter lower end. Checked by its sign; BETA_MIN where the check fails.
    lo = np.clip(L0 / tau_hi, BETA_MIN, 1.0)
    g_lo = lo - L0 / mean_tau(lo, every)
    retry = ~(g_lo < 0)
    if np.any(retry):
        rows = np.flatnonzero(retry)
        lo[rows] = BETA_MIN
        g_lo[rows] = BETA_MIN - L0 / mean_tau(lo[rows], rows)
    evaluations = 3
    capped = g_hi < 0  # the self-consistent beta would exceed 1: take beta = 1
    active = ~capped & (g_lo < 0)
    x, g_x = hi.copy(), g_hi.copy()
    side = np.zeros(size, int)
    iterations = 0
    while np.any(active) and iterations < max_iter:
        iterations += 1
        with np.errstate(divide="ignore", invalid="ignore"):
            trial = (lo * g_hi - hi * g_lo) / (g_hi - g_lo)
        bad = ~np.isfinite(trial) | (trial <= lo) | (trial >= hi)
        trial = np.where(bad, 0.5 * (lo + hi), trial)
        g_t = np.full(size, np.nan)
        rows = np.flatnonzero(active)
        g_t[rows] = trial[rows] - L0 / mean_tau(trial[rows], rows)
        evaluations += 1
        upper = active & (g_t >= 0)
        lower = active & (g_t < 0)
        # Illinois: halve the function value at an end that was kept twice in a row.
        g_lo = np.where(upper & (side == 1), 0.5 * g_lo, g_lo)
        g_hi = np.where(lower & (side == -1), 0.5 * g_hi, g_hi)
        hi, g_hi = np.where(upper, trial, hi), np.where(upper, g_t, g_hi)
        lo, g_lo = np.where(lower, trial, lo), np.where(lower, g_t, g_lo)
        side = np.where(upper, 1, np.where(lower, -1, side))
        x = np.where(active, trial, x)
        g_x = np.where(active, g_t, g_x)
        active &= (hi - lo > xtol * hi) & (g_t != 0)
    converged = capped | ((hi - lo <= xtol * hi) | (g_x == 0))
    x = np.where(capped, 1.0, x)
    g_x = np.where(capped, g_hi, g_x)
    # A sign change over a bracket of width xtol with |G| not small: G jumps there.
    jump = ~capped & (np.abs(g_x) > 1e3 * xtol)
    return BetaSolution(beta=x, residual=g_x, iterations=iterations, evaluations=evaluations,
                        converged=converged, capped=capped, jump=jump)


@dataclass(frozen=True)
class ScalarBeta:
    """One self-consistent beta from ``solve_beta_scalar`` (scipy's brentq)."""

    beta: float
    residual: float
    iterations: int
    evaluations: int
    converged: bool
    capped: bool
    slope: float = math.nan  # dG/dbeta near the root (secant estimate), for the next solve


def solve_beta_scalar(mean_tau, L0: float, xtol: float = 1e-8, guess: float | None = None,
                      width: float = 0.05) -> ScalarBeta:
    """Solve beta = L0 / mean_tau(beta) for one problem with Brent's bracketed method.

    With a ``guess`` the bracket [guess (1 - width), guess (1 + width)] is tried first
    (cheap when refining a known solution), else the full [BETA_MIN, 1].
    """
    from scipy.optimize import brentq

    calls = [0]

    def G(b):
        calls[0] += 1
        return b - L0 / mean_tau(b)

    lo, hi = BETA_MIN, 1.0
    if guess is not None:
        a, b = max(BETA_MIN, guess * (1 - width)), min(1.0, guess * (1 + width))
        ga, gb = G(a), G(b)
        if ga < 0 <= gb:
            lo, hi = a, b
    g_hi = G(hi) if hi == 1.0 else 1.0
    if hi == 1.0 and g_hi < 0:  # contacts shorter than L0 even at beta = 1
        return ScalarBeta(1.0, g_hi, 0, calls[0], True, True)
    root, info = brentq(G, lo, hi, xtol=xtol * hi, full_output=True, disp=False)
    return ScalarBeta(root, G(root), info.iterations, calls[0], bool(info.converged), False)


def solve_beta_secant(mean_tau, L0: float, xtol: float = 1e-8, guess: float | None = None,
                      slope: float | None = None, max_evals: int = 30,
                      gtol: float = 0.0, known=None) -> ScalarBeta:
    """Solve beta = L0 / mean_tau(beta) by a safeguarded secant method from a guess.

    G(beta) = beta - L0/mean_tau(beta) is smooth where the contacts are (its slope is
    ~1 to ~60): from a nearby ``guess`` and the ``slope`` of a neighbouring problem
    (continuation) the first step is Newton's, and two or three secant steps reach
    ``xtol``. Without a guess it starts at beta = 1 and the fixed-point value
    L0/tau(1). Once the root is bracketed, a secant step leaving the bracket is
    replaced by the Illinois step on it, so the method cannot wander; should it
    still not converge within ``max_evals``, ``solve_beta_scalar`` (Brent on
    [BETA_MIN, 1]) finishes. The returned beta is always the last evaluated point,
    so the caller's evaluation there can be reused. ``gtol > 0`` also accepts a point
    with |G| <= gtol (the residual a caller guarantees anyway). ``known`` = (beta, G) is a
    point where G is already known (the caller's last evaluation): the second step is
    then the secant through it rather than a second step with ``slope``.
    """
    calls = [0]

    def G(b):
        calls[0] += 1
        return b - L0 / mean_tau(b)

    def clip(b):
        return min(1.0, max(BETA_MIN, b))

    if guess is None:
        b0, g0 = 1.0, G(1.0)
        if g0 < 0:  # contacts shorter than L0 even at beta = 1
            return ScalarBeta(1.0, g0, 0, calls[0], True, True)
        b1 = clip(1.0 - g0)  # L0/tau(1), the fixed-point iterate
    else:
        b0 = clip(guess)
        g0 = G(b0)
        if b0 == 1.0 and g0 < 0:
            return ScalarBeta(1.0, g0, 0, calls[0], True, True)
        if abs(g0) <= gtol or g0 == 0:
            return ScalarBeta(b0, g0, 0, calls[0], True, False, slope or math.nan)
        s = slope if slope is not None and math.isfinite(slope) and slope > 0 else 1.0
        if known is not None and known[0] != b0:
            through = (g0 - known[1]) / (b0 - known[0])
            s = through if math.isfinite(through) and through > 0 else s
        b1 = clip(b0 - g0 / s)
    lo = hi = None  # bracket: G(lo) < 0 <= G(hi)
    side = 0
    g_lo = g_hi = 0.0

    def enclose(b, g):
        nonlocal lo, hi, g_lo, g_hi
        if g < 0 and (lo is None or b > lo):
            lo, g_lo = b, g
        elif g >= 0 and (hi is None or b < hi):
            hi, g_hi = b, g

    enclose(b0, g0)
    if known is not None:
        enclose(*known)
    it = 0
    while calls[0] < max_evals:
        if b1 == b0:
            b1 = clip(b0 * (1 - 1e-3) if g0 > 0 else b0 * (1 + 1e-3))
            if b1 == b0:  # pinned at an end of [BETA_MIN, 1]
                break
        g1 = G(b1)
        it += 1
        enclose(b1, g1)
        if b1 == 1.0 and g1 < 0:
            return ScalarBeta(1.0, g1, it, calls[0], True, True)
        sl = (g1 - g0) / (b1 - b0)
        # Converged when the next secant correction is below xtol: b1 is then within
        # about xtol of the root (the secant converges superlinearly), and evaluated.
        if (g1 == 0 or abs(g1) <= gtol or (sl > 0 and abs(g1 / sl) <= xtol * b1)
                or abs(b1 - b0) <= 0.1 * xtol * b1):
            return ScalarBeta(b1, g1, it, calls[0], True, False, sl)
        if lo is not None and hi is not None and hi - lo <= xtol * hi:
            # A bracket of width xtol: converged, or G jumps there (|G| large).
            return ScalarBeta(b1, g1, it, calls[0], True, False, sl)
        b2 = b1 - g1 / sl if sl != 0 and math.isfinite(sl) else math.nan
        if lo is not None and hi is not None:
            if not (lo < b2 < hi):
                # Illinois on the bracket: halve the value at an end kept twice.
                if g1 < 0:
                    g_hi = 0.5 * g_hi if side == -1 else g_hi
                    side = -1
                else:
                    g_lo = 0.5 * g_lo if side == 1 else g_lo
                    side = 1
                b2 = (lo * g_hi - hi * g_lo) / (g_hi - g_lo)
                if not (lo < b2 < hi):
                    b2 = 0.5 * (lo + hi)
        elif not math.isfinite(b2) or sl <= 0:
            b2 = clip(b1 * 2.0 if g1 < 0 else b1 * 0.5)  # look for a sign change
        else:
            # No bracket yet: trust the secant at most a factor 4 away.
            b2 = clip(min(4 * b1, max(0.25 * b1, b2)))
        b0, g0, b1 = b1, g1, b2
    cold = solve_beta_scalar(mean_tau, L0, xtol=xtol)
    return ScalarBeta(cold.beta, cold.residual, it + cold.iterations,
                      calls[0] + cold.evaluations, cold.converged, cold.capped)
