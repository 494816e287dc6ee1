"""The compiled kernel: the only place numba is used.

Everything here takes plain floats and numpy arrays; ``model.support`` wraps it.
``pack`` turns a ``Params`` into the flat array the kernel reads.
"""
import numpy as np

from ..friction import series_coefficients
from .driver import N_STATS, integrate
from .rhs import N_MOTION, N_PARAM, N_STATE, jacobian, mu_over_s, rhs

__all__ = ["pack", "initial_state", "integrate", "rhs", "jacobian", "mu_over_s",
           "N_STATE", "N_MOTION", "N_STATS", "METHOD_CODES"]

METHOD_CODES = {"auto": 0, "explicit": 1, "implicit": 2}


def pack(params) -> np.ndarray:
    """The kernel's parameter array for ``params`` (slots named in ``rhs``)."""
    c0, c2, c4, c6 = series_coefficients(params.A, params.B)
    x0 = params.rest_position[0]
    P = np.array([params.k_r, params.k_theta, params.f_N, params.theta0, params.mu_s,
                  params.A, params.B, params.zeta, params.lam, params.L0,
                  c0, c2, c4, c6, x0], dtype=float)
    assert P.size == N_PARAM
    return P


def initial_state(params) -> np.ndarray:
    """At rest at (cos theta0, sin theta0) with theta = theta0; quadratures zero."""
    y0 = np.zeros(N_STATE)
    y0[0], y0[1] = params.rest_position
    y0[4] = params.theta0
    return y0
