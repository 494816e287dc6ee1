"""The regime map of Fig. 5: uniform arrays over a log grid of (k_r, k_theta).

Precomputed 24 x 24 maps (tol 1e-3, self-consistent beta, paper average Eq. 10) at
the loads ``SHIPPED_LOADS`` = F_N 0.1, 0.3, 1, 3, 10 ship inside the package
(``model/data/regime_map_FN<F_N>.npz``) so they can be shown instantly::

    >>> from model.runs.shipped_map import load_regime_map
    >>> m = load_regime_map()          # F_N = 1
    >>> m = load_regime_map(F_N=3)
    >>> m.FTx_over_mu0FN[i, j]         # at k_r = m.k_r[i], k_theta = m.k_theta[j]

Regenerate one (prints progress, the time taken and the largest quadrature error)::

    python -m model.runs.shipped_map --n 24 --workers 2 --F-N 3 [--out PATH]
"""
from __future__ import annotations

import argparse
import datetime as _dt
import json
import math
import sys
import time
from dataclasses import dataclass, field, fields
from importlib import resources
from pathlib import Path

import numpy as np

from .._version import __version__
from ..controls import STIFFNESS_RANGE

__all__ = ["RegimeMap", "load_regime_map", "compute_regime_map", "save_regime_map",
           "packaged_path", "GRID_RANGE", "SHIPPED_LOADS"]

#: Range of both stiffness axes (Fig. 5), sampled logarithmically.
GRID_RANGE = STIFFNESS_RANGE.bounds
#: Loads F_N of the maps shipped in model/data.
SHIPPED_LOADS = (0.1, 0.3, 1.0, 3.0, 10.0)
#: Quantities taken from each ``UniformArrayResult`` (one (n, m) array each).
QUANTITIES = ("FTx_over_mu0FN", "FTx_over_mu0FN_duration", "Dy_over_Dx", "Nc_over_Nc0")


@dataclass(frozen=True)
class RegimeMap:
    """Uniform-array results on the grid k_r (n,) x k_theta (m,); arrays are (n, m).

    ``quadrature_error`` is the quadrature error estimate of ``FTx_over_mu0FN``
    (the quadrature also meets ``tol`` on ``Nc_over_Nc0``). ``success`` is False where the
    quadrature tolerance was not met or members did not finish their contact;
    ``n_failed`` and ``n_pivot`` count the members that did not finish and the
    members driven into the region of their pivot at each point.
    """

    k_r: np.ndarray
    k_theta: np.ndarray
    FTx_over_mu0FN: np.ndarray
    FTx_over_mu0FN_duration: np.ndarray
    Dy_over_Dx: np.ndarray
    Nc_over_Nc0: np.ndarray
    beta: np.ndarray
    quadrature_error: np.ndarray
    success: np.ndarray
    n_failed: np.ndarray | None = None
    n_pivot: np.ndarray | None = None
    metadata: dict = field(default_factory=dict)

    @property
    def shape(self) -> tuple[int, int]:
        return self.FTx_over_mu0FN.shape

    def arrays(self) -> dict:
        """Every array by its name in the ``.npz`` file."""
        out = {name: getattr(self, name) for name in
               ("k_r", "k_theta", *QUANTITIES, "beta", "quadrature_error", "success")}
        out.update({k: getattr(self, k) for k in ("n_failed", "n_pivot") if getattr(self, k) is not None})
        return out


def packaged_path(F_N: float = 1.0) -> Path:
    """Path of the map shipped with the package for the load ``F_N`` (one of
    ``SHIPPED_LOADS``)."""
    matches = [f for f in SHIPPED_LOADS if math.isclose(f, F_N, rel_tol=1e-9)]
    if not matches:
        raise ValueError(f"F_N={F_N!r} has no shipped regime map; shipped loads are "
                         f"{', '.join(f'{f:g}' for f in SHIPPED_LOADS)} (compute others with "
                         "model.runs.sweeps.regime_map)")
    return Path(str(resources.files("model") / "data" / f"regime_map_FN{matches[0]:g}.npz"))


def load_regime_map(path=None, F_N: float | None = None) -> RegimeMap:
    """Read a regime map: ``path``, or the one shipped for ``F_N`` (default F_N = 1)."""
    if path is not None and F_N is not None:
        raise ValueError("give path or F_N, not both")
    path = packaged_path(1.0 if F_N is None else F_N) if path is None else Path(path)
    with np.load(path, allow_pickle=False) as npz:
        data = {name: npz[name] for name in npz.files}
    meta = json.loads(str(data.pop("metadata")[()]))
    known = {f.name for f in fields(RegimeMap)}
    return RegimeMap(metadata=meta, **{k: v for k, v in data.items() if k in known})


def save_regime_map(regime_map: RegimeMap, path) -> Path:
    """Write ``regime_map`` to ``path`` (.npz, metadata as a JSON string array)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".part")
    with open(tmp, "wb") as f:
        np.savez(f, allow_pickle=False, metadata=np.array(json.dumps(regime_map.metadata)),
                 **regime_map.arrays())
    tmp.replace(path)
    return path


def grid(n: int) -> np.ndarray:
    """n log-spaced stiffnesses on ``GRID_RANGE`` (the axes of ``model.runs.sweeps.regime_map``)."""
    lo, hi = GRID_RANGE
    return np.logspace(math.log10(lo), math.log10(hi), n)


def compute_regime_map(n: int = 24, F_N: float = 1.0, tol: float = 1e-3, progress=None,
                       workers: int = 1) -> RegimeMap:
    """Uniform arrays (self-consistent beta) on an n x n log grid of (k_r, k_theta).

    Runs ``model.runs.sweeps.regime_map``; ``progress(done, total)`` is called after every
    point and ``workers > 1`` spreads the points over that many processes.
    """
    from .sweeps import regime_map

    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 2:
        raise ValueError(f"n={n!r} must be a whole number >= 2")
    k = grid(int(n))
    sweep = regime_map(k_r=k, k_theta=k, F_N=F_N, tol=tol, progress=progress,
                       workers=int(workers))
    return _from_sweep(k, sweep)


def _from_sweep(k, sweep) -> RegimeMap:
    """The ``SweepResult`` rows (k_r outer, k_theta inner) as (n, n) arrays."""
    cols = sweep.columns
    grid2 = lambda name: np.asarray(cols[name]).reshape(k.size, k.size)  # noqa: E731
    if not (np.allclose(grid2("k_r")[:, 0], k) and np.allclose(grid2("k_theta")[0], k)):
        raise RuntimeError("regime_map sweep rows are not in (k_r outer, k_theta inner) order")
    success = grid2("success").astype(bool)
    qerr = grid2("quadrature_error_FTx")
    meta = {
        **{key: value for key, value in sweep.settings.items() if key != "scheduler"},
        "beta_mode": sweep.settings.get("beta"), "average": "paper (Eq. 10)",
        "grid": {"n": int(k.size), "range": list(GRID_RANGE), "spacing": "log"},
        "index_order": "[i, j] is k_r[i], k_theta[j]",
        "package_version": __version__, "numpy_version": np.__version__,
        "date": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        "seconds": round(float(sweep.seconds), 2),
        "max_quadrature_error": float(np.max(qerr)),
        "n_unsuccessful": int(np.sum(~success)),
        "unsuccessful": [[float(k[i]), float(k[j])] for i, j in zip(*np.nonzero(~success))],
        "n_points_with_failed_members": int(np.sum(grid2("n_failed") > 0)),
        "n_points_with_pivot_passage": int(np.sum(grid2("n_pivot") > 0)),
    }
    return RegimeMap(k_r=k.copy(), k_theta=k.copy(),
                     **{q: grid2(q).astype(float) for q in QUANTITIES},
                     beta=grid2("beta").astype(float), quadrature_error=qerr.astype(float),
                     success=success, n_failed=grid2("n_failed").astype(int),
                     n_pivot=grid2("n_pivot").astype(int), metadata=meta)


def _progress_printer(start):
    """Progress on stderr: one updating line on a terminal, else a line per ~5 %."""
    tty = sys.stderr.isatty()

    def report(done, total):
        if tty or done == total or done % max(1, total // 20) == 0:
            print(f"{chr(13) if tty else ''}{done}/{total} points, {time.perf_counter() - start:.1f} s",
                  end="\n" if done == total or not tty else "", file=sys.stderr, flush=True)
    return report


def main(argv=None) -> int:
    """Command line: regenerate the regime map and report time and largest error."""
    ap = argparse.ArgumentParser(prog="python -m model.runs.shipped_map", description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=24, help="grid points per axis (default 24)")
    ap.add_argument("--F-N", dest="F_N", type=float, default=1.0, help="normal load (default 1)")
    ap.add_argument("--tol", type=float, default=1e-3, help="quadrature tolerance (default 1e-3)")
    ap.add_argument("--workers", type=int, default=1, help="processes (default 1)")
    ap.add_argument("--out", default=None,
                    help="output .npz (default: the packaged map of that load)")
    args = ap.parse_args(argv)
    start = time.perf_counter()
    m = compute_regime_map(n=args.n, F_N=args.F_N, tol=args.tol, workers=args.workers,
                           progress=_progress_printer(start))
    out = save_regime_map(m, args.out or packaged_path(args.F_N))
    meta = m.metadata
    print(f"wrote {out}")
    print(f"{m.shape[0]}x{m.shape[1]} points in {meta['seconds']:.1f} s with {args.workers} worker(s)")
    print(f"largest quadrature error of F_T,x/(mu0 F_N): {meta['max_quadrature_error']:.3g}")
    print(f"unsuccessful points: {meta['n_unsuccessful']}; points with failed members: "
          f"{meta['n_points_with_failed_members']}; with pivot passage: "
          f"{meta['n_points_with_pivot_passage']}")
    for a, b in meta["unsuccessful"]:
        print(f"  k_r={a:.4g} k_theta={b:.4g}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
