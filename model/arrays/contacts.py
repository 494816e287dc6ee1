"""Many contacts at once: supports that differ only in theta0 (Eqs. 8, 12, 13).

``run_contacts`` integrates them in one compiled call and turns the exit states and
quadratures into per-contact quantities; ``simulate_support`` is its one-row case.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from .. import _kernel
from ..contact.energy import elastic_energy, kinetic_energy
from ..contact.options import SolverOptions, array_method
from ..contact.params import Params, rest_positions

__all__ = ["Contacts", "run_contacts", "PIVOT_RADIUS_OVER_LAMBDA"]

#: A trajectory "approaches its pivot" when r < PIVOT_RADIUS_OVER_LAMBDA * lambda
#: (0.01 at the default lambda = 0.05): there the repulsion of Eq. (3) dominates and
#: the terms k_theta (theta - theta0)/r and theta' = (x v_y - y v_x)/r^2 grow without bound.
PIVOT_RADIUS_OVER_LAMBDA = 0.2
STAT_NAMES = _kernel.STAT_NAMES


@dataclass(frozen=True)
class Contacts:
    """One row per contact; forces are time averages over f_N (Eq. 8), energies per contact.

    ``status`` uses the codes named in ``model.contact.results.Status`` (``Status.OK`` = 0: the
    contact ended normally).
    """

    params: Params
    options: SolverOptions
    theta0: np.ndarray
    beta: np.ndarray
    status: np.ndarray
    t_out: np.ndarray
    state_out: np.ndarray
    F_x: np.ndarray
    F_y: np.ndarray
    W: np.ndarray
    D_x: np.ndarray
    D_y: np.ndarray
    U_el: np.ndarray
    K: np.ndarray
    energy_residual: np.ndarray
    dtheta_rms: np.ndarray
    dr_rms: np.ndarray
    r_min: np.ndarray
    pivot_approach: np.ndarray
    stats: np.ndarray  # (m, 8) in the order of STAT_NAMES
    r_max: np.ndarray  # largest distance of the mass from its pivot during the contact

    @property
    def ok(self) -> np.ndarray:
        return self.status == _kernel.slots.OK

    @property
    def pivot_radius(self) -> float:
        return PIVOT_RADIUS_OVER_LAMBDA * self.params.lam

    @property
    def n_rhs(self) -> int:
        return int(self.stats[:, _kernel.slots.ST_RHS].sum())


@lru_cache(maxsize=256)
def _base_row(params: Params) -> np.ndarray:
    """The kernel's parameter row of ``params`` with theta0, x0, f_N set per contact."""
    row = _kernel.pack(params, x0=0.0)
    row.flags.writeable = False
    return row


def run_contacts(params: Params, theta0, options: SolverOptions, record: bool = False,
                 beta=None):
    """Integrate supports of orientations ``theta0`` (other parameters from ``params``).

    ``beta`` (array, optional) sets each row's load factor instead of ``params.beta``.
    Returns (Contacts, nodes): ``nodes`` are the step nodes of the last row when
    ``record`` is set (for time series), else None.
    """
    array_method(options.method)
    # Copies: the result's arrays are made read-only, the caller's must not be.
    theta0 = np.array(theta0, dtype=float, ndmin=1)
    m = theta0.size
    beta = np.full(m, params.beta) if beta is None else np.array(beta, dtype=float)
    x0, y0 = rest_positions(theta0)
    P = np.repeat(_base_row(params)[None, :], m, axis=0)
    P[:, _kernel.TH0] = theta0
    P[:, _kernel.X0] = x0
    P[:, _kernel.FN] = beta * params.F_N
    P[:, _kernel.REG] = y0 != 0.0  # no time regularisation on the exact axis
    Y0 = np.zeros((m, _kernel.N_STATE))
    Y0[:, _kernel.X], Y0[:, _kernel.Y], Y0[:, _kernel.THETA] = x0, y0, theta0
    status, t, Y, D, stats, r_min, r_max, nodes, n_nodes = _kernel.integrate_batch(
        Y0, P, options.rtol, options.atol, _kernel.METHOD_CODES[options.method],
        options.max_steps, options.tau_max, record)
    r_min = np.fmin(r_min, D[:, 7])
    r_max = np.fmax(r_max, D[:, 7])
    pivot = r_min < PIVOT_RADIUS_OVER_LAMBDA * params.lam
    for a in (theta0, beta, status, t, Y, D, stats, r_min, r_max, pivot):
        a.flags.writeable = False  # column views below inherit this
    F_x, F_y, U_el, K, residual, dtheta_rms, dr_rms, _ = D.T
    S = _kernel.slots
    contacts = Contacts(
        params=params, options=options, theta0=theta0, beta=beta, status=status, t_out=t,
        state_out=Y[:, :S.N_MOTION], F_x=F_x, F_y=F_y, W=Y[:, S.W], D_x=Y[:, S.D_X],
        D_y=Y[:, S.D_Y], U_el=U_el, K=K, energy_residual=residual, dtheta_rms=dtheta_rms,
        dr_rms=dr_rms, r_min=r_min, pivot_approach=pivot, stats=stats, r_max=r_max)
    return contacts, (nodes[:n_nodes] if record else None)


def exit_quantities(params, options, theta0, status, t, Y, stats, r_min, beta=None,
                    r_max=None) -> Contacts:
    """Per-contact quantities from exit states and quadratures, with numpy.

    The kernel computes the same quantities itself (``_kernel.batch.derived``); this
    independent version serves the scipy reference path and the tests.
    """
    beta = np.full(len(theta0), params.beta) if beta is None else np.asarray(beta, dtype=float)
    f_N = beta * params.F_N
    x, y, vx, vy, th, W, Iy, Dx, Dy, S_th, S_r = np.asarray(Y, dtype=float).T
    r = np.hypot(x, y)
    U_el = elastic_energy(params, r, th, theta0)
    K = kinetic_energy(vx, vy)
    t = np.asarray(t, dtype=float)
    scale = 1.0 / np.where(t > 0, t, np.nan)  # time averages need tau_out > 0
    F_x, F_y = W * scale / f_N, Iy * scale / f_N
    dtheta_rms = np.sqrt(np.maximum(S_th, 0.0) * scale)
    dr_rms = np.sqrt(np.maximum(S_r, 0.0) * scale)
    r_min = np.fmin(np.asarray(r_min, dtype=float), r)
    r_max = r if r_max is None else np.fmax(np.asarray(r_max, dtype=float), r)
    arrays = dict(
        theta0=theta0, beta=beta, status=np.asarray(status), t_out=t, state_out=np.asarray(Y)[:, :5],
        F_x=F_x, F_y=F_y, W=W, D_x=Dx, D_y=Dy, U_el=U_el, K=K,
        energy_residual=W - (Dx + Dy + U_el + K), dtheta_rms=dtheta_rms, dr_rms=dr_rms,
        r_min=r_min, pivot_approach=r_min < PIVOT_RADIUS_OVER_LAMBDA * params.lam,
        stats=np.asarray(stats), r_max=r_max)
    for a in arrays.values():
        a.flags.writeable = False
    return Contacts(params=params, options=options, **arrays)
