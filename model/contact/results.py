"""Result objects of one contact, in the spirit of scipy's ``OdeResult``."""
from __future__ import annotations

from dataclasses import dataclass, field
from enum import IntEnum

import numpy as np

from .._kernel import slots as _slots
from ..arrays.quantities import record
from .options import SolverOptions
from .params import Params

__all__ = ["SupportResult", "TimeSeries", "ArrayResult", "IntegrationError", "Status",
           "STATUS", "ACCURACY_FACTOR"]

class Status(IntEnum):
    """Outcome of one contact: the kernel's codes (``model._kernel.slots``) named, each
    with a message and a remedy (in the manner of diffrax's ``RESULTS``)."""

    OK = _slots.OK
    STEP_BUDGET = _slots.STEP_BUDGET
    TIME_BUDGET = _slots.TIME_BUDGET
    STEP_UNDERFLOW = _slots.STEP_UNDERFLOW
    NONFINITE = _slots.NONFINITE

    @property
    def message(self) -> str:
        return _STATUS_TEXT[self][0]

    @property
    def remedy(self) -> str:
        return _STATUS_TEXT[self][1]


_STATUS_TEXT = {
    Status.OK: ("contact ended: the slab slid L0 over the support (Eq. 9)", ""),
    Status.STEP_BUDGET: ("step budget exhausted before the contact ended",
                         "raise max_steps or loosen rtol"),
    Status.TIME_BUDGET: ("time budget tau_max reached before the contact ended", "raise tau_max"),
    Status.STEP_UNDERFLOW: ("step size underflow", "try method='implicit' or a looser rtol"),
    Status.NONFINITE: ("non-finite state", "try method='implicit' or a looser rtol"),
}

#: Status code -> message, for code that has only the number.
STATUS = {int(s): s.message for s in Status}


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

    Forces are the friction on the support divided by f_N. The energy split of Eq. (12)
    at every tau: slab work ``W`` so far, dissipation ``D_x``, ``D_y`` (Eq. 13) so far,
    elastic energy ``U_el`` and kinetic energy ``K`` of the state at tau, so that
    W = D_x + D_y + U_el + K holds at every sample; at tau_out they equal the result's.
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
    W: np.ndarray
    D_x: np.ndarray
    D_y: np.ndarray
    U_el: np.ndarray
    K: np.ndarray

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
    (the mass was driven into the region of its own pivot; docs/model.md, "Hard cases");
    ``r_min`` and ``r_max`` are the smallest and largest distance of the mass from its pivot.
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
    r_max: float
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
        """JSON-ready summary (no time series): the quantities of
        ``model.arrays.quantities.TABLES["support"]``, the solver statistics and the parameters."""
        return {**record(self, "support"), "stats": dict(self.stats),
                "params": self.params.as_dict()}


@dataclass(frozen=True)
class ArrayResult:
    """What every array result carries (Eqs. 9-13), declared once for all of them.

    One number per array (``FixedArrayResult``, ``UniformArrayResult``) or one per theta0
    (``OrientationSweep``): the apparent friction F_T,x/(mu0 F_N) (Eq. 10), the transverse
    force F_T,y/(mu0 F_N) (Eq. 11), D_y/D_x (Eq. 13), the contact count N_c/N_c0, the split
    of the slab work (Eq. 12), the fluctuations (Fig. 10f) and the load factor beta with
    its residual G(beta) = beta - L0/<tau_out>(beta) (0 for a fixed beta). ``params``
    carries the springs, load and friction law (and, for arrays of one orientation, theta0).
    """

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

    def to_dict(self) -> dict:
        """JSON-ready: every field (tuples as lists), ``params`` as a dict."""
        d = {k: getattr(self, k) for k in self.__dataclass_fields__
             if k not in ("params", "contacts")}
        d = {k: list(v) if isinstance(v, tuple) else v for k, v in d.items()}
        d["params"] = self.params.as_dict()
        return d
