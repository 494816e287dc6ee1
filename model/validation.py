"""Checks of user input, one function per kind, each raising ``ValueError``.

Every message starts with ``name=value`` (the CLI maps ``name`` to its flag) and says
what the value must be, so the fix is in the message::

    k_r=-1.0 is invalid: radial stiffness k_r must be finite and in (0, 1e+06]
    method='rk45' is unknown; choose one of auto, explicit, implicit, reference
    n=0 must be a whole number >= 1

Params, SolverOptions, the array functions, the sweeps and the CLI use these; the
intervals themselves live beside what they bound (``model.contact.params.RANGES``,
``model.contact.options``, ``model.controls``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .arrays.beta import BETA_MIN

__all__ = ["Interval", "number", "whole", "choice", "load_factor", "angles", "grid",
           "instance"]


@dataclass(frozen=True)
class Interval:
    """A real interval; ``lo_open``/``hi_open`` exclude an end."""

    lo: float
    hi: float
    lo_open: bool = False
    hi_open: bool = False

    def __contains__(self, x) -> bool:
        lo_ok = x > self.lo if self.lo_open else x >= self.lo
        hi_ok = x < self.hi if self.hi_open else x <= self.hi
        return bool(lo_ok and hi_ok)

    @property
    def bounds(self) -> tuple[float, float]:
        return (self.lo, self.hi)

    def __str__(self) -> str:
        return (f"{'(' if self.lo_open else '['}{self.lo:g}, {self.hi:g}"
                f"{')' if self.hi_open else ']'}")


def _as_float(value) -> float | None:
    """``float(value)`` for a real number, None for anything else (bool and text included,
    which ``float`` would accept); an int beyond the float range is infinite."""
    if isinstance(value, (bool, np.bool_, str, bytes)):
        return None
    try:
        return float(value)
    except (TypeError, ValueError):
        return None
    except OverflowError:
        return math.inf


def number(name: str, value, interval: Interval, meaning: str | None = None) -> float:
    """A finite real number in ``interval``, as a float."""
    what = meaning or name
    x = _as_float(value)
    if x is None:
        raise ValueError(f"{name}={value!r} is not a number; {what} must be a real number "
                         f"in {interval}")
    if not (math.isfinite(x) and x in interval):
        raise ValueError(f"{name}={value!r} is invalid: {what} must be finite and in {interval}")
    return x


def whole(name: str, value, lo: int, hi: float | None = None) -> int:
    """A whole number >= ``lo`` (and <= ``hi``); ``1e6`` counts as whole, ``2.5`` and
    ``True`` do not."""
    x = _as_float(value)
    ok = x is not None and math.isfinite(x) and x.is_integer() and x >= lo \
        and (hi is None or x <= hi)
    if not ok:
        where = f">= {lo:g}" if hi is None else f"in [{lo:g}, {hi:g}]"
        raise ValueError(f"{name}={value!r} must be a whole number {where}")
    return int(x)


def choice(name: str, value, options) -> str:
    """One of the names ``options``."""
    options = tuple(options)
    if not isinstance(value, str) or value not in options:
        raise ValueError(f"{name}={value!r} is unknown; choose one of {', '.join(options)}")
    return value


#: The load factor beta = N_c0/N_c = L0/<tau_out>: the fraction of F_N one support carries
#: (docs/model.md, "Contact count and the load factor β"). Its lower end BETA_MIN = 1e-3
#: is a contact lasting a thousand slab lengths, N_c = 1000 N_c0 supports sharing the
#: load; the self-consistent solver brackets its root in the same [BETA_MIN, 1]
#: (model/arrays/beta.py), so a fixed beta has the range a solved one has. Below it the page showed energies of 1e285 W.
BETA = Interval(BETA_MIN, 1.0)


def load_factor(name: str, value, allow_self: bool = True):
    """``"self"`` (solve beta = L0/<tau_out>(beta)) or a number in (0, 1]."""
    if allow_self and isinstance(value, str):
        if value != "self":
            raise ValueError(f"{name}={value!r} must be 'self' or a number in {BETA}")
        return value
    x = _as_float(value)
    if x is None or not (math.isfinite(x) and x in BETA):
        fix = f"'self' or a number in {BETA}" if allow_self else f"a number in {BETA}"
        raise ValueError(f"{name}={value!r} is invalid: beta must be {fix}")
    return x


def angles(name: str, values, interval: Interval) -> np.ndarray:
    """A non-empty 1-D float array of finite angles [rad] in ``interval``."""
    try:
        a = np.atleast_1d(np.asarray(values, dtype=float))
    except (TypeError, ValueError, OverflowError):
        a = np.array([[]])
    if a.ndim != 1 or a.size == 0 or not np.all(np.isfinite(a)):
        raise ValueError(f"{name}={values!r} must be a non-empty 1-D array of finite angles")
    bad = [float(t) for t in a if t not in interval]
    if bad:
        raise ValueError(f"{name}={bad[0]!r} is invalid: every angle must be in {interval} rad")
    return a


def grid(name: str, values, positive: bool = True) -> np.ndarray:
    """A non-empty 1-D float array of finite (and, by default, positive) numbers."""
    try:
        g = np.atleast_1d(np.asarray(values, dtype=float))
    except (TypeError, ValueError, OverflowError):
        g = np.array([])
    bad = g.ndim != 1 or g.size == 0 or not np.all(np.isfinite(g))
    if bad or (positive and np.any(g <= 0)):
        kind = "positive finite" if positive else "finite"
        raise ValueError(f"{name}={values!r} must be a non-empty 1-D sequence of {kind} numbers")
    return g


def instance(name: str, value, cls):
    """``value`` when it is a ``cls``; ``TypeError`` naming the type expected otherwise."""
    if not isinstance(value, cls):
        raise TypeError(f"{name} must be a {cls.__module__.split('.')[0]}.{cls.__name__}, "
                        f"not {type(value).__name__}")
    return value
