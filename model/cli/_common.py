"""Pieces shared by the commands: the one-line error convention, number parsing, output."""
from __future__ import annotations

import argparse
import math
import re

import numpy as np

from ..params import REGIMES

PROG = "python -m model"

#: Argument names in the model's ``ValueError`` messages -> the flag that sets them.
FIELD_FLAGS = {
    "k_r": "--k-r", "k_theta": "--k-theta", "F_N": "--F-N", "theta0": "--theta0",
    "beta": "--beta", "rtol": "--rtol", "atol": "--atol", "method": "--method",
    "max_steps": "--max-steps", "samples": "--samples", "tau_max": "--tau-max",
    "tol": "--tol", "n": "--n", "workers": "--workers", "scheduler": "--scheduler",
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
        message = re.sub(r"^the following arguments are required: (.+)$", r"\1: required", message)
        # Unrecognized arguments are echoed as given: escape line breaks and control
        # characters, so the error stays one line and cannot drive the terminal.
        message = "".join(c if c.isprintable() else repr(c)[1:-1] for c in message)
        self.exit(2, f"{self.prog}: error: {message}\n")


def real(text: str) -> float:
    """A real number (range checks, non-finite values included, are left to the model)."""
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None


def whole(text: str) -> int:
    """A whole number; written as ``1000`` or ``1e6`` (range checks are left to the model)."""
    value = real(text)
    if not value.is_integer():
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number")
    return int(value)


def beta_value(text: str):
    """``self`` (the self-consistent load factor) or a number."""
    return "self" if text == "self" else real(text)


def flag_of(error: ValueError) -> str | None:
    """The flag behind a model ``ValueError`` (its messages start with ``field=value``)."""
    match = re.match(r"(\w+)=", str(error))
    return FIELD_FLAGS.get(match.group(1)) if match else None


def as_usage_error(error: ValueError) -> UsageError:
    """A model ``ValueError`` naming an argument as a ``UsageError`` naming its flag."""
    flag = flag_of(error)
    if flag is None:
        raise error
    return UsageError(flag, str(error))


def add_stiffness(group) -> None:
    """``--regime``, ``--k-r`` and ``--k-theta`` (explicit stiffnesses override the regime)."""
    group.add_argument("--regime", choices=sorted(REGIMES),
                       help="take k_r and k_theta from a named regime (--k-r/--k-theta override)")
    group.add_argument("--k-r", type=real, metavar="K", help="radial stiffness k_r")
    group.add_argument("--k-theta", type=real, metavar="K", help="torsional stiffness k_theta")


def add_atol_method(group) -> None:
    """``--atol`` and ``--method``, shared by the array commands."""
    from ..options import METHODS

    group.add_argument("--atol", type=real, metavar="A",
                       help="absolute tolerance (default rtol/100)")
    group.add_argument("--method", choices=METHODS, default="auto",
                       help="integrator (default auto: stiffness switching)")


def stiffness(args) -> tuple[float, float]:
    """(k_r, k_theta) from the flags; ``UsageError`` when one is missing."""
    base = REGIMES[args.regime] if args.regime else None
    k_r = args.k_r if args.k_r is not None else (base.k_r if base else None)
    k_theta = args.k_theta if args.k_theta is not None else (base.k_theta if base else None)
    for flag, value in (("--k-r", k_r), ("--k-theta", k_theta)):
        if value is None:
            raise UsageError(flag, "required unless --regime is given")
    return k_r, k_theta


def jsonable(value):
    """Plain JSON types; non-finite numbers become ``null`` (strict JSON has no NaN)."""
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [jsonable(v) for v in value]
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(value) if math.isfinite(value) else None
    return value


def fmt(value) -> str:
    if isinstance(value, (bool, np.bool_)):
        return "yes" if value else "no"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return f"{float(value):.8g}"
    return str(value)


def table(sections) -> str:
    """Sections of (name, value, meaning) rows, with names and values in aligned columns."""
    sections = [(title, [(name, fmt(value), meaning) for name, value, meaning in rows])
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
