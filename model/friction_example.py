"""The shipped example of a measured friction curve (``examples/flat_friction.csv``):
not a measurement, but Eq. (4) with known coefficients plus Gaussian noise, so that a fit
can be checked against the truth. ``python -m model.friction_example FILE`` writes it."""
from __future__ import annotations

import sys

import numpy as np

from .friction_law import FrictionLaw

__all__ = ["TRUE_LAW", "NOISE", "SEED", "SPEEDS_MM_S", "example_text"]

#: The coefficients the example is made from: the paper's, with V_s = 1 mm/s.
TRUE_LAW = FrictionLaw(V_s="1 mm/s")
#: Standard deviation of the noise added to mu, and the seed of its generator.
NOISE, SEED = 0.02, 27
#: The speeds of the example (mm/s): 40, evenly spaced in log from 0.01 to 100 mm/s.
SPEEDS_MM_S = np.geomspace(0.01, 100.0, 40)


def example_text() -> str:
    """The example file's text (the same on every run)."""
    rng = np.random.default_rng(SEED)
    mu = TRUE_LAW.mu(SPEEDS_MM_S * 1e-3) + rng.normal(0.0, NOISE, SPEEDS_MM_S.size)
    law = TRUE_LAW
    lines = [f"# Example data, not a measurement: Eq. (4) with mu_s = {law.mu_s:g}, "
             f"A = {law.A:g}, B = {law.B:g}, V_s = {law.V_s * 1e3:g} mm/s,",
             f"# plus Gaussian noise of standard deviation {NOISE:g} (numpy default_rng("
             f"{SEED})); written by python -m model.friction_example.",
             "v [mm/s],mu,mu_err"]
    lines += [f"{v:.6g},{m:.5f},{NOISE:g}" for v, m in zip(SPEEDS_MM_S, mu)]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":  # pragma: no cover - exercised by tests/test_friction_fit.py
    from .files import write_text_atomic

    write_text_atomic(sys.argv[1] if len(sys.argv) > 1 else "flat_friction.csv", example_text())
