"""The recorded history of one contact (``record``): nodes for cubic Hermite sampling.

A node is (tau, the ``REC_SLOTS`` of the state, their tau-derivatives). Nodes are taken at
every accepted step and, inside each DOP853 step (rtol <= ``driver.DOP853_RTOL``), at
N_SUB - 1 evenly spaced points of its 7th-order continuous extension (its three extra
stages are computed only for recording runs); the shorter Dormand-Prince 5(4) steps
give nodes at their ends only (candidate numbers n * N_SUB). The 8th-order steps are long
(about half as many as the Dormand-Prince 5(4) steps at equal rtol): cubic Hermite
sampling between their ends
alone would lose about two digits of the series (``model.contact.support._series_from_nodes``);
with the inner nodes the spacing is shorter than the old steps and the sampled series are
at least as accurate as before (``tests/test_series.py``). The recorded run takes exactly
the steps of the unrecorded one, so its exit state is the same.
"""
import numpy as np
from numba import njit

from . import dop853
from .rhs import copy_into
from .slots import D_X, D_Y, TAU, THETA, VX, VY, W, X, Y

#: State slots recorded (with ``record``): the motion and the cumulative quadratures of
#: the energy split (Eq. 12), W, D_x, D_y.
REC_SLOTS = (X, Y, VX, VY, THETA, W, D_X, D_Y)
N_REC = len(REC_SLOTS)
N_NODE_COLS = 1 + 2 * N_REC
#: Nodes per explicit step: its end and N_SUB - 1 points inside it.
N_SUB = 3

#: Most nodes kept (``record``): a contact of any length stores at most MAX_NODES rows
#: (4.5 MB). Past it every other node is dropped and only every other candidate node
#: recorded from then on (the stride doubles), so the nodes stay evenly spread over the
#: whole contact; shorter contacts keep every node.
MAX_NODES = 1 << 15


@njit(cache=True, error_model="numpy")
def record(nodes, count, stride, cand, force, y, f):
    """Append (tau, the REC_SLOTS of y, and their tau-derivatives) to ``nodes`` when the
    candidate node number ``cand`` falls on ``stride`` (or ``force``: the last state).
    Candidate ``n * N_SUB`` is the end of accepted step n; ``n * N_SUB + j`` lies inside
    step n + 1. ``f`` is any multiple of the derivative (only ratios to f[TAU] are used).

    Returns (nodes, count, stride); node i holds candidate i * stride."""
    if cand % stride != 0 and not force:
        return nodes, count, stride
    if count == nodes.shape[0]:
        if count >= MAX_NODES:
            half = (count + 1) // 2
            for i in range(1, half):
                copy_into(nodes[i], nodes[2 * i])
            count = half
            stride *= 2
            if cand % stride != 0 and not force:
                return nodes, count, stride
        else:
            bigger = np.empty((min(2 * nodes.shape[0], MAX_NODES), nodes.shape[1]))
            for i in range(count):
                copy_into(bigger[i], nodes[i])
            nodes = bigger
    nodes[count, 0] = y[TAU]
    for k in range(N_REC):
        i = REC_SLOTS[k]
        nodes[count, 1 + k] = y[i]
        nodes[count, 1 + N_REC + k] = f[i] / f[TAU]  # d/dtau = (d/ds) / w
    return nodes, count + 1, stride


@njit(cache=True, error_model="numpy")
def record_inside(nodes, count, stride, cand0, y, ynew, K, h, F, ysub, fsub):
    """Nodes at theta = j / N_SUB (j = 1 .. N_SUB - 1) inside the explicit step from y to
    ynew, on its continuous extension; K must hold the three dense-output stages
    (``dop853.dense_stages``). Candidate numbers follow ``cand0``, the step's start."""
    for j in range(1, N_SUB):
        if (cand0 + j) % stride != 0:
            continue
        th = j / N_SUB
        for k in range(N_REC + 1):
            i = TAU if k == N_REC else REC_SLOTS[k]
            dop853.poly(y, ynew, K, h, i, F)
            ysub[i], fsub[i] = dop853.poly_with_slope(y[i], F, th)
        nodes, count, stride = record(nodes, count, stride, cand0 + j, False, ysub, fsub)
    return nodes, count, stride
