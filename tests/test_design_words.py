"""The Design tab's figures in words (app/views/design_words.py; its polar diagram:
tests/test_plot_words.py): every number said is the design result's (two designs, two
texts with their own numbers), never fixed per preset."""
import re

import numpy as np
import pytest

from app import worker
from app.views.design_words import design_map_description, law_description, speeds_description
from model import FrictionCurve, compare_friction
from model.lab.friction_fit import fit_friction
from model.lab.friction_law import FrictionLaw
from model.lab.speed_curve import SpeedCurve, SpeedPoint
from model.designs.units import PillarDesign

NUMBER = r"(−?[0-9]+(?:\.[0-9]+)?(?:e[+−]?[0-9]+)?)"


def _n(text: str) -> float:
    return float(text.replace("−", "-"))


def _array(ftx: float, error: float = 0.002) -> dict:
    """The parts of a ``DesignPoint.to_dict`` record the words read."""
    return {"array": {"FTx_over_mu0FN": ftx, "quadrature_error": {"FTx_over_mu0FN": error},
                      "bounds": None}}


@pytest.mark.parametrize("V0, ftx", [("1 m/s", 0.93), ("100 m/s", 1.08)])
def test_the_map_words_are_the_designs_point_regime_and_friction(V0, ftx):
    point = worker.compute_design_point(PillarDesign.example(V0=V0))
    p = point["point"]
    text = design_map_description(point, _array(ftx))
    found = re.search(rf"star at k̃_r = {NUMBER}, k̃_θ = {NUMBER} \(F̃_N = {NUMBER}, at "
                      rf"V₀ = {NUMBER} m/s\): (\w+) regime", text)
    assert _n(found[1]) == pytest.approx(p["k_r"], rel=5e-3)
    assert _n(found[2]) == pytest.approx(p["k_theta"], rel=5e-3)
    assert _n(found[3]) == pytest.approx(p["F_N"], rel=5e-3)
    assert _n(found[4]) == pytest.approx(point["V0_m_per_s"], rel=5e-3)
    assert found[5] == point["regime"]
    change = 100 * (ftx - 1)
    assert f"{abs(change):.2g} % {'above' if change > 0 else 'below'} a rigid surface" in text
    speeds = point["speed_line"]["V0_m_per_s"]
    found = re.search(rf"as V₀ changes, from {NUMBER} to {NUMBER} m/s", text)
    assert (_n(found[1]), _n(found[2])) == pytest.approx((min(speeds), max(speeds)), rel=5e-3)
    assert "being computed" in design_map_description(point, None)


def test_two_designs_are_said_differently():
    slow, fast = (design_map_description(worker.compute_design_point(
        PillarDesign.example(V0=v)), _array(0.9)) for v in ("1 m/s", "300 m/s"))
    assert slow != fast
    assert "stiff regime" in slow and "stiff regime" not in fast


@pytest.mark.parametrize("law, V0", [(FrictionLaw(V_s=1e-3), 1.0),
                                     (FrictionLaw(mu_s=0.9, A=1.1, B=-5.0, V_s=0.02), 0.003)])
def test_the_law_words_are_mu_at_the_designs_speed(law, V0):
    text = law_description(law, V0=V0)
    assert _n(re.search(rf"At the design's V₀ = {NUMBER} m/s", text)[1]) == \
        pytest.approx(V0, rel=5e-3)
    assert _n(re.search(rf"\(a square\): μ = {NUMBER}", text)[1]) == \
        pytest.approx(float(law.mu(V0, V0)), rel=5e-3)
    assert f"μ_s = {law.mu_s:.3g}, A = {law.A:.3g}, B = {law.B:.3g}".replace("-", "−") in text
    v = np.geomspace(1e-6, 10, 2000)
    lowest = _n(re.search(rf"lowest {NUMBER}", text)[1])
    assert lowest >= float(law.mu(v).min()) - 1e-3


def test_the_law_words_name_the_fit():
    v = np.geomspace(1e-4, 1.0, 25)
    law = FrictionLaw(mu_s=1.2, A=1.4, B=-18.0, V_s=2e-3)
    curve = FrictionCurve(v, law.mu(v) + 0.01 * np.sin(7 * np.arange(25)), source="lab.csv")
    fit = fit_friction(curve)
    text = law_description(law, fit, curve, 0.01)
    assert "Fitted to 25 measured points" in text
    assert f"rms residual {fit.rms_residual:.3g}" in text
    assert "not drawn: bad V_s" in law_description(None, problem="bad V_s")


def _points(mus, speeds=(0.01, 0.1, 1.0, 3.0)):
    return [SpeedPoint(v, 0.5, m, 1e-3, 1e-6, True, "in_map", "ok") for v, m in zip(speeds, mus)]


@pytest.mark.parametrize("mus", [(0.9, 0.6, 0.8, 0.85), (0.4, 0.5, 0.7, 0.75)])
def test_the_speed_words_are_the_curve_its_lowest_point_and_the_comparison(mus):
    points = _points(mus)
    law = FrictionLaw(V_s=1e-3)
    text = speeds_description(points, law)
    i = int(np.argmin(mus))
    assert (f"from {mus[0]:.3g} at 0.01 m/s to {mus[-1]:.3g} at 3 m/s, lowest "
            f"{mus[i]:.3g} at {points[i].V0:.3g} m/s") in text
    measured = FrictionCurve([0.01, 0.1, 1.0, 3.0], [0.9, 0.62, 0.5, 0.8],
                             [0.005] * 4)
    c = compare_friction(SpeedCurve(law={}, points=tuple(points), seconds=0.0), measured)
    text = speeds_description(points, law, measured, c)
    assert f"RMS {c.rms:.3g} over 4 speeds" in text and "Diamonds: the measured curve, 4" in text
    assert ("disagree beyond" in text) == bool(c.disagree)
    running = speeds_description(points[:1] + [None] * 4, law, running=True)
    assert running == speeds_description([None] * 4, law, running=True)
