"""The plots of the Array, Polar, Regime map and Load tabs in words (app/plot_words.py)
and their numbers as a table (app/views/data_table.py): every number said is read from
the result given (two results, two texts), never fixed per preset."""
import math
import re
from types import SimpleNamespace

import numpy as np
import pytest

from app.export import load_csv, map_csv
from app.plot_words import (array_description, load_description, map_description,
                            polar_description)
from app.views.design_words import design_polar_description
from app.views.data_table import column_header, shown_rows, table_html
from model import Params, csvfile
from model.arrays.quantities import QUANTITIES
from model.runs.shipped_map import load_regime_map

NUMBER = r"(−?[0-9]+(?:\.[0-9]+)?(?:e[+−]?[0-9]+)?)"


def _n(text: str) -> float:
    return float(text.replace("−", "-"))


def _motion(ftx: float, nc: float, orientation="uniform", theta0=90.0):
    return SimpleNamespace(
        model={"FTx_over_mu0FN_duration": ftx, "Nc_over_Nc0": nc, "beta": 0.5},
        n_supports=96, n_rows=8, n_cols=12, orientation=orientation,
        params=Params(k_r=0.03, k_theta=0.03, F_N=1.0, theta0=math.radians(theta0)))


@pytest.mark.parametrize("ftx, nc", [(0.845, 3.02), (1.07, 0.8)])
def test_the_array_words_are_its_settled_force(ftx, nc):
    text = array_description(_motion(ftx, nc), "uniform")
    assert re.search(rf"F_T,x/\(μ₀F_N\) = {NUMBER}", text)[1] == f"{ftx:.3g}"
    assert f"N_c/N_c0 = {nc:.3g}" in text and "96 supports on a 8 × 12 grid" in text
    change = abs(100 * (1 - ftx))
    assert f"{change:.1f} % {'below' if ftx < 1 else 'above'} a rigid surface" in text
    fixed = array_description(_motion(ftx, nc, "fixed", 30.0), "fixed")
    assert "every support at θ₀ = 30°" in fixed and "uniform" not in fixed


def _sweep(shift_deg: float, k_r: float = 0.5):
    theta = (np.arange(72) + 0.5) * math.pi / 72
    ftx = 1.0 - 0.3 * np.sin(theta - math.radians(shift_deg)) ** 2
    fty = -0.2 * np.sin(2 * (theta - math.radians(shift_deg)))
    return SimpleNamespace(columns={"theta0": theta, "FTx_over_mu0FN": ftx,
                                    "FTy_over_mu0FN": fty, "Dy_over_Dx": 0.1 + 0 * theta},
                           settings={"k_r": k_r, "k_theta": 0.2, "F_N": 3.0})


def _assert_extremes(text: str, sweep) -> None:
    """``text`` says where the sweep's F_T,x/(mu0 F_N) is lowest and highest, and the values."""
    theta = np.degrees(sweep.columns["theta0"])
    ftx = sweep.columns["FTx_over_mu0FN"]
    m = re.search(rf"lowest, {NUMBER}, at θ₀ = {NUMBER}° and highest, {NUMBER}, at "
                  rf"θ₀ = {NUMBER}°", text)
    assert _n(m[1]) == pytest.approx(ftx.min(), rel=5e-3)
    assert _n(m[2]) == pytest.approx(theta[ftx.argmin()], abs=0.51)
    assert _n(m[3]) == pytest.approx(ftx.max(), rel=5e-3)
    assert _n(m[4]) == pytest.approx(theta[ftx.argmax()], abs=0.51)


@pytest.mark.parametrize("shift", [0.0, 30.0])
def test_the_polar_words_say_where_the_curves_peak(shift):
    sweep = _sweep(shift)
    text = polar_description(sweep)
    theta = np.degrees(sweep.columns["theta0"])
    fty = sweep.columns["FTy_over_mu0FN"]
    _assert_extremes(text, sweep)
    i = np.abs(fty).argmax()
    m = re.search(rf"strongest at θ₀ = {NUMBER}°, {NUMBER}, pushing the slab towards (.y)", text)
    assert _n(m[1]) == pytest.approx(theta[i], abs=0.51)
    assert _n(m[2]) == pytest.approx(fty[i], rel=5e-3)
    assert m[3] == ("+y" if fty[i] > 0 else "−y")
    assert "k_r = 0.5, k_θ = 0.2, F_N = 3" in text and "-" not in re.sub(r"[a-z]-[a-z]", "", text)
    support = SimpleNamespace(params=Params(k_r=0.5, k_theta=0.2, theta0=math.radians(40.0)), fixed=SimpleNamespace(
        FTx_over_mu0FN=0.91, Dy_over_Dx=0.12, FTy_over_mu0FN=-0.05))
    assert ("At the current θ₀ = 40°: F_T,x/(μ₀F_N) = 0.91, D_y/D_x = 0.12, "
            "F_T,y/(μ₀F_N) = −0.05.") in polar_description(sweep, support)


@pytest.mark.parametrize("shift, k_r", [(0.0, 553.0), (30.0, 5.5)])
def test_the_design_polar_words_are_its_curve_distribution_and_array(shift, k_r):
    """The Design tab's Fig. 11a of the design's springs (app/views/design_words.py)."""
    sweep = _sweep(shift, k_r)
    d = {"family": "vonmises", "mean_deg": 60.0 + shift, "kappa": 2.0}
    ftx = 0.8 + shift / 100
    array = {"array": {"FTx_over_mu0FN": ftx, "quadrature_error": {}, "bounds": None}}
    text = design_polar_description(sweep, d, 0.0, array)
    _assert_extremes(text, sweep)
    assert f"k̃_r = {k_r:.3g}" in text
    assert f"von Mises about {60 + shift:g}°, κ = 2" in text
    assert f"the array's F_T,x/(μ₀F_N) = {ftx:.3g}" in text
    assert "being computed" in design_polar_description(sweep, d, 0.0, None)


@pytest.mark.parametrize("quantity, column", [("5a", "FTx_over_mu0FN"),
                                              ("5b", "Dy_over_Dx")])
def test_the_map_words_are_its_extremes_and_the_current_cell(quantity, column):
    m = load_regime_map(F_N=1.0)
    values = getattr(m, column)
    i, j = 3, 17
    text = map_description(m, quantity, "paper", float(m.k_r[i]), float(m.k_theta[j]))
    lo = np.unravel_index(np.nanargmin(values), values.shape)
    found = re.search(rf"Lowest {NUMBER} at k_r = {NUMBER}, k_θ = {NUMBER}", text)
    assert _n(found[1]) == pytest.approx(values[lo], rel=5e-3)
    assert _n(found[2]) == pytest.approx(m.k_r[lo[0]], rel=5e-3)
    assert _n(found[3]) == pytest.approx(m.k_theta[lo[1]], rel=5e-3)
    assert _n(re.search(rf"lie in a cell where it is {NUMBER}", text)[1]) == \
        pytest.approx(values[i, j], rel=5e-3)
    assert "lie outside the map" in map_description(m, quantity, "paper", 50.0, 0.1)


def _curve(values: dict, k_r=0.03, k_theta=0.03) -> dict:
    return {F_N: {"k_r": k_r, "k_theta": k_theta, "FTx_over_mu0FN": v,
                  "FTx_over_mu0FN_duration": v - 0.01} for F_N, v in values.items()}


def test_the_load_words_follow_the_curves_and_the_average():
    curves = {"current": _curve({0.1: 0.9, 1.0: 0.7, 10.0: 0.8}),
              "pendulum": _curve({0.1: 0.95, 10.0: 0.99}, 3.0, 0.01)}
    text = load_description(curves, 1.0, "paper", {"FTx_over_mu0FN": 0.7})
    assert "soft regime) it goes from 0.9 at F_N = 0.1 to 0.8 at F_N = 10" in text
    assert "lowest 0.7 at F_N = 1" in text and "At the current F_N = 1: 0.7." in text
    assert "The paper's regimes at F_N = 10: pendulum 0.99." in text
    duration = load_description(curves, 1.0, "duration")
    assert "from 0.89 at F_N = 0.1" in duration and "duration-weighted" in duration
    assert load_description({}, 1.0, "paper") == "The load curves are being computed."


def test_a_table_is_the_csv_download_with_units_in_its_headers():
    m = load_regime_map(F_N=1.0)
    text = map_csv(m)
    _, columns = csvfile.read_text(text)
    page = table_html(text, "the map")
    heads = re.findall(r'<th scope="col">([^<]*)</th>', page)
    assert heads[:2] == ["k_r [–]", "k_θ [–]"] and len(heads) == len(columns)
    numbers = [h for h, name in zip(heads, columns) if QUANTITIES[name].units]  # not counts
    assert len(numbers) == 8 and all("[" in h for h in numbers), heads
    rows = re.findall(r"<tr><td>(.*?)</td></tr>", page)
    kept = shown_rows(m.k_r.size * m.k_theta.size)
    assert len(rows) == len(kept) < m.k_r.size * m.k_theta.size
    assert f"one row in {kept[1]} of {m.k_r.size * m.k_theta.size}" in page
    for row, k in zip(rows, kept):
        cells = row.split("</td><td>")
        assert float(cells[0]) == pytest.approx(columns["k_r"][k], rel=1e-3)
        assert float(cells[2]) == pytest.approx(columns["FTx_over_mu0FN"][k], rel=1e-3)
    assert shown_rows(30).tolist() == list(range(30))
    assert shown_rows(1000)[-1] == 999 and len(shown_rows(1000)) <= 121
    assert "being computed" in table_html(load_csv(None), "the load curves")
    assert column_header("theta0_deg") == "θ₀ [°]" and column_header("tau") == "τ [r₀/V₀]"
