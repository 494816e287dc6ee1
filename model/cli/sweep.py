"""``python -m model sweep KIND``: the parameter sweep behind one of the paper's figures.

The sweep is written to a CSV file (``--out``) with a ``# key: value`` header; progress is
drawn on stderr and one summary line is printed at the end. Ctrl-C cancels cleanly: pending
points are dropped, workers stopped, nothing is written and the exit code is 130.

Before any work, ``--out`` is checked (a file, not a folder or a device, in a folder where
a file can be created) and the memory of the points (``--n``) and of the worker processes
(``--workers``) against what the machine has. The CSV goes to a temporary file beside
``--out`` and replaces it in one step, so a failed or interrupted write leaves it as it was.
"""
from __future__ import annotations

import inspect
import sys
import time

from ..contact.params import REGIMES, Params
from ..runs.sweeps import SweepCancelled, load_sweep, orientation_table, regime_map, stiffness_sweep
from ._common import (PROG, UsageError, add_atol_method, as_usage_error, beta_value,
                      check_memory, flag_of, output_file, real, whole)

#: Command-line name -> (function, what it computes).
SWEEPS = {
    "regime-map": (regime_map, "Fig. 5a/b: uniform arrays on a log (k_r, k_theta) grid, "
                               "[0.01, 3]^2"),
    "load": (load_sweep, "Fig. 6: uniform arrays of the four regimes against F_N in [0.1, 10]"),
    "stiffness": (stiffness_sweep, "Fig. 8a/b: N_c/N_c0 and the work split against k_r, "
                                   "k_theta = 0.01 ... 3"),
    "orientation": (orientation_table, "Figs. 10f, 11: fixed arrays of one regime against "
                                       "theta0 in [0, pi]"),
}


#: Memory per point, measured with tracemalloc (about 0.4 kB of parameters and task plus
#: the result row of a uniform array; 0.64 kB peak per orientation of the batched fixed
#: arrays) and rounded up.
POINT_BYTES = {"regime-map": 4096, "load": 4096, "stiffness": 4096, "orientation": 1024}

def _default(function, name):
    return inspect.signature(function).parameters[name].default


#: What the swept axes hold when a flag does not say (the sweep functions' defaults).
_DEFAULT_N = {kind: _default(function, "n") for kind, (function, _) in SWEEPS.items()}
_K_THETA_CURVES = len(_default(stiffness_sweep, "k_theta"))
_LOAD_REGIMES = len(_default(load_sweep, "regimes"))
#: Memory of one local worker process (the interpreter, numpy, scipy and the compiled
#: kernel; about 230 MB measured for the dashboard's workers), rounded up.
WORKER_BYTES = 256 * 1024**2


def points(args) -> int:
    """How many parameter points the sweep of ``args`` computes."""
    n = _DEFAULT_N[args.kind] if args.n is None else args.n
    if args.kind == "regime-map":
        return n * n
    if args.kind == "load":
        return n * (1 if args.regime else _LOAD_REGIMES)
    if args.kind == "stiffness":
        return n * _K_THETA_CURVES
    return n


def add_command(commands) -> None:
    p = commands.add_parser(
        "sweep", help="a parameter sweep behind one of the paper's figures, to CSV",
        description="Run the parameter sweep behind one of the paper's figures and write it to "
                    "a CSV file. " + "; ".join(f"{k}: {v[1]}" for k, v in SWEEPS.items()) + ".")
    p.add_argument("kind", choices=list(SWEEPS), help="which sweep")
    sweep = p.add_argument_group("sweep")
    sweep.add_argument("--n", type=whole, metavar="N",
                       help="points per swept axis (default 8 stiffnesses, 9 loads, 37 angles)")
    sweep.add_argument("--F-N", type=real, metavar="F",
                       help="normal load (default 1; not for load)")
    sweep.add_argument("--regime", choices=sorted(REGIMES),
                       help="orientation: the regime (required); load: only this regime")
    sweep.add_argument("--beta", type=beta_value, default="self", metavar="self|B",
                       help="load factor: 'self' (self-consistent, default) or a number in (0, 1]")
    solver = p.add_argument_group("solver")
    solver.add_argument("--tol", type=real, metavar="T",
                        help="quadrature tolerance of the uniform arrays (default 1e-3)")
    solver.add_argument("--rtol", type=real, metavar="R",
                        help="relative tolerance per contact (default tol/100, at most 1e-5; "
                             "1e-6 for orientation)")
    add_atol_method(solver)
    where = p.add_argument_group("where to run (uniform-array sweeps)")
    where.add_argument("--workers", type=whole, metavar="N", help="local processes (default 1)")
    where.add_argument("--scheduler", metavar="ADDRESS",
                       help="run on a dask.distributed cluster, e.g. tcp://host:8786 "
                            "(needs the 'cluster' extra)")
    p.add_argument("--out", required=True, metavar="FILE.csv", help="CSV file to write")
    p.set_defaults(run=run)


def _not_for(args, kinds, flags) -> None:
    """A ``UsageError`` for the first of ``flags`` given although the sweep is in ``kinds``."""
    if args.kind in kinds:
        for flag in flags:
            if getattr(args, flag.lstrip("-").replace("-", "_")) is not None:
                raise UsageError(flag, f"not used by the {args.kind} sweep")


def _arguments(args) -> dict:
    """Keyword arguments of the sweep function; ``UsageError`` for flags that do not apply."""
    _not_for(args, ("regime-map", "stiffness"), ["--regime"])
    _not_for(args, ("orientation",), ["--tol", "--workers", "--scheduler"])
    _not_for(args, ("load",), ["--F-N"])
    kwargs = dict(beta=args.beta, atol=args.atol, method=args.method)
    if args.n is not None:
        kwargs["n"] = args.n
    if args.kind == "orientation":
        if args.regime is None:
            raise UsageError("--regime", "required for the orientation sweep")
        F_N = 1.0 if args.F_N is None else args.F_N
        return dict(kwargs, params=Params.regime(args.regime).replace(F_N=F_N),
                    rtol=1e-6 if args.rtol is None else args.rtol)
    kwargs.update(tol=1e-3 if args.tol is None else args.tol, rtol=args.rtol,
                  workers=1 if args.workers is None else args.workers, scheduler=args.scheduler)
    if args.F_N is not None:
        kwargs["F_N"] = args.F_N
    if args.kind == "load" and args.regime is not None:
        kwargs["regimes"] = (args.regime,)
    return kwargs


class ProgressBar:
    """``progress(done, total)`` drawn as ``[#####.....] 12/24  3.1 s``: redrawn in place on
    a terminal, else written as a new line every tenth of the sweep (for logs)."""

    def __init__(self, stream, width: int = 30):
        self.stream, self.width = stream, width
        self.tty = hasattr(stream, "isatty") and stream.isatty()
        self.done, self.total, self.drawn, self.step = 0, None, False, -1
        self.start = time.perf_counter()

    def __call__(self, done: int, total: int) -> None:
        self.done, self.total = done, total
        step = 10 * done // max(total, 1)
        if not self.tty and step == self.step:
            return
        self.step = step
        filled = self.width * done // max(total, 1)
        bar = "#" * filled + "." * (self.width - filled)
        elapsed = time.perf_counter() - self.start
        line = f"[{bar}] {done}/{total}  {elapsed:.1f} s"
        self.stream.write(f"\r{line}" if self.tty else f"{line}\n")
        self.stream.flush()
        self.drawn = self.tty

    def close(self) -> None:
        if self.drawn:
            self.stream.write("\n")
            self.stream.flush()
            self.drawn = False


def run(args) -> int:
    """``sweep``: run it, write the CSV; 0 if every point succeeded, 1 if some did not."""
    out = output_file("--out", args.out)
    if args.n is not None and args.n >= 1:  # n < 1 is named by the sweep itself
        count = points(args)
        check_memory("--n", count * POINT_BYTES[args.kind],
                      f"{count:,} points of the {args.kind} sweep")
    if args.workers is not None and args.workers > 1:
        check_memory("--workers", args.workers * WORKER_BYTES,
                     f"{args.workers:,} worker processes")
    bar = ProgressBar(sys.stderr)
    try:
        kwargs = _arguments(args)
        result = SWEEPS[args.kind][0](**kwargs, progress=bar)
    except (KeyboardInterrupt, SweepCancelled):
        bar.close()
        total = f" of {bar.total}" if bar.total else ""
        print(f"{PROG} sweep: cancelled after {bar.done}{total} points; {out} not written",
              file=sys.stderr)
        return 130
    except (ValueError, ImportError, OSError) as error:
        bar.close()
        raise _usage_error(error, args.scheduler) from None
    bar.close()
    try:
        result.to_csv(out)
    except OSError as error:
        raise UsageError("--out", f"cannot write {str(out)!r}: {error.strerror or error}") from None
    ok = int(result.columns["success"].sum())
    print(f"{args.kind}: {len(result)} points, {ok} succeeded, {result.seconds:.1f} s -> {out}")
    return 0 if ok == len(result) else 1


def _usage_error(error: Exception, scheduler) -> UsageError:
    """The flag to blame: the one the model's message names, else the scheduler."""
    if isinstance(error, ValueError) and flag_of(error):
        return as_usage_error(error)
    if scheduler is not None:
        return UsageError("--scheduler", f"cannot use {scheduler!r}: {error}")
    raise error
