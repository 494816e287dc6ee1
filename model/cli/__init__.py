"""Command line: ``python -m model <command> ...``.

Commands
--------
support
    Integrate one contact of one support and print its results (readable, or one JSON
    object with ``--json``).
array
    A fixed- or uniform-orientation array (Figs. 5, 6, 8-11): apparent friction, D_y/D_x,
    contact count and work split, with both averages of the uniform array.
sweep
    A parameter sweep behind one of the paper's figures, written to a CSV file.
friction
    ``friction fit FILE.csv``: fit the friction law of Eq. (4) to a measured curve.
reproduce
    Every figure's data of the paper as CSV, and its findings checked in a report
    (``report.md``, ``index.html``); ``python -m app.reproduce`` adds the pictures.
pack
    The offline explorer: one self-contained HTML file that computes in the browser
    (added by the app through the ``micropillar.commands`` entry point).
warmup
    Compile the kernel into numba's on-disk cache (run once after installing).

Exit codes: 0 success, 1 the integration ran but did not succeed (results are printed
anyway), 2 bad usage (one line on stderr naming the offending flag; also a request for
more memory than the machine has, checked before any work), 130 interrupted (Ctrl-C),
141 the output was closed early (``| head``).
"""
from __future__ import annotations

import json
import math
import os
import sys

from ..arrays.quantities import describe
from ..contact.friction import mu0
from ..contact.options import METHODS, SolverOptions
from ..contact.params import Params
from ..contact.support import simulate_support
from importlib.metadata import entry_points

from . import array, design, friction, reproduce, snippet, sweep
from ._common import (FIELD_FLAGS, PROG, CommandParser, UsageError, add_stiffness,
                      as_usage_error, check_memory, jsonable, real, stiffness, table, whole)

__all__ = ["main", "build_parser", "UsageError", "CommandParser", "FIELD_FLAGS", "PROG"]


# --------------------------------------------------------------------------- support

def _add_support(commands) -> None:
    p = commands.add_parser(
        "support", help="integrate one contact of one support",
        description="Integrate one contact of one support with the sliding slab (dimensionless "
                    "units: lengths r0, time r0/V0, energies m V0^2).")
    model = p.add_argument_group("support")
    add_stiffness(model)
    model.add_argument("--F-N", type=real, default=1.0, metavar="F",
                       help="normal load F_N (default 1)")
    model.add_argument("--theta0", type=real, default=math.pi / 2, metavar="T",
                       help="rest orientation in radians from +x (default pi/2)")
    model.add_argument("--beta", type=real, default=1.0, metavar="B",
                       help="load factor N_c0/N_c; each support carries beta F_N (default 1)")
    solver = p.add_argument_group("solver")
    solver.add_argument("--rtol", type=real, default=1e-6, metavar="R",
                        help="relative tolerance (default 1e-6)")
    solver.add_argument("--atol", type=real, metavar="A",
                        help="absolute tolerance (default rtol/100)")
    solver.add_argument("--method", choices=METHODS, default="auto",
                        help="integrator (default auto: stiffness switching)")
    solver.add_argument("--max-steps", type=whole, default=1_000_000, metavar="N",
                        help="step budget (default 1000000)")
    solver.add_argument("--tau-max", type=real, default=1e5, metavar="T",
                        help="time budget in tau (default 1e5)")
    output = p.add_argument_group("output")
    output.add_argument("--json", action="store_true", help="print one JSON object")
    output.add_argument("--samples", type=whole, default=0, metavar="N",
                        help="uniform samples of the time series, added to the JSON output "
                             "(default 0: none)")
    p.set_defaults(run=_run_support)


def _support_inputs(args) -> tuple[Params, SolverOptions]:
    """Validated parameters and solver options; a bad value raises ``UsageError``."""
    k_r, k_theta = stiffness(args)
    try:
        params = Params(k_r=k_r, k_theta=k_theta, F_N=args.F_N, theta0=args.theta0, beta=args.beta)
        options = SolverOptions(rtol=args.rtol, atol=args.atol, method=args.method,
                                max_steps=args.max_steps, tau_max=args.tau_max)
    except ValueError as error:
        raise as_usage_error(error) from None
    return params, options


#: Bytes per time-series sample: the TimeSeries arrays and the interpolation's temporaries.
SAMPLE_BYTES = 512


def _check_support_memory(options: SolverOptions, samples: int) -> None:
    """The time series' memory, checked before integrating: the recorded step nodes (the
    kernel keeps at most ``MAX_NODES``, whatever ``--max-steps``; three times that while
    its buffer grows) and the samples returned."""
    if samples <= 0:
        return
    from .._kernel import MAX_NODES, N_NODE_COLS

    nodes = 3 * min(options.max_steps + 1, MAX_NODES) * N_NODE_COLS * 8
    check_memory("--samples", nodes + samples * SAMPLE_BYTES, f"{samples:,} samples")


def _run_support(args) -> int:
    """``support``: integrate one contact and print it; 0 on success, 1 if the run failed."""
    params, options = _support_inputs(args)
    _check_support_memory(options, args.samples)
    try:
        result = simulate_support(params, rtol=options.rtol, atol=options.atol,
                                  method=options.method, samples=args.samples,
                                  max_steps=options.max_steps, tau_max=options.tau_max)
    except ValueError as error:  # an input only simulate_support checks (samples)
        raise as_usage_error(error) from None
    if args.json:
        record = result.to_dict()
        if result.series is not None:
            record["series"] = result.series.as_dict()
        print(json.dumps(jsonable(record)))
    else:
        print(_summary(result, args.samples))
    return 0 if result.success else 1


def _summary(result, samples: int) -> str:
    """A readable, aligned report: parameters, results, solver statistics."""
    p, o = result.params, result.options
    m0 = mu0(p)
    energy_scale = max(abs(result.W), 1e-300)
    params = [
        ("k_r", p.k_r, "radial stiffness"),
        ("k_theta", p.k_theta, "torsional stiffness"),
        ("F_N", p.F_N, "normal load"),
        ("theta0", p.theta0, f"rest orientation [rad] ({math.degrees(p.theta0):.6g} deg)"),
        ("beta", p.beta, "load factor N_c0/N_c"),
        ("f_N", p.f_N, "load on the support, beta F_N"),
        ("mu0", m0, "rigid-contact friction coefficient mu(1)"),
        ("L0", p.L0, "slab length"),
    ]
    fx, fy = (float(v) for v in result.F_mean)
    results = [
        ("success", result.success, f"status {result.status}: {result.message}"),
        ("t_out", result.t_out, "contact duration [r0/V0] (Eq. 9)"),
        ("F_mean_x", fx, "time-averaged friction on the support, x, over f_N (Eq. 8)"),
        ("F_mean_y", fy, "time-averaged friction on the support, y, over f_N"),
        ("F_mean_x/mu0", fx / m0, "apparent friction F_T,x/(mu0 F_N) of a fixed-orientation array"),
        ("W", result.W, "slab work [m V0^2]"),
        ("D_x", result.D_x, "dissipation along x"),
        ("D_y", result.D_y, "dissipation along y"),
        ("U_el", result.U_el, "elastic energy left at exit"),
        ("K", result.K, "kinetic energy left at exit"),
        ("energy_residual", result.energy_residual,
         f"W - (D_x + D_y + U_el + K); relative {abs(result.energy_residual) / energy_scale:.2g}"),
        ("dtheta_rms", result.dtheta_rms, "orientation fluctuation over the contact [rad] (Fig. 10f)"),
        ("dr_rms", result.dr_rms, "length fluctuation over the contact [r0] (Fig. 10f)"),
        ("r_min", result.r_min, "closest approach of the mass to its pivot [r0]"),
        ("r_max", result.r_max, describe("r_max")),
        ("pivot_approach", result.pivot_approach,
         f"r fell below the pivot radius {result.pivot_radius:g}"),
    ]
    solver = [("rtol", o.rtol, "relative tolerance"),
              ("atol", o.atol, "absolute tolerance"),
              ("max_steps", o.max_steps, "step budget"),
              ("tau_max", o.tau_max, "time budget")]
    solver += [(str(k), v, "") for k, v in result.stats.items()]
    if samples:
        solver.append(("samples", samples, "time-series samples (printed with --json)"))
    return table([("Parameters (dimensionless)", params), ("Results", results), ("Solver", solver)])


# --------------------------------------------------------------------------- warmup

def _add_warmup(commands) -> None:
    p = commands.add_parser(
        "warmup", help="compile the kernel into numba's on-disk cache",
        description="Compile every integrator path (or load it from the cache) and report the "
                    "time taken; run once after installing so the first trajectory is fast.")
    p.set_defaults(run=_run_warmup)


def _run_warmup(args) -> int:
    from .._kernel import warmup

    print(f"kernel ready in {warmup():.2f} s")
    return 0


# --------------------------------------------------------------------------- entry point

#: Entry-point group of commands that other installed packages add (``name = "module:add"``,
#: ``add(commands)`` adds a subparser): the app's ``pack`` is one, so ``model`` never
#: imports the app.
COMMANDS_GROUP = "micropillar.commands"


def build_parser() -> CommandParser:
    """The ``python -m model`` parser with every command."""
    parser = CommandParser(
        prog=PROG,
        description="Dynamically induced friction reduction in micro-structured interfaces: "
                    "elastic micropillar supports dragged by a sliding slab (Sci. Rep. 11, 8093, "
                    "2021).",
        epilog="Exit codes: 0 success, 1 the integration ran but did not succeed (results are "
               "printed anyway), 2 bad usage, 130 interrupted.")
    commands = parser.add_subparsers(title="commands", metavar="command", dest="command")
    _add_support(commands)
    array.add_command(commands)
    design.add_command(commands)
    friction.add_command(commands)
    sweep.add_command(commands)
    reproduce.add_command(commands)
    for command in entry_points(group=COMMANDS_GROUP):  # commands of other packages (app's pack)
        try:
            add = command.load()
        except ModuleNotFoundError:  # declared by an install whose code is not importable here
            continue
        add(commands)
    _add_warmup(commands)
    snippet.add_flag(commands)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run one command; returns the exit code (0 success, 1 failed run, 2 usage error,
    130 interrupted)."""
    code = _run(argv)
    if code == 130:
        # Interrupted and reported: a further Ctrl-C (the terminal sends one to every
        # process of the group, late ones included) must not break the shutdown with a
        # traceback while the worker pools are joined.
        import signal
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    return code


def _run(argv: list[str] | None) -> int:
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as stop:  # --help (0) or a usage error already reported (2)
        return stop.code if isinstance(stop.code, int) else 2
    if args.command is None:
        parser.print_help(sys.stderr)
        return 2
    try:
        if getattr(args, "kernel", True):  # commands that integrate nothing set kernel=False
            from .._kernel import announce_cold_start

            announce_cold_start(sys.stderr)
        return args.run(args)
    except UsageError as error:
        print(f"{PROG} {args.command}: error: {error}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"\n{PROG} {args.command}: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # the reader of the output left (`... | head`): stop quietly
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # no error at exit
        return 141
