"""Physical parameters of one support and its contact with the slab.

Everything is dimensionless as in the paper (Eq. 5): lengths in r0, time
tau = t V0 / r0, forces in m V0^2 / r0. ``Params`` is frozen and hashable, so
it doubles as a cache key.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields, replace

import numpy as np

from ..validation import BETA, Interval, number

__all__ = ["Params", "REGIMES", "DEFAULTS", "RANGES", "rest_positions", "check_array_params"]

#: Constants of the friction law (Eq. 4), the repulsion (Eq. 3) and the slab length (Eq. 9);
#: docs/model.md, "Defaults".
DEFAULTS = dict(mu_s=1.3, A=1.44, B=-20.0, zeta=10.0, lam=0.05, L0=10.0)

#: (interval, meaning) of every field: what the model accepts (Eqs. 3-5).
RANGES = {
    "k_r": (Interval(0.0, 1e6, lo_open=True), "radial stiffness k_r"),
    "k_theta": (Interval(0.0, 1e6, lo_open=True), "torsional stiffness k_theta"),
    "F_N": (Interval(0.0, 1e3, lo_open=True), "normal load F_N"),
    "theta0": (Interval(-2 * math.pi, 2 * math.pi), "rest orientation theta0 [rad]"),
    "beta": (BETA, "load factor beta = N_c0/N_c"),
    "mu_s": (Interval(0.0, 100.0, lo_open=True), "static friction coefficient mu_s"),
    "A": (Interval(0.0, 100.0, lo_open=True), "friction-law shape A"),
    "B": (Interval(-1e4, 1e4), "friction-law shape B"),
    "zeta": (Interval(0.0, 1e6, lo_open=True), "friction-law velocity scale zeta = V0/V_s"),
    "lam": (Interval(1e-4, 0.5), "repulsion range lambda"),
    "L0": (Interval(0.0, 1e6, lo_open=True), "slab length L0"),
}


#: The rest orientation of ``Params`` when none is given (the paper's Figs. 6, 7).
THETA0_DEFAULT = math.pi / 2


def _check(name: str, value) -> float:
    interval, meaning = RANGES[name]
    return number(name, value, interval, meaning)


@dataclass(frozen=True)
class Params:
    """One support in contact with the sliding slab (dimensionless, Eqs. 3-5).

    Frozen, hashable and validated: a value outside the model's range raises
    ``ValueError`` naming the field.

    Parameters
    ----------
    k_r, k_theta : float
        Radial and torsional stiffness (k~_r, k~_theta of Eq. 5), in m V0^2 / r0^2 and
        m V0^2; the paper's map spans [0.01, 3] for both.
    F_N : float, default 1
        Normal load on the slab per support at rest (F~_N), in m V0^2 / r0; each support
        carries f_N = beta * F_N.
    theta0 : float, default pi/2
        Rest orientation of the support [rad], measured from the sliding direction +x
        (used by ``simulate_support`` and ``fixed_orientation``; arrays over theta0 take
        their orientations as an argument and refuse another theta0 here).
    beta : float, default 1
        N_c0 / N_c, the load correction for supports dragged beyond L0 (1 = no
        correction). One support uses it; an array's load factor is the ``beta``
        argument of the array function ("self" solves it), which refuses a different
        value here rather than ignoring it (``check_array_params``).
    mu_s, A, B, zeta : float, default 1.3, 1.44, -20, 10
        Friction law, Eq. (4), with zeta = V0/V_s (dimensionless).
    lam : float, default 0.05
        Range of the repulsion phi(r) = exp(-r/lam) / (2 lam), Eq. (3), in r0.
    L0 : float, default 10
        Slab length in r0; a contact ends when the slab has slid L0 over the support
        (Eq. 9).

    See Also
    --------
    REGIMES : the four regimes of the paper.
    simulate_support : one contact of this support.

    Examples
    --------
    >>> from model import Params, REGIMES
    >>> Params(k_r=3, k_theta=0.01) == REGIMES["pendulum"]
    True
    >>> Params(k_r=3, k_theta=0.01).replace(F_N=2.0).f_N
    2.0
    >>> Params(k_r=-1, k_theta=0.01)
    Traceback (most recent call last):
    ...
    ValueError: k_r=-1 is invalid: radial stiffness k_r must be finite and in (0, 1e+06]
    """

    k_r: float
    k_theta: float
    F_N: float = 1.0
    theta0: float = THETA0_DEFAULT
    beta: float = 1.0
    mu_s: float = DEFAULTS["mu_s"]
    A: float = DEFAULTS["A"]
    B: float = DEFAULTS["B"]
    zeta: float = DEFAULTS["zeta"]
    lam: float = DEFAULTS["lam"]
    L0: float = DEFAULTS["L0"]

    def __post_init__(self):
        for f in fields(self):
            object.__setattr__(self, f.name, _check(f.name, getattr(self, f.name)))

    @property
    def f_N(self) -> float:
        """Normal load carried by one support, f_N = beta F_N."""
        return self.beta * self.F_N

    @property
    def rest_position(self) -> tuple[float, float]:
        """(cos theta0, sin theta0), exactly on the x-axis when theta0 is a multiple of pi.

        sin(float(pi)) = 1.2e-16 would start the mass a hair off the axis; the exact
        mirror-symmetric start keeps y = 0 for all time (docs/model.md, "Hard cases").
        """
        x, y = rest_positions(self.theta0)
        return float(x), float(y)

    def replace(self, **changes) -> "Params":
        """A copy with some fields changed (validated again)."""
        return replace(self, **changes)

    def as_dict(self) -> dict:
        return asdict(self)

    @classmethod
    def regime(cls, name: str, **changes) -> "Params":
        """The named regime of Fig. 5/6 (``pendulum``, ``slider``, ``stiff``, ``soft``)."""
        try:
            base = REGIMES[name]
        except KeyError:
            raise ValueError(f"regime={name!r} is unknown; choose one of {sorted(REGIMES)}") from None
        return base.replace(**changes)


def check_array_params(params: Params, function: str, beta, uses_theta0: bool) -> None:
    """Refuse the fields of ``params`` that the array function ``function`` would ignore.

    An array's load factor is its ``beta`` argument (``"self"`` or a number), so a
    ``params.beta`` other than 1 must agree with it; an array over theta0 (uniform, or a
    sweep given its theta0 values) has no use for ``params.theta0``, which must then be
    left at its default. Raises ``ValueError`` naming the field and the fix.
    """
    if not uses_theta0 and params.theta0 != THETA0_DEFAULT:
        raise ValueError(
            f"theta0={params.theta0!r} is not used by {function}, which covers its own "
            f"orientations; leave params.theta0 at its default pi/2 "
            f"(params.replace(theta0=math.pi / 2))")
    if params.beta != 1.0 and (isinstance(beta, str) or float(beta) != params.beta):
        raise ValueError(
            f"beta={params.beta!r} in params would be ignored by {function}(beta={beta!r}): "
            f"an array's load factor is its beta argument; pass beta={params.beta!r} or "
            f"leave params.beta at 1")


def rest_positions(theta0):
    """(cos theta0, sin theta0) for an array of orientations, exact on the x-axis.

    Used by ``Params.rest_position`` and the batch paths, so both start identically.
    """
    theta0 = np.asarray(theta0, dtype=float)
    x, y = np.cos(theta0), np.sin(theta0)
    on_axis = np.abs(y) < 4 * math.ulp(2 * math.pi)
    return np.where(on_axis, np.copysign(1.0, x), x), np.where(on_axis, 0.0, y)


#: The four dynamic regimes of the paper (Fig. 6 caption), at F_N = 1, theta0 = pi/2.
REGIMES = {
    "pendulum": Params(k_r=3.0, k_theta=0.01),
    "slider": Params(k_r=0.01, k_theta=3.0),
    "stiff": Params(k_r=3.0, k_theta=3.0),
    "soft": Params(k_r=0.03, k_theta=0.03),
}
