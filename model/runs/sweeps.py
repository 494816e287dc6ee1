"""Parameter sweeps behind the paper's figures, each returning a ``SweepResult``.

* ``regime_map`` (Fig. 5a/b): uniform arrays on a (k_r, k_theta) grid;
* ``load_sweep`` (Fig. 6): uniform arrays of the four regimes against F_N;
* ``stiffness_sweep`` (Fig. 8a/b): N_c/N_c0 and the split of the slab work (Eq. 12)
  against k_r for several k_theta;
* ``orientation_table`` (Figs. 10f, 11): fixed-orientation arrays against theta0.

Every point of the uniform-array sweeps is one independent ``uniform_array`` call, kept
in the on-disk cache (``model.runs.cache``: the user's cache directory, or
``$MICROPILLAR_CACHE_DIR``) so that no point is computed twice. The points run
serially (``workers=1``), on a local process pool (``workers > 1``) or on a
dask.distributed cluster (``scheduler``), with identical results; ``progress(done, total)``
is called after each point, and setting the ``cancel`` event raises ``SweepCancelled``.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from .. import csvfile
from .._version import __version__
from ..arrays.fixed import orientation_sweep
from ..arrays.quantities import TABLES, value_of
from ..arrays.uniform import TOL, uniform_array
from ..contact.options import SolverOptions
from ..contact.params import REGIMES, Params
from ..controls import LOAD_RANGE, STIFFNESS_RANGE
from ..files import write_atomic
from ..validation import grid, load_factor, number, whole
from .cache import DiskCache, make_key
from .parallel import SweepCancelled, run_points

__all__ = ["SweepResult", "SweepCancelled", "regime_map", "load_sweep", "stiffness_sweep",
           "orientation_table", "read_csv", "KINDS"]

#: Sweep kind -> the figures it reproduces.
KINDS = {"regime_map": "5a, 5b", "load": "6", "stiffness": "8a, 8b", "orientation": "10f, 11"}


@dataclass(frozen=True)
class SweepResult:
    """One row per parameter point: ``columns`` maps names to equally long 1-D arrays."""

    kind: str
    columns: dict
    settings: dict
    seconds: float

    def __len__(self) -> int:
        return len(next(iter(self.columns.values()))) if self.columns else 0

    def to_csv(self, path) -> None:
        """CSV with a header block of ``# key: value`` lines (kind, figure, version, settings,
        what each column holds), written atomically; ``read_csv`` reads it back (format:
        ``model.csvfile``)."""
        header = {"kind": self.kind, "figure": KINDS.get(self.kind, ""), "version": __version__,
                  "points": len(self), "seconds": round(self.seconds, 3), **self.settings}
        def write(tmp):
            with open(tmp, "w", newline="", encoding="utf-8") as out:
                csvfile.write(out, self.columns, header)

        write_atomic(path, write)  # a crash or Ctrl-C never leaves half a table


def read_csv(path) -> SweepResult:
    """A ``SweepResult`` read back from ``SweepResult.to_csv`` output."""
    header, columns = csvfile.read(path)
    kind, seconds = header.pop("kind"), float(header.pop("seconds", 0.0))
    for key in ("figure", "version", "points"):
        header.pop(key, None)
    return SweepResult(kind=kind, columns=columns, settings=header, seconds=seconds)


# --------------------------------------------------------------------------- the sweeps

def regime_map(k_r=None, k_theta=None, n: int = 8, F_N: float = 1.0, tol: float = 1e-3,
               beta="self", rtol=None, atol=None, method="auto", max_intervals: int = 256,
               progress=None, cancel=None, workers: int = 1, scheduler=None,
               coarse=None) -> SweepResult:
    """Fig. 5a/b: uniform arrays at every (k_r, k_theta) pair (k_r outer, k_theta inner).

    Columns: k_r, k_theta, the paper (Eq. 10) and duration-weighted F_T,x/(mu0 F_N),
    D_y/D_x, N_c/N_c0, beta, the quadrature error of F_T,x/(mu0 F_N), failed and
    pivot-passing members, success. On grids larger than 8 x 8 an 8 x 8 subgrid (ends
    included) is computed first and ``coarse(SweepResult)`` called with it. Along each
    k_theta row one point's beta starts the next (continuation; within ``tol`` of
    independent points).

    Parameters
    ----------
    k_r, k_theta, n, F_N
        The axes (default ``n`` = 8 log-spaced values on [0.01, 3]); the load (default 1).
    tol, beta, rtol, atol, method, max_intervals, progress, cancel, workers, scheduler
        As in ``uniform_array``; ``progress(done, total)``, ``cancel`` a threading.Event
        (``SweepCancelled``), ``workers`` local processes, ``scheduler`` a Dask Client.

    Examples
    --------
    >>> from model import regime_map
    >>> table = regime_map(n=2, tol=1e-2)   # the corners of the paper's map
    >>> table.columns["FTx_over_mu0FN"].round(3)
    array([0.821, 0.911, 0.945, 0.999])
    """
    n = _count(n)
    k_r, k_theta = (_grid(name, _log_axis(n) if g is None else g)
                    for name, g in (("k_r", k_r), ("k_theta", k_theta)))
    points = [Params(a, b, F_N=F_N) for a in k_r for b in k_theta]
    return _uniform_sweep("regime_map", points, {}, TABLES["regime_map"],
                          dict(F_N=float(F_N)), _run_args(locals()),
                          plan=_grid_plan(k_r.size, k_theta.size), coarse=coarse)


def load_sweep(regimes=("pendulum", "slider", "stiff", "soft"), F_N=None, n: int = 9,
               tol: float = 1e-3, beta="self", rtol=None, atol=None, method="auto",
               max_intervals: int = 256, progress=None, cancel=None, workers: int = 1,
               scheduler=None) -> SweepResult:
    """Fig. 6: uniform arrays of each regime against the load F_N (regime outer).

    Parameters
    ----------
    regimes, F_N : str or sequence of str, array_like
        Names in ``REGIMES`` (all four by default); loads (``n`` log-spaced on [0.1, 10]).
    tol, beta, rtol, atol, method, max_intervals, progress, cancel, workers, scheduler
        As in ``regime_map``.

    Examples
    --------
    >>> from model import load_sweep
    >>> load_sweep("soft", F_N=[0.1, 10], tol=1e-2).columns["FTx_over_mu0FN"].round(3)
    array([1.001, 0.686])
    """
    n = _count(n)
    regimes = [regimes] if isinstance(regimes, str) else list(regimes)
    unknown = [r for r in regimes if r not in REGIMES]
    if not regimes or unknown:
        raise ValueError(f"regimes={regimes!r} must name regimes among {sorted(REGIMES)}")
    loads = _grid("F_N", _log_axis(n, LOAD_RANGE) if F_N is None else F_N)
    points = [REGIMES[r].replace(F_N=f) for r in regimes for f in loads]
    labels = {"regime": [r for r in regimes for _ in loads]}
    # Continuation along the load axis, one chain per regime.
    return _uniform_sweep("load", points, labels, TABLES["load"], {}, _run_args(locals()),
                          plan=_grid_plan(len(regimes), loads.size, coarse=False))


def stiffness_sweep(k_r=None, k_theta=(0.01, 0.03, 0.1, 0.3, 1, 3), n: int = 8,
                    F_N: float = 1.0, tol: float = 1e-3, beta="self", rtol=None, atol=None,
                    method="auto", max_intervals: int = 256, progress=None, cancel=None,
                    workers: int = 1, scheduler=None) -> SweepResult:
    """Fig. 8a/b: N_c/N_c0 and the work split W = D_x + D_y + U_el + K (Eq. 12) vs k_r.

    One curve per k_theta (k_theta outer, k_r inner); k_r defaults to ``n`` log-spaced
    values on [0.01, 3]. The split columns are ratios of ensemble sums (D_x/W, ...).

    Parameters
    ----------
    k_r, k_theta : array_like
        Radial stiffnesses (``n`` log-spaced on [0.01, 3] by default) and one curve per
        torsional stiffness.
    tol, beta, rtol, atol, method, max_intervals, progress, cancel, workers, scheduler
        As in ``regime_map``.

    Examples
    --------
    >>> from model import stiffness_sweep
    >>> stiffness_sweep(k_r=[0.01, 3], k_theta=[3], tol=1e-2).columns["Nc_over_Nc0"].round(2)
    array([3.02, 1.04])
    """
    n = _count(n)
    k_r = _grid("k_r", _log_axis(n) if k_r is None else k_r)
    k_theta = _grid("k_theta", k_theta)
    points = [Params(a, b, F_N=F_N) for b in k_theta for a in k_r]
    return _uniform_sweep("stiffness", points, {}, TABLES["stiffness"], dict(F_N=float(F_N)),
                          _run_args(locals()), plan=_grid_plan(k_theta.size, k_r.size, coarse=False))


def orientation_table(params, theta0=None, n: int = 37, beta="self", rtol: float = 1e-6,
                      atol=None, method="auto", progress=None, cancel=None) -> SweepResult:
    """Figs. 10f, 11: fixed-orientation arrays for every theta0 (one batched call).

    Columns: theta0, F_T,x and F_T,y over mu0 F_N, D_y/D_x, N_c/N_c0, dtheta_rms, dr_rms,
    beta, pivot_approach, the relative energy residual abs(W - (D_x + D_y + U_el + K))/W
    (the integration error), success.

    Parameters
    ----------
    params : Params or str
        The springs and load, or a regime name.
    theta0 : array_like, optional
        Orientations [rad]; the midpoints of ``n`` equal cells of [0, pi] by default.
    beta, rtol, atol, method
        As in ``orientation_sweep``.

    Examples
    --------
    >>> from model import orientation_table
    >>> orientation_table("slider", n=4).columns["FTx_over_mu0FN"].round(3)
    array([0.855, 0.833, 0.997, 0.965])
    """
    start = time.perf_counter()
    if isinstance(params, str):
        params = Params.regime(params)
    # Default: midpoints of n equal cells of [0, pi], off the exact axis orientations
    # 0 and pi (where the mass starts on the axis; docs/model.md "Hard cases").
    theta0 = (np.arange(_count(n)) + 0.5) * math.pi / n if theta0 is None else theta0
    theta0 = _grid("theta0", theta0, positive=False)
    if cancel is not None and cancel.is_set():
        raise SweepCancelled(0, theta0.size)
    s = orientation_sweep(params, theta0, beta=beta, rtol=rtol, atol=atol, method=method)
    columns = {name: value_of(s, name) for name in TABLES["orientation"]}
    if progress is not None:
        progress(theta0.size, theta0.size)
    fields = {k: v for k, v in params.as_dict().items() if k not in ("theta0", "beta")}
    settings = {**fields, "beta": beta if isinstance(beta, str) else float(beta),
                "rtol": s.contacts.options.rtol, "atol": s.contacts.options.atol,
                "method": method, "beta_iterations": int(s.beta_iterations)}
    return SweepResult("orientation", {k: np.asarray(v) for k, v in columns.items()},
                       settings, time.perf_counter() - start)


# --------------------------------------------------------------------------- validation

def _count(n) -> int:
    return whole("n", n, 1)


def _log_axis(n: int, span=STIFFNESS_RANGE) -> np.ndarray:
    """``n`` log-spaced values on ``span``: the stiffness axes of Figs. 5 and 8 ([0.01, 3])
    by default, the loads of Fig. 6 with ``LOAD_RANGE``."""
    return np.logspace(math.log10(span.lo), math.log10(span.hi), n)


_grid = grid


_RUN_KEYS = ("tol", "beta", "rtol", "atol", "method", "max_intervals", "progress", "cancel",
             "workers", "scheduler")


def _run_args(scope: dict) -> dict:
    """The keyword arguments shared by the uniform-array sweeps, from a sweep's locals."""
    return {key: scope[key] for key in _RUN_KEYS}


def _solver_settings(args: dict) -> dict:
    """Validated uniform-array settings from a sweep's arguments (``ValueError`` if bad)."""
    # What uniform_array accepts, checked here so a bad value fails before any work.
    tol = number("tol", args["tol"], TOL, "quadrature tolerance tol")
    beta = load_factor("beta", args["beta"])
    SolverOptions(rtol=1e-6 if args["rtol"] is None else args["rtol"], atol=args["atol"],
                  method=args["method"])
    workers = whole("workers", args["workers"], 1)
    intervals = whole("max_intervals", args["max_intervals"], 1)
    if args["scheduler"] is not None and workers != 1:
        raise ValueError(f"workers={workers!r} must be 1 when a scheduler is given")
    return dict(tol=tol, beta=beta, rtol=args["rtol"], atol=args["atol"],
                method=args["method"], max_intervals=intervals)


# --------------------------------------------------------------------------- uniform points

def _grid_plan(n_outer: int, n_inner: int, coarse: bool = True, first: int = 8) -> list:
    """(n_inner, phases of chains of flat point indices outer * n_inner + inner): the
    order of work of a grid sweep.

    Each chain runs along the inner axis, each point starting from its predecessor's
    self-consistent beta. With ``coarse`` and a grid over ``first`` points on a side,
    the first phase is a ``first`` x ``first`` subgrid (ends included), the second the
    rest: a complete coarse picture early.
    """
    def take(count):
        return sorted(set(np.linspace(0, count - 1, min(first, count)).round().astype(int)))

    if not coarse or (n_outer <= first and n_inner <= first):
        return n_inner, [[[o * n_inner + i for i in range(n_inner)] for o in range(n_outer)]]
    rows, cols = take(n_outer), take(n_inner)
    phase1 = [[o * n_inner + i for i in cols] for o in rows]
    done = set(i for chain in phase1 for i in chain)
    phase2 = [[o * n_inner + i for i in range(n_inner) if o * n_inner + i not in done]
              for o in range(n_outer)]
    return n_inner, [phase1, [c for c in phase2 if c]]


def _uniform_sweep(kind, points, labels, names, fixed, args, plan=None,
                   coarse=None) -> SweepResult:
    """Run ``uniform_array`` at every point and gather the columns ``names``.

    ``plan`` (phases of chains of point indices, see ``_grid_plan``) orders the work:
    the chains of one phase run in parallel, each point of a chain seeded with the beta
    of its predecessor or of the nearest point of an earlier phase; ``coarse`` gets the
    ``SweepResult`` of the first phase when there are several.
    """
    start = time.perf_counter()
    settings = _solver_settings(args)
    width, plan = (1, [[[i] for i in range(len(points))]]) if plan is None else plan
    rows = [None] * len(points)
    total, done_before = len(points), 0
    progress = args["progress"]
    for phase_number, phase in enumerate(plan):
        def seed(i):
            """(beta, slope) of the nearest point already computed, and its distance."""
            best = None
            for j, row in enumerate(rows):
                if row is None:
                    continue
                d = abs(i // width - j // width) + abs(i % width - j % width)
                if best is None or d < best[0]:
                    best = (d, (row["beta"], row.get("beta_slope", math.nan)))
            return best or (math.inf, None)

        tasks = [[(points[i], settings) + seed(i) for i in chain] for chain in phase]
        report = None if progress is None else (
            lambda done, _total, base=done_before: progress(base + done, total))
        results = run_points(_uniform_chain, tasks, args["workers"], args["scheduler"], report,
                             args["cancel"], sizes=[len(c) for c in phase])
        for chain, chain_rows in zip(phase, results):
            for i, row in zip(chain, chain_rows):
                rows[i] = row
        done_before += sum(len(c) for c in phase)
        if coarse is not None and phase_number == 0 and len(plan) > 1:
            ids = sorted(i for chain in phase for i in chain)
            coarse(_sweep_result(kind, [rows[i] for i in ids],
                                 {k: [v[i] for i in ids] for k, v in labels.items()},
                                 names, fixed, settings, args, start))
    return _sweep_result(kind, rows, labels, names, fixed, settings, args, start)


def _sweep_result(kind, rows, labels, names, fixed, settings, args, start) -> SweepResult:
    columns = {name: np.asarray(labels[name] if name in labels else [r[name] for r in rows])
               for name in names}
    scheduler = args["scheduler"]
    where = scheduler if isinstance(scheduler, str) or scheduler is None else "dask client"
    settings = {**fixed, **settings, "rtol": rows[0]["rtol"], "workers": int(args["workers"]),
                "scheduler": where}
    return SweepResult(kind, columns, settings, time.perf_counter() - start)


def _uniform_chain(chain) -> list:
    """Rows of a chain of points, each continued from its predecessors' beta.

    A task is (params, settings, distance, (beta, slope) or None) with the seed from an
    earlier phase; the predecessor in the chain (distance 1) is preferred when nearer,
    and two predecessors extrapolate beta linearly in the log of the swept parameter.
    """
    rows, done = [], []
    for params, settings, distance, seeded in chain:
        close = False
        if len(done) >= 2 and distance > 1:
            guess, close = _extrapolate(done[-2], done[-1], params)
        else:
            guess = (done[-1][1]["beta"], done[-1][1].get("beta_slope", math.nan)) \
                if done and distance > 1 else seeded
        row = _uniform_point((params, settings), guess, close)
        rows.append(row)
        done.append((params, row))
    return rows


def _extrapolate(first, second, params) -> tuple:
    """((beta, slope), True) extrapolated from two points along the one parameter that
    changes (linearly in its log); the second point's own when none does or it jumps."""
    (p1, r1), (p2, r2) = first, second
    beta, slope = r2["beta"], r2.get("beta_slope", math.nan)
    changed = [k for k in ("k_r", "k_theta", "F_N") if getattr(p1, k) != getattr(p2, k)]
    if len(changed) != 1 or changed != [k for k in ("k_r", "k_theta", "F_N")
                                        if getattr(params, k) != getattr(p2, k)]:
        return (beta, slope), False
    x1, x2, x = (math.log(getattr(p, changed[0])) for p in (p1, p2, params))
    step = (beta - r1["beta"]) / (x2 - x1) * (x - x2)
    if not (r1["beta"] < 1.0 and beta < 1.0) or abs(step) > 0.1 * beta:
        return (beta, slope), False  # capped, or too far to trust a straight line
    return (min(1.0, beta + step), slope), True


def _uniform_point(task, guess=None, close=False) -> dict:
    """One uniform array (Figs. 5, 6, 8) as a row of plain numbers, from the disk cache
    when this point was computed before with the same settings and package version.
    ``guess`` (beta, slope) only starts the self-consistent solve: not part of the key."""
    params, settings = task
    key = make_key("uniform_array", params=params.as_dict(), **settings)
    row = DiskCache().get_or_compute(key, lambda: _compute_point(params, settings, guess, close))
    return {name: value.item() for name, value in row.items()}


def _compute_point(params, settings, guess=None, close=False) -> dict:
    if settings["beta"] != "self" or guess is None or not 0 < guess[0] <= 1:
        guess = None
    r = uniform_array(params, **settings, beta_guess=guess, guess_is_close=close)
    inputs = {"k_r": params.k_r, "k_theta": params.k_theta, "F_N": params.F_N,
              "rtol": r.stats["rtol"]}
    return {name: np.asarray(inputs[name] if name in inputs else value_of(r, name))
            for name in TABLES["uniform_point"]}
