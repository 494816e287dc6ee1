"""``--print-python``: the Python that reproduces a command's numbers, printed instead of
computing them.

The command runs as usual up to the model call it would make (so flags are parsed and
validated by the same code, and a bad value is the same usage error), and that call is
recorded instead of made: the snippet is that call, written with the public API
(``from model import ...``), followed by the lines that print or write its results. What
the snippet computes is therefore what the command computes, by construction.
"""
from __future__ import annotations

import inspect
import math
import sys
from contextlib import contextmanager
from dataclasses import fields

import numpy as np

from ..contact.params import Params

__all__ = ["add_flag", "snippet_of", "print_snippet", "source", "params_source"]

#: Commands that take ``--print-python``.
COMMANDS = ("support", "array", "sweep")


class _Call(BaseException):
    """The model call a command was about to make (raised instead of making it; not an
    ``Exception``, so no handler of the command's own can take it for a failure)."""

    def __init__(self, name: str, args: tuple, kwargs: dict):
        super().__init__(name)
        self.name, self.args, self.kwargs = name, args, kwargs


def _recorder(name: str):
    def record(*args, **kwargs):
        raise _Call(name, args, kwargs)
    return record


def add_flag(commands) -> None:
    """Add ``--print-python`` to each command of ``COMMANDS`` (the subparsers' action):
    with it, the command's ``run`` prints its snippet instead."""
    for name in COMMANDS:
        parser = commands.choices[name]
        parser.add_argument(
            "--print-python", action="store_true",
            help="print the Python (public API) that reproduces this command's numbers, "
                 "instead of computing them")
        parser.set_defaults(run=_or_print(parser.get_default("run")))


def _or_print(run):
    def run_or_print(args) -> int:
        return print_snippet(args, run) if args.print_python else run(args)
    return run_or_print


# --------------------------------------------------------------------------- source text

_PARAM_DEFAULTS = {f.name: f.default for f in fields(Params)}


def source(value) -> str:
    """Python source of a plain value: numbers in their shortest round-trip form."""
    if isinstance(value, Params):
        return params_source(value)
    if isinstance(value, (bool, np.bool_)) or value is None:
        return repr(None if value is None else bool(value))
    if isinstance(value, (int, np.integer)):
        return repr(int(value))
    if isinstance(value, (float, np.floating)):
        value = float(value)
        return repr(value) if math.isfinite(value) else f"float({str(value)!r})"
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, np.ndarray):
        return f"np.array({source(value.tolist())})"
    if isinstance(value, tuple):
        inner = ", ".join(source(v) for v in value)
        return f"({inner},)" if len(value) == 1 else f"({inner})"
    if isinstance(value, list):
        return "[" + ", ".join(source(v) for v in value) + "]"
    raise TypeError(f"no Python source for {type(value).__name__}")


def params_source(params: Params, theta0: str | None = None, always=("k_r", "k_theta", "F_N"),
                  skip=()) -> str:
    """``Params(...)`` with the springs and load, and every other field that differs from
    its default; ``theta0`` replaces the angle's number by an expression (e.g. degrees)."""
    parts = []
    for name, value in params.as_dict().items():
        if name in skip or (name not in always and value == _PARAM_DEFAULTS[name]
                            and not (name == "theta0" and theta0)):
            continue
        parts.append(f"{name}={theta0 if name == 'theta0' and theta0 else source(value)}")
    return f"Params({', '.join(parts)})"


def _call_source(name: str, args: tuple, kwargs: dict, width: int = 92) -> str:
    """``result = name(args, kwargs)``, wrapped to ``width`` columns."""
    items = [source(a) if not isinstance(a, Params) else "params" for a in args]
    items += [f"{k}={source(v)}" for k, v in kwargs.items()]
    head = f"result = {name}("
    lines, line = [], head
    for i, item in enumerate(items):
        piece = item + (", " if i < len(items) - 1 else ")")
        if len(line) + len(piece.rstrip()) > width and line != head:
            lines.append(line.rstrip())
            line = " " * len(head)
        line += piece
    if not items:
        line += ")"
    lines.append(line)
    return "\n".join(lines)


# --------------------------------------------------------------------------- what follows

_SUPPORT_OUTPUT = '''\
print(f"success: {result.success} ({result.message})")
print(f"t_out = {result.t_out!r}   (contact duration, Eq. 9)")
print(f"F_mean/f_N = {tuple(float(v) for v in result.F_mean)!r}   (Eq. 8)")
print(f"W = {result.W!r}, D_x = {result.D_x!r}, D_y = {result.D_y!r}, "
      f"U_el = {result.U_el!r}, K = {result.K!r}")'''

_ARRAY_OUTPUT = '''\
print(f"success: {result.success} ({result.message})")
print(f"F_T,x/(mu0 F_N) = {float(result.FTx_over_mu0FN)!r}   (%s)")
print(f"D_y/D_x = {float(result.Dy_over_Dx)!r}, N_c/N_c0 = {float(result.Nc_over_Nc0)!r}, "
      f"beta = {float(result.beta)!r}")'''


def _sweep_output(out: str) -> str:
    return (f"result.to_csv({out!r})\n"
            f"print(f\"{{len(result)}} points, {{int(result.columns['success'].sum())}} "
            f"succeeded -> {out}\")")


def _snippet(command: str, call: _Call, args) -> str:
    from .._version import __version__

    values = [*call.args, *call.kwargs.values()]
    imports = ["Params"] if any(isinstance(v, Params) for v in values) else []
    what = f"{command} {args.kind}" if command == "sweep" else command
    lines = [f"# `python -m model {what}` as Python (micropillar-friction {__version__})",
             f"from model import {', '.join(sorted(set(imports + [call.name])))}"]
    if any(isinstance(v, np.ndarray) for v in values):
        lines.insert(1, "import numpy as np")
    lines.append("")
    params = next((a for a in call.args if isinstance(a, Params)), None)
    if params is not None:
        lines.append(f"params = {params_source(params)}")
    lines.append(_call_source(call.name, call.args, call.kwargs))
    if command == "support":
        lines.append(_SUPPORT_OUTPUT)
    elif command == "array":
        lines.append(_ARRAY_OUTPUT % ("Eq. 10, paper average over supports"
                                      if call.name == "uniform_array" else "Eq. 8"))
    else:
        lines.append(_sweep_output(str(args.out)))
    return "\n".join(lines) + "\n"


# --------------------------------------------------------------------------- running

def _api_functions() -> set:
    """Names of the public API's computing functions (``model.__all__``; not the friction
    law, which the commands call only to report)."""
    import model

    return {name for name in model.__all__ if inspect.isfunction(getattr(model, name))
            and not name.startswith("mu")}


@contextmanager
def _recording():
    """Swap the public API functions the commands call for recorders, for the duration:
    wherever a command module holds one by name, and in the sweep table."""
    from . import sweep as sweep_cmd

    names = _api_functions()
    modules = [m for key, m in list(sys.modules.items())
               if m is not None and (key == __package__ or key.startswith(__package__ + "."))]
    saved = [(m, name, getattr(m, name)) for m in modules for name in names
             if inspect.isfunction(getattr(m, name, None))]
    sweeps = dict(sweep_cmd.SWEEPS)
    try:
        for m, name, _ in saved:
            setattr(m, name, _recorder(name))
        for kind, (fn, text) in sweeps.items():
            if fn.__name__ in names:
                sweep_cmd.SWEEPS[kind] = (_recorder(fn.__name__), text)
        yield
    finally:
        for m, name, fn in saved:
            setattr(m, name, fn)
        sweep_cmd.SWEEPS.update(sweeps)


def snippet_of(args, run) -> str:
    """The snippet of parsed command-line ``args`` of the command ``run`` (``UsageError``
    on a bad flag)."""
    try:
        with _recording():
            run(args)
    except _Call as call:
        # The progress bar of a sweep draws on the terminal: not part of the numbers.
        kwargs = {k: v for k, v in call.kwargs.items() if k != "progress"}
        return _snippet(args.command, _Call(call.name, call.args, kwargs), args)
    raise RuntimeError(f"{args.command} made no model call to print")


def print_snippet(args, run) -> int:
    """Print the snippet of ``args`` for the command ``run``; 0."""
    print(snippet_of(args, run), end="")
    return 0
