"""The shipped examples of measured friction curves: not measurements, but the model at
known coefficients plus seeded Gaussian noise, so that a fit and a comparison can be
checked against the truth.

* ``examples/flat_friction.csv``: the flat material, Eq. (4) (``example_text``);
  ``python -m model.lab.friction_example FILE`` writes it.
* ``examples/structured_friction.csv``: the structured sample, F_T,x/F_N of a uniform
  array of ``STRUCTURED_DESIGN`` with the same law (``model.lab.speed_curve``;
  ``structured_text``); ``python -m model.lab.friction_example --structured FILE`` writes it.
"""
from __future__ import annotations

import sys

import numpy as np

from .friction_law import FrictionLaw

__all__ = ["TRUE_LAW", "NOISE", "SEED", "SPEEDS_MM_S", "example_text", "STRUCTURED_DESIGN",
           "STRUCTURED_NOISE", "STRUCTURED_SPEEDS", "structured_design", "structured_text"]

#: The coefficients the example is made from: the paper's, with V_s = 1 mm/s.
TRUE_LAW = FrictionLaw(V_s="1 mm/s")
#: Standard deviation of the noise added to mu, and the seed of its generator.
NOISE, SEED = 0.02, 27
#: The speeds of the example (mm/s): 40, evenly spaced in log from 0.01 to 100 mm/s.
SPEEDS_MM_S = np.geomspace(0.01, 100.0, 40)


def _law_words(law: FrictionLaw) -> str:
    return f"mu_s = {law.mu_s:g}, A = {law.A:g}, B = {law.B:g}, V_s = {law.V_s * 1e3:g} mm/s"


def _csv(comments, v_unit: str, v, mu, noise: float) -> str:
    """The file: ``comments`` as ``#`` lines, the header, one row per point."""
    lines = [f"# {c}" for c in comments] + [f"v [{v_unit}],mu,mu_err"]
    lines += [f"{a:.6g},{m:.5f},{noise:g}" for a, m in zip(v, mu)]
    return "\n".join(lines) + "\n"


def example_text() -> str:
    """The example file's text (the same on every run)."""
    rng = np.random.default_rng(SEED)
    mu = TRUE_LAW.mu(SPEEDS_MM_S * 1e-3) + rng.normal(0.0, NOISE, SPEEDS_MM_S.size)
    return _csv([f"Example data, not a measurement: Eq. (4) with {_law_words(TRUE_LAW)},",
                 f"plus Gaussian noise of standard deviation {NOISE:g} (numpy default_rng("
                 f"{SEED})); written by python -m model.lab.friction_example."],
                "mm/s", SPEEDS_MM_S, mu, NOISE)


#: The structured sample (soft LDPE-like pillars, uniform orientations), as
#: ``PillarDesign.example`` changes; its friction law is ``TRUE_LAW``.
STRUCTURED_DESIGN = dict(E="1 MPa", V0="1 m/s", L_x="0.1 mm", F_N="10 uN")
#: Standard deviation of the noise added to its F_T,x/F_N (the structured effect is ~1 %).
STRUCTURED_NOISE = 0.002
#: Its speeds (m/s): 12, evenly spaced in log from 0.1 to 3 m/s.
STRUCTURED_SPEEDS = np.geomspace(0.1, 3.0, 12)


def structured_design():
    """The structured sample's ``PillarDesign`` (``STRUCTURED_DESIGN`` with ``TRUE_LAW``)."""
    from ..designs.units import PillarDesign

    return PillarDesign.example(**STRUCTURED_DESIGN).with_friction(TRUE_LAW)


def structured_text() -> str:
    """The structured example's text: the model's F_T,x/F_N at ``STRUCTURED_SPEEDS`` plus
    noise (numpy ``default_rng(SEED + 1)``); a few seconds."""
    from .speed_curve import friction_velocity

    curve = friction_velocity(structured_design(), STRUCTURED_SPEEDS)
    rng = np.random.default_rng(SEED + 1)
    mu = curve.column("mu_apparent") + rng.normal(0.0, STRUCTURED_NOISE, STRUCTURED_SPEEDS.size)
    changes = ", ".join(f"{k} = {v}" for k, v in STRUCTURED_DESIGN.items() if k != "V0")
    return _csv([f"Example data, not a measurement: F_T,x/F_N of a uniform array of "
                 f"PillarDesign.example({changes}),",
                 f"friction law Eq. (4) with {_law_words(TRUE_LAW)} (model.lab.speed_curve), plus "
                 f"Gaussian noise",
                 f"of standard deviation {STRUCTURED_NOISE:g} (numpy default_rng({SEED + 1})); "
                 f"written by python -m model.lab.friction_example --structured."],
                "m/s", STRUCTURED_SPEEDS, mu, STRUCTURED_NOISE)


if __name__ == "__main__":  # pragma: no cover - exercised by tests/test_friction_compare.py
    from ..files import write_text_atomic

    argv = sys.argv[1:]
    structured = "--structured" in argv
    argv = [a for a in argv if a != "--structured"]
    default = "structured_friction.csv" if structured else "flat_friction.csv"
    write_text_atomic(argv[0] if argv else default,
                      structured_text() if structured else example_text())
