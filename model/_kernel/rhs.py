"""Right-hand side and analytic Jacobian of one support, Eqs. (3)-(6), compiled.

State vector (N_STATE = 12, slots named in ``slots``): the motion (x, y, v_x, v_y,
theta), six quadratures integrated alongside it, and the time tau.

Pivot regularisation (Sundman transformation). The independent variable is s with
dtau/ds = w(r) = (r^2 + DELTA^2) / (r^2 + R_S^2), and every derivative is multiplied by
w. This is the same ODE, reparametrised: near the pivot the terms k_theta (theta -
theta0)/r and theta' = (x v_y - y v_x)/r^2, which grow without bound, become bounded,
so a support driven through the region of its pivot is resolved in s where it would
need steps below the resolution of tau. Away from the pivot w = 1 to within
R_S^2/r^2 = 1e-12 (r ~ 1). DELTA > 0 keeps w(0) > 0. A support starting exactly on the
x-axis moves on it for all time (the torsional terms vanish identically) and meets only
the cusp of the repulsion at the pivot, which the transformation would merely slow
down: for it P[REG] = 0 and w = 1.

Parameters travel as one float array ``P`` (see ``pack`` in ``model/_kernel/__init__``).
"""
import math

from numba import njit

from .slots import D_X, D_Y, I_Y, N_MOTION, N_STATE, S_R, S_TH, TAU, THETA, VX, VY, W, X, Y

R_S = 1e-6
DELTA = 1e-14
# Slots of the parameter array P.
K_R, K_TH, FN, TH0, MU_S, A_, B_, ZETA, LAM, L0, C0, C2, C4, C6, X0, REG = range(16)
N_PARAM = 16
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


@njit(cache=True, error_model="numpy", inline="always")
def sundman(r2, P):
    """w = dtau/ds and (dw/dr)/r at r^2 = r2 (see the module docstring)."""
    if P[REG] == 0.0:
        return 1.0, 0.0
    den = r2 + R_S * R_S
    return (r2 + DELTA * DELTA) / den, 2.0 * (R_S * R_S - DELTA * DELTA) / (den * den)


def _rhs(u, P, out):
    """du/ds for the 12-component state: w(r) times Eqs. (5), (6), the quadratures, 1."""
    x, y, vx, vy, th = u[X], u[Y], u[VX], u[VY], u[THETA]
    dth = th - P[TH0]
    # _elastic inlined with one division by r^2 shared by q, p and theta'.
    r2 = x * x + y * y
    if r2 > 0.0:
        r = math.sqrt(r2)
        inv_r2 = 1.0 / r2
        lam = P[LAM]
        g = -P[K_R] * (r - 1.0) + math.exp(-r / lam) / (2.0 * lam)
        q = g * r * inv_r2
        p = -P[K_TH] * dth * inv_r2
        om = (x * vy - y * vx) * inv_r2
    else:
        r = q = p = om = 0.0
    vrx = vx - 1.0
    s = math.sqrt(vrx * vrx + vy * vy)
    c = -P[FN] * mu_over_s(s, P)
    Fx = c * vrx
    Fy = c * vy
    w, _ = sundman(r2, P)
    out[X] = w * vx
    out[Y] = w * vy
    out[VX] = w * (q * x - p * y + Fx)
    out[VY] = w * (q * y + p * x + Fy)
    out[THETA] = w * om
    out[W] = w * Fx
    out[I_Y] = w * Fy
    out[D_X] = -w * Fx * vrx
    out[D_Y] = -w * Fy * vy
    out[S_TH] = w * dth * dth
    out[S_R] = w * (r - 1.0) * (r - 1.0)
    out[TAU] = w


rhs = njit(cache=True, error_model="numpy")(_rhs)
#: The same, inlined where it is called: the stages of the explicit pair (~15 % of a step).
rhs_inline = njit(cache=True, error_model="numpy", inline="always")(_rhs)


@njit(cache=True, error_model="numpy")
def jacobian(u, P, f, J):
    """J[i, j] = d(du_i/ds)/du_j for all 12 rows and the 5 motion columns.

    ``f`` is ``rhs(u)``, the w-scaled derivative. The quadratures and tau never feed
    back, so their columns are zero and omitted.
    """
    x, y, vx, vy, th = u[X], u[Y], u[VX], u[VY], u[THETA]
    dth = th - P[TH0]
    for i in range(J.shape[0]):
        for j in range(J.shape[1]):
            J[i, j] = 0.0
    J[X, VX] = 1.0
    J[Y, VY] = 1.0
    q, p, r, phi = _elastic(x, y, dth, P)
    if r > 0.0:
        r2 = r * r
        g = q * r
        qp = ((-P[K_R] - phi / P[LAM]) * r - g) / r2  # dq/dr
        pp = -2.0 * p / r  # dp/dr
        pth = -P[K_TH] / r2  # dp/dtheta
        xr = x / r
        yr = y / r
        J[VX, X] = q + x * qp * xr - y * pp * xr
        J[VX, Y] = x * qp * yr - p - y * pp * yr
        J[VY, X] = y * qp * xr + p + x * pp * xr
        J[VY, Y] = q + y * qp * yr + x * pp * yr
        J[VX, THETA] = -y * pth
        J[VY, THETA] = x * pth
        L = x * vy - y * vx
        J[THETA, X] = vy / r2 - 2.0 * L * x / (r2 * r2)
        J[THETA, Y] = -vx / r2 - 2.0 * L * y / (r2 * r2)
        J[THETA, VX] = -y / r2
        J[THETA, VY] = x / r2
        J[S_R, X] = 2.0 * (r - 1.0) * xr
        J[S_R, Y] = 2.0 * (r - 1.0) * yr
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
    J[VX, VX] += F00
    J[VX, VY] += F01
    J[VY, VX] += F01
    J[VY, VY] += F11
    J[W, VX] = F00
    J[W, VY] = F01
    J[I_Y, VX] = F01
    J[I_Y, VY] = F11
    J[D_X, VX] = -(F00 * vrx + Fx)
    J[D_X, VY] = -F01 * vrx
    J[D_Y, VX] = -F01 * vy
    J[D_Y, VY] = -(F11 * vy + Fy)
    J[S_TH, THETA] = 2.0 * dth
    # Product rule for w(r) f: J <- w J + f (grad w)^T, grad w = (dw/dr / r) (x, y).
    w, dw_r = sundman(x * x + y * y, P)
    for i in range(N_STATE):
        fi = f[i] / w
        for j in range(N_MOTION):
            J[i, j] *= w
        J[i, X] += fi * dw_r * x
        J[i, Y] += fi * dw_r * y


@njit(cache=True, error_model="numpy", inline="always")
def exit_gap(t, x, P):
    """Slid distance minus L0, s(tau) - L0 with s = tau - (x - x0) (Eq. 9); >= 0 ends contact."""
    return t - (x - P[X0]) - P[L0]
