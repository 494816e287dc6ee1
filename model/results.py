"""Result objects of one contact, in the spirit of scipy's ``OdeResult``."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .options import SolverOptions
from .params import Params

__all__ = ["SupportResult", "TimeSeries", "IntegrationError", "STATUS", "ACCURACY_FACTOR"]

#: Status codes shared by the compiled kernel and the reference path.
STATUS = {
    0: "contact ended: the slab slid L0 over the support (Eq. 9)",
    1: "step budget exhausted before the contact ended",
    2: "time budget tau_max reached before the contact ended",
    3: "step size underflow",
    4: "non-finite state",
}


#: A result is flagged inaccurate when |W - (D_x + D_y + U_el + K)| > ACCURACY_FACTOR rtol W.
ACCURACY_FACTOR = 3.0


class IntegrationError(RuntimeError):
    """A contact could not be integrated to its end; ``.result`` holds the partial result."""

    def __init__(self, result: "SupportResult"):
        super().__init__(result.message)
        self.result = result


@dataclass(frozen=True)
class TimeSeries:
    """Uniformly sampled histories over [0, tau_out] for plotting (Figs. 7, 10).

    Forces are the friction on the support divided by f_N.
    """

    tau: np.ndarray
    x: np.ndarray
    y: np.ndarray
    v_x: np.ndarray
    v_y: np.ndarray
    theta: np.ndarray
    r: np.ndarray
    F_x: np.ndarray
    F_y: np.ndarray
    F_abs: np.ndarray

    def as_dict(self) -> dict:
        return {k: getattr(self, k) for k in self.__dataclass_fields__}


@dataclass(frozen=True)
class SupportResult:
    """Everything one contact yields (Eqs. 8, 9, 12, 13).

    Energies are per contact, in m V0^2: slab work ``W`` = D_x + D_y + U_el + K for
    the true solution; ``energy_residual`` = W - (D_x + D_y + U_el + K) measures the
    integration error. ``F_mean`` is the time-averaged friction on the support over
    f_N (Eq. 8); the slab needs F_T = -sum F_f, so F_mean[0] > 0 means the support is
    dragged forward. ``pivot_approach`` is True when r fell below ``pivot_radius``
    (the mass was driven into the region of its own pivot; see MODEL.md).
    """

    params: Params
    options: SolverOptions
    success: bool
    status: int
    message: str
    t_out: float
    state_out: np.ndarray
    F_mean: np.ndarray
    W: float
    D_x: float
    D_y: float
    U_el: float
    K: float
    energy_residual: float
    dtheta_rms: float
    dr_rms: float
    r_min: float
    pivot_approach: bool
    pivot_radius: float
    stats: dict = field(default_factory=dict)
    series: TimeSeries | None = None

    @property
    def relative_energy_residual(self) -> float:
        return abs(self.energy_residual) / max(abs(self.W), 1e-300)

    @property
    def accurate(self) -> bool:
        """False when the energy balance misses by more than ``ACCURACY_FACTOR`` rtol.

        The balance holds exactly for the true solution, so a larger residual shows
        that the integration error exceeds what was asked for (e.g. an explicit
        method held at its stability limit on a stiff case at a loose tolerance).
        """
        return self.relative_energy_residual <= ACCURACY_FACTOR * max(self.options.rtol, 1e-9)

    def check(self) -> "SupportResult":
        """Return self, or raise ``IntegrationError`` when the run did not succeed."""
        if not self.success:
            raise IntegrationError(self)
        return self

    def to_dict(self) -> dict:
        """JSON-ready summary (no time series)."""
        return {
            "t_out": self.t_out,
            "state_out": [float(v) for v in self.state_out],
            "F_mean_x": float(self.F_mean[0]),
            "F_mean_y": float(self.F_mean[1]),
            "W": self.W, "D_x": self.D_x, "D_y": self.D_y, "U_el": self.U_el, "K": self.K,
            "energy_residual": self.energy_residual,
            "dtheta_rms": self.dtheta_rms, "dr_rms": self.dr_rms, "r_min": self.r_min,
            "pivot_approach": self.pivot_approach, "accurate": self.accurate,
            "success": self.success, "status": self.status, "message": self.message,
            "stats": dict(self.stats),
            "params": self.params.as_dict(),
        }
