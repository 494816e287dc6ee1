"""Fixed-orientation arrays (Figs. 9-11): every support shares theta0.

One trajectory is then the whole array: F_T = -sum F_f gives
F_T,x/(mu0 F_N) = F_x/(f_N mu0) with F_x the time-averaged friction of Eq. (8), and
N_c/N_c0 = tau_out/L0. ``orientation_sweep`` evaluates many such arrays (one per
theta0) in one compiled batch, for the polar plots of Fig. 11 and Fig. 10f.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field, fields

import numpy as np

from ..contact.friction import mu0
from ..contact.options import SolverOptions
from ..contact.params import RANGES, THETA0_DEFAULT, Params, check_array_params
from ..contact.results import ArrayResult, Status
from ..validation import Interval, angles, instance, load_factor, number
from .beta import solve_beta
from .contacts import Contacts, run_contacts
from .quantities import value_of

__all__ = ["OrientationSweep", "orientation_sweep", "fixed_orientation", "FixedArrayResult"]

#: Relative width of the bracket on the self-consistent beta.
BETA_XTOL = Interval(1e-15, 0.1)


@dataclass(frozen=True)
class OrientationSweep(ArrayResult):
    """Fixed-orientation arrays, one per theta0: every ``ArrayResult`` field is an array
    over ``theta0``; ``beta`` is the load factor each array was computed with
    (self-consistent or fixed). The per-contact quantities are in ``contacts``.
    """

    theta0: np.ndarray
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
    """Fixed-orientation arrays for every value in ``theta0``, in one compiled batch call.

    Each array has all its supports at one rest orientation, so one contact is the array
    (Figs. 10f, 11: F_T,x, F_T,y over mu0 F_N, D_y/D_x, N_c/N_c0 against theta0).

    Parameters
    ----------
    params : Params
        The springs, load and friction law; its theta0 must be left at the default and
        its beta at 1 (or equal to ``beta``): ``ValueError`` otherwise.
    theta0 : array_like
        Rest orientations [rad], measured from the sliding direction +x.
    beta : "self" or float, default "self"
        ``"self"`` solves beta = L0/tau_out(beta) for each orientation with a bracketed
        root finder (Illinois); a number uses that fixed load factor (1 = no correction).
    rtol, atol, method
        Solver settings of each contact, as in ``simulate_support``.
    beta_xtol : float, default 1e-8
        Tolerance of the self-consistent beta.

    Returns
    -------
    OrientationSweep
        Every quantity an array over ``theta0``; ``beta`` the load factor each array was
        computed with.

    Examples
    --------
    >>> import numpy as np
    >>> from model import REGIMES, orientation_sweep
    >>> sweep = orientation_sweep(REGIMES["pendulum"], np.linspace(0.5, 2.5, 3))
    >>> sweep.FTx_over_mu0FN.round(3)     # F_T,x / (mu0 F_N) at each theta0
    array([0.995, 0.952, 0.895])
    >>> sweep.beta.round(3)               # self-consistent N_c0 / N_c
    array([0.97 , 0.904, 0.833])
    """
    start = time.perf_counter()
    instance("params", params, Params)
    theta0 = angles("theta0", theta0, RANGES["theta0"][0])
    check_array_params(params, "orientation_sweep", load_factor("beta", beta), uses_theta0=False)
    beta_xtol = number("beta_xtol", beta_xtol, BETA_XTOL, "bracket width beta_xtol")
    options = SolverOptions(rtol=rtol, atol=atol, method=method)
    if load_factor("beta", beta) == "self":
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
class FixedArrayResult(ArrayResult):
    """A fixed-orientation array: one ``OrientationSweep`` row as scalars, with the
    quantities of its one contact (r_min, r_max, pivot_approach, energy_residual)."""

    beta_iterations: int
    success: bool
    message: str
    r_min: float
    pivot_approach: bool
    energy_residual: float
    r_max: float


def fixed_orientation(params: Params, beta="self", rtol: float = 1e-6,
                      atol: float | None = None, method: str = "auto") -> FixedArrayResult:
    """A fixed-orientation array at ``params.theta0`` (Figs. 9-11).

    Every support of the array shares ``params.theta0``, so one trajectory is the array.

    Parameters
    ----------
    params : Params
        The support, load and orientation; ``params.beta`` must be 1 or equal ``beta``
        (the array's load factor is ``beta``).
    beta : "self" or float, default "self"
        ``"self"`` solves the self-consistent load factor beta = L0/tau_out(beta); a number
        fixes it (1 = no correction).
    rtol, atol, method
        Solver settings of the contact, as in ``simulate_support``.

    Returns
    -------
    FixedArrayResult
        F_T,x/(mu0 F_N), F_T,y/(mu0 F_N), D_y/D_x, N_c/N_c0 = tau_out/L0, the work split,
        Delta theta_rms, Delta r_rms and beta.

    See Also
    --------
    orientation_sweep : many orientations in one call.

    Examples
    --------
    >>> from model import REGIMES, fixed_orientation
    >>> array = fixed_orientation(REGIMES["slider"].replace(theta0=1.0))
    >>> round(array.FTx_over_mu0FN, 3), round(array.Dy_over_Dx, 3), round(array.beta, 3)
    (0.945, 0.203, 0.228)
    """
    instance("params", params, Params)
    check_array_params(params, "fixed_orientation", load_factor("beta", beta), uses_theta0=True)
    s = orientation_sweep(params.replace(theta0=THETA0_DEFAULT), [params.theta0], beta=beta,
                          rtol=rtol, atol=atol, method=method)
    c = s.contacts
    status = int(c.status[0])
    message = Status(status).message if status in set(Status) else str(status)
    if s.beta_note[0]:
        message += f"; self-consistent beta {s.beta_note[0]}"
    # Every other field is the sweep's (or its contact's) first row, read by name.
    row = {name: _first(value_of(s, name)) for name in _ROW_FIELDS}
    return FixedArrayResult(params=params.replace(beta=row["beta"]), message=message, **row)


def _first(value):
    """Row 0 of a per-orientation value as plain Python (dicts of arrays included)."""
    if isinstance(value, np.ndarray):
        return value[0].item()
    if isinstance(value, dict):
        return {k: _first(v) for k, v in value.items()}
    return value


#: The fields of a fixed array read from its sweep by name (params and message are its own).
_ROW_FIELDS = tuple(f.name for f in fields(FixedArrayResult) if f.name not in ("params", "message"))
