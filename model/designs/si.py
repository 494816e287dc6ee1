"""Physical quantities as text: read with their units (pint) and written with SI prefixes.

``quantity(name, text)`` reads an input of a pillar design (``model.designs.units.PillarDesign``,
the friction law's ``V_s``) and checks its dimension, ``to_si`` gives it in SI units within
its bound, and ``measure_text`` writes a result with an SI prefix, its significant figures
and its error bar (or what is known when it did not converge).
"""
from __future__ import annotations

import math
from tokenize import TokenError

import pint

from ..contact.params import DEFAULTS

__all__ = ["ureg", "INPUTS", "quantity", "to_si", "from_si", "measure_text"]

#: One registry for the package: pint's application registry, so quantities made by a
#: caller with ``pint.Quantity`` combine with ours.
ureg = pint.get_application_registry()

#: The inputs of a design: name -> (pint dimensionality, unit shown in messages and used
#: in ``PillarDesign.to_dict``, example, lower bound (exclusive), required)
INPUTS = {
    "D": ("[length]", "um", "5 um", 0.0, True),
    "h": ("[length]", "um", "50 um", 0.0, True),
    "E": ("[pressure]", "GPa", "1 GPa", 0.0, True),
    "G": ("[pressure]", "GPa", "0.36 GPa", 0.0, False),
    "nu": ("", "", "0.4", -1.0, False),
    "rho": ("[mass] / [length] ** 3", "kg/m^3", "920 kg/m^3", 0.0, True),
    "mass_fraction": ("", "", "1", 0.0, False),
    "r0": ("[length]", "um", "10 um", 0.0, True),
    "d_x": ("[length]", "um", "20 um", 0.0, True),
    "d_y": ("[length]", "um", "20 um", 0.0, True),
    "L_x": ("[length]", "mm", "1 mm", 0.0, True),
    "L_y": ("[length]", "mm", "1 mm", 0.0, True),
    "F_N": ("[force]", "mN", "1 mN", 0.0, True),
    "V0": ("[length] / [time]", "cm/s", "1 cm/s", 0.0, True),
    "V_s": ("[length] / [time]", "cm/s", "0.1 cm/s", 0.0, False),
    "mu_s": ("", "", f"{DEFAULTS['mu_s']:g}", 0.0, False),
    "A": ("", "", f"{DEFAULTS['A']:g}", 0.0, False),
    "B": ("", "", f"{DEFAULTS['B']:g}", -math.inf, False),
    "prefactor_r": ("", "", "1", 0.0, False),
    "prefactor_theta": ("", "", "1", 0.0, False),
}


def quantity(name: str, value):
    """``value`` (text, pint quantity or, for dimensionless inputs, a number) as a pint
    quantity of the dimension ``name`` needs; ``ValueError`` naming the input otherwise."""
    dim, unit, example, _, _ = INPUTS[name]
    if isinstance(value, bool):
        raise ValueError(f"{name}={value!r} is not a quantity; write it like {example!r}")
    if isinstance(value, str):
        try:
            q = ureg.Quantity(value.strip())
        except (pint.PintError, ValueError, TypeError, AssertionError, AttributeError,
                SyntaxError, TokenError) as error:
            detail = str(error) or "malformed expression"
            raise ValueError(f"{name}={value!r} cannot be read as a quantity ({detail}); "
                             f"write it like {example!r}") from None
    elif isinstance(value, pint.Quantity):
        q = ureg.Quantity(value.magnitude, str(value.units))
    elif isinstance(value, (int, float)):
        q = ureg.Quantity(float(value), "")
    else:
        raise ValueError(f"{name}={value!r} is not a quantity; write it like {example!r}")
    if not dim:
        if not q.dimensionless:
            raise ValueError(f"{name}={value!r} must be dimensionless, not [{q.dimensionality}]; "
                             f"write it like {example!r}")
    elif not q.check(dim):
        what = "has no unit" if q.dimensionless else f"has dimension {q.dimensionality}"
        raise ValueError(f"{name}={value!r} {what}; {name} is a {dim} such as {example!r}")
    return q


def to_si(name: str, value) -> float:
    """Input ``name`` (text, quantity or number) as a finite SI float above its lower
    bound; ``ValueError`` naming the input and an example otherwise."""
    dim, _, example, lower, _ = INPUTS[name]
    q = quantity(name, value)
    x = float(q.to_base_units().magnitude) if dim else float(q.to("").magnitude)
    if not math.isfinite(x) or x <= lower:
        bound = "positive" if lower == 0 else f"greater than {lower:g}"
        raise ValueError(f"{name}={value!r} must be finite and {bound} (e.g. {example!r})")
    return x


def measure_text(value: float, unit: str, error: float | None = None, bounds=None,
                 digits: int = 4, converged: bool = True) -> str:
    """A physical result with an SI prefix (pint's compact form), ``digits`` significant
    figures and its error bar: ``1.017 ± 0.002 mN``; with ``bounds`` (not converged)
    ``1.017 mN (not converged: between 0.51 and 1.2 mN)``; not ``converged`` and without
    either, ``1.017 mN (not converged: no error bar)``; "–" when not a number."""
    if value is None or not math.isfinite(value):
        return "–"
    known = bounds is not None and all(b is not None and math.isfinite(b) for b in bounds)
    sizes = [abs(value)] + ([abs(error)] if error is not None and math.isfinite(error) else []) \
        + ([abs(b) for b in bounds] if known else [])
    prefixed = ureg.Quantity(max(sizes) or 1.0, unit).to_compact().units
    factor = ureg.Quantity(1.0, unit).to(prefixed).magnitude
    shown = f"{prefixed:~P}"
    text = f"{value * factor:#.{digits}g}".rstrip(".")
    if known:
        lo, hi = (b * factor for b in bounds)
        return f"{text} {shown} (not converged: between {lo:.3g} and {hi:.3g} {shown})"
    if error is not None and math.isfinite(error):
        return f"{text} ± {abs(error * factor):.2g} {shown}"
    return f"{text} {shown}" + ("" if converged else " (not converged: no error bar)")


def from_si(name: str, value: float):
    """An SI float of input ``name`` back as a pint quantity (a number if dimensionless)."""
    dim, unit = INPUTS[name][:2]
    return ureg.Quantity(value, ureg.Quantity(1.0, unit).to_base_units().units) if dim else value
