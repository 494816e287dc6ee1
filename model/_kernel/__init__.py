"""The compiled kernel: the only place numba is used.

Everything here takes plain floats and numpy arrays; ``model.contact.support`` wraps it.
``pack`` turns a ``Params`` into the flat array the kernel reads.
"""
import hashlib
from pathlib import Path

import numpy as np

from ..contact.friction import series_coefficients
from . import slots
from .batch import DERIVED, integrate_batch
from .driver import DOP853_RTOL, integrate
from .record import MAX_NODES, N_NODE_COLS, N_REC, REC_SLOTS
from .rhs import FN, N_PARAM, REG, TH0, X0, jacobian, mu_over_s, rhs
from .slots import N_MOTION, N_STATE, N_STATS, STAT_NAMES, TAU, THETA, X, Y

__all__ = ["pack", "initial_state", "integrate", "integrate_batch", "warmup", "cache_is_cold",
           "announce_cold_start", "rhs", "jacobian", "mu_over_s",
           "slots", "STAT_NAMES", "N_STATE", "N_MOTION", "N_STATS", "N_REC", "REC_SLOTS", "N_NODE_COLS", "MAX_NODES", "METHOD_CODES", "DOP853_RTOL", "TH0", "X0", "FN", "TAU", "REG", "DERIVED"]

METHOD_CODES = {"auto": 0, "explicit": 1, "implicit": 2}
_MODULES = ("slots", "rhs", "dopri5", "dop853", "rodas4", "event", "record", "driver", "batch")


def _purge_stale_cache() -> None:
    """Drop numba's cached kernel when any kernel source file changed.

    numba checks only the source file of the cached function itself, so an edit of
    ``driver.py`` would leave ``batch.integrate_batch`` (which inlines it) stale. A stamp
    with the hash of every kernel module sits beside the cache; on a mismatch the
    kernel's cache files are deleted and the kernel is compiled afresh.
    """
    here = Path(__file__).parent
    digest = hashlib.sha256(b"".join((here / f"{m}.py").read_bytes() for m in _MODULES))
    try:
        cache_dir = Path(integrate_batch._cache._cache_path)
    except AttributeError:  # numba internals changed: nothing to check
        return
    stamp = cache_dir / "micropillar-kernel.stamp"
    try:
        if stamp.is_file() and stamp.read_text() == digest.hexdigest():
            return
        for f in cache_dir.glob("*.nb[ic]"):
            if f.name.split(".")[0] in _MODULES:
                f.unlink()
        cache_dir.mkdir(parents=True, exist_ok=True)
        stamp.write_text(digest.hexdigest())
    except OSError:  # a read-only cache: numba will compile in memory
        pass


_purge_stale_cache()


#: Seconds a cold compile of the kernel takes on a 2-core machine (for the message).
COLD_COMPILE_SECONDS = 20


def cache_is_cold() -> bool:
    """True when numba's on-disk cache holds no compiled kernel (first start, or the
    kernel sources changed), so the first integration will compile for several seconds."""
    try:
        cache_dir = Path(integrate_batch._cache._cache_path)
    except AttributeError:  # numba internals changed: assume the worst
        return True
    if integrate_batch.signatures:  # compiled or loaded in this process already
        return False
    return not any(cache_dir.glob("batch.integrate_batch-*.nbi"))


def announce_cold_start(stream) -> bool:
    """Write "preparing the solver (first start, ~N s)" to ``stream`` when the kernel
    must be compiled first (instead of a silent pause); True if it did."""
    if not cache_is_cold():
        return False
    stream.write(f"preparing the solver (first start, ~{COLD_COMPILE_SECONDS} s)\n")
    stream.flush()
    return True


def warmup() -> float:
    """Compile (or load from numba's on-disk cache) every kernel path; returns seconds.

    A cold compile takes ~18 s on a 2-core machine, loading the cache < 1 s; servers
    and images call this once at build or start so no visitor waits.
    """
    import time

    from ..contact.params import REGIMES

    start = time.perf_counter()
    params = REGIMES["soft"]
    for code in METHOD_CODES.values():
        integrate_batch(initial_state(params)[None], pack(params)[None], 1e-6, 1e-8, code,
                        100_000, 1e5, True)
    return time.perf_counter() - start


def pack(params, x0=None) -> np.ndarray:
    """The kernel's parameter array for ``params`` (slots named in ``rhs``).

    ``x0`` (the rest position's x) may be given when the caller has it already.
    """
    c0, c2, c4, c6 = series_coefficients(params.A, params.B)
    x0 = params.rest_position[0] if x0 is None else x0
    on_axis = params.rest_position[1] == 0.0
    P = np.array([params.k_r, params.k_theta, params.f_N, params.theta0, params.mu_s,
                  params.A, params.B, params.zeta, params.lam, params.L0,
                  c0, c2, c4, c6, x0, 0.0 if on_axis else 1.0], dtype=float)
    assert P.size == N_PARAM
    return P


def initial_state(params) -> np.ndarray:
    """At rest at (cos theta0, sin theta0) with theta = theta0; quadratures zero."""
    y0 = np.zeros(N_STATE)
    y0[X], y0[Y] = params.rest_position
    y0[THETA] = params.theta0
    return y0
