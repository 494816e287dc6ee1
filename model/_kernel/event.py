"""Inside one accepted step: the exit event of Eq. (9) and the turning points of r.

The exit (first crossing of s(tau) = L0) is located on the step's continuous extension:
``DP8``: DOP853's 7th-order output (its polynomial coefficients of x and tau in FX, FT),
``DP5``: the 4th-order output of Dormand-Prince 5(4), ``HERMITE``: the cubic Hermite
interpolant through the step's ends and slopes (after a Rodas4 step). The driver then
retakes the step exactly to the located time.
"""
import math

from numba import njit

from . import dop853, dopri5
from .rhs import exit_gap
from .slots import TAU, VX, X, Y

HERMITE, DP5, DP8 = 0, 1, 2


@njit(cache=True, error_model="numpy", inline="always")
def hermite(y0, f0, y1, f1, h, th, i):
    """Cubic Hermite interpolant of component i: the dense output used with Rodas4."""
    h00 = (1 + 2 * th) * (1 - th) ** 2
    h10 = th * (1 - th) ** 2
    h01 = th * th * (3 - 2 * th)
    h11 = th * th * (th - 1)
    return h00 * y0[i] + h10 * h * f0[i] + h01 * y1[i] + h11 * h * f1[i]


@njit(cache=True, error_model="numpy", inline="always")
def _hermite_slope(y0, f0, y1, f1, h, th, i):
    """d/dtheta of ``hermite`` (component i)."""
    return ((6 * th * th - 6 * th) * (y0[i] - y1[i]) + (3 * th * th - 4 * th + 1) * h * f0[i]
            + (3 * th * th - 2 * th) * h * f1[i])


@njit(cache=True, error_model="numpy", inline="always")
def _radial_rate(y0, f0, y1, f1, h, th):
    """(r dr/dtheta, r) on the cubic Hermite interpolant of x and y over the step."""
    x = hermite(y0, f0, y1, f1, h, th, X)
    yy = hermite(y0, f0, y1, f1, h, th, Y)
    return (x * _hermite_slope(y0, f0, y1, f1, h, th, X)
            + yy * _hermite_slope(y0, f0, y1, f1, h, th, Y)), math.sqrt(x * x + yy * yy)


@njit(cache=True, error_model="numpy")
def r_inside(y0, f0, y1, f1, h):
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
def may_exit(y, ynew, P):
    """True when the exit may lie in the step: s(tau) ends at or above L0, or may peak
    inside it (v_x crosses 1)."""
    return exit_gap(ynew[TAU], ynew[X], P) >= 0.0 or (y[VX] < 1.0 and ynew[VX] > 1.0)


@njit(cache=True, error_model="numpy", inline="always")
def _gap_at(kind, th, h, y, f, ynew, fnew, K, FX, FT, P):
    if kind == DP8:
        x = dop853.poly_at(y[X], FX, th)
        tau = dop853.poly_at(y[TAU], FT, th)
    elif kind == DP5:
        x = dopri5.dense_component(y, K, h, th, X)
        tau = dopri5.dense_component(y, K, h, th, TAU)
    else:
        x = hermite(y, f, ynew, fnew, h, th, X)
        tau = hermite(y, f, ynew, fnew, h, th, TAU)
    return exit_gap(tau, x, P)


@njit(cache=True, error_model="numpy")
def locate_exit(kind, h, y, f, ynew, fnew, K, FX, FT, P, scan_points):
    """First theta in (0, 1] where the exit gap crosses zero on the step's continuous
    extension of ``kind``, or -1 if none (call when ``may_exit``; for ``DP8`` FX and FT
    must hold ``dop853.poly`` of x and tau).

    Scans the step at ``scan_points`` points (s may cross L0 and come back within it),
    then refines the first bracket by the Illinois method.
    """
    g1 = exit_gap(ynew[TAU], ynew[X], P)
    lo = 0.0
    glo = exit_gap(y[TAU], y[X], P)
    hi = -1.0
    ghi = 0.0
    for k in range(1, scan_points + 1):
        th = k / scan_points
        g = g1 if k == scan_points else _gap_at(kind, th, h, y, f, ynew, fnew, K, FX, FT, P)
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
        g = _gap_at(kind, th, h, y, f, ynew, fnew, K, FX, FT, P)
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
