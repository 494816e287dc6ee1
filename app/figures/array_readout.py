"""The Array tab's live readout (``app.figures.array_scene``): the counts and the force
*now* (instantaneous), the mean over the steady window that the force settles to, and,
once the slab has left the grid, the last values of a sliding slab (Eqs. 7-10)."""
from __future__ import annotations

import numpy as np

__all__ = ["readout_text", "settled_mean", "last_counted"]


def settled_mean(motion) -> np.ndarray:
    """The mean of F_T,x/(mu0 F_N) over the steady window so far (NaN before it opens),
    held at the window's mean once it has closed: the force the array settles to."""
    run = np.array(motion.FTx_running, dtype=float)
    closed = motion.t > motion.steady[1]
    inside = np.flatnonzero(~closed & np.isfinite(run))
    if closed.any() and inside.size:
        run[closed] = run[inside[-1]]
    return run


def last_counted(motion) -> np.ndarray:
    """Per frame, the latest frame (up to it) whose counts describe a sliding slab (before
    the last support's entry, N_c0 > 0): after the slab leaves the grid the readout keeps
    those values."""
    valid = (motion.t <= motion.t_start.max()) & (motion.N_c0 > 0)
    index = np.where(valid, np.arange(motion.t.size), -1)
    last = np.maximum.accumulate(index)
    return np.where(last < 0, np.arange(motion.t.size), last)


def readout_text(s: dict, f: int, steady) -> str:
    """The live readout at frame ``f`` (``s``: the columns of the "array_series" source):
    the counts and the force *now* (labelled instantaneous), the mean over the steady
    window (so far, settled, or when it opens); after the slab has left the grid, the
    last values of a sliding slab. ``_FRAME_JS`` writes the same text in the page."""
    t, g = float(s["t"][f]), int(s["last"][f])
    nc, nc0 = int(s["N_c"][g]), int(s["N_c0"][g])
    ftx, run = float(s["ftx"][g]), float(s["run"][g])

    def fmt(v, p):
        return f"{v:.{p}f}" if np.isfinite(v) else "–"
    ratio = fmt(nc / nc0, 2) if nc0 else "–"
    beta = fmt(nc0 / nc, 2) if nc else "–"
    if not np.isfinite(run):
        mean = f"mean over the steady window: from τ = {steady[0]:.1f}"
    else:
        mean = (f"<b>mean over the steady window: {fmt(run, 3)}</b>"
                + (" (settled)" if t > steady[1] else " (so far)"))
    now = (f"N_c = {int(s['N_c'][f])}</b> supports in contact" if g == f else
           f"N_c = {int(s['N_c'][f])}</b> still in contact; the slab has left the grid, "
           f"last values (τ = {float(s['t'][g]):.1f}): N_c = {nc}")
    return (f"τ = {t:.1f} · <b>{now}, N_c0 = {nc0} under a rigid slab: N_c/N_c0 = {ratio}, "
            f"β = N_c0/N_c = {beta} · F_T,x/(μ₀F_N) instantaneous {fmt(ftx, 3)}, {mean}")
