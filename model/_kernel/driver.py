"""Adaptive integration of one contact until the exit event of Eq. (9).

Methods: 1 = explicit, 2 = implicit Rodas4, 0 = automatic: start explicit, switch to
Rodas4 when the stiffness detector of Hairer & Wanner (IV.2) fires repeatedly, and back
when h ||J|| shows the explicit pair would be stable at the current step.

The explicit pair follows the requested rtol (``use_dop853``): DOP853 (Dormand-Prince
8(5,3)) at rtol <= DOP853_RTOL, Dormand-Prince 5(4) above it, each where it costs least
at equal exit-state error (docs/model.md, "Solvers").

The exit is located on the dense output of the accepted step (``event.locate_exit``:
first crossing of s(tau) = L0, scanning the step when s may cross and re-cross), then
the step is retaken exactly to the located time, so the exit state has the method's
full accuracy rather than the interpolant's.
"""
import math

import numpy as np
from numba import njit

from . import dop853, dopri5, event, rodas4
from .record import N_NODE_COLS, N_SUB, record as _record, record_inside
from .rhs import copy_into, jacobian, rhs
from .slots import (ERROR_SLOTS, N_ERROR, N_MOTION, N_STATE, N_STATS, NONFINITE, OK, ST_ACC,
                    ST_ACC_EXPL, ST_ACC_IMPL, ST_JAC, ST_LU, ST_REJ, ST_RHS, ST_SWITCH,
                    STEP_BUDGET, STEP_UNDERFLOW, TAU, TIME_BUDGET, X, Y)

#: The explicit pair is DOP853 at a requested rtol <= DOP853_RTOL and Dormand-Prince 5(4)
#: above it (measured crossover: docs/model.md, "Solvers").
DOP853_RTOL = 1e-6
SAFETY = 0.9
# Stability boundaries on the negative real axis (Hairer's DOPRI5 and DOP853 codes).
STIFF_HLAMBDA_DP5 = 3.25
STIFF_HLAMBDA_DP8 = 6.1
STIFF_COUNT = 15
NONSTIFF_HNORM = 2.0  # back to explicit when h ||J||_inf stays below this
NONSTIFF_COUNT = 5
# Within this radius of the pivot the motion is fast and non-smooth (the cusp of the
# repulsion, the torsional barrier): ``auto`` uses the explicit pair there.
PIVOT_EXPLICIT = 1e-3
SCAN_POINTS = 8
# PI step-size control (Gustafsson; Hairer & Wanner I, IV.2): the explicit pair uses
# err^-(1/q - 0.75 BETA) * err_old^BETA (q = 5 or 8), which damps the accept/reject oscillation.
PI_BETA = 0.04
LOG_EN_FLOOR = math.log(1e-4)  # err_old is taken as at least 1e-4
# Step-size factors (scipy's MIN_FACTOR/MAX_FACTOR; Hairer's DOPRI5/DOP853 use 0.2 and 10,
# his RODAS 6): a step shrinks at most 5-fold after a rejection, grows at most MAX_FACTOR_*.
MIN_FACTOR = 0.2
MAX_FACTOR_EXPLICIT = 10.0
MAX_FACTOR_IMPLICIT = 6.0
# Hairer's DOPRI5/DOP853: this many non-stiff steps in a row clear the stiffness count.
NONSTIFF_RESET = 6
# The smallest step: this many units of roundoff of the time (Hairer's codes use 10-16).
HMIN_ULPS = 16.0
# After falling back to the other method at the smallest step, it starts this much larger.
FALLBACK_STEP = 1e6


@njit(cache=True, error_model="numpy", inline="always")
def use_dop853(rtol):
    """True when the explicit pair for ``rtol`` is DOP853 (else Dormand-Prince 5(4))."""
    return rtol <= DOP853_RTOL


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
def _jac_norm(J):
    big = 0.0
    for i in range(N_MOTION):
        row = 0.0
        for j in range(N_MOTION):
            row += abs(J[i, j])
        big = max(big, row)
    return big


@njit(cache=True, error_model="numpy")
def integrate(y0, P, rtol, atol, method, max_steps, tau_max, record, high):
    """Integrate from y0 until the exit event, a budget, or a failure; the explicit
    steps by DOP853 when ``high`` (``use_dop853(rtol)``), else by Dormand-Prince 5(4).

    Returns (status, t, y, stats, r_min, r_max, nodes, n_nodes); status codes are those
    named in ``slots`` (``model.contact.results.Status``); r_min and r_max are the extremes of the
    distance r from the pivot over the contact (at the accepted steps and the turning
    points of r inside them, ``event.r_inside``). ``nodes`` rows are (tau, the ``REC_SLOTS`` of the
    state, and their tau-derivatives) when ``record`` is set: at the accepted steps and
    inside the DOP853 ones (``record.record_inside``), every one or every 2^k-th once
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
    h = _initial_step(y, f, P, rtol, atol, 4 if implicit else (8 if high else 5), ystage,
                      fnew)
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
        hmin = HMIN_ULPS * 2.220446049250313e-16 * max(1.0, abs(t))
        if h < hmin:
            if method == 0 and not fell_back:
                # The other method may resolve what this one cannot (pivot passage).
                fell_back = True
                implicit = not implicit
                stats[ST_SWITCH] += 1
                h = FALLBACK_STEP * hmin
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
            maxfac = MAX_FACTOR_IMPLICIT
        elif high:
            dop853.step(y, f, h, P, K, ynew, ystage)
            dense_done = False
            stats[ST_RHS] += 12
            en = dop853.error_norm(h, K, y, ynew, rtol, atol)
            expo = 1.0 / dop853.ORDER
            maxfac = MAX_FACTOR_EXPLICIT
        else:
            dopri5.step(y, f, h, P, K, ynew, err, ystage)
            stats[ST_RHS] += 6
            en = _err_norm(err, y, ynew, rtol, atol)
            expo = 1.0 / dopri5.ORDER
            maxfac = MAX_FACTOR_EXPLICIT
        if en > 1.0 and not finishing:
            stats[ST_REJ] += 1
            nonfinite = en == np.inf
            h *= MIN_FACTOR if nonfinite else max(MIN_FACTOR, SAFETY * math.exp(-expo * math.log(en)))
            last_rejected = True
            continue
        nonfinite = False
        if implicit:
            rhs(ynew, P, fnew)
            stats[ST_RHS] += 1
        else:
            last = dop853.N_STAGES if high else 6  # f(ynew), the last stage (FSAL)
            for i in range(n):
                fnew[i] = K[last, i]
        if finishing:
            status = OK
        else:
            th = -1.0
            if event.may_exit(y, ynew, P):
                kind = event.HERMITE if implicit else (event.DP8 if high else event.DP5)
                if kind == event.DP8:
                    dop853.dense_stages(y, h, P, K, ydense)
                    stats[ST_RHS] += 3
                    dense_done = True
                    dop853.poly(y, ynew, K, h, X, FX)
                    dop853.poly(y, ynew, K, h, TAU, FT)
                th = event.locate_exit(kind, h, y, f, ynew, fnew, K, FX, FT, P, SCAN_POINTS)
            if th > 0.0:
                # Retake this step exactly to the located exit time.
                h = th * h
                finishing = True
                continue
        stats[ST_ACC] += 1
        stats[ST_ACC_IMPL if implicit else ST_ACC_EXPL] += 1
        if record and high and not implicit:  # nodes inside the step, on its continuous extension
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
            elif (dop853.stiffness_ratio(h, K, ynew, ystage) > STIFF_HLAMBDA_DP8 if high
                  else dopri5.stiffness_ratio(h, K, ynew, ystage) > STIFF_HLAMBDA_DP5):
                nonstiff = 0
                stiff += 1
                if stiff >= STIFF_COUNT:
                    implicit = True
                    switched = True
            else:
                nonstiff += 1
                if nonstiff >= NONSTIFF_RESET:
                    stiff = 0
        if switched:
            stats[ST_SWITCH] += 1
            stiff = 0
            nonstiff = 0
            easy = 0
        r_in = event.r_inside(y, f, ynew, fnew, h)
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
            fac = min(maxfac, max(MIN_FACTOR, SAFETY * math.exp(
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
