"""Command line: ``python -m model <command> ...``.

Commands
--------
support
    Integrate one contact of one support and print its results (readable, or one JSON
    object with ``--json``).
warmup
    Compile the kernel into numba's on-disk cache (run once after installing).

Exit codes: 0 success, 1 the integration ran but did not succeed (results are printed
anyway), 2 bad usage (one line on stderr naming the offending flag).
"""
from __future__ import annotations

import argparse
import json
import math
import re
import sys

import numpy as np

from .friction import mu0
from .options import METHODS, SolverOptions
from .params import REGIMES, Params
from .support import simulate_support

__all__ = ["main", "build_parser"]

PROG = "python -m model"

#: Field names of ``Params`` / ``SolverOptions`` / ``simulate_support`` -> the flag that sets them.
FIELD_FLAGS = {
    "k_r": "--k-r", "k_theta": "--k-theta", "F_N": "--F-N", "theta0": "--theta0",
    "beta": "--beta", "rtol": "--rtol", "atol": "--atol", "method": "--method",
    "max_steps": "--max-steps", "samples": "--samples", "tau_max": "--tau-max",
}


class UsageError(Exception):
    """A bad flag value, reported as ``<flag>: <message>``."""

    def __init__(self, flag: str | None, message: str):
        super().__init__(f"{flag}: {message}" if flag else message)


class CommandParser(argparse.ArgumentParser):
    """An argument parser whose errors are one line on stderr, exit code 2."""

    def error(self, message: str):
        # argparse says "argument --k-r: ..."; keep just the flag.
        message = re.sub(r"^argument ([^:]+): ", r"\1: ", message)
        self.exit(2, f"{self.prog}: error: {message}\n")


def _real(text: str) -> float:
    """A real number (range checks, non-finite values included, are left to the model)."""
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None


def _whole(text: str) -> int:
    """A whole number; written as ``1000`` or ``1e6`` (range checks are left to the model)."""
    value = _real(text)
    if not value.is_integer():
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number")
    return int(value)


def _flag_of(error: ValueError) -> str | None:
    """The flag behind a model ``ValueError`` (its messages start with ``field=value``)."""
    match = re.match(r"(\w+)=", str(error))
    return FIELD_FLAGS.get(match.group(1)) if match else None


# --------------------------------------------------------------------------- support

def _add_support(commands) -> None:
    p = commands.add_parser(
        "support", help="integrate one contact of one support",
        description="Integrate one contact of one support with the sliding slab (dimensionless "
                    "units: lengths r0, time r0/V0, energies m V0^2).")
    model = p.add_argument_group("support")
    model.add_argument("--regime", choices=sorted(REGIMES),
                       help="take k_r and k_theta from a named regime (--k-r/--k-theta override)")
    model.add_argument("--k-r", type=_real, metavar="K", help="radial stiffness k_r")
    model.add_argument("--k-theta", type=_real, metavar="K", help="torsional stiffness k_theta")
    model.add_argument("--F-N", type=_real, default=1.0, metavar="F",
                       help="normal load F_N (default 1)")
    model.add_argument("--theta0", type=_real, default=math.pi / 2, metavar="T",
                       help="rest orientation in radians from +x (default pi/2)")
    model.add_argument("--beta", type=_real, default=1.0, metavar="B",
                       help="load factor N_c0/N_c; each support carries beta F_N (default 1)")
    solver = p.add_argument_group("solver")
    solver.add_argument("--rtol", type=_real, default=1e-6, metavar="R",
                        help="relative tolerance (default 1e-6)")
    solver.add_argument("--atol", type=_real, metavar="A",
                        help="absolute tolerance (default rtol/100)")
    solver.add_argument("--method", choices=METHODS, default="auto",
                        help="integrator (default auto: stiffness switching)")
    solver.add_argument("--max-steps", type=_whole, default=1_000_000, metavar="N",
                        help="step budget (default 1000000)")
    solver.add_argument("--tau-max", type=_real, default=1e5, metavar="T",
                        help="time budget in tau (default 1e5)")
    output = p.add_argument_group("output")
    output.add_argument("--json", action="store_true", help="print one JSON object")
    output.add_argument("--samples", type=_whole, default=0, metavar="N",
                        help="uniform samples of the time series, added to the JSON output "
                             "(default 0: none)")
    p.set_defaults(run=_run_support)


def _support_inputs(args) -> tuple[Params, SolverOptions]:
    """Validated parameters and solver options; a bad value raises ``UsageError``."""
    base = REGIMES[args.regime] if args.regime else None
    k_r = args.k_r if args.k_r is not None else (base.k_r if base else None)
    k_theta = args.k_theta if args.k_theta is not None else (base.k_theta if base else None)
    for flag, value in (("--k-r", k_r), ("--k-theta", k_theta)):
        if value is None:
            raise UsageError(flag, "required unless --regime is given")
    try:
        params = Params(k_r=k_r, k_theta=k_theta, F_N=args.F_N, theta0=args.theta0, beta=args.beta)
        options = SolverOptions(rtol=args.rtol, atol=args.atol, method=args.method,
                                max_steps=args.max_steps, tau_max=args.tau_max)
    except ValueError as error:
        raise UsageError(_flag_of(error), str(error)) from None
    return params, options


def _run_support(args) -> int:
    """``support``: integrate one contact and print it; 0 on success, 1 if the run failed."""
    params, options = _support_inputs(args)
    try:
        result = simulate_support(params, rtol=options.rtol, atol=options.atol,
                                  method=options.method, samples=args.samples,
                                  max_steps=options.max_steps, tau_max=options.tau_max)
    except ValueError as error:  # an input only simulate_support checks (samples)
        flag = _flag_of(error)
        if flag is None:
            raise
        raise UsageError(flag, str(error)) from None
    if args.json:
        record = result.to_dict()
        if result.series is not None:
            record["series"] = result.series.as_dict()
        print(json.dumps(_jsonable(record)))
    else:
        print(_summary(result, args.samples))
    return 0 if result.success else 1


def _jsonable(value):
    """Plain JSON types; non-finite numbers become ``null`` (strict JSON has no NaN)."""
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [_jsonable(v) for v in value]
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(value) if math.isfinite(value) else None
    return value


def _fmt(value) -> str:
    if isinstance(value, (bool, np.bool_)):
        return "yes" if value else "no"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return f"{float(value):.8g}"
    return str(value)


def _table(sections) -> str:
    """Sections of (name, value, meaning) rows, with names and values in aligned columns."""
    sections = [(title, [(name, _fmt(value), meaning) for name, value, meaning in rows])
                for title, rows in sections]
    rows = [row for _, section in sections for row in section]
    name_width = max(len(name) for name, _, _ in rows)
    value_width = max(len(value) for _, value, _ in rows)
    lines = []
    for title, section in sections:
        lines += ["", title] if lines else [title]
        lines += [f"  {name:<{name_width}}  {value:>{value_width}}  {meaning}".rstrip()
                  for name, value, meaning in section]
    return "\n".join(lines)


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
    return _table([("Parameters (dimensionless)", params), ("Results", results), ("Solver", solver)])


# --------------------------------------------------------------------------- warmup

def _add_warmup(commands) -> None:
    p = commands.add_parser(
        "warmup", help="compile the kernel into numba's on-disk cache",
        description="Compile every integrator path (or load it from the cache) and report the "
                    "time taken; run once after installing so the first trajectory is fast.")
    p.set_defaults(run=_run_warmup)


def _run_warmup(args) -> int:
    from ._kernel import warmup

    print(f"kernel ready in {warmup():.2f} s")
    return 0


# --------------------------------------------------------------------------- entry point

def build_parser() -> CommandParser:
    """The ``python -m model`` parser with every command."""
    parser = CommandParser(
        prog=PROG,
        description="Dynamically induced friction reduction in micro-structured interfaces: "
                    "elastic micropillar supports dragged by a sliding slab (Sci. Rep. 11, 8093, "
                    "2021).",
        epilog="Exit codes: 0 success, 1 the integration ran but did not succeed (results are "
               "printed anyway), 2 bad usage.")
    commands = parser.add_subparsers(title="commands", metavar="command", dest="command")
    _add_support(commands)
    _add_warmup(commands)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run one command; returns the exit code (0 success, 1 failed run, 2 usage error)."""
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as stop:  # --help (0) or a usage error already reported (2)
        return stop.code if isinstance(stop.code, int) else 2
    if args.command is None:
        parser.print_help(sys.stderr)
        return 2
    try:
        return args.run(args)
    except UsageError as error:
        print(f"{PROG} {args.command}: error: {error}", file=sys.stderr)
        return 2
