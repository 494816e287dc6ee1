"""Dormand-Prince 8(5,3) step with 7th-order dense output (the pair of scipy's DOP853).

Coefficients: E. Hairer, S. P. Norsett, G. Wanner, Solving ODEs I (1993), II.10 (code
DOP853); read from scipy's copy at import. The error estimate combines the 5th- and
3rd-order embedded solutions as DOP853 does, err5^2 / sqrt(err5^2 + E3_WEIGHT err3^2),
with the 3rd-order weight E3_WEIGHT = 0.001 instead of DOP853's 0.01 (see below). The
dense output needs three more stages, taken only for a step in which the exit may lie
(``event.locate_exit``) and, in recording runs, for the nodes inside every step
(``record.record_inside``).

E3_WEIGHT. Where the motion crosses the steep part of mu(v) near v_R ~ 1/zeta, the
combined estimate with DOP853's weight can be far below the step's true error (the large
3rd-order estimate in the denominator shrinks it): in 30 551 steps over the four regimes
(13 orientations, beta = 1 and 0.234, rtol 1e-5 to 1e-7) 133 accepted steps had a local
error above the tolerance (true/tol up to ~500; such a step put tau_out of the slider at
theta0 = 300 deg, beta = 0.234, off by 2.5e-4 at rtol 1e-6). With 0.001 that count halves
(61 of 33 358) for ~8 % more right-hand-side evaluations at equal rtol. Rare steps with
errors above 10 tol remain (about 2 in 10 000 steps; the 5(4) pair's estimator: 1 in
10 000 of its shorter steps); the energy residual of every result still checks it.
"""
import math

import numpy as np
from numba import njit
from scipy.integrate._ivp import dop853_coefficients as _c

from .dopri5 import stage_stiffness
from .rhs import rhs, rhs_inline
from .slots import ERROR_SLOTS, N_ERROR, N_MOTION, N_STATE

ORDER = 8  # the step-size exponent is 1/ORDER (error estimator of order 7)
N_STAGES = _c.N_STAGES  # 12, plus f(y1) (FSAL)
N_ROWS = _c.N_STAGES_EXTENDED  # 16: with the three dense-output stages
A = np.ascontiguousarray(_c.A, dtype=float)
B = np.ascontiguousarray(_c.B, dtype=float)
C = np.ascontiguousarray(_c.C, dtype=float)
E3 = np.ascontiguousarray(_c.E3, dtype=float)
E5 = np.ascontiguousarray(_c.E5, dtype=float)
D = np.ascontiguousarray(_c.D, dtype=float)
N_POLY = _c.INTERPOLATOR_POWER  # 7
E3_WEIGHT = 1e-3  # DOP853: 0.01 (module docstring)


@njit(cache=True, error_model="numpy")
def step(y, f, h, P, K, ynew, ystage):
    """One step of size h from (y, f = f(y)).

    Fills K[0:13] (K[12] = f(ynew) for FSAL), ynew, and ystage, the argument of the
    last stage (at t0 + h, for the stiffness detector). The right-hand side reads
    only the motion, so the stage arguments are formed for the motion slots alone.
    """
    for i in range(N_STATE):
        K[0, i] = f[i]
    for s in range(1, N_STAGES):
        for i in range(N_MOTION):
            acc = 0.0
            for j in range(s):
                acc += A[s, j] * K[j, i]
            ystage[i] = y[i] + h * acc
        rhs_inline(ystage, P, K[s])
    for i in range(N_STATE):
        acc = 0.0
        for j in range(N_STAGES):
            acc += B[j] * K[j, i]
        ynew[i] = y[i] + h * acc
    rhs_inline(ynew, P, K[N_STAGES])


@njit(cache=True, error_model="numpy", inline="always")
def error_norm(h, K, y, ynew, rtol, atol):
    """DOP853's error norm over ``ERROR_SLOTS``; inf if the new state is non-finite."""
    for i in range(N_STATE):
        if not math.isfinite(ynew[i]):
            return np.inf
    e5 = 0.0
    e3 = 0.0
    for k in range(N_ERROR):
        i = ERROR_SLOTS[k]
        sc = atol + rtol * max(abs(y[i]), abs(ynew[i]))
        a5 = 0.0
        a3 = 0.0
        for j in range(N_STAGES + 1):
            a5 += E5[j] * K[j, i]
            a3 += E3[j] * K[j, i]
        a5 /= sc
        a3 /= sc
        e5 += a5 * a5
        e3 += a3 * a3
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    v = abs(h) * e5 / math.sqrt((e5 + E3_WEIGHT * e3) * N_ERROR)
    return v if math.isfinite(v) else np.inf


@njit(cache=True, error_model="numpy")
def dense_stages(y, h, P, K, ystage):
    """The three extra stages K[13:16] of the dense output (motion arguments only)."""
    for s in range(N_STAGES + 1, N_ROWS):
        for i in range(N_MOTION):
            acc = 0.0
            for j in range(s):
                acc += A[s, j] * K[j, i]
            ystage[i] = y[i] + h * acc
        rhs(ystage, P, K[s])


@njit(cache=True, error_model="numpy", inline="always")
def poly(y, ynew, K, h, i, F):
    """F[0:7] of the dense output of component i (scipy's Dop853DenseOutput)."""
    dy = ynew[i] - y[i]
    F[0] = dy
    F[1] = h * K[0, i] - dy
    F[2] = 2.0 * dy - h * (K[N_STAGES, i] + K[0, i])
    for k in range(N_POLY - 3):
        acc = 0.0
        for j in range(N_ROWS):
            acc += D[k, j] * K[j, i]
        F[3 + k] = h * acc


@njit(cache=True, error_model="numpy", inline="always")
def poly_at(y0, F, th):
    v = 0.0
    for k in range(N_POLY):
        v += F[N_POLY - 1 - k]
        v *= th if k % 2 == 0 else 1.0 - th
    return y0 + v


@njit(cache=True, error_model="numpy", inline="always")
def poly_with_slope(y0, F, th):
    """The dense output at th (as ``poly_at``) and its derivative d/dtheta (= h dy/ds)."""
    v = 0.0
    dv = 0.0
    for k in range(N_POLY):
        v += F[N_POLY - 1 - k]
        if k % 2 == 0:
            dv = dv * th + v
            v *= th
        else:
            dv = dv * (1.0 - th) - v
            v *= 1.0 - th
    return y0 + v, dv


@njit(cache=True, error_model="numpy", inline="always")
def stiffness_ratio(h, K, ynew, ystage):
    """h |lambda| from the last stage and f(y1) (``dopri5.stage_stiffness``)."""
    return stage_stiffness(h, K, N_STAGES, ynew, ystage)
