"""Many contacts in one compiled call (orientation sweeps, array quadrature)."""
import numpy as np
from numba import njit

from .driver import N_STATS, integrate
from .rhs import N_STATE


@njit(cache=True, error_model="numpy")
def integrate_batch(Y0, Ps, rtol, atol, method, max_steps, tau_max, record):
    """Integrate row i from Y0[i] with parameters Ps[i].

    Returns (status, t, Y, stats, r_min) stacked over the rows, and the step nodes
    (see ``driver.integrate``) of the last row when ``record`` is set. This is the
    kernel's only entry point, so it is compiled once.
    """
    m = Y0.shape[0]
    status = np.empty(m, np.int64)
    t = np.empty(m)
    Y = np.empty((m, N_STATE))
    stats = np.empty((m, N_STATS), np.int64)
    r_min = np.empty(m)
    nodes = np.empty((1, 11))
    n_nodes = 0
    for i in range(m):
        st, ti, yi, si, ri, nodes, n_nodes = integrate(Y0[i], Ps[i], rtol, atol, method,
                                                       max_steps, tau_max, record)
        status[i] = st
        t[i] = ti
        for j in range(N_STATE):
            Y[i, j] = yi[j]
        for j in range(N_STATS):
            stats[i, j] = si[j]
        r_min[i] = ri
    return status, t, Y, stats, r_min, nodes, n_nodes
