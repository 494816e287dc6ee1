"""How the headline numbers move with the choices the paper left open.

For the four regimes at F_N = 1, F_T,x/(mu0 F_N) and D_y/D_x of the uniform array under:
the repulsion range lambda (Eq. 3; 0.05 by default, halved and doubled), the average
(paper, Eq. 10, or duration-weighted), the load factor (self-consistent or beta = 1), and
the theta0 average (adaptive quadrature, or the paper's mean over 200 random supports,
repeated to show its spread).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..arrays.fixed import orientation_sweep
from ..arrays.uniform import uniform_array
from ..contact.friction import mu0
from ..contact.params import REGIMES

LAMBDAS = (0.025, 0.1)
N_RANDOM = 200


@dataclass(frozen=True)
class Variant:
    """One choice: per regime the (F_T,x/(mu0 F_N), D_y/D_x) and an error or spread."""

    name: str
    description: str
    FTx: dict
    DyDx: dict
    error: dict  # regime -> text


def _from_arrays(name, description, arrays) -> Variant:
    return Variant(name, description,
                   {r: a.FTx_over_mu0FN for r, a in arrays.items()},
                   {r: a.Dy_over_Dx for r, a in arrays.items()},
                   {r: f"±{a.quadrature_error['FTx_over_mu0FN']:.1e}" for r, a in arrays.items()})


def random_supports(params, beta: float, draws: int, seed: int = 2021) -> tuple:
    """The paper's estimate: ``draws`` means over 200 supports with theta0 uniform on
    [0, 2 pi) (folded onto [0, pi] by mirror symmetry), all at the load factor ``beta``.
    Returns arrays (F_T,x/(mu0 F_N), D_y/D_x) of length ``draws``."""
    rng = np.random.default_rng(seed)
    theta = rng.uniform(0.0, 2 * math.pi, size=(draws, N_RANDOM))
    folded = np.where(theta > math.pi, 2 * math.pi - theta, theta)
    s = orientation_sweep(params, folded.ravel(), beta=beta, rtol=1e-6)
    c = s.contacts
    fx = np.asarray(c.F_x).reshape(draws, N_RANDOM)
    dx, dy = (np.asarray(v).reshape(draws, N_RANDOM) for v in (c.D_x, c.D_y))
    return fx.mean(axis=1) / mu0(params), dy.sum(axis=1) / dx.sum(axis=1)


def variants(headline: dict, tol: float, draws: int, progress=None) -> list:
    """Every variant, the baseline first. ``headline`` maps regime -> baseline array."""
    base = {r: headline[r] for r in REGIMES}
    tick = progress or (lambda done, total: None)
    total, done = 2 + 1 + 1, 0
    out = [_from_arrays("baseline", "λ = 0.05, self-consistent β, paper average (Eq. 10), "
                        f"adaptive quadrature (tol {tol:g})", base)]
    for lam in LAMBDAS:
        arrays = {r: uniform_array(p.replace(lam=lam), tol=tol) for r, p in REGIMES.items()}
        out.append(_from_arrays(f"λ = {lam:g}", f"repulsion range λ = {lam:g} (Eq. 3)", arrays))
        done += 1
        tick(done, total)
    out.append(Variant("duration-weighted", "duration-weighted average of the same arrays",
                       {r: a.FTx_over_mu0FN_duration for r, a in base.items()},
                       {r: a.Dy_over_Dx for r, a in base.items()},
                       {r: f"±{a.quadrature_error['FTx_over_mu0FN_duration']:.1e}"
                        for r, a in base.items()}))
    fixed = {r: uniform_array(p, beta=1.0, tol=tol) for r, p in REGIMES.items()}
    out.append(_from_arrays("β = 1", "no contact-count correction (β = 1)", fixed))
    done += 1
    tick(done, total)
    ftx, dydx, spread = {}, {}, {}
    for r, a in base.items():
        f, d = random_supports(REGIMES[r], a.beta, draws)
        ftx[r], dydx[r] = float(f.mean()), float(d.mean())
        spread[r] = f"sd {f.std(ddof=1):.1e} over {draws} draws" if draws > 1 else "one draw"
    out.append(Variant(f"{N_RANDOM} random supports",
                       f"mean over {N_RANDOM} random θ₀ (the paper's method), averaged over "
                       f"{draws} draws; β as in the baseline", ftx, dydx, spread))
    tick(total, total)
    return out
