"""Parameter sweeps behind the paper's figures, each returning a ``SweepResult``.

* ``regime_map`` (Fig. 5a/b): uniform arrays on a (k_r, k_theta) grid;
* ``load_sweep`` (Fig. 6): uniform arrays of the four regimes against F_N;
* ``stiffness_sweep`` (Fig. 8a/b): N_c/N_c0 and the split of the slab work (Eq. 12)
  against k_r for several k_theta;
* ``orientation_table`` (Figs. 10f, 11): fixed-orientation arrays against theta0.

Every point of the uniform-array sweeps is one independent ``uniform_array`` call, kept
in the on-disk cache (``model.cache``: the user's cache directory, or
``$MICROPILLAR_CACHE_DIR``) so that no point is computed twice. The points run
serially (``workers=1``), on a local process pool (``workers > 1``) or on a
dask.distributed cluster (``scheduler``), with identical results. ``progress(done,
total)`` is called after each point; setting the ``cancel`` event stops the sweep,
which then raises ``SweepCancelled``.
"""
from __future__ import annotations

import csv
import json
import math
import time
from dataclasses import dataclass

import numpy as np

from .cache import DiskCache, make_key
from .fixed import orientation_sweep
from .options import SolverOptions
from .parallel import SweepCancelled, run_points
from .params import REGIMES, Params
from .uniform import uniform_array

__all__ = ["SweepResult", "SweepCancelled", "regime_map", "load_sweep", "stiffness_sweep",
           "orientation_table", "read_csv", "KINDS"]

#: Sweep kind -> the figures it reproduces.
KINDS = {"regime_map": "5a, 5b", "load": "6", "stiffness": "8a, 8b", "orientation": "10f, 11"}
_ARRAY = ["FTx_over_mu0FN", "FTx_over_mu0FN_duration", "Dy_over_Dx", "Nc_over_Nc0", "beta"]
_CHECKS = ["quadrature_error_FTx", "n_failed", "n_pivot", "success"]
_SPLIT = ["Dx_over_W", "Dy_over_W", "Uel_over_W", "K_over_W"]


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
        """CSV with a header block of ``# key: value`` lines (kind, figure, version, settings).

        ``read_csv`` reads it back; so does ``numpy.genfromtxt(path, delimiter=",",
        names=True, dtype=None, encoding="utf-8", skip_header=<number of # lines>)``.
        """
        from . import __version__

        header = {"kind": self.kind, "figure": KINDS.get(self.kind, ""), "version": __version__,
                  "points": len(self), "seconds": round(self.seconds, 3), **self.settings}
        with open(path, "w", newline="", encoding="utf-8") as out:
            for key, value in header.items():
                out.write(f"# {key}: {value if isinstance(value, str) else json.dumps(value)}\n")
            writer = csv.writer(out)
            writer.writerow(self.columns)
            for row in zip(*self.columns.values()):
                writer.writerow([_cell(v) for v in row])


def _cell(value) -> str:
    """Text of one CSV cell; floats in their shortest round-trip form."""
    if isinstance(value, (bool, np.bool_)):
        return str(bool(value))
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    return str(value)


def read_csv(path) -> SweepResult:
    """A ``SweepResult`` read back from ``SweepResult.to_csv`` output."""
    header, lines = {}, []
    with open(path, encoding="utf-8") as src:
        for line in src:
            if line.startswith("# "):
                key, _, text = line[2:].rstrip("\n").partition(": ")
                try:
                    header[key] = json.loads(text)
                except ValueError:
                    header[key] = text
            else:
                lines.append(line)
    names, *rows = list(csv.reader(lines))
    columns = {name: _parse_column([r[j] for r in rows]) for j, name in enumerate(names)}
    kind, seconds = header.pop("kind"), float(header.pop("seconds", 0.0))
    for key in ("figure", "version", "points"):
        header.pop(key, None)
    return SweepResult(kind=kind, columns=columns, settings=header, seconds=seconds)


def _parse_column(texts):
    if texts and set(texts) <= {"True", "False"}:
        return np.array([t == "True" for t in texts])
    for kind in (int, float):
        try:
            return np.array([kind(t) for t in texts], dtype=kind)
        except ValueError:
            pass
    return np.array(texts)


# --------------------------------------------------------------------------- the sweeps

def regime_map(k_r=None, k_theta=None, n: int = 8, F_N: float = 1.0, tol: float = 1e-3,
               beta="self", rtol=None, atol=None, method="auto", max_intervals: int = 256,
               progress=None, cancel=None, workers: int = 1, scheduler=None) -> SweepResult:
    """Fig. 5a/b: uniform arrays at every (k_r, k_theta) pair (k_r outer, k_theta inner).

    Both axes default to ``n`` log-spaced values on [0.01, 3]. Columns: k_r, k_theta, the
    paper (Eq. 10) and duration-weighted F_T,x/(mu0 F_N), D_y/D_x, N_c/N_c0, beta, the
    quadrature error of F_T,x/(mu0 F_N), failed and pivot-passing members, success.
    """
    n = _count(n)
    k_r, k_theta = (_grid(name, _log_axis(n) if g is None else g)
                    for name, g in (("k_r", k_r), ("k_theta", k_theta)))
    points = [Params(a, b, F_N=F_N) for a in k_r for b in k_theta]
    return _uniform_sweep("regime_map", points, {}, ["k_r", "k_theta", *_ARRAY, *_CHECKS],
                          dict(F_N=float(F_N)), _run_args(locals()))


def load_sweep(regimes=("pendulum", "slider", "stiff", "soft"), F_N=None, n: int = 9,
               tol: float = 1e-3, beta="self", rtol=None, atol=None, method="auto",
               max_intervals: int = 256, progress=None, cancel=None, workers: int = 1,
               scheduler=None) -> SweepResult:
    """Fig. 6: uniform arrays of each regime against the load F_N (regime outer).

    F_N defaults to ``n`` log-spaced values on [0.1, 10]; increasing F_N lowers
    F_T,x/(mu0 F_N) in every regime.
    """
    n = _count(n)
    regimes = [regimes] if isinstance(regimes, str) else list(regimes)
    unknown = [r for r in regimes if r not in REGIMES]
    if not regimes or unknown:
        raise ValueError(f"regimes={regimes!r} must name regimes among {sorted(REGIMES)}")
    loads = _grid("F_N", np.logspace(-1, 1, n) if F_N is None else F_N)
    points = [REGIMES[r].replace(F_N=f) for r in regimes for f in loads]
    labels = {"regime": [r for r in regimes for _ in loads]}
    names = ["regime", "k_r", "k_theta", "F_N", *_ARRAY, *_CHECKS]
    return _uniform_sweep("load", points, labels, names, {}, _run_args(locals()))


def stiffness_sweep(k_r=None, k_theta=(0.01, 0.03, 0.1, 0.3, 1, 3), n: int = 8,
                    F_N: float = 1.0, tol: float = 1e-3, beta="self", rtol=None, atol=None,
                    method="auto", max_intervals: int = 256, progress=None, cancel=None,
                    workers: int = 1, scheduler=None) -> SweepResult:
    """Fig. 8a/b: N_c/N_c0 and the work split W = D_x + D_y + U_el + K (Eq. 12) vs k_r.

    One curve per k_theta (k_theta outer, k_r inner); k_r defaults to ``n`` log-spaced
    values on [0.01, 3]. The split columns are ratios of ensemble sums (D_x/W, ...).
    """
    n = _count(n)
    k_r = _grid("k_r", _log_axis(n) if k_r is None else k_r)
    k_theta = _grid("k_theta", k_theta)
    points = [Params(a, b, F_N=F_N) for b in k_theta for a in k_r]
    names = ["k_theta", "k_r", "Nc_over_Nc0", *_SPLIT, *_ARRAY[:3], "beta",
             "quadrature_error_Nc", *_CHECKS]
    return _uniform_sweep("stiffness", points, {}, names, dict(F_N=float(F_N)),
                          _run_args(locals()))


def orientation_table(params, theta0=None, n: int = 37, beta="self", rtol: float = 1e-6,
                      atol=None, method="auto", progress=None, cancel=None) -> SweepResult:
    """Figs. 10f, 11: fixed-orientation arrays for every theta0 (one batched call).

    ``params`` is a ``Params`` or a regime name; theta0 defaults to the midpoints of
    ``n`` equal cells of [0, pi]. Columns: theta0, F_T,x and F_T,y over mu0 F_N, D_y/D_x, N_c/N_c0,
    dtheta_rms, dr_rms, beta, pivot_approach, the relative energy residual
    |W - (D_x + D_y + U_el + K)|/W (the integration error), success.
    """
    start = time.perf_counter()
    if isinstance(params, str):
        params = Params.regime(params)
    # Default: midpoints of n equal cells of [0, pi], off the exact axis orientations
    # 0 and pi (where the mass starts on the axis; MODEL.md "Hard cases").
    theta0 = (np.arange(_count(n)) + 0.5) * math.pi / n if theta0 is None else theta0
    theta0 = _grid("theta0", theta0, positive=False)
    if cancel is not None and cancel.is_set():
        raise SweepCancelled(0, theta0.size)
    s = orientation_sweep(params, theta0, beta=beta, rtol=rtol, atol=atol, method=method)
    columns = {"theta0": s.theta0, "FTx_over_mu0FN": s.FTx_over_mu0FN,
               "FTy_over_mu0FN": s.FTy_over_mu0FN, "Dy_over_Dx": s.Dy_over_Dx,
               "Nc_over_Nc0": s.Nc_over_Nc0, "dtheta_rms": s.dtheta_rms, "dr_rms": s.dr_rms,
               "beta": s.beta, "pivot_approach": s.contacts.pivot_approach,
               "relative_residual": np.abs(s.contacts.energy_residual) / np.abs(s.contacts.W),
               "success": s.success}
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
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"n={n!r} must be a whole number >= 1")
    return int(n)


def _log_axis(n: int) -> np.ndarray:
    """``n`` log-spaced stiffnesses on [0.01, 3], the axes of Figs. 5 and 8."""
    return np.logspace(-2, math.log10(3.0), n)


def _grid(name: str, values, positive: bool = True) -> np.ndarray:
    """A non-empty 1-D array of finite (and positive) numbers, else ``ValueError``."""
    try:
        grid = np.atleast_1d(np.asarray(values, dtype=float))
    except (TypeError, ValueError):
        grid = np.array([])
    bad = grid.ndim != 1 or grid.size == 0 or not np.all(np.isfinite(grid))
    if bad or (positive and np.any(grid <= 0)):
        kind = "positive finite" if positive else "finite"
        raise ValueError(f"{name}={values!r} must be a non-empty 1-D sequence of {kind} numbers")
    return grid


_RUN_KEYS = ("tol", "beta", "rtol", "atol", "method", "max_intervals", "progress", "cancel",
             "workers", "scheduler")


def _run_args(scope: dict) -> dict:
    """The keyword arguments shared by the uniform-array sweeps, from a sweep's locals."""
    return {key: scope[key] for key in _RUN_KEYS}


def _solver_settings(args: dict) -> dict:
    """Validated uniform-array settings from a sweep's arguments (``ValueError`` if bad)."""
    tol, beta, workers = args["tol"], args["beta"], args["workers"]
    # The range uniform_array accepts, checked here so a bad value fails before any work.
    if isinstance(tol, bool) or not isinstance(tol, (int, float)) or not 1e-8 <= tol <= 0.5:
        raise ValueError(f"tol={tol!r} must be in [1e-8, 0.5]")
    if isinstance(beta, str):
        if beta != "self":
            raise ValueError(f"beta={beta!r} must be 'self' or a number in (0, 1]")
    else:
        beta = Params(1.0, 1.0, beta=beta).beta
    SolverOptions(rtol=1e-6 if args["rtol"] is None else args["rtol"], atol=args["atol"],
                  method=args["method"])
    if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or workers < 1:
        raise ValueError(f"workers={workers!r} must be a whole number >= 1")
    intervals = args["max_intervals"]
    if isinstance(intervals, bool) or not isinstance(intervals, (int, np.integer)) \
            or intervals < 1:
        raise ValueError(f"max_intervals={intervals!r} must be a whole number >= 1")
    if args["scheduler"] is not None and workers != 1:
        raise ValueError(f"workers={workers!r} must be 1 when a scheduler is given")
    return dict(tol=float(tol), beta=beta, rtol=args["rtol"], atol=args["atol"],
                method=args["method"], max_intervals=int(args["max_intervals"]))


# --------------------------------------------------------------------------- uniform points

def _uniform_sweep(kind, points, labels, names, fixed, args) -> SweepResult:
    """Run ``uniform_array`` at every point and gather the columns ``names``."""
    start = time.perf_counter()
    settings = _solver_settings(args)
    tasks = [(p, settings) for p in points]
    rows = run_points(_uniform_point, tasks, args["workers"], args["scheduler"],
                      args["progress"], args["cancel"])
    columns = {name: np.asarray(labels[name] if name in labels else [r[name] for r in rows])
               for name in names}
    scheduler = args["scheduler"]
    where = scheduler if isinstance(scheduler, str) or scheduler is None else "dask client"
    settings = {**fixed, **settings, "rtol": rows[0]["rtol"], "workers": int(args["workers"]),
                "scheduler": where}
    return SweepResult(kind, columns, settings, time.perf_counter() - start)


def _uniform_point(task) -> dict:
    """One uniform array (Figs. 5, 6, 8) as a row of plain numbers, from the disk cache
    when this point was computed before with the same settings and package version."""
    params, settings = task
    key = make_key("uniform_array", params=params.as_dict(), **settings)
    row = DiskCache().get_or_compute(key, lambda: _compute_point(params, settings))
    return {name: value.item() for name, value in row.items()}


def _compute_point(params, settings) -> dict:
    r = uniform_array(params, **settings)
    q, split = r.quadrature_error, r.work_split
    row = {"k_r": params.k_r, "k_theta": params.k_theta, "F_N": params.F_N,
            "FTx_over_mu0FN": r.FTx_over_mu0FN,
            "FTx_over_mu0FN_duration": r.FTx_over_mu0FN_duration,
            "Dy_over_Dx": r.Dy_over_Dx, "Nc_over_Nc0": r.Nc_over_Nc0, "beta": r.beta,
            "Dx_over_W": split["D_x"], "Dy_over_W": split["D_y"], "Uel_over_W": split["U_el"],
            "K_over_W": split["K"], "quadrature_error_FTx": q["FTx_over_mu0FN"],
            "quadrature_error_Nc": q["Nc_over_Nc0"], "n_failed": r.n_failed,
            "n_pivot": r.n_pivot, "success": r.success, "rtol": r.stats["rtol"]}
    return {name: np.asarray(value) for name, value in row.items()}
