"""Dormand-Prince 5(4) step with 4th-order dense output (the pair of scipy's RK45).

Coefficients: J. R. Dormand, P. J. Prince, J. Comput. Appl. Math. 6 (1980); the
dense-output matrix is Shampine's (Math. Comp. 46, 1986), as used by scipy.
``tests/test_kernel.py`` checks them against scipy's copy.
"""
import math

import numpy as np
from numba import njit

from .rhs import rhs
from .slots import ERROR_SLOTS, N_ERROR, N_MOTION, N_STATE

ORDER = 5
A = np.array([
    [0.0, 0.0, 0.0, 0.0, 0.0],
    [1 / 5, 0.0, 0.0, 0.0, 0.0],
    [3 / 40, 9 / 40, 0.0, 0.0, 0.0],
    [44 / 45, -56 / 15, 32 / 9, 0.0, 0.0],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0.0],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656],
])
B = np.array([35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84])
E = np.array([-71 / 57600, 0.0, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525, 1 / 40])
P_DENSE = np.array([
    [1.0, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432],
    [0.0, 0.0, 0.0, 0.0],
    [0.0, 131558114200 / 32700410799, -68118460800 / 10900136933, 87487479700 / 32700410799],
    [0.0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072],
    [0.0, 127303824393 / 49829197408, -318862633887 / 49829197408, 701980252875 / 199316789632],
    [0.0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
    [0.0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423],
])


# The coefficients as scalars, so that the compiled step holds them as constants.
A21 = A[1, 0]
A31, A32 = A[2, 0], A[2, 1]
A41, A42, A43 = A[3, 0], A[3, 1], A[3, 2]
A51, A52, A53, A54 = A[4, 0], A[4, 1], A[4, 2], A[4, 3]
A61, A62, A63, A64, A65 = A[5, 0], A[5, 1], A[5, 2], A[5, 3], A[5, 4]
B1, B3, B4, B5, B6 = B[0], B[2], B[3], B[4], B[5]
E1, E3, E4, E5, E6, E7 = E[0], E[2], E[3], E[4], E[5], E[6]


@njit(cache=True, error_model="numpy")
def step(y, f, h, P, K, ynew, err, ystage):
    """One step of size h from (y, f = f(y)).

    Fills K (7 stages, K[6] = f(ynew) for FSAL), ynew, the error estimate err on
    ``ERROR_SLOTS`` and ystage, the argument of stage 6 (used by the stiffness
    detector). The right-hand side reads only the motion, so the stage arguments are
    formed for the motion slots alone; the quadratures and tau enter ynew only.
    """
    m = N_MOTION
    # The stages are read as K[j, i]: row views cost ~10 % of a step.
    for i in range(N_STATE):
        K[0, i] = f[i]
    for i in range(m):
        ystage[i] = y[i] + h * A21 * K[0, i]
    rhs(ystage, P, K[1])
    for i in range(m):
        ystage[i] = y[i] + h * (A31 * K[0, i] + A32 * K[1, i])
    rhs(ystage, P, K[2])
    for i in range(m):
        ystage[i] = y[i] + h * (A41 * K[0, i] + A42 * K[1, i] + A43 * K[2, i])
    rhs(ystage, P, K[3])
    for i in range(m):
        ystage[i] = y[i] + h * (A51 * K[0, i] + A52 * K[1, i] + A53 * K[2, i] + A54 * K[3, i])
    rhs(ystage, P, K[4])
    for i in range(m):
        ystage[i] = y[i] + h * (A61 * K[0, i] + A62 * K[1, i] + A63 * K[2, i] + A64 * K[3, i]
                                + A65 * K[4, i])
    rhs(ystage, P, K[5])
    for i in range(N_STATE):
        ynew[i] = y[i] + h * (B1 * K[0, i] + B3 * K[2, i] + B4 * K[3, i] + B5 * K[4, i]
                              + B6 * K[5, i])
    rhs(ynew, P, K[6])
    for k in range(N_ERROR):
        i = ERROR_SLOTS[k]
        err[i] = h * (E1 * K[0, i] + E3 * K[2, i] + E4 * K[3, i] + E5 * K[4, i] + E6 * K[5, i]
                      + E7 * K[6, i])


@njit(cache=True, error_model="numpy", inline="always")
def dense_component(y, K, h, theta, i):
    """Component i of the 4th-order continuous extension at t0 + theta h."""
    acc = 0.0
    for j in range(7):
        pj = P_DENSE[j]
        acc += K[j, i] * theta * (pj[0] + theta * (pj[1] + theta * (pj[2] + theta * pj[3])))
    return y[i] + h * acc


@njit(cache=True, error_model="numpy", inline="always")
def stage_stiffness(h, K, last, ynew, ystage):
    """h |lambda| from K[last] = f(ynew) and K[last - 1] = f(ystage), both at t0 + h
    (Hairer & Wanner, IV.2), over the motion slots; used by both explicit pairs."""
    num = 0.0
    den = 0.0
    for i in range(N_MOTION):
        d = K[last, i] - K[last - 1, i]
        num += d * d
        e = ynew[i] - ystage[i]
        den += e * e
    if den <= 0.0:
        return 0.0
    return h * math.sqrt(num / den)


@njit(cache=True, error_model="numpy", inline="always")
def stiffness_ratio(h, K, ynew, ystage):
    """h |lambda| estimated from stages 6 and 7 (``stage_stiffness``)."""
    return stage_stiffness(h, K, 6, ynew, ystage)
