"""Many contacts in one compiled call (orientation sweeps, array quadrature)."""
import math

import numpy as np
from numba import njit

from .driver import integrate, use_dop853
from .record import N_NODE_COLS
from .rhs import FN, K_R, K_TH, LAM, TH0
from .slots import D_X, D_Y, I_Y, N_STATE, N_STATS, S_R, S_TH, THETA, VX, VY, W, X, Y

#: Columns of the derived quantities returned per contact (see ``derived``).
DERIVED = ("F_x", "F_y", "U_el", "K", "energy_residual", "dtheta_rms", "dr_rms", "r_out")


@njit(cache=True, error_model="numpy")
def derived(y, t, P, out):
    """Eqs. (8), (12), (13) at the exit: mean friction over f_N, energies, residual, rms.

    U_el is the potential energy of ``model.contact.energy.elastic_energy`` (relative to the
    initial state); the tests check the two agree.
    """
    x, yy, vx, vy, th = y[X], y[Y], y[VX], y[VY], y[THETA]
    r = math.sqrt(x * x + yy * yy)
    dth = th - P[TH0]
    lam = P[LAM]
    U = (0.5 * P[K_R] * (r - 1.0) ** 2 + 0.5 * P[K_TH] * dth * dth
         + 0.5 * (math.exp(-r / lam) - math.exp(-1.0 / lam)))
    K = 0.5 * (vx * vx + vy * vy)
    inv = 1.0 / t if t > 0.0 else math.nan
    out[0] = y[W] * inv / P[FN]
    out[1] = y[I_Y] * inv / P[FN]
    out[2] = U
    out[3] = K
    out[4] = y[W] - (y[D_X] + y[D_Y] + U + K)
    out[5] = math.sqrt(max(y[S_TH], 0.0) * inv)
    out[6] = math.sqrt(max(y[S_R], 0.0) * inv)
    out[7] = r


@njit(cache=True, error_model="numpy")
def integrate_batch(Y0, Ps, rtol, atol, method, max_steps, tau_max, record):
    """Integrate row i from Y0[i] with parameters Ps[i].

    Returns (status, t, Y, D, stats, r_min, r_max) stacked over the rows (D: the ``DERIVED``
    quantities), and the step nodes (see ``driver.integrate``) of the last row when
    ``record`` is set. This is the kernel's only entry point, so it is compiled once.
    """
    m = Y0.shape[0]
    status = np.empty(m, np.int64)
    t = np.empty(m)
    Y = np.empty((m, N_STATE))
    D = np.empty((m, len(DERIVED)))
    stats = np.empty((m, N_STATS), np.int64)
    r_min = np.empty(m)
    r_max = np.empty(m)
    nodes = np.empty((1, N_NODE_COLS))
    n_nodes = 0
    high = use_dop853(rtol)
    for i in range(m):
        st, ti, yi, si, ri, rx, nodes, n_nodes = integrate(Y0[i], Ps[i], rtol, atol, method,
                                                       max_steps, tau_max, record, high)
        status[i] = st
        t[i] = ti
        for j in range(N_STATE):
            Y[i, j] = yi[j]
        for j in range(N_STATS):
            stats[i, j] = si[j]
        r_min[i] = ri
        r_max[i] = rx
        derived(yi, ti, Ps[i], D[i])
    return status, t, Y, D, stats, r_min, r_max, nodes, n_nodes
