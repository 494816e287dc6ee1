"""Right-hand side and analytic Jacobian of one support, Eqs. (3)-(6), compiled.

State vector (N_STATE = 11): the motion (x, y, v_x, v_y, theta) followed by six
quadratures integrated alongside it (MODEL.md, "What one contact yields"):

    5  W     = int F_f,x dtau             (slab work; the slab moves at speed 1)
    6  I_y   = int F_f,y dtau
    7  D_x   = -int F_f,x v_R,x dtau      (Eq. 13)
    8  D_y   = -int F_f,y v_R,y dtau
    9  int (theta - theta0)^2 dtau        (for Delta theta_rms, Fig. 10f)
    10 int (r - 1)^2 dtau                 (for Delta r_rms)

Parameters travel as one float array ``P`` (see ``pack`` in ``model/_kernel/__init__``).
"""
import math

import numpy as np
from numba import njit

N_STATE = 11
N_MOTION = 5
# Slots of the parameter array P.
K_R, K_TH, FN, TH0, MU_S, A_, B_, ZETA, LAM, L0, C0, C2, C4, C6, X0 = range(15)
N_PARAM = 15
# Below this zeta*s the Taylor series of mu(s)/s is used (no 0/0 at v_R = 0).
SERIES_BELOW = 1e-3


@njit(cache=True, error_model="numpy", inline="always")
def copy_into(dst, src):
    """dst[:] = src as a loop: numba's slice assignment compiles a costly error path."""
    for i in range(dst.shape[0]):
        dst[i] = src[i]


@njit(cache=True, error_model="numpy", inline="always")
def mu_over_s(s, P):
    """m(s) = mu(s)/s of Eq. (4), smooth through s = 0."""
    z = P[ZETA] * s
    if z < SERIES_BELOW:
        z2 = z * z
        return P[MU_S] * P[ZETA] * (P[C0] + z2 * (P[C2] + z2 * (P[C4] + z2 * P[C6])))
    u = z - P[B_] * (z - math.atan(z))
    return P[MU_S] * math.sin(P[A_] * math.atan(u)) / s


@njit(cache=True, error_model="numpy")
def mu_over_s_and_slope(s, P):
    """m(s) = mu(s)/s and (dm/ds)/s, both smooth through s = 0 (for the Jacobian)."""
    zeta = P[ZETA]
    z = zeta * s
    if z < SERIES_BELOW:
        z2 = z * z
        m = P[MU_S] * zeta * (P[C0] + z2 * (P[C2] + z2 * (P[C4] + z2 * P[C6])))
        dm_s = P[MU_S] * zeta * zeta * zeta * (2 * P[C2] + z2 * (4 * P[C4] + 6 * z2 * P[C6]))
        return m, dm_s
    u = z - P[B_] * (z - math.atan(z))
    Aw = P[A_] * math.atan(u)
    mu = P[MU_S] * math.sin(Aw)
    du_dz = 1.0 - P[B_] * z * z / (1.0 + z * z)
    dmu_ds = P[MU_S] * math.cos(Aw) * P[A_] * du_dz / (1.0 + u * u) * zeta
    return mu / s, (dmu_ds * s - mu) / (s * s * s)


@njit(cache=True, error_model="numpy", inline="always")
def _elastic(x, y, dth, P):
    """q = g(r)/r, p = -k_theta (theta - theta0)/r^2 with g(r) = -k_r (r-1) + phi(r).

    The elastic acceleration of Eq. (5) is q (x, y) + p (-y, x). At r = 0 exactly
    the direction is undefined; both terms are set to zero there (a measure-zero
    point that a trajectory only meets when it runs exactly through the pivot).
    """
    r2 = x * x + y * y
    if r2 == 0.0:
        return 0.0, 0.0, 0.0, 0.0
    r = math.sqrt(r2)
    phi = math.exp(-r / P[LAM]) / (2.0 * P[LAM])
    g = -P[K_R] * (r - 1.0) + phi
    return g / r, -P[K_TH] * dth / r2, r, phi


@njit(cache=True, error_model="numpy")
def rhs(u, P, out):
    """du/dtau for the 11-component state (Eqs. 5, 6 and the quadratures)."""
    x, y, vx, vy, th = u[0], u[1], u[2], u[3], u[4]
    dth = th - P[TH0]
    q, p, r, _ = _elastic(x, y, dth, P)
    vrx = vx - 1.0
    s = math.sqrt(vrx * vrx + vy * vy)
    c = -P[FN] * mu_over_s(s, P)
    Fx = c * vrx
    Fy = c * vy
    out[0] = vx
    out[1] = vy
    out[2] = q * x - p * y + Fx
    out[3] = q * y + p * x + Fy
    out[4] = (x * vy - y * vx) / (r * r) if r > 0.0 else 0.0
    out[5] = Fx
    out[6] = Fy
    out[7] = -Fx * vrx
    out[8] = -Fy * vy
    out[9] = dth * dth
    out[10] = (r - 1.0) * (r - 1.0)


@njit(cache=True, error_model="numpy")
def jacobian(u, P, J):
    """J[i, j] = d(du_i/dtau)/du_j for all 11 rows and the 5 motion columns.

    The quadratures never feed back, so their columns are zero and omitted.
    """
    x, y, vx, vy, th = u[0], u[1], u[2], u[3], u[4]
    dth = th - P[TH0]
    for i in range(J.shape[0]):
        for j in range(J.shape[1]):
            J[i, j] = 0.0
    J[0, 2] = 1.0
    J[1, 3] = 1.0
    q, p, r, phi = _elastic(x, y, dth, P)
    if r > 0.0:
        r2 = r * r
        g = q * r
        qp = ((-P[K_R] - phi / P[LAM]) * r - g) / r2  # dq/dr
        pp = -2.0 * p / r  # dp/dr
        pth = -P[K_TH] / r2  # dp/dtheta
        xr = x / r
        yr = y / r
        J[2, 0] = q + x * qp * xr - y * pp * xr
        J[2, 1] = x * qp * yr - p - y * pp * yr
        J[3, 0] = y * qp * xr + p + x * pp * xr
        J[3, 1] = q + y * qp * yr + x * pp * yr
        J[2, 4] = -y * pth
        J[3, 4] = x * pth
        L = x * vy - y * vx
        J[4, 0] = vy / r2 - 2.0 * L * x / (r2 * r2)
        J[4, 1] = -vx / r2 - 2.0 * L * y / (r2 * r2)
        J[4, 2] = -y / r2
        J[4, 3] = x / r2
        J[10, 0] = 2.0 * (r - 1.0) * xr
        J[10, 1] = 2.0 * (r - 1.0) * yr
    vrx = vx - 1.0
    s = math.sqrt(vrx * vrx + vy * vy)
    m, dm_s = mu_over_s_and_slope(s, P)
    fN = P[FN]
    Fx = -fN * m * vrx
    Fy = -fN * m * vy
    # dF/dv_R = -f_N (m I + (dm/ds)/s v_R v_R^T)
    F00 = -fN * (m + dm_s * vrx * vrx)
    F01 = -fN * dm_s * vrx * vy
    F11 = -fN * (m + dm_s * vy * vy)
    J[2, 2] += F00
    J[2, 3] += F01
    J[3, 2] += F01
    J[3, 3] += F11
    J[5, 2] = F00
    J[5, 3] = F01
    J[6, 2] = F01
    J[6, 3] = F11
    J[7, 2] = -(F00 * vrx + Fx)
    J[7, 3] = -F01 * vrx
    J[8, 2] = -F01 * vy
    J[8, 3] = -(F11 * vy + Fy)
    J[9, 4] = 2.0 * dth


@njit(cache=True, error_model="numpy", inline="always")
def exit_gap(t, x, P):
    """Slid distance minus L0, s(tau) - L0 with s = tau - (x - x0) (Eq. 9); >= 0 ends contact."""
    return t - (x - P[X0]) - P[L0]


def empty_jacobian():
    return np.zeros((N_STATE, N_MOTION))
