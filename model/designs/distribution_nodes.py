"""Where an orientation average puts its nodes (``model.designs.distribution_array``).

Mirror symmetry (y -> -y) makes F_x, tau_out and the energies even and F_y odd in
theta0, so a distribution on the circle folds onto [0, pi] with the weights
p(theta) + p(-theta) (even quantities) and p(theta) - p(-theta) (F_y); point masses
fold likewise. The first partition puts equal shares of the folded mass in each
interval (and ends intervals where a histogram jumps), so a concentrated distribution
has its Kronrod nodes where its mass is.
"""
from __future__ import annotations

import math

import numpy as np

from ..arrays.quadrature import NODES, W_K
from .distributions import wrap

__all__ = ["EMPTY", "fold_atoms", "folded", "density_grid", "initial_edges", "quantile_nodes",
           "nodes", "kronrod", "repair"]

#: Density below this fraction of its largest value is treated as empty (no trajectory).
EMPTY = 1e-14


def fold_atoms(atoms):
    """Point masses moved onto [0, pi] as (theta, even weight, odd weight): F_y changes
    sign under the mirror, so +-theta share one trajectory (a pair's F_y cancels exactly)."""
    merged = {}
    for theta, w in atoms:
        if w <= 0:
            continue
        t = float(wrap(theta))
        key = round(abs(t), 12)
        even, odd = merged.get(key, (0.0, 0.0))
        merged[key] = (even + w, odd + (-w if t < 0 else w))
    return [(t, e, o) for t, (e, o) in sorted(merged.items())]


def folded(dist, theta):
    """Weights p(theta) + p(-theta) and p(theta) - p(-theta) on [0, pi]."""
    plus, minus = dist.density(theta), dist.density(-theta)
    return plus + minus, plus - minus


def density_grid(dist) -> np.ndarray:
    """Angles on [0, pi] that resolve the folded density (uniform plus its mass points)."""
    pts = np.abs(wrap(np.concatenate([dist.points(), dist.breaks()])))
    return np.unique(np.concatenate([np.linspace(0.0, math.pi, 2049), pts]))


def initial_edges(dist, n_mass: int = 4) -> np.ndarray:
    """Partition of [0, pi]: equal shares of the folded mass per interval, plus the jumps."""
    grid = density_grid(dist)
    even, _ = folded(dist, grid)
    cdf = np.concatenate([[0.0], np.cumsum(0.5 * (even[1:] + even[:-1]) * np.diff(grid))])
    edges = [0.0, math.pi] + list(np.abs(wrap(np.concatenate([dist.breaks(),
                                                               dist.partition_hint()]))))
    if cdf[-1] > 0:
        cdf /= cdf[-1]
        for q in np.interp(np.arange(1, n_mass) / n_mass, cdf, grid):
            # A quantile next to a given end would only add a sliver of an interval.
            if np.min(np.abs(np.asarray(edges) - q)) > 1e-5:
                edges.append(q)
    edges = np.unique(np.clip(edges, 0.0, math.pi))
    keep = np.concatenate([[True], np.diff(edges) > 1e-9])
    edges = edges[keep]
    edges[-1] = math.pi
    return edges


def quantile_nodes(dist, n: int) -> np.ndarray:
    """``n`` orientations on [0, pi] at the mid-quantiles of the folded continuous mass."""
    grid = density_grid(dist)
    even, _ = folded(dist, grid)
    cdf = np.concatenate([[0.0], np.cumsum(0.5 * (even[1:] + even[:-1]) * np.diff(grid))])
    return np.interp((np.arange(n) + 0.5) / n, cdf / cdf[-1], grid)


def nodes(edges):
    mid, half = 0.5 * (edges[1:] + edges[:-1]), 0.5 * np.diff(edges)
    return (mid[:, None] + half[:, None] * NODES[None, :]).ravel()


def kronrod(edges, values):
    """Kronrod integrals of every column on the partition ``edges`` (values at ``nodes``)."""
    widths = np.diff(edges)
    v = values.reshape(widths.size, 15, -1)
    return np.einsum("i,j,ijk->k", 0.5 * widths, W_K, v)


def repair(vals):
    """Failed members (NaN rows) take the values of their nearest successful neighbour."""
    bad = np.isnan(vals[:, 0])
    if not np.any(bad):
        return vals
    if np.all(bad):
        return np.nan_to_num(vals)
    good = np.flatnonzero(~bad)
    nearest = good[np.abs(np.flatnonzero(bad)[:, None] - good[None, :]).argmin(axis=1)]
    vals = vals.copy()
    vals[bad] = vals[nearest]
    return vals
