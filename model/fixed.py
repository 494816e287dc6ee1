"""Fixed-orientation arrays (Figs. 9-11): every support shares theta0.

One trajectory is then the whole array: F_T = -sum F_f gives
F_T,x/(mu0 F_N) = F_x/(f_N mu0) with F_x the time-averaged friction of Eq. (8), and
N_c/N_c0 = tau_out/L0. ``orientation_sweep`` evaluates many such arrays (one per
theta0) in one compiled batch, for the polar plots of Fig. 11 and Fig. 10f.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from .beta import solve_beta
from .contacts import Contacts, run_contacts
from .friction import mu0
from .options import SolverOptions
from .params import Params
from .results import STATUS

__all__ = ["OrientationSweep", "orientation_sweep", "fixed_orientation", "FixedArrayResult"]


@dataclass(frozen=True)
class OrientationSweep:
    """Fixed-orientation arrays, one per theta0 (arrays over ``theta0``).

    ``beta`` is the load factor each array was computed with (self-consistent or fixed);
    ``beta_residual`` is G(beta) = beta - L0/tau_out(beta) (0 for a fixed beta).
    """

    params: Params
    theta0: np.ndarray
    FTx_over_mu0FN: np.ndarray
    FTy_over_mu0FN: np.ndarray
    Dy_over_Dx: np.ndarray
    Nc_over_Nc0: np.ndarray
    work_split: dict
    dtheta_rms: np.ndarray
    dr_rms: np.ndarray
    beta: np.ndarray
    beta_residual: np.ndarray
    beta_note: np.ndarray  # "", "capped at 1" or "no root: tau_out jumps"
    contacts: Contacts
    beta_iterations: int = 0
    seconds: float = 0.0
    stats: dict = field(default_factory=dict)

    @property
    def success(self) -> np.ndarray:
        return self.contacts.ok & (self.beta_note != "no root: tau_out jumps")


def orientation_sweep(params: Params, theta0, beta="self", rtol: float = 1e-6,
                      atol: float | None = None, method: str = "auto",
                      beta_xtol: float = 1e-8) -> OrientationSweep:
    """Fixed-orientation arrays for every value in ``theta0`` (radians).

    ``beta="self"`` (default) solves beta = L0/tau_out(beta) for each orientation with a
    bracketed root finder; a number uses that fixed load factor (1 = no correction).
    """
    start = time.perf_counter()
    if not isinstance(params, Params):
        raise TypeError(f"params must be a model.Params, not {type(params).__name__}")
    try:
        theta0 = shown = np.atleast_1d(np.asarray(theta0, dtype=float))
    except (TypeError, ValueError, OverflowError):
        theta0, shown = np.array([]), theta0
    if theta0.ndim != 1 or theta0.size == 0 or not np.all(np.isfinite(theta0)):
        raise ValueError(f"theta0={shown!r} must be a non-empty 1-D array of finite angles")
    for t in (theta0.min(), theta0.max()):
        params.replace(theta0=t)  # range check with the message of Params
    if isinstance(beta_xtol, bool) or not (isinstance(beta_xtol, (int, float))
                                           and 1e-15 <= beta_xtol <= 0.1):
        raise ValueError(f"beta_xtol={beta_xtol!r} must be a number in [1e-15, 0.1]")
    options = SolverOptions(rtol=rtol, atol=atol, method=method)
    if isinstance(beta, str):
        if beta != "self":
            raise ValueError(f"beta={beta!r} must be 'self' or a number in (0, 1]")
        betas, residual, note, iterations = _self_consistent(params, theta0, options, beta_xtol)
    else:
        params = params.replace(beta=beta)
        betas = np.full(theta0.size, params.beta)
        residual, note, iterations = np.zeros(theta0.size), np.full(theta0.size, ""), 0
    contacts = _contacts_at(params, theta0, betas, options)
    return _sweep_result(params, theta0, betas, residual, note, iterations, contacts,
                         time.perf_counter() - start)


def _contacts_at(params, theta0, betas, options) -> Contacts:
    """Contacts of orientation theta0[i] under load factor betas[i]."""
    return run_contacts(params, theta0, options, beta=betas)[0]


def _self_consistent(params, theta0, options, xtol):
    def tau_out(beta, rows):
        return run_contacts(params, theta0[rows], options, beta=beta)[0].t_out

    sol = solve_beta(tau_out, params.L0, theta0.size, xtol=xtol)
    note = np.where(sol.capped, "capped at 1", np.where(sol.jump, "no root: tau_out jumps", ""))
    return sol.beta, sol.residual, note, sol.iterations


def _sweep_result(params, theta0, betas, residual, note, iterations, c, seconds):
    m0 = mu0(params)
    with np.errstate(divide="ignore", invalid="ignore"):
        split = {k: getattr(c, k) / c.W for k in ("D_x", "D_y", "U_el", "K")}
        Dy_over_Dx = c.D_y / c.D_x
    return OrientationSweep(
        params=params, theta0=theta0, FTx_over_mu0FN=c.F_x / m0, FTy_over_mu0FN=c.F_y / m0,
        Dy_over_Dx=Dy_over_Dx, Nc_over_Nc0=c.t_out / params.L0, work_split=split,
        dtheta_rms=c.dtheta_rms, dr_rms=c.dr_rms, beta=betas, beta_residual=residual,
        beta_note=note, contacts=c, beta_iterations=iterations, seconds=seconds,
        stats={"trajectories": int(c.stats.shape[0]), "n_rhs": c.n_rhs})


@dataclass(frozen=True)
class FixedArrayResult:
    """A fixed-orientation array: one ``OrientationSweep`` row as scalars."""

    params: Params
    FTx_over_mu0FN: float
    FTy_over_mu0FN: float
    Dy_over_Dx: float
    Nc_over_Nc0: float
    work_split: dict
    dtheta_rms: float
    dr_rms: float
    beta: float
    beta_residual: float
    beta_iterations: int
    success: bool
    message: str
    r_min: float
    pivot_approach: bool
    energy_residual: float

    def to_dict(self) -> dict:
        d = {k: getattr(self, k) for k in self.__dataclass_fields__ if k != "params"}
        d["params"] = self.params.as_dict()
        return d


def fixed_orientation(params: Params, beta="self", rtol: float = 1e-6,
                      atol: float | None = None, method: str = "auto") -> FixedArrayResult:
    """A fixed-orientation array at ``params.theta0`` (Figs. 9-11); see ``orientation_sweep``."""
    if not isinstance(params, Params):
        raise TypeError(f"params must be a model.Params, not {type(params).__name__}")
    s = orientation_sweep(params, [params.theta0], beta=beta, rtol=rtol, atol=atol, method=method)
    c = s.contacts
    status = int(c.status[0])
    message = STATUS.get(status, str(status))
    if s.beta_note[0]:
        message += f"; self-consistent beta {s.beta_note[0]}"
    return FixedArrayResult(
        params=params.replace(beta=float(s.beta[0])),
        FTx_over_mu0FN=float(s.FTx_over_mu0FN[0]), FTy_over_mu0FN=float(s.FTy_over_mu0FN[0]),
        Dy_over_Dx=float(s.Dy_over_Dx[0]), Nc_over_Nc0=float(s.Nc_over_Nc0[0]),
        work_split={k: float(v[0]) for k, v in s.work_split.items()},
        dtheta_rms=float(s.dtheta_rms[0]), dr_rms=float(s.dr_rms[0]), beta=float(s.beta[0]),
        beta_residual=float(s.beta_residual[0]), beta_iterations=s.beta_iterations,
        success=bool(s.success[0]), message=message, r_min=float(c.r_min[0]),
        pivot_approach=bool(c.pivot_approach[0]), energy_residual=float(c.energy_residual[0]))
