"""Rodas4: L-stable, stiffly accurate Rosenbrock method of order 4(3), 6 stages.

Coefficients of E. Hairer and G. Wanner, Solving ODEs II (1996), Sec. IV.7
(their code RODAS, METH=1), in the form

    (I/(h gamma) - J) k_i = f(y0 + sum_j a_ij k_j) + sum_j (c_ij / h) k_j,
    y1 = y0 + sum_j b_j k_j,   error estimate = k_6.

The Jacobian J is exact (``rhs.jacobian``). Only the 5x5 motion block is
factorised: the quadrature rows have zero columns, so their stage values follow
from the motion ones by a product (block elimination).
"""
import math

import numpy as np
from numba import njit

from .rhs import N_MOTION, N_STATE, copy_into, rhs

ORDER = 4
GAMMA = 0.25
A = np.zeros((6, 6))
A[1, 0] = 1.544
A[2, 0], A[2, 1] = 0.9466785280815826, 0.2557011698983284
A[3, 0], A[3, 1], A[3, 2] = 3.314825187068521, 2.896124015972201, 0.9986419139977817
A[4, 0], A[4, 1], A[4, 2], A[4, 3] = (1.221224509226641, 6.019134481288629,
                                      12.53708332932087, -0.6878860361058950)
A[5, :4] = A[4, :4]
A[5, 4] = 1.0
C = np.zeros((6, 6))
C[1, 0] = -5.6688
C[2, 0], C[2, 1] = -2.430093356833875, -0.2063599157091915
C[3, 0], C[3, 1], C[3, 2] = -0.1073529058151375, -9.594562251023355, -20.47028614809616
C[4, 0], C[4, 1], C[4, 2], C[4, 3] = (7.496443313967647, -10.24680431464352,
                                      -33.99990352819905, 11.70890893206160)
C[5, 0], C[5, 1], C[5, 2], C[5, 3], C[5, 4] = (8.083246795921522, -7.981132988064893,
                                               -31.52159432874371, 16.31930543123136,
                                               -6.058818238834054)


@njit(cache=True, error_model="numpy")
def lu_factor(M, piv):
    """In-place LU with partial pivoting of the small dense matrix M; False if singular.

    The diagonal of U is stored inverted (``lu_solve`` multiplies by it)."""
    n = M.shape[0]
    for k in range(n):
        p = k
        big = abs(M[k, k])
        for i in range(k + 1, n):
            if abs(M[i, k]) > big:
                big = abs(M[i, k])
                p = i
        if big == 0.0 or not math.isfinite(big):
            return False
        piv[k] = p
        if p != k:
            for j in range(n):
                M[k, j], M[p, j] = M[p, j], M[k, j]
        inv = 1.0 / M[k, k]
        M[k, k] = inv
        for i in range(k + 1, n):
            M[i, k] *= inv
            for j in range(k + 1, n):
                M[i, j] -= M[i, k] * M[k, j]
    return True


@njit(cache=True, error_model="numpy", inline="always")
def lu_solve(M, piv, b):
    """Solve in place with the factors of ``lu_factor`` (its diagonal holds 1/U_kk).

    ``lu_factor`` swaps whole rows (the multipliers of earlier columns too), so it
    factors P M = L U: every row swap is applied to b before the forward substitution.
    """
    n = M.shape[0]
    for k in range(n):
        p = piv[k]
        if p != k:
            b[k], b[p] = b[p], b[k]
    for k in range(n):
        for i in range(k + 1, n):
            b[i] -= M[i, k] * b[k]
    for k in range(n - 1, -1, -1):
        for j in range(k + 1, n):
            b[k] -= M[k, j] * b[j]
        b[k] *= M[k, k]


@njit(cache=True, error_model="numpy", inline="always")
def _solve_stage(M, piv, J, hg, b, k):
    """k = (I/(h gamma) - J)^-1 b for the block-triangular matrix (see module doc)."""
    for i in range(N_MOTION):
        k[i] = b[i]
    lu_solve(M, piv, k[:N_MOTION])
    for i in range(N_MOTION, N_STATE):
        acc = b[i]
        for j in range(N_MOTION):
            acc += J[i, j] * k[j]
        k[i] = hg * acc


@njit(cache=True, error_model="numpy")
def step(y, f, h, P, J, M, piv, Kr, ynew, err, ystage, b):
    """One Rodas4 step of size h from (y, f = f(y)) with Jacobian J at y.

    Returns False when I/(h gamma) - J is singular (the caller rejects the step).
    """
    hg = h * GAMMA
    inv_h = 1.0 / h
    inv_hg = 1.0 / hg
    for i in range(N_MOTION):
        for j in range(N_MOTION):
            M[i, j] = -J[i, j]
        M[i, i] += inv_hg
    if not lu_factor(M, piv):
        return False
    for s in range(6):
        if s == 0:
            copy_into(b, f)
        else:
            for i in range(N_STATE):
                acc = 0.0
                for j in range(s):
                    acc += A[s, j] * Kr[j, i]
                ystage[i] = y[i] + acc
            rhs(ystage, P, b)
            for i in range(N_STATE):
                acc = 0.0
                for j in range(s):
                    acc += C[s, j] * Kr[j, i]
                b[i] += acc * inv_h
        _solve_stage(M, piv, J, hg, b, Kr[s])
    for i in range(N_STATE):
        ynew[i] = ystage[i] + Kr[5, i]
        err[i] = Kr[5, i]
    return True
