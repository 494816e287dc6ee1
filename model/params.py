"""Physical parameters of one support and its contact with the slab.

Everything is dimensionless as in the paper (Eq. 5): lengths in r0, time
tau = t V0 / r0, forces in m V0^2 / r0. ``Params`` is frozen and hashable, so
it doubles as a cache key.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields, replace

import numpy as np

__all__ = ["Params", "REGIMES", "DEFAULTS", "rest_positions"]

#: Constants fixed by MODEL.md (friction law Eq. 4, repulsion Eq. 3, slab length).
DEFAULTS = dict(mu_s=1.3, A=1.44, B=-20.0, zeta=10.0, lam=0.05, L0=10.0)

# (lower, upper, lower_open, upper_open, meaning) for every field.
_RANGES = {
    "k_r": (0.0, 1e6, True, False, "radial stiffness k_r"),
    "k_theta": (0.0, 1e6, True, False, "torsional stiffness k_theta"),
    "F_N": (0.0, 1e3, True, False, "normal load F_N"),
    "theta0": (-2 * math.pi, 2 * math.pi, False, False, "rest orientation theta0 [rad]"),
    "beta": (0.0, 1.0, True, False, "load factor beta = N_c0/N_c"),
    "mu_s": (0.0, 100.0, True, False, "static friction coefficient mu_s"),
    "A": (0.0, 100.0, True, False, "friction-law shape A"),
    "B": (-1e4, 1e4, False, False, "friction-law shape B"),
    "zeta": (0.0, 1e6, True, False, "friction-law velocity scale zeta = V0/V_s"),
    "lam": (1e-4, 0.5, False, False, "repulsion range lambda"),
    "L0": (0.0, 1e6, True, False, "slab length L0"),
}


def _check(name: str, value) -> float:
    lo, hi, lo_open, hi_open, meaning = _RANGES[name]
    try:
        if isinstance(value, (bool, np.bool_, str, bytes)):  # float() would accept these
            raise TypeError
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value!r} is not a number; {meaning} must be a real number") from None
    except OverflowError:  # an int beyond the float range
        x = math.inf
    lo_ok = x > lo if lo_open else x >= lo
    hi_ok = x < hi if hi_open else x <= hi
    if not (math.isfinite(x) and lo_ok and hi_ok):
        interval = f"{'(' if lo_open else '['}{lo:g}, {hi:g}{')' if hi_open else ']'}"
        raise ValueError(f"{name}={value!r} is invalid: {meaning} must be finite and in {interval}")
    return x


@dataclass(frozen=True)
class Params:
    """One support in contact with the sliding slab (dimensionless, Eqs. 3-5).

    Parameters
    ----------
    k_r, k_theta : radial and torsional stiffness (k~_r, k~_theta of Eq. 5).
    F_N : normal load on the slab per support at rest (F~_N); each support carries
        f_N = beta * F_N.
    theta0 : rest orientation of the support [rad], measured from the sliding
        direction +x.
    beta : N_c0 / N_c, the load correction for supports dragged beyond L0
        (1 = no correction; the array functions solve it self-consistently).
    mu_s, A, B, zeta : friction law, Eq. (4), with zeta = V0/V_s.
    lam : range of the repulsion phi(r) = exp(-r/lam) / (2 lam), Eq. (3).
    L0 : slab length; a contact ends when the slab has slid L0 over the support (Eq. 9).
    """

    k_r: float
    k_theta: float
    F_N: float = 1.0
    theta0: float = math.pi / 2
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
        mirror-symmetric start keeps y = 0 for all time (MODEL.md, "Hard cases").
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
