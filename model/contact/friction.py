"""The velocity-dependent friction law, Eq. (4), vectorised with numpy.

    mu(v) = mu_s sin(A atan(zeta v - B (zeta v - atan(zeta v))))

The compiled kernel has its own scalar copy; the tests check both agree.
"""
from __future__ import annotations

import numpy as np

from .params import DEFAULTS, Params

__all__ = ["mu", "mu0", "mu_over_s", "series_coefficients", "law"]

# Below this zeta*s the closed form of mu(s)/s is replaced by its Taylor series:
# the series is exact to rounding there and has no 0/0 at s = 0.
SERIES_BELOW = 1e-3


def _consts(params: Params | None):
    if params is None:
        d = DEFAULTS
        return d["mu_s"], d["A"], d["B"], d["zeta"]
    return params.mu_s, params.A, params.B, params.zeta


def law(z, mu_s: float, A: float, B: float):
    """Eq. (4) of the speed ratio z = v/V_s (= zeta v in units of V0):
    mu_s sin(A atan(z - B (z - atan(z)))). The one place the formula is written."""
    z = np.asarray(z, dtype=float)
    return mu_s * np.sin(A * np.arctan(z - B * (z - np.arctan(z))))


def mu(v, params: Params | None = None):
    """Friction coefficient mu(v) of Eq. (4).

    Parameters
    ----------
    v : float or array_like
        Relative speed of slab and support, v >= 0, in V0 (the slab speed).
    params : Params, optional
        Its friction constants mu_s, A, B, zeta; the defaults of ``Params`` if omitted.

    Returns
    -------
    float or numpy.ndarray
        mu(v) = mu_s sin(A atan(zeta v - B (zeta v - atan(zeta v)))), dimensionless,
        shaped as ``v``.

    Examples
    --------
    >>> from model import mu
    >>> mu([0.0, 0.1, 1.0]).round(4)
    array([0.    , 1.1858, 1.0082])
    """
    mu_s, A, B, zeta = _consts(params)
    return law(zeta * np.asarray(v, dtype=float), mu_s, A, B)


def mu0(params: Params | None = None) -> float:
    """Rigid-contact friction coefficient mu0 = mu(1), at the slab speed.

    Every friction result of an array is quoted over mu0 F_N: 1 is the friction of a rigid
    surface, below 1 a reduction.

    Parameters
    ----------
    params : Params, optional
        Its friction constants; the defaults of ``Params`` (mu0 = 1.00824) if omitted.

    Returns
    -------
    float
        mu(1), dimensionless.

    Examples
    --------
    >>> from model import mu0
    >>> round(mu0(), 5)
    1.00824
    """
    return float(mu(1.0, params))


def series_coefficients(A: float, B: float):
    """Taylor coefficients c0, c2, c4, c6 of mu(s)/(mu_s zeta) in powers of z = zeta s."""
    A2 = A * A
    c2 = -A * (A2 + 2 * B + 2) / 6
    c4 = A * (A2 * A2 + 20 * A2 * B + 20 * A2 + 64 * B + 24) / 120
    c6 = -A * (A2**3 + 70 * A2 * A2 * B + 70 * A2 * A2 + 280 * A2 * B * B
               + 1904 * A2 * B + 784 * A2 + 560 * B * B + 3408 * B + 720) / 5040
    return A, c2, c4, c6


def mu_over_s(s, params: Params | None = None):
    """mu(s)/s, smooth and finite through s = 0 (limit mu_s A zeta).

    The friction force is F_f = -f_N (mu(s)/s) v_R with s = ``abs(v_R)``; writing it this
    way keeps it smooth where the relative velocity vanishes. Below zeta s = 1e-3 the closed
    form is replaced by its Taylor series.

    Parameters
    ----------
    s : float or array_like
        Relative speed, s >= 0, in V0.
    params : Params, optional
        Its friction constants; the defaults of ``Params`` if omitted.

    Returns
    -------
    float or numpy.ndarray
        mu(s)/s, in 1/V0, shaped as ``s``.

    Examples
    --------
    >>> from model import mu_over_s
    >>> mu_over_s([0.0, 1e-5, 1.0]).round(4)   # mu_s A zeta = 18.72 at s = 0
    array([18.72  , 18.72  ,  1.0082])
    """
    mu_s, A, B, zeta = _consts(params)
    s = np.asarray(s, dtype=float)
    z = zeta * s
    c0, c2, c4, c6 = series_coefficients(A, B)
    z2 = z * z
    series = mu_s * zeta * (c0 + z2 * (c2 + z2 * (c4 + z2 * c6)))
    with np.errstate(divide="ignore", invalid="ignore"):
        closed = mu(s, params) / s
    return np.where(z < SERIES_BELOW, series, closed)
