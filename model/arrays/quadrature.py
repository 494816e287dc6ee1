"""Adaptive Gauss-Kronrod (7, 15) quadrature of vector integrands, evaluated in batches.

Generic (no physics): ``integrate`` splits [a, b] into intervals, evaluates all 15
Kronrod nodes of every new interval in one call of the integrand, and bisects the
intervals whose error estimate |K15 - G7| is above their share of the tolerance,
until the total estimate meets it or the interval budget runs out. The estimate
|K15 - G7| is deliberately the plain, pessimistic one: the orientation integrand of
the uniform array can jump, and an optimistic estimate would hide that.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["XGK", "WGK", "WG", "QuadratureResult", "integrate"]

# Kronrod nodes on [-1, 1] (non-negative half) and weights; Gauss weights at the odd nodes.
XGK = np.array([0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                0.207784955007898467600689403773245, 0.0])
WGK = np.array([0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                0.204432940075298892414161999234649, 0.209482141084727828012999174891714])
WG = np.array([0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
               0.381830050505118944950369775488975, 0.417959183673469387755102040816327])
# The 15 nodes in increasing order and their Kronrod and Gauss weights.
NODES = np.concatenate([-XGK[:-1], XGK[::-1]])
W_K = np.concatenate([WGK[:-1], WGK[::-1]])
W_G = np.zeros(15)
W_G[[1, 3, 5, 7, 9, 11, 13]] = np.concatenate([WG[:-1], WG[::-1]])


@dataclass(frozen=True)
class QuadratureResult:
    """Integrals and error estimates (one per component) with the partition used."""

    integral: np.ndarray
    error: np.ndarray
    edges: np.ndarray  # interval end points, increasing
    nodes: np.ndarray  # every evaluated node
    values: np.ndarray  # integrand at ``nodes``, shape (len(nodes), q)
    converged: bool
    rounds: int


def _rule(a, b, values):
    """Kronrod and Gauss estimates on [a, b] from the 15 node values (15, q)."""
    half = 0.5 * (b - a)
    return half * W_K @ values, half * W_G @ values


def integrate(f, a: float, b: float, tol, control=None, edges=None, max_intervals: int = 512,
              max_rounds: int = 30) -> QuadratureResult:
    """Integrate the vector function ``f(x: (n,)) -> (n, q)`` over [a, b].

    ``tol`` bounds the error estimate of the components listed in ``control`` (all by
    default); it may be a scalar or one value per controlled component. ``edges`` is
    an initial partition (default: 4 equal intervals).
    """
    edges = np.linspace(a, b, 5) if edges is None else np.asarray(edges, dtype=float)
    intervals = list(zip(edges[:-1], edges[1:]))
    cache: dict = {}
    rounds = 0
    while True:
        rounds += 1
        new = [iv for iv in intervals if iv not in cache]
        if new:
            x = np.concatenate([0.5 * (lo + hi) + 0.5 * (hi - lo) * NODES for lo, hi in new])
            vals = np.asarray(f(x), dtype=float).reshape(x.size, -1)
            for k, iv in enumerate(new):
                v = vals[15 * k:15 * (k + 1)]
                kron, gauss = _rule(*iv, v)
                cache[iv] = (kron, np.abs(kron - gauss), v)
        kron = np.array([cache[iv][0] for iv in intervals])
        err = np.array([cache[iv][1] for iv in intervals])
        ctrl = slice(None) if control is None else list(control)
        total = err.sum(axis=0)
        limit = np.broadcast_to(np.asarray(tol, dtype=float), total[ctrl].shape)
        converged = bool(np.all(total[ctrl] <= limit))
        if converged or rounds >= max_rounds or len(intervals) >= max_intervals:
            break
        # Bisect intervals whose error density exceeds the tolerance density.
        width = np.array([hi - lo for lo, hi in intervals])
        share = np.max(err[:, ctrl] / (limit * width[:, None] / (b - a)), axis=1)
        split = share > 1.0
        if not np.any(split):
            split = share >= share.max()
        # Within max_intervals, bisect the roughest intervals first; never drop one
        # (the partition must keep covering [a, b]).
        budget = max_intervals - len(intervals)
        if np.count_nonzero(split) > budget:
            split = np.zeros_like(split)
            split[np.argsort(-share, kind="stable")[:budget]] = True
        refined = []
        for (lo, hi), s in zip(intervals, split):
            refined += [(lo, 0.5 * (lo + hi)), (0.5 * (lo + hi), hi)] if s else [(lo, hi)]
        intervals = refined
    nodes = np.concatenate([0.5 * (lo + hi) + 0.5 * (hi - lo) * NODES for lo, hi in intervals])
    values = np.concatenate([cache[iv][2] for iv in intervals])
    return QuadratureResult(integral=kron.sum(axis=0), error=err.sum(axis=0),
                            edges=np.array([intervals[0][0]] + [hi for _, hi in intervals]),
                            nodes=nodes, values=values, converged=converged, rounds=rounds)
