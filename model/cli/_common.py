"""Pieces shared by the commands: the one-line error convention, number parsing, output."""
from __future__ import annotations

import argparse
import math
import os
import re
import sys
import tempfile
from pathlib import Path

import numpy as np

from ..contact.params import REGIMES

#: How the user called the command line: its usage lines and errors repeat it.
PROG = "micropillar" if Path(sys.argv[0]).name == "micropillar" else "python -m model"

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
    from ..contact.options import METHODS

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


# --------------------------------------------------------------------------- resources

def memory_budget() -> int:
    """Bytes one command may plan to hold: half the memory the system has available as
    it starts (``MemAvailable``; the physical memory where that is unknown)."""
    try:
        with open("/proc/meminfo", encoding="ascii") as info:
            for line in info:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024 // 2
    except (OSError, ValueError, IndexError):
        pass
    try:
        return os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE") // 2
    except (AttributeError, ValueError, OSError):
        return 2 * 1024**3


def _size(nbytes: float) -> str:
    for unit in ("B", "kB", "MB", "GB", "TB", "PB"):
        if nbytes < 1000 or unit == "PB":
            return f"{nbytes:.3g} {unit}"
        nbytes /= 1000
    raise AssertionError("unreachable")


def check_memory(flag: str, nbytes: float, what: str) -> None:
    """``UsageError`` naming ``flag`` when ``what`` would need more than ``memory_budget``;
    called before any work starts."""
    budget = memory_budget()
    if nbytes > budget:
        raise UsageError(flag, f"{what} would need about {_size(nbytes)} of memory, more than "
                               f"the {_size(budget)} this command may use (half the memory "
                               f"available); lower {flag}")


# --------------------------------------------------------------------------- output files

def output_file(flag: str, text: str) -> Path:
    """The file ``text`` names, checked before any work: not a folder or a device, in an
    existing folder where a file can be created (tried, not guessed)."""
    out = Path(text)
    if out.is_dir():
        raise UsageError(flag, f"{text!r} is a folder; name a file in it, such as "
                               f"{str(out / 'sweep.csv')!r}")
    if out.exists() and not out.is_file():
        raise UsageError(flag, f"{text!r} exists and is not a regular file")
    if not out.parent.is_dir():
        raise UsageError(flag, f"directory {str(out.parent)!r} does not exist")
    try:
        fd, probe = tempfile.mkstemp(prefix=f".{out.name}.", suffix=".tmp", dir=out.parent)
    except OSError as error:
        raise UsageError(flag, f"cannot write into {str(out.parent)!r}: "
                               f"{error.strerror or error}") from None
    os.close(fd)
    os.unlink(probe)
    return out


def output_folder(flag: str, text: str) -> Path:
    """The folder ``text`` names, created if missing, checked before any work: a folder
    (not a file) where a file can be created (tried, not guessed)."""
    out = Path(text)
    if out.exists() and not out.is_dir():
        raise UsageError(flag, f"{text!r} exists and is not a folder")
    try:
        out.mkdir(parents=True, exist_ok=True)
        fd, probe = tempfile.mkstemp(prefix=".probe.", suffix=".tmp", dir=out)
    except OSError as error:
        raise UsageError(flag, f"cannot write into {text!r}: {error.strerror or error}") from None
    os.close(fd)
    os.unlink(probe)
    return out
