"""A real micropillar array in physical units, and where it sits on the paper's map.

``PillarDesign`` takes the pillar geometry and material, the array layout, the load,
the sliding speed and the friction law with units (text such as ``"5 um"``,
``"1.2 GPa"`` parsed by pint, or pint quantities). It derives, with the paper's
scalings (lengths in r0, time r0/V0, forces m V0^2/r0, energies m V0^2):

    m = f_m rho pi D^2 h / 4          (f_m: effective-mass fraction, default 1)
    k_r = c_r E D^4 / h^3,  k_theta = c_theta G D^4 / h     (G = E / (2 (1 + nu)))
    N_c0 = L_x L_y / (d_x d_y),  L0 = L_x / r0,  zeta = V0 / V_s
    k~_r = r0^2 k_r / (m V0^2),  k~_theta = k_theta / (m V0^2),  F~_N = r0 F_N / (N_c0 m V0^2)

The stiffness prefactors c_r = c_theta = 1 are the paper's order-of-magnitude
scalings; beam theory gives c_r = 3 pi / 64 (cantilever bending, 3 E I / h^3 with
I = pi D^4 / 64) and c_theta = pi / 32 (torsion, G J / h with J = pi D^4 / 32):
``BEAM_PREFACTORS``.

Both k~ scale as 1/V0^2 (F~_N too), so changing the speed moves a design along a
diagonal of the log-log map; k~_theta/k~_r = G h^2 c_theta / (E r0^2 c_r) depends on
geometry and material alone. Where a design sits on the map, and its array in physical
units: ``model.designs.design_point``.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields

from ..contact.params import DEFAULTS, RANGES, Params
from ..contact.regimes import regime_of
from ..lab.friction_law import FrictionLaw, zeta
from .si import INPUTS, from_si, measure_text, quantity, to_si, ureg  # noqa: F401 (public here too)

__all__ = ["ureg", "PillarDesign", "quantity", "to_si", "BEAM_PREFACTORS", "PAPER_PREFACTORS",
           "Scales", "F_N_MAX", "measure_text"]

PAPER_PREFACTORS = {"k_r": 1.0, "k_theta": 1.0}
BEAM_PREFACTORS = {"k_r": 3 * math.pi / 64, "k_theta": math.pi / 32}

#: The model's largest load per support F~_N.
F_N_MAX = RANGES["F_N"][0].hi


@dataclass(frozen=True)
class Scales:
    """The paper's units of a design: length r0, time r0/V0, force m V0^2/r0, energy m V0^2."""

    m: float  # kg
    r0: float  # m
    V0: float  # m/s
    N_c0: float

    @property
    def time(self) -> float:
        return self.r0 / self.V0

    @property
    def force(self) -> float:
        return self.m * self.V0 ** 2 / self.r0

    @property
    def energy(self) -> float:
        return self.m * self.V0 ** 2


@dataclass(frozen=True)
class PillarDesign:
    """A micropillar array in physical units (SI floats after parsing; see module doc).

    Give ``G`` or ``nu`` (not both). ``V_s`` is the friction law's velocity scale (Eq. 4,
    zeta = V0/V_s); when omitted zeta takes the model default 10. ``mu_s``, ``A``, ``B``
    and ``V_s`` are the friction law (``friction_law``; ``with_friction`` sets a fitted one). ``F_N`` is the total
    normal load on the slab, shared by the N_c0 pillars it covers.
    """

    D: object
    h: object
    E: object
    rho: object
    r0: object
    d_x: object
    d_y: object
    L_x: object
    L_y: object
    F_N: object
    V0: object
    G: object = None
    nu: object = None
    mass_fraction: object = 1.0
    V_s: object = None
    mu_s: object = DEFAULTS["mu_s"]
    A: object = DEFAULTS["A"]
    B: object = DEFAULTS["B"]
    prefactor_r: object = PAPER_PREFACTORS["k_r"]
    prefactor_theta: object = PAPER_PREFACTORS["k_theta"]

    def __post_init__(self):
        if (self.G is None) == (self.nu is None):
            raise ValueError(f"G={self.G!r}, nu={self.nu!r}: give the shear modulus G or "
                             f"Poisson's ratio nu (G = E / (2 (1 + nu))), exactly one of them")
        for f in fields(self):
            value = getattr(self, f.name)
            if value is not None:
                object.__setattr__(self, f.name, to_si(f.name, value))
        if self.nu is not None and not self.nu <= 0.5:
            raise ValueError(f"nu={self.nu!r} must be in (-1, 0.5]")
        if self.mass_fraction > 1:
            raise ValueError(f"mass_fraction={self.mass_fraction!r} must be in (0, 1]: the "
                             f"share of the pillar's mass that moves with its tip")

    @classmethod
    def example(cls, **changes) -> "PillarDesign":
        """The worked example of the notes: LDPE pillars, D = 5 um, h = 50 um, V0 = 1 cm/s."""
        base = dict(D="5 um", h="50 um", E="1 GPa", nu=0.4, rho="920 kg/m^3", r0="10 um",
                    d_x="20 um", d_y="20 um", L_x="1 mm", L_y="1 mm", F_N="1 mN",
                    V0="1 cm/s", V_s="0.1 cm/s")
        base.update(changes)
        return cls(**base)

    def replace(self, **changes) -> "PillarDesign":
        """A copy with some inputs changed (parsed and validated again)."""
        d = {k: None if v is None else from_si(k, v) for k, v in asdict(self).items()}
        if "G" in changes:
            d["nu"] = None
        if "nu" in changes:
            d["G"] = None
        d.update(changes)
        return PillarDesign(**d)

    # ------------------------------------------------------------------ derived, SI
    @property
    def shear_modulus(self) -> float:
        return self.G if self.G is not None else self.E / (2 * (1 + self.nu))

    @property
    def mass(self) -> float:
        """m = f_m rho pi D^2 h / 4 (kg)."""
        return self.mass_fraction * self.rho * math.pi * self.D ** 2 * self.h / 4

    @property
    def k_r(self) -> float:
        """Radial stiffness c_r E D^4 / h^3 (N/m)."""
        return self.prefactor_r * self.E * self.D ** 4 / self.h ** 3

    @property
    def k_theta(self) -> float:
        """Torsional stiffness c_theta G D^4 / h (N m)."""
        return self.prefactor_theta * self.shear_modulus * self.D ** 4 / self.h

    @property
    def N_c0(self) -> float:
        """Pillars under the slab at rest, L_x L_y / (d_x d_y)."""
        return self.L_x * self.L_y / (self.d_x * self.d_y)

    @property
    def scales(self) -> Scales:
        return Scales(m=self.mass, r0=self.r0, V0=self.V0, N_c0=self.N_c0)

    # ------------------------------------------------------------------ dimensionless
    def dimensionless(self) -> dict:
        """k~_r, k~_theta, F~_N, zeta and L0 of this design (may lie outside MODEL_RANGE)."""
        s = self.scales
        return {"k_r": self.r0 ** 2 * self.k_r / s.energy,
                "k_theta": self.k_theta / s.energy,
                "F_N": self.r0 * self.F_N / (self.N_c0 * s.energy),
                "zeta": zeta(self.V0, self.V_s),
                "L0": self.L_x / self.r0}

    def params(self, **changes) -> Params:
        """The model's ``Params``; ``ValueError`` when the point lies outside its ranges."""
        d = self.dimensionless()
        return Params(k_r=d["k_r"], k_theta=d["k_theta"], F_N=d["F_N"], zeta=d["zeta"],
                      L0=d["L0"], mu_s=self.mu_s, A=self.A, B=self.B, **changes)

    @property
    def friction_law(self) -> FrictionLaw:
        """The design's friction law, Eq. (4) (``model.lab.friction_law.FrictionLaw``)."""
        return FrictionLaw(mu_s=self.mu_s, A=self.A, B=self.B, V_s=self.V_s)

    def with_friction(self, law) -> "PillarDesign":
        """A copy with the friction law ``law`` (a ``FrictionLaw``, e.g. a fit's ``.law``)."""
        return self.replace(**law.design_fields())

    def regime(self) -> str:
        d = self.dimensionless()
        return regime_of(d["k_r"], d["k_theta"])

    def to_dict(self) -> dict:
        """Inputs in readable units (keys ``<name>`` with the unit in ``units``)."""
        out, units = {}, {}
        for name, (dim, unit, _, _, _) in INPUTS.items():
            value = getattr(self, name)
            if value is None:
                continue
            if dim:
                value = float(from_si(name, value).to(unit).magnitude)
                units[name] = unit
            out[name] = value
        return {**out, "units": units}
