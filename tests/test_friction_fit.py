"""Fitting the friction law of Eq. (4) to a measured curve: ``model.lab.friction_fit`` and
``micropillar friction fit``. The fit recovers known coefficients within its intervals,
warns when the data do not determine them, and refuses bad files naming the line."""
import json
import math
from pathlib import Path

import numpy as np
import pytest

from model.cli import main
from model.lab.friction_curve import CurveFileError, FrictionCurve, read_curve
from model.lab.friction_example import TRUE_LAW, example_text
from model.lab.friction_fit import _jacobian, fit_friction

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "flat_friction.csv"
TRUE = TRUE_LAW.to_dict()
#: 100 speeds from 0.01 to 100 V_s: both sides of the peak and the plateau.
SPEEDS = np.geomspace(1e-2, 1e2, 100) * TRUE["V_s"]


def _draw(seed, noise=0.02, v=SPEEDS):
    return TRUE_LAW.mu(v) + np.random.default_rng(seed).normal(0.0, noise, v.size)


@pytest.mark.parametrize("weighted", [False, True], ids=["scatter", "mu_err"])
def test_intervals_hold_the_true_coefficients_in_90_percent_of_50_draws(weighted):
    hits = dict.fromkeys(TRUE, 0)
    for seed in range(50):
        err = np.full(SPEEDS.size, 0.02) if weighted else None
        fit = fit_friction(FrictionCurve(SPEEDS, _draw(seed), err))
        assert fit.success and not fit.warnings, (seed, fit.message, fit.warnings)
        for name, value in TRUE.items():
            lo, hi = fit.ci95[name]
            hits[name] += lo <= value <= hi
    assert all(n >= 45 for n in hits.values()), hits


def test_intervals_scale_with_the_noise():
    """Ten times the noise, ten times the interval (the linearised covariance)."""
    wide = fit_friction(FrictionCurve(SPEEDS, _draw(1, noise=0.05)))
    narrow = fit_friction(FrictionCurve(SPEEDS, _draw(1, noise=0.005)))
    for name in TRUE:
        (a, b), (c, d) = wide.ci95[name], narrow.ci95[name]
        ratio = math.log(b / a) / math.log(d / c) if name == "V_s" else (b - a) / (d - c)
        assert 5 < ratio < 20, (name, ratio)


def test_plateau_only_data_are_flagged_as_undetermined():
    v = np.geomspace(50, 1000, 40) * TRUE["V_s"]
    fit = fit_friction(FrictionCurve(v, _draw(3, noise=0.01, v=v)))
    text = " ".join(fit.warnings)
    assert "mu_s sin(A pi/2)" in text and "constant mu" in text
    plateau = TRUE["mu_s"] * math.sin(TRUE["A"] * math.pi / 2)
    assert fit.values["mu_s"] * math.sin(fit.values["A"] * math.pi / 2) == \
        pytest.approx(plateau, abs=0.01)
    undetermined = {w.split()[0] for w in fit.warnings if "not determined" in w}
    assert {"mu_s", "A", "V_s"} <= undetermined


def test_analytic_jacobian_matches_finite_differences():
    p = np.array([1.1, 1.6, -7.0, math.log(2e-3)])
    v = np.geomspace(1e-5, 1.0, 50)
    from model.lab.friction_fit import _model

    jac = _jacobian(p, v)
    for k in range(4):
        h = 1e-6 * max(1.0, abs(p[k]))
        up, down = p.copy(), p.copy()
        up[k] += h
        down[k] -= h
        numeric = (_model(up, v) - _model(down, v)) / (2 * h)
        assert np.allclose(jac[:, k], numeric, rtol=1e-6, atol=1e-8), k


def test_the_shipped_example_is_what_its_header_says_and_fits_back():
    assert EXAMPLE.read_text() == example_text()
    curve = read_curve(EXAMPLE)
    assert curve.v.min() == pytest.approx(1e-5) and curve.mu_err is not None
    fit = fit_friction(curve)
    for name, value in TRUE.items():
        lo, hi = fit.ci95[name]
        assert lo <= value <= hi, name


def test_units_from_the_header_or_the_flag_give_the_same_fit(tmp_path):
    rows = [f"{v * 1e3:.17g},{m:.17g}" for v, m in zip(SPEEDS, _draw(5))]
    (tmp_path / "mm.csv").write_text("v [mm/s],mu\n" + "\n".join(rows) + "\n")
    (tmp_path / "bare.csv").write_text("# from the tribometer\nv,mu\n" + "\n".join(rows) + "\n")
    a = fit_friction(read_curve(tmp_path / "mm.csv"))
    b = fit_friction(read_curve(tmp_path / "bare.csv", v_unit="um/s"))
    assert a.values["mu_s"] == pytest.approx(b.values["mu_s"], rel=1e-6)
    assert b.values["V_s"] == pytest.approx(a.values["V_s"] / 1000, rel=1e-6)  # um, not mm
    assert a.values["V_s"] == pytest.approx(TRUE["V_s"], rel=0.1)  # SI: m/s


def _cli(capsys, *argv):
    code = main(["friction", "fit", *map(str, argv)])
    out, err = capsys.readouterr()
    return code, out, err


def test_cli_json_has_the_documented_keys_in_si(capsys, tmp_path):
    code, out, err = _cli(capsys, EXAMPLE, "--json", "--out", tmp_path / "fit.json")
    assert (code, err) == (0, "")
    record = json.loads(out)
    assert {"mu_s", "A", "B", "V_s", "rms_residual", "n_points", "warnings"} <= set(record)
    for name in TRUE:
        value, (lo, hi) = record[name]["value"], record[name]["ci95"]
        assert lo < value < hi
    assert record["V_s"]["value"] == pytest.approx(1e-3, rel=0.2)  # m/s
    assert record["n_points"] == 40 and record["warnings"] == []
    assert 0.01 < record["rms_residual"] < 0.03  # the noise is 0.02
    assert json.loads((tmp_path / "fit.json").read_text()) == record
    code, out, _ = _cli(capsys, EXAMPLE)
    assert code == 0 and "95 % interval" in out and "corr(B, ln V_s)" in out


BAD = {
    "no header": ("1,0.5\n2,0.6\n3,0.7\n4,0.8\n", 1, "no header"),
    "no mu column": ("v [mm/s],friction\n1,0.5\n", 1, "no column 'mu'"),
    "no unit": ("v,mu\n1,0.5\n2,0.6\n3,0.7\n4,0.8\n", 1, "no unit for v"),
    "not a number": ("v [mm/s],mu\n1,0.5\n2,0.6\n3,high\n4,0.8\n", 4, "non-numeric value 'high'"),
    "negative speed": ("v [mm/s],mu\n1,0.5\n-2,0.6\n3,0.7\n4,0.8\n", 3, "negative speed"),
    "too few points": ("# two\nv [mm/s],mu\n1,0.5\n2,0.6\n3,0.7\n", 5, "fewer than the 4"),
    "short row": ("v [mm/s],mu\n1,0.5\n2\n3,0.7\n4,0.8\n", 3, "1 cells"),
    "mu_err zero": ("v [mm/s],mu,mu_err\n1,0.5,0.1\n2,0.6,0\n3,0.7,0.1\n4,0.8,0.1\n", 3,
                    "mu_err"),
    "infinite": ("v [mm/s],mu\n1,0.5\n2,inf\n3,0.7\n4,0.8\n", 3, "not finite ('inf')"),
}


@pytest.mark.parametrize("case", list(BAD))
def test_bad_files_get_one_line_naming_the_line_and_nothing_is_written(case, capsys, tmp_path):
    text, line, words = BAD[case]
    path = tmp_path / "curve.csv"
    path.write_text(text)
    out_file = tmp_path / "fit.json"
    code, out, err = _cli(capsys, path, "--json", "--out", out_file)
    assert code == 2 and out == "" and not out_file.exists()
    assert len(err.strip().splitlines()) == 1, err
    assert f"line {line}" in err and "curve.csv" in err and words in err, err
    with pytest.raises(CurveFileError, match=f"line {line}\\b"):
        read_curve(path)


def test_the_api_refuses_what_the_file_reader_refuses():
    with pytest.raises(ValueError, match="point 1: negative speed"):
        FrictionCurve([1e-3, -1e-3, 2e-3, 3e-3], [0.5, 0.6, 0.7, 0.8])
    with pytest.raises(ValueError, match="fewer than the 4"):
        FrictionCurve([1e-3, 2e-3, 3e-3], [0.5, 0.6, 0.7])


def test_a_unit_that_is_not_a_speed_is_refused(capsys, tmp_path):
    path = tmp_path / "c.csv"
    path.write_text("v [mm],mu\n1,0.5\n2,0.6\n3,0.7\n4,0.8\n")
    code, _, err = _cli(capsys, path)
    assert code == 2 and "c.csv line 1: 'mm' is not a unit of speed" in err
    path.write_text("v,mu\n1,0.5\n2,0.6\n3,0.7\n4,0.8\n")
    code, _, err = _cli(capsys, path, "--v-unit", "kg")
    assert code == 2 and "--v-unit: 'kg' is not a unit of speed" in err
