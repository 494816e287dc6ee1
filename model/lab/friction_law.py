"""A friction law of Eq. (4) in physical units: the four coefficients mu_s, A, B, V_s.

    mu(v) = mu_s sin(A atan(v/V_s - B (v/V_s - atan(v/V_s))))

The model's dimensionless form has zeta = V0/V_s (``model.contact.friction``). ``FrictionLaw()``
is the paper's law (mu_s, A, B from ``model.contact.params.DEFAULTS``) with ``V_s`` unset, which
means V_s = V0/zeta for the model's default zeta (the paper's V0 = 10 V_s). A law comes
typed in, or from a fit of a measured curve (``model.lab.friction_fit``), whose JSON file
``FrictionLaw.from_json`` reads back.
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..contact.friction import law
from ..contact.params import DEFAULTS, RANGES
from ..designs.si import to_si, ureg
from ..validation import number

__all__ = ["FrictionLaw", "COEFFICIENTS", "zeta"]

#: The coefficients of Eq. (4) in the order the fit and its files give them (V_s in m/s).
COEFFICIENTS = ("mu_s", "A", "B", "V_s")


def zeta(V0: float, V_s: float | None) -> float:
    """zeta = V0/V_s of Eq. (4) (speeds in one unit); the model's default without V_s."""
    return DEFAULTS["zeta"] if V_s is None else V0 / V_s


def _speed(value) -> float:
    """V_s in m/s from a number (m/s), text such as ``"1 mm/s"`` or a pint quantity."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        value = f"{value!r} m/s"
    return to_si("V_s", value)


@dataclass(frozen=True)
class FrictionLaw:
    """Eq. (4) with its coefficients: mu_s, A, B and the velocity scale V_s (m/s; a number
    in m/s, text such as ``"1 mm/s"`` or a pint quantity; None: V0/zeta with the model's
    default zeta, as in the paper). The model's ranges (``model.contact.params.RANGES``) apply."""

    mu_s: float = DEFAULTS["mu_s"]
    A: float = DEFAULTS["A"]
    B: float = DEFAULTS["B"]
    V_s: float | None = None

    def __post_init__(self):
        for name in ("mu_s", "A", "B"):
            interval, meaning = RANGES[name]
            object.__setattr__(self, name, number(name, getattr(self, name), interval, meaning))
        if self.V_s is not None:
            object.__setattr__(self, "V_s", _speed(self.V_s))

    @property
    def is_paper(self) -> bool:
        """The paper's coefficients with the default velocity scale."""
        return self == FrictionLaw()

    def mu(self, v, V0: float | None = None):
        """mu at sliding speeds ``v`` (m/s), Eq. (4); ``V0`` is needed only without V_s."""
        if self.V_s is None:
            if V0 is None:
                raise ValueError("V0=None: this law has no V_s of its own (V_s = V0/zeta); "
                                 "give the sliding speed V0 or set V_s")
            V_s = V0 / DEFAULTS["zeta"]
        else:
            V_s = self.V_s
        return law(np.asarray(v, dtype=float) / V_s, self.mu_s, self.A, self.B)

    def dimensionless(self, V0: float | None = None) -> dict:
        """The law as ``Params`` fields mu_s, A, B and zeta = V0/V_s (``V0`` in m/s; not
        needed without V_s): ``Params(k_r=..., k_theta=..., **law.dimensionless(V0))``."""
        if self.V_s is not None and V0 is None:
            raise ValueError(f"V0=None: zeta = V0/V_s needs the sliding speed V0 (m/s) of a "
                             f"law with V_s = {self.V_s!r} m/s")
        return {"mu_s": self.mu_s, "A": self.A, "B": self.B, "zeta": zeta(V0, self.V_s)}

    def design_fields(self) -> dict:
        """The law as ``PillarDesign`` inputs (``design.replace(**law.design_fields())``)."""
        return {"mu_s": self.mu_s, "A": self.A, "B": self.B,
                "V_s": None if self.V_s is None else ureg.Quantity(self.V_s, "m/s")}

    def to_dict(self) -> dict:
        """The four coefficients, V_s in m/s (None: V0/zeta)."""
        return {name: getattr(self, name) for name in COEFFICIENTS}

    @classmethod
    def from_dict(cls, record: dict, source: str = "friction law") -> "FrictionLaw":
        """A law from a dict of the four coefficients or from a fit's JSON.

        Plain numbers (``{"mu_s": 1.3, "A": 1.44, ...}``) or the fit's records
        (``{"mu_s": {"value": 1.3, "ci95": [1.2, 1.4]}, ...}``); V_s in m/s.
        ``ValueError`` naming the key otherwise."""
        if not isinstance(record, dict):
            raise ValueError(f"{source}: expected a JSON object with keys "
                             f"{', '.join(COEFFICIENTS)}, not {type(record).__name__}")
        if record.get("success") is False:
            raise ValueError(f"{source}: the fit it holds did not converge "
                             f"({record.get('message', 'no message')}); fit again")
        values = {}
        for name in COEFFICIENTS:
            if name not in record:
                if name == "V_s":
                    continue
                raise ValueError(f"{source}: no {name!r}; a friction law needs "
                                 f"{', '.join(COEFFICIENTS)} (V_s in m/s)")
            value = record[name]
            if isinstance(value, dict):
                value = value.get("value")
            if value is None and name == "V_s":
                continue
            if not isinstance(value, (int, float)) or isinstance(value, bool) \
                    or not math.isfinite(value):
                raise ValueError(f"{source}: {name} = {value!r} is not a finite number")
            values[name] = value
        try:
            return cls(**values)
        except ValueError as error:
            raise ValueError(f"{source}: {error}") from None

    @classmethod
    def from_json(cls, path) -> "FrictionLaw":
        """The law in a JSON file (``micropillar friction fit FILE.csv --out fit.json``)."""
        from ..files import read_user_text

        name, text = Path(path).name, read_user_text(path, "JSON")
        try:
            record = json.loads(text)
        except ValueError as error:
            raise ValueError(f"{name}: not JSON ({error})") from None
        return cls.from_dict(record, name)
