"""The self-consistent load factor beta = N_c0 / N_c (MODEL.md, "Contact count").

Supports dragged beyond L0 stay in contact longer, so more of them share the load:
N_c/N_c0 = <tau_out>/L0 and each carries f_N = beta F_N with beta = L0/<tau_out>(beta).
The map beta -> L0/<tau_out>(beta) can be steep (slope ~ -60), so plain fixed-point
iteration falls into a 2-cycle; here the root of G(beta) = beta - L0/<tau_out>(beta)
is bracketed in [BETA_MIN, 1] and found by the Illinois (modified regula falsi)
method, vectorised so that many independent problems share each kernel call.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["BetaSolution", "solve_beta", "ScalarBeta", "solve_beta_scalar", "BETA_MIN"]

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
