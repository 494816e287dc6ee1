"""Adaptive integration of one contact until the exit event of Eq. (9).

Methods: 1 = explicit DOP853 (Dormand-Prince 8(5,3)), 2 = implicit Rodas4, 0 = automatic:
start explicit, switch to Rodas4 when the stiffness detector of Hairer & Wanner
(IV.2) fires repeatedly, and back when h ||J|| shows the explicit pair would be
stable at the current step.

The exit is located on the dense output of the accepted step (first crossing of
s(tau) = L0, scanning the step when s may cross and re-cross: DOP853's 7th-order
output, cubic Hermite after a Rodas4 step), then the step is
retaken exactly to the located time, so the exit state has the method's full
accuracy rather than the interpolant's.
"""
import math

import numpy as np
from numba import njit

from . import dop853, rodas4
from .record import N_NODE_COLS, N_SUB, record as _record, record_inside
from .rhs import copy_into, exit_gap, jacobian, rhs
from .slots import (ERROR_SLOTS, N_ERROR, N_MOTION, N_STATE, N_STATS, NONFINITE, OK, ST_ACC,
                    ST_ACC_EXPL, ST_ACC_IMPL, ST_JAC, ST_LU, ST_REJ, ST_RHS, ST_SWITCH,
                    STEP_BUDGET, STEP_UNDERFLOW, TAU, TIME_BUDGET, VX, X, Y)

SAFETY = 0.9
STIFF_HLAMBDA = 6.1  # DOP853 stability boundary on the negative real axis (Hairer's DOP853)
STIFF_COUNT = 15
NONSTIFF_HNORM = 2.0  # back to explicit when h ||J||_inf stays below this
NONSTIFF_COUNT = 5
# Within this radius of the pivot the motion is fast and non-smooth (the cusp of the
# repulsion, the torsional barrier): ``auto`` uses the explicit pair there.
PIVOT_EXPLICIT = 1e-3
SCAN_POINTS = 8
# PI step-size control (Gustafsson; Hairer & Wanner I, IV.2): the explicit pair uses
# err^-(1/8 - 0.75 BETA) * err_old^BETA, which damps the accept/reject oscillation.
PI_BETA = 0.04
LOG_EN_FLOOR = math.log(1e-4)  # err_old is taken as at least 1e-4


@njit(cache=True, error_model="numpy", inline="always")
def _err_norm(err, y, ynew, rtol, atol):
    """RMS of the scaled error over ``ERROR_SLOTS`` (the motion and tau); inf if non-finite."""
    for i in range(N_STATE):
        if not math.isfinite(ynew[i]):
            return np.inf
    acc = 0.0
    for k in range(N_ERROR):
        i = ERROR_SLOTS[k]
        sc = atol + rtol * max(abs(y[i]), abs(ynew[i]))
        e = err[i] / sc
        acc += e * e
    v = math.sqrt(acc / N_ERROR)
    return v if math.isfinite(v) else np.inf


@njit(cache=True, error_model="numpy")
def _initial_step(y, f, P, rtol, atol, order, work, fwork):
    """Hairer & Wanner's starting step (Solving ODEs I, II.4), on ``ERROR_SLOTS``."""
    d0 = 0.0
    d1 = 0.0
    for k in range(N_ERROR):
        i = ERROR_SLOTS[k]
        sc = atol + rtol * abs(y[i])
        d0 += (y[i] / sc) ** 2
        d1 += (f[i] / sc) ** 2
    d0 = math.sqrt(d0 / N_ERROR)
    d1 = math.sqrt(d1 / N_ERROR)
    h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    for i in range(N_STATE):
        work[i] = y[i] + h0 * f[i]
    rhs(work, P, fwork)
    d2 = 0.0
    for k in range(N_ERROR):
        i = ERROR_SLOTS[k]
        sc = atol + rtol * abs(y[i])
        d2 += ((fwork[i] - f[i]) / sc) ** 2
    d2 = math.sqrt(d2 / N_ERROR) / h0
    dm = max(d1, d2)
    h1 = max(1e-6, h0 * 1e-3) if dm <= 1e-15 else math.exp(math.log(0.01 / dm) / (order + 1))
    return min(100 * h0, h1)


@njit(cache=True, error_model="numpy", inline="always")
def _hermite(y0, f0, y1, f1, h, th, i):
    """Cubic Hermite interpolant of component i: the dense output used with Rodas4."""
    h00 = (1 + 2 * th) * (1 - th) ** 2
    h10 = th * (1 - th) ** 2
    h01 = th * th * (3 - 2 * th)
    h11 = th * th * (th - 1)
    return h00 * y0[i] + h10 * h * f0[i] + h01 * y1[i] + h11 * h * f1[i]


@njit(cache=True, error_model="numpy", inline="always")
def _hermite_slope(y0, f0, y1, f1, h, th, i):
    """d/dtheta of ``_hermite`` (component i)."""
    return ((6 * th * th - 6 * th) * (y0[i] - y1[i]) + (3 * th * th - 4 * th + 1) * h * f0[i]
            + (3 * th * th - 2 * th) * h * f1[i])


@njit(cache=True, error_model="numpy", inline="always")
def _radial_rate(y0, f0, y1, f1, h, th):
    """(r dr/dtheta, r) on the cubic Hermite interpolant of x and y over the step."""
    x = _hermite(y0, f0, y1, f1, h, th, X)
    yy = _hermite(y0, f0, y1, f1, h, th, Y)
    return (x * _hermite_slope(y0, f0, y1, f1, h, th, X)
            + yy * _hermite_slope(y0, f0, y1, f1, h, th, Y)), math.sqrt(x * x + yy * yy)


@njit(cache=True, error_model="numpy")
def _r_inside(y0, f0, y1, f1, h):
    """r at an extremum of r inside the step (r dr/ds changes sign), or -1 if none.

    The accepted steps alone would miss a turning point of r by up to the step's length:
    r_min and r_max are refined on the cubic Hermite interpolant of x and y (error O(h^4))
    by the Illinois method on r dr/dtheta."""
    glo = y0[X] * f0[X] + y0[Y] * f0[Y]
    ghi = y1[X] * f1[X] + y1[Y] * f1[Y]
    if not (glo * ghi < 0.0):
        return -1.0
    lo, hi = 0.0, 1.0
    r = -1.0
    side = 0
    for _ in range(60):
        th = (lo * ghi - hi * glo) / (ghi - glo)
        if not (lo < th < hi):
            th = 0.5 * (lo + hi)
        g, r = _radial_rate(y0, f0, y1, f1, h, th)
        if g == 0.0 or hi - lo <= 1e-12:
            break
        if (g < 0.0) == (glo < 0.0):
            lo, glo = th, g
            if side == -1:
                ghi *= 0.5
            side = -1
        else:
            hi, ghi = th, g
            if side == 1:
                glo *= 0.5
            side = 1
    return r


@njit(cache=True, error_model="numpy", inline="always")
def _gap_at(th, h, y, f, ynew, fnew, P):
    x = _hermite(y, f, ynew, fnew, h, th, X)
    tau = _hermite(y, f, ynew, fnew, h, th, TAU)
    return exit_gap(tau, x, P)


@njit(cache=True, error_model="numpy")
def _locate_exit(h, y, f, ynew, fnew, P):
    """First theta in (0, 1] where the exit gap crosses zero after a Rodas4 step, or -1.

    (``dop853.locate_exit`` does the same on the explicit pair's dense output.)

    Scans the step when s(tau) ends above L0 or may have a maximum inside
    (v_x crosses 1), then refines the first bracket by the Illinois method.
    """
    g1 = exit_gap(ynew[TAU], ynew[X], P)
    may_peak = (y[VX] < 1.0) and (ynew[VX] > 1.0)
    if g1 < 0.0 and not may_peak:
        return -1.0
    lo = 0.0
    glo = exit_gap(y[TAU], y[X], P)
    hi = -1.0
    ghi = 0.0
    for k in range(1, SCAN_POINTS + 1):
        th = k / SCAN_POINTS
        g = g1 if k == SCAN_POINTS else _gap_at(th, h, y, f, ynew, fnew, P)
        if g >= 0.0:
            hi = th
            ghi = g
            break
        lo = th
        glo = g
    if hi < 0.0:
        return -1.0
    side = 0
    for _ in range(200):
        if hi - lo <= 4e-16 * hi:
            break
        th = (lo * ghi - hi * glo) / (ghi - glo)
        if not (lo < th < hi):
            th = 0.5 * (lo + hi)
        g = _gap_at(th, h, y, f, ynew, fnew, P)
        if g >= 0.0:
            hi, ghi = th, g
            if side == 1:
                glo *= 0.5
            side = 1
        else:
            lo, glo = th, g
            if side == -1:
                ghi *= 0.5
            side = -1
        if g == 0.0:
            break
    return hi


@njit(cache=True, error_model="numpy", inline="always")
def _jac_norm(J):
    big = 0.0
    for i in range(N_MOTION):
        row = 0.0
        for j in range(N_MOTION):
            row += abs(J[i, j])
        big = max(big, row)
    return big


@njit(cache=True, error_model="numpy")
def integrate(y0, P, rtol, atol, method, max_steps, tau_max, record):
    """Integrate from y0 until the exit event, a budget, or a failure.

    Returns (status, t, y, stats, r_min, r_max, nodes, n_nodes); status codes are those
    named in ``slots`` (``model.results.Status``); r_min and r_max are the extremes of the
    distance r from the pivot over the contact (at the accepted steps and the turning
    points of r inside them, ``_r_inside``). ``nodes`` rows are (tau, the ``REC_SLOTS`` of the
    state, and their tau-derivatives) when ``record`` is set: at the accepted steps and
    inside the explicit ones (``record.record_inside``), every one or every 2^k-th once
    there are more than ``MAX_NODES``, and the last state.
    """
    n = N_STATE
    stats = np.zeros(N_STATS, np.int64)
    y = y0.copy()
    f = np.empty(n)
    ynew = np.empty(n)
    fnew = np.empty(n)
    err = np.empty(n)
    ystage = np.empty(n)
    ydense = np.empty(n)  # stage arguments of the dense output (ystage stays for the detector)
    ysub = np.empty(n if record else 1)
    fsub = np.empty(n if record else 1)
    b = np.empty(n)
    K = np.zeros((dop853.N_ROWS, n))
    FX = np.empty(dop853.N_POLY)
    FT = np.empty(dop853.N_POLY)
    Kr = np.zeros((6, n))
    J = np.zeros((n, N_MOTION))
    M = np.empty((N_MOTION, N_MOTION))
    piv = np.zeros(N_MOTION, np.int64)
    rhs(y, P, f)
    implicit = method == 2
    dense_done = False
    h = _initial_step(y, f, P, rtol, atol, 4 if implicit else 8, ystage, fnew)
    stats[ST_RHS] += 2
    nodes = np.empty((256 if record else 1, N_NODE_COLS))
    n_nodes = 0
    stride = 1
    if record:
        nodes, n_nodes, stride = _record(nodes, n_nodes, stride, 0, False, y, f)
    t = 0.0
    r_min = math.sqrt(y[X] * y[X] + y[Y] * y[Y])
    r_max = r_min
    stiff = 0
    nonstiff = 0
    easy = 0
    last_rejected = False
    log_en_old = LOG_EN_FLOOR
    nonfinite = False
    finishing = False
    fell_back = False
    status = -1
    while status < 0:
        if stats[ST_ACC] + stats[ST_REJ] >= max_steps:
            status = STEP_BUDGET
            break
        if y[TAU] >= tau_max:
            status = TIME_BUDGET
            break
        hmin = 16.0 * 2.220446049250313e-16 * max(1.0, abs(t))
        if h < hmin:
            if method == 0 and not fell_back:
                # The other method may resolve what this one cannot (pivot passage).
                fell_back = True
                implicit = not implicit
                stats[ST_SWITCH] += 1
                h = 1e6 * hmin
                continue
            status = NONFINITE if nonfinite else STEP_UNDERFLOW
            break
        if implicit:
            jacobian(y, P, f, J)
            stats[ST_JAC] += 1
            stats[ST_LU] += 1
            stats[ST_RHS] += 5
            ok = rodas4.step(y, f, h, P, J, M, piv, Kr, ynew, err, ystage, b)
            en = _err_norm(err, y, ynew, rtol, atol) if ok else np.inf
            expo = 1.0 / rodas4.ORDER
            maxfac = 6.0
        else:
            dop853.step(y, f, h, P, K, ynew, ystage)
            dense_done = False
            stats[ST_RHS] += 12
            en = dop853.error_norm(h, K, y, ynew, rtol, atol)
            expo = 1.0 / dop853.ORDER
            maxfac = 10.0
        if en > 1.0 and not finishing:
            stats[ST_REJ] += 1
            nonfinite = en == np.inf
            h *= 0.2 if nonfinite else max(0.2, SAFETY * math.exp(-expo * math.log(en)))
            last_rejected = True
            continue
        nonfinite = False
        if implicit:
            rhs(ynew, P, fnew)
            stats[ST_RHS] += 1
        else:
            for i in range(n):
                fnew[i] = K[dop853.N_STAGES, i]
        if finishing:
            status = OK
        else:
            if implicit:
                th = _locate_exit(h, y, f, ynew, fnew, P)
            else:
                th, extra = dop853.locate_exit(h, y, ynew, K, P, ydense, SCAN_POINTS, FX, FT)
                stats[ST_RHS] += extra
                dense_done = extra > 0
            if th > 0.0:
                # Retake this step exactly to the located exit time.
                h = th * h
                finishing = True
                continue
        stats[ST_ACC] += 1
        stats[ST_ACC_IMPL if implicit else ST_ACC_EXPL] += 1
        if record and not implicit:  # nodes inside the step, on its continuous extension
            if not dense_done:
                dop853.dense_stages(y, h, P, K, ydense)
                stats[ST_RHS] += 3
            nodes, n_nodes, stride = record_inside(nodes, n_nodes, stride,
                                                   (stats[ST_ACC] - 1) * N_SUB, y, ynew, K, h,
                                                   FX, ysub, fsub)
        switched = False
        r_new = math.sqrt(ynew[X] * ynew[X] + ynew[Y] * ynew[Y])
        if method == 0 and status < 0 and r_new < PIVOT_EXPLICIT:
            if implicit:
                implicit = False
                switched = True
        elif method == 0 and status < 0:
            if implicit:
                hnorm = h * _jac_norm(J)
                easy = easy + 1 if hnorm < NONSTIFF_HNORM else 0
                if easy >= NONSTIFF_COUNT:
                    implicit = False
                    switched = True
            elif dop853.stiffness_ratio(h, K, ynew, ystage) > STIFF_HLAMBDA:
                nonstiff = 0
                stiff += 1
                if stiff >= STIFF_COUNT:
                    implicit = True
                    switched = True
            else:
                nonstiff += 1
                if nonstiff >= 6:
                    stiff = 0
        if switched:
            stats[ST_SWITCH] += 1
            stiff = 0
            nonstiff = 0
            easy = 0
        r_in = _r_inside(y, f, ynew, fnew, h)
        if r_in >= 0.0:
            r_min = min(r_min, r_in)
            r_max = max(r_max, r_in)
        t += h
        copy_into(y, ynew)
        copy_into(f, fnew)
        r_min = min(r_min, r_new)
        r_max = max(r_max, r_new)
        if record:
            nodes, n_nodes, stride = _record(nodes, n_nodes, stride, stats[ST_ACC] * N_SUB,
                                             False, y, f)
        log_en = math.log(max(en, 1e-300))
        if en == 0.0:
            fac = maxfac
        elif implicit:
            fac = min(maxfac, SAFETY * math.exp(-expo * log_en))
        else:
            fac = min(maxfac, max(0.2, SAFETY * math.exp(
                -(expo - 0.75 * PI_BETA) * log_en + PI_BETA * log_en_old)))
        log_en_old = max(log_en, LOG_EN_FLOOR)
        if last_rejected:
            fac = min(1.0, fac)
        last_rejected = False
        h *= fac
    if record and (stats[ST_ACC] * N_SUB) % stride != 0:  # the last state, off the stride
        nodes, n_nodes, stride = _record(nodes, n_nodes, stride, stats[ST_ACC] * N_SUB, True,
                                         y, f)
    return status, y[TAU], y, stats, r_min, r_max, nodes, n_nodes
