"""Dormand-Prince 5(4) step with 4th-order dense output (the pair of scipy's RK45).

Coefficients: J. R. Dormand, P. J. Prince, J. Comput. Appl. Math. 6 (1980); the
dense-output matrix is Shampine's (Math. Comp. 46, 1986), as used by scipy.
``tests/test_kernel.py`` checks them against scipy's copy.
"""
import math

import numpy as np
from numba import njit

from .rhs import N_STATE, copy_into, rhs

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


@njit(cache=True, error_model="numpy")
def step(y, f, h, P, K, ynew, err, ystage):
    """One step of size h from (y, f = f(y)).

    Fills K (7 stages, K[6] = f(ynew) for FSAL), ynew, the error estimate err and
    ystage, the argument of stage 6 (used by the stiffness detector).
    """
    n = N_STATE
    copy_into(K[0], f)
    for s in range(1, 6):
        for i in range(n):
            acc = 0.0
            for j in range(s):
                acc += A[s, j] * K[j, i]
            ystage[i] = y[i] + h * acc
        rhs(ystage, P, K[s])
    for i in range(n):
        acc = 0.0
        for j in range(6):
            acc += B[j] * K[j, i]
        ynew[i] = y[i] + h * acc
    rhs(ynew, P, K[6])
    for i in range(n):
        acc = 0.0
        for j in range(7):
            acc += E[j] * K[j, i]
        err[i] = h * acc


@njit(cache=True, error_model="numpy", inline="always")
def dense_component(y, K, h, theta, i):
    """Component i of the 4th-order continuous extension at t0 + theta h."""
    acc = 0.0
    for j in range(7):
        pj = P_DENSE[j]
        acc += K[j, i] * theta * (pj[0] + theta * (pj[1] + theta * (pj[2] + theta * pj[3])))
    return y[i] + h * acc


@njit(cache=True, error_model="numpy", inline="always")
def stiffness_ratio(h, K, ynew, ystage):
    """h |lambda| estimated from stages 6 and 7, both at t0 + h (Hairer & Wanner, IV.2)."""
    num = 0.0
    den = 0.0
    for i in range(5):
        d = K[6, i] - K[5, i]
        num += d * d
        e = ynew[i] - ystage[i]
        den += e * e
    if den <= 0.0:
        return 0.0
    return h * math.sqrt(num / den)
