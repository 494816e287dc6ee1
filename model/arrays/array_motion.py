"""The array under the slab, in motion (Fig. 2a and Fig. 4 of the paper, live).

A slab of length L0 slides at unit speed along +x over a rectangular grid of supports
(spacing ``spacing`` in x and y). A support enters contact when the slab's leading edge
reaches its mass (at rest at pivot + (cos theta0, sin theta0)) and is released at its own
tau_out (Eq. 9), when the trailing edge passes it. Each support follows the one-contact
trajectory of ``simulate_support`` for its theta0, under the load f_N = beta F_N with the
self-consistent beta of the array (``uniform_array`` or ``fixed_orientation``), so the
live count and force below agree with the readouts of those functions.

``array_motion`` computes the trajectories once per parameter set and samples them on a
common time grid of frames, as compact float32 arrays for a browser-side player:

* per support and frame: mass position relative to its pivot, contact flag and the
  direction of the friction force on it;
* per frame: the slab's leading edge, the live count N_c of supports in contact, the
  count N_c0 of a rigid array (supports under the slab's footprint), and the force the
  drive needs, F_T,x/(mu0 F_N) with F_N the slab's load per rigid support (Eqs. 7-10).

In the steady window (the slab fully over the grid, every support it ever touched
within the grid) N_c/N_c0 -> <tau_out>/L0 (Fig. 8a) and the time average of F_T,x tends
to the *duration-weighted* average of docs/model.md, sum int F_f,x dtau / (f_N sum tau_out):
the steady force on a sliding slab. It equals the paper's Eq. (10) average for a
fixed-orientation array and differs from it by several per cent in the slider regime.

Released supports are drawn at rest: the model follows a support only during contact.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..contact.friction import mu0
from ..contact.params import Params, rest_positions
from ..contact.support import simulate_support
from .contacts import PIVOT_RADIUS_OVER_LAMBDA
from .fixed import fixed_orientation
from .uniform import uniform_array

__all__ = ["ArrayMotion", "array_motion", "ORIENTATIONS"]

ORIENTATIONS = ("uniform", "fixed")
#: Samples per trajectory before resampling on the frame grid (cubic Hermite in the model).
TRAJECTORY_SAMPLES = 4000
#: Upper bounds that keep the browser payload small (float32: 12 bytes per support-frame).
MAX_SUPPORTS = 2000
MAX_FRAMES = 5000


@dataclass(frozen=True)
class ArrayMotion:
    """Frames of a slab sliding over an array of supports; arrays are read-only.

    Shapes: ``n`` supports, ``m`` frames. Per support (``n``): ``pivot_x``, ``pivot_y``,
    ``theta0`` [rad], ``t_start``, ``t_end`` (contact start and end on the frame clock),
    ``tau_out``. Per support and frame (``n, m``, float32): ``x``, ``y`` (mass relative to
    its pivot), ``in_contact`` (bool), ``F_angle`` (direction of the friction force on the
    support [rad] from +x, NaN out of contact), ``F_x``, ``F_y`` (friction / f_N, 0 out of
    contact). Per frame (``m``): ``t``, ``slab_lead`` (leading edge x; the trailing edge
    is L0 behind), ``N_c``, ``N_c0``, ``FTx`` (instantaneous F_T,x/(mu0 F_N)),
    ``FTx_running`` (its mean since the steady window opened, NaN before); ``FTx`` is NaN
    while no rigid support would be under the slab (N_c0 = 0).
    ``steady`` = (start, end) of the steady window on the frame clock.
    ``model`` holds the array function's readouts (N_c/N_c0, both F_T,x averages, beta).
    """

    params: Params
    orientation: str
    spacing: float
    n_rows: int
    n_cols: int
    pivot_x: np.ndarray
    pivot_y: np.ndarray
    theta0: np.ndarray
    tau_out: np.ndarray
    t_start: np.ndarray
    t_end: np.ndarray
    t: np.ndarray
    x: np.ndarray
    y: np.ndarray
    in_contact: np.ndarray
    F_angle: np.ndarray
    F_x: np.ndarray
    F_y: np.ndarray
    slab_lead: np.ndarray
    N_c: np.ndarray
    N_c0: np.ndarray
    FTx: np.ndarray
    FTx_running: np.ndarray
    steady: tuple
    model: dict
    success: bool
    message: str
    stats: dict = field(default_factory=dict)

    @property
    def n_supports(self) -> int:
        return int(self.pivot_x.size)

    @property
    def n_frames(self) -> int:
        return int(self.t.size)

    @property
    def N_c0_nominal(self) -> float:
        """Supports under the static projection of a slab covering the grid's width:
        N_c0 = L_x L_y / (d_x d_y), with L_y = n_rows d."""
        return self.n_rows * self.params.L0 / self.spacing

    def steady_mask(self) -> np.ndarray:
        return (self.t >= self.steady[0]) & (self.t <= self.steady[1])

    def steady_means(self) -> dict:
        """Time averages over the steady window (NaN when it is empty)."""
        mask = self.steady_mask()
        if not np.any(mask):
            return {"Nc_over_Nc0": math.nan, "FTx_over_mu0FN": math.nan, "frames": 0}
        return {"Nc_over_Nc0": float(self.N_c[mask].mean() / self.N_c0[mask].mean()),
                "FTx_over_mu0FN": float(self.FTx[mask].mean()), "frames": int(mask.sum())}


def array_motion(params: Params, orientation: str = "uniform", n_supports: int = 100,
                 n_orientations: int = 100, spacing: float = 1.0, n_rows: int | None = None,
                 n_cols: int | None = None, n_frames: int = 600, seed: int = 0,
                 rtol: float = 1e-6, tol: float = 1e-3) -> ArrayMotion:
    """Frames of the slab sliding over an array of supports (see the module docstring).

    Parameters
    ----------
    params : springs and load (``params.theta0`` is the shared orientation when
        ``orientation="fixed"``; it is ignored for ``"uniform"``).
    orientation : ``"uniform"`` (theta0 stratified on [0, 2 pi): n_orientations values
        2 pi (k + 1/2)/n_orientations, shuffled over the grid with ``seed``) or ``"fixed"``.
    n_supports : the size the grid aims at when ``n_rows``/``n_cols`` are not given.
    spacing : d_x = d_y [r0].
    n_rows, n_cols : the grid; by default ``n_cols`` makes the grid long enough for a
        steady window of about L0/2 (longest contact + 1.5 L0) and ``n_rows`` fills
        ``n_supports`` (at least 2 rows).
    n_frames : frames on [0, last release + 1].
    rtol : integration tolerance of each trajectory; ``tol``: of the uniform array's beta.
    """
    start = time.perf_counter()
    if not isinstance(params, Params):
        raise TypeError(f"params must be a model.Params, not {type(params).__name__}")
    if orientation not in ORIENTATIONS:
        raise ValueError(f"orientation={orientation!r} must be one of {ORIENTATIONS}")
    n_supports = _whole("n_supports", n_supports, 1, MAX_SUPPORTS)
    n_orientations = _whole("n_orientations", n_orientations, 2, 2000)
    n_frames = _whole("n_frames", n_frames, 2, MAX_FRAMES)
    seed = _whole("seed", seed, 0, 2**32 - 1)
    if isinstance(spacing, bool) or not isinstance(spacing, (int, float)) \
            or not (math.isfinite(spacing) and 0.05 <= spacing <= 100):
        raise ValueError(f"spacing={spacing!r} must be a number in [0.05, 100] (r0)")
    for name, value in (("n_rows", n_rows), ("n_cols", n_cols)):
        if value is not None:
            _whole(name, value, 1, MAX_SUPPORTS)

    model, base = _model_readouts(params, orientation, rtol, tol)
    # Distinct orientations and their trajectories, computed once.
    if orientation == "uniform":
        # Even count: theta0 and 2 pi - theta0 pair up, and the mirror image (y -> -y)
        # of the first half gives the second without integrating it.
        n_orientations += n_orientations % 2
        th = 2 * math.pi * (np.arange(n_orientations) + 0.5) / n_orientations
    else:
        th = np.array([params.theta0])
    trajectories, failures, pivot = _trajectories(base, th, rtol)
    tau_out = np.array([tr["tau"][-1] for tr in trajectories])

    # Grid: long enough for a steady window, then rows to reach n_supports.
    L0 = params.L0
    if n_cols is None:
        n_cols = max(2, math.ceil((tau_out.max() + 1.5 * L0 + 2.0) / spacing))
    if n_rows is None:
        n_rows = max(2, round(n_supports / n_cols))
    n = n_rows * n_cols
    if n > MAX_SUPPORTS:
        raise ValueError(f"the grid {n_rows} x {n_cols} = {n} supports exceeds {MAX_SUPPORTS}; "
                         f"give fewer n_rows/n_cols or a larger spacing")
    col, row = np.meshgrid(np.arange(n_cols), np.arange(n_rows))
    pivot_x = (col.ravel() * spacing).astype(float)
    pivot_y = ((row.ravel() - (n_rows - 1) / 2) * spacing).astype(float)
    rng = np.random.default_rng(seed)
    # Each orientation used equally often (up to one), in shuffled order over the grid.
    reps = math.ceil(n / th.size)
    which = np.concatenate([rng.permutation(th.size) for _ in range(reps)])[:n]
    theta0 = th[which]
    x_rest, _ = rest_positions(theta0)
    lead0 = float((pivot_x + x_rest).min()) - 0.5
    t_start = pivot_x + x_rest - lead0
    t_end = t_start + tau_out[which]

    T = float(t_end.max()) + 1.0
    t = np.linspace(0.0, T, n_frames)
    frames = _sample(trajectories, which, t_start, t)
    in_contact = (t[None, :] >= t_start[:, None]) & (t[None, :] < t_end[:, None])
    N_c = in_contact.sum(axis=0)
    N_c0 = ((t[None, :] >= t_start[:, None]) & (t[None, :] < t_start[:, None] + L0)).sum(axis=0)

    # Steady window: every support a slab over an endless grid would hold is on this one
    # (all that entered before column 0 entered are released; none beyond the last column
    # has entered). Column 0 enters within 2 (cos theta0 jitter) of the first entry.
    first_col, last_col = col.ravel() == 0, col.ravel() == n_cols - 1
    steady = (float(t_start[first_col].max() + tau_out.max()), float(t_start[last_col].min()))
    # F_T,x/(mu0 F_N): the drive balances the friction of the supports in contact, each
    # loaded with f_N = beta F_N, over the load of the rigid supports under the slab's
    # footprint, N_c0(t) F_N (Eq. 7 with the norm of Eq. 10). The live N_c0(t) rather than
    # the nominal count: columns enter the footprint one at a time.
    with np.errstate(divide="ignore", invalid="ignore"):
        FTx = np.where(N_c0 > 0, base.beta * frames["F_x"].sum(axis=0, dtype=float)
                       / (mu0(params) * np.maximum(N_c0, 1)), np.nan)
    running = np.full(t.size, np.nan)
    inside = t >= steady[0]
    running[inside] = np.cumsum(FTx[inside]) / np.arange(1, inside.sum() + 1)

    F_angle = np.where(in_contact, np.arctan2(frames["F_y"], frames["F_x"]), np.nan)
    arrays = dict(
        pivot_x=pivot_x, pivot_y=pivot_y, theta0=theta0, tau_out=tau_out[which], t_start=t_start,
        t_end=t_end, t=t, x=frames["x"], y=frames["y"], in_contact=in_contact,
        F_angle=F_angle.astype(np.float32), F_x=frames["F_x"], F_y=frames["F_y"],
        slab_lead=lead0 + t, N_c=N_c, N_c0=N_c0, FTx=FTx, FTx_running=running)
    for a in arrays.values():
        a.flags.writeable = False

    messages = []
    if failures:
        messages.append(f"{len(failures)} of {th.size} trajectories did not end normally "
                        f"({failures[0]}); they are drawn up to where they stopped")
    if steady[1] - steady[0] < spacing:
        messages.append(f"the grid ({n_cols} columns) is too short for a steady window: the "
                        f"longest contact lasts tau_out = {tau_out.max():.3g}; give more n_cols")
    if not model["success"]:
        messages.append(f"the array's beta is uncertain: {model['message']}")
    success = not messages
    if pivot:  # integrated through (docs/model.md, "Hard cases"): a note, not a failure
        messages.append(f"{len(pivot)} of {th.size} orientations drive the mass into the "
                        f"region of its pivot (r < {PIVOT_RADIUS_OVER_LAMBDA * params.lam:.3g}); "
                        f"drawn as integrated")
    return ArrayMotion(
        params=base, orientation=orientation, spacing=float(spacing), n_rows=int(n_rows),
        n_cols=int(n_cols), steady=steady, model=model, success=success,
        message="; ".join(messages) or "ok",
        stats={"trajectories": int(th.size) if orientation == "fixed" else int(th.size // 2),
               "orientations": int(th.size), "pivot_approach": len(pivot),
               "supports": int(n), "frames": int(n_frames),
               "frame_dt": float(t[1] - t[0]), "seconds": time.perf_counter() - start,
               "payload_bytes": int(n * n_frames * 12)},
        **arrays)


def _whole(name, value, lo, hi) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not lo <= value <= hi:
        raise ValueError(f"{name}={value!r} must be a whole number in [{lo}, {hi}]")
    return int(value)


def _model_readouts(params, orientation, rtol, tol):
    """The array function's beta and readouts, so the live count matches them."""
    if orientation == "uniform":
        u = uniform_array(params.replace(theta0=math.pi / 2), tol=tol)  # theta0 unused
        model = {"beta": u.beta, "Nc_over_Nc0": u.Nc_over_Nc0,
                 "Nc_over_Nc0_error": u.quadrature_error["Nc_over_Nc0"],
                 "FTx_over_mu0FN": u.FTx_over_mu0FN,
                 "FTx_over_mu0FN_duration": u.FTx_over_mu0FN_duration,
                 "FTx_over_mu0FN_duration_error": u.quadrature_error["FTx_over_mu0FN_duration"],
                 "success": u.success, "message": u.message}
    else:
        f = fixed_orientation(params, rtol=rtol)
        model = {"beta": f.beta, "Nc_over_Nc0": f.Nc_over_Nc0, "Nc_over_Nc0_error": 0.0,
                 "FTx_over_mu0FN": f.FTx_over_mu0FN, "FTx_over_mu0FN_duration": f.FTx_over_mu0FN,
                 "FTx_over_mu0FN_duration_error": 0.0, "success": f.success,
                 "message": f.message}
    return model, params.replace(beta=model["beta"])


def _trajectories(base, th, rtol):
    """Sampled trajectory per orientation; the upper half by mirror symmetry (y -> -y)."""
    half = th.size // 2 if th.size > 1 else 1
    out, failures, pivot = [None] * th.size, [], []
    for k in range(half):
        res = simulate_support(base.replace(theta0=float(th[k])), rtol=rtol,
                               samples=TRAJECTORY_SAMPLES)
        if not res.success:
            failures.append(res.message)
        if res.pivot_approach:  # and its mirror image, when there is one
            pivot.extend([k] if th.size == 1 else [k, th.size - 1 - k])
        s = res.series
        if s is None:  # nothing to draw: the support stays at rest
            tr = {"tau": np.array([0.0, max(res.t_out, 1e-9)]),
                  "x": np.full(2, math.cos(th[k])), "y": np.full(2, math.sin(th[k])),
                  "F_x": np.zeros(2), "F_y": np.zeros(2)}
        else:
            tr = {"tau": s.tau, "x": s.x, "y": s.y, "F_x": s.F_x, "F_y": s.F_y}
        out[k] = tr
        if th.size > 1:
            out[th.size - 1 - k] = {**tr, "y": -tr["y"], "F_y": -tr["F_y"]}
    return out, failures, pivot


def _sample(trajectories, which, t_start, t):
    """Each support's trajectory on the frame clock; at rest outside its contact."""
    n, m = which.size, t.size
    out = {k: np.empty((n, m), np.float32) for k in ("x", "y", "F_x", "F_y")}
    for i in range(n):
        tr = trajectories[which[i]]
        tau = t - t_start[i]
        inside = (tau >= 0) & (tau < tr["tau"][-1])
        for k in ("x", "y"):
            out[k][i] = np.where(inside, np.interp(tau, tr["tau"], tr[k]), tr[k][0])
        for k in ("F_x", "F_y"):
            out[k][i] = np.where(inside, np.interp(tau, tr["tau"], tr[k]), 0.0)
    return out
