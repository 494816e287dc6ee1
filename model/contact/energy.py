"""Energy terms of one contact (Eqs. 12-13) and their balance.

Per contact the slab work W = int F_f,x dtau (the slab moves at speed 1) splits
into friction dissipation D_x + D_y (Eq. 13), elastic energy U_el left in the
support at exit and its kinetic energy K:

    W = D_x + D_y + U_el + K                                    (Eq. 12, integrated)

which holds exactly for the true solution, so its residual measures the
integration error.
"""
from __future__ import annotations

import math

import numpy as np

from .params import Params

__all__ = ["potential_energy", "kinetic_energy", "elastic_energy"]


def potential_energy(params: Params, r, theta):
    """U = 1/2 k_r (r-1)^2 + 1/2 k_theta (theta-theta0)^2 + 1/2 exp(-r/lambda).

    The last term is the potential of the repulsion phi(r) of Eq. (3) (alpha = 1);
    its barrier at the pivot has height exactly 1/2 whatever lambda is.
    """
    r = np.asarray(r, dtype=float)
    dth = np.asarray(theta, dtype=float) - params.theta0
    return (0.5 * params.k_r * (r - 1.0) ** 2 + 0.5 * params.k_theta * dth**2
            + 0.5 * np.exp(-r / params.lam))


def elastic_energy(params: Params, r, theta, theta0=None):
    """U_el: potential energy relative to the initial state (r = 1, theta = theta0).

    ``theta0`` (array) overrides ``params.theta0`` for supports of several orientations.
    """
    if theta0 is not None:
        theta = np.asarray(theta, dtype=float) - np.asarray(theta0, dtype=float) + params.theta0
    # At the initial state only the repulsion term is non-zero: 1/2 exp(-1/lambda).
    return potential_energy(params, r, theta) - 0.5 * math.exp(-1.0 / params.lam)


def kinetic_energy(v_x, v_y):
    """K = 1/2 |v|^2 of the unit mass in the pivot's frame."""
    return 0.5 * (np.asarray(v_x, dtype=float) ** 2 + np.asarray(v_y, dtype=float) ** 2)
