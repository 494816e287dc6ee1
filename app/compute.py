"""What the dashboard computes, as plain data for the figure functions.

* ``support_future`` (``compute_support`` of ``app/worker.py``, in a worker process): one
  support at the current theta0 -- the trajectory of one contact (Eqs. 5-6, 9) with
  ``SAMPLES`` points for the scene and Fig. 7, and the fixed-orientation array at theta0
  (Figs. 9-11: F_T,x/(mu0 F_N), F_T,y/(mu0 F_N), D_y/D_x, N_c/N_c0). The trajectory is
  integrated with the array's load factor beta, so it is the motion behind the readouts.
* ``polar_future``: fixed arrays over ``POLAR_N`` orientations (Fig. 11), in a worker process.
* ``uniform_future``: the uniform array (Figs. 5, 6, 8; quadrature tolerance
  ``UNIFORM_TOL``), in a worker process, through the model's on-disk sweep cache.

Finished results are kept in bounded caches shared by every session of the server.
"""
from __future__ import annotations

import math

import numpy as np

from model import Params
from model.sweeps import orientation_table, regime_map

from .jobs import ResultCache, cached_submit, process_pool, worker_module

_worker = worker_module()
SupportData, compute_support, SAMPLES = (_worker.SupportData, _worker.compute_support,
                                         _worker.SAMPLES)
POLAR_N = 72
#: Midpoints of POLAR_N equal cells of [0, pi]: off the on-axis starts 0 and pi.
POLAR_THETA0 = (np.arange(POLAR_N) + 0.5) * math.pi / POLAR_N
#: The loads of the Fig. 6 curves (log-spaced on [0.1, 10]).
LOAD_F_N = tuple(float(f) for f in np.logspace(-1, 1, 7))
UNIFORM_TOL = 1e-3

_SUPPORT = ResultCache(256)
_POLAR = ResultCache(64)
_UNIFORM = ResultCache(1024)


def support_future(params: Params, beta="self", rtol: float = 1e-6, samples: int = SAMPLES):
    """Future of ``compute_support`` (a ``SupportData``), computed in the "support" worker.

    The kernel never runs on the server's event loop, so even a contact that takes
    seconds (theta0 exactly on the axis at tight tolerances) leaves the page responsive.
    Finished results are cached for every session; the result never is an exception.
    """
    return cached_submit(_SUPPORT, (params, beta, rtol, samples), process_pool("support"),
                         compute_support, params, beta, rtol, samples)


def _sweep_params(params: Params) -> Params:
    """``params`` without what a sweep over theta0 ignores (a shared cache key)."""
    return params.replace(theta0=math.pi / 2, beta=1.0)


def polar_future(params: Params, beta="self", rtol: float = 1e-6):
    """Future of ``orientation_table`` (Fig. 11) over ``POLAR_THETA0``: a ``SweepResult``."""
    p = _sweep_params(params)
    return cached_submit(_POLAR, (p, beta, rtol), process_pool("sweep"), orientation_table,
                         p, theta0=POLAR_THETA0, beta=beta, rtol=rtol)


def polar_cached(params: Params, beta="self", rtol: float = 1e-6):
    """The polar sweep if it was computed already, else None."""
    return _POLAR.get((_sweep_params(params), beta, rtol))


def uniform_future(k_r: float, k_theta: float, F_N: float, beta="self"):
    """Future of the uniform array at (k_r, k_theta, F_N): a one-row ``SweepResult``.

    Columns: F_T,x/(mu0 F_N) (paper, Eq. 10, and duration-weighted), D_y/D_x, N_c/N_c0,
    beta, the quadrature error, failed and pivot-passing members, success.
    """
    key = (float(k_r), float(k_theta), float(F_N), beta)
    return cached_submit(_UNIFORM, key, process_pool("array"), regime_map, k_r=[key[0]],
                         k_theta=[key[1]], F_N=key[2], beta=beta, tol=UNIFORM_TOL)


def sweep_row(sweep, i: int = 0) -> dict:
    """Row ``i`` of a ``SweepResult`` as plain Python numbers."""
    return {k: np.asarray(v)[i].item() for k, v in sweep.columns.items()}
