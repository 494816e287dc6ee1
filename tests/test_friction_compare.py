"""The predicted friction-velocity curve of the structured surface compared with a measured
one (``model.lab.friction_compare``, ``micropillar pillar --compare``): the differences, their
RMS and the speeds named as disagreeing are right on constructed cases; bad inputs are
refused with one line; the shipped example is what its header says."""
import json
import math
from pathlib import Path

import numpy as np
import pytest

from model import FrictionCurve, compare_friction
from model.cli import main
from model.lab.friction_compare import DEFAULT_MU_ERR, read_measured
from model.lab.friction_curve import CurveFileError
from model.lab.friction_example import STRUCTURED_SPEEDS, structured_text
from model.lab.speed_curve import SpeedCurve, SpeedPoint, friction_velocity

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "structured_friction.csv"
ARGS = ["pillar", "--D", "5 um", "--h", "50 um", "--E", "1 MPa", "--nu", "0.4", "--rho",
        "920 kg/m^3", "--r0", "10 um", "--d-x", "20 um", "--d-y", "20 um", "--L-x", "0.1 mm",
        "--L-y", "1 mm", "--F-N", "10 uN", "--V0", "1 m/s", "--V-s", "1 mm/s"]


def _known(V0, errors=None, mu=lambda v: 0.9 + 0.05 * np.log10(v), failed=()):
    """A predicted curve of known values: mu(V0), with per-point errors."""
    errors = np.full(len(V0), 1e-3) if errors is None else errors
    points = tuple(SpeedPoint(float(v), 1.0, math.nan if i in failed else float(mu(v)),
                              math.nan if i in failed else float(e), 1e-6, i not in failed,
                              "outside_range" if i in failed else "in_map", "")
                   for i, (v, e) in enumerate(zip(V0, errors)))
    return SpeedCurve(law={}, points=points, seconds=0.0)


def test_rms_and_disagreeing_speeds_at_computed_speeds():
    V0 = np.geomspace(0.1, 10.0, 6)
    predicted = _known(V0, errors=np.array([1e-3, 2e-3, 1e-3, 5e-3, 1e-3, 1e-3]))
    offsets = np.array([0.0, 0.02, -0.004, -0.014, 0.0109, -0.0111])
    truth = 0.9 + 0.05 * np.log10(V0)
    c = compare_friction(predicted, FrictionCurve(V0, truth + offsets, np.full(6, 0.005)))
    assert c.success and c.n_compared == 6
    np.testing.assert_allclose(c.difference, offsets, atol=1e-12)
    assert c.rms == pytest.approx(math.sqrt(np.mean(offsets ** 2)), rel=1e-12)
    # allowed: model error + 2 x 0.005 -> 0.011, 0.012, 0.011, 0.015, 0.011, 0.011
    np.testing.assert_allclose(c.tolerance, [0.011, 0.012, 0.011, 0.015, 0.011, 0.011])
    assert c.disagree == pytest.approx((V0[1], V0[5]))


def test_between_computed_speeds_the_prediction_is_linear_in_log_speed():
    V0 = np.array([0.1, 1.0, 10.0])
    predicted = _known(V0, errors=np.array([1e-3, 4e-3, 2e-3]))  # linear in log10 v
    v = np.array([0.1, np.sqrt(0.1), 3.0, 10.0])
    c = compare_friction(predicted, FrictionCurve(v, np.full(4, 0.95)), mu_err=0.0)
    np.testing.assert_allclose(c.predicted, 0.9 + 0.05 * np.log10(v), rtol=1e-12)
    # an interpolated point's model error is the larger neighbour's
    np.testing.assert_allclose(c.model_error, [1e-3, 4e-3, 4e-3, 2e-3])
    assert not c.mu_err_given and np.all(c.measured_error == 0.0)


def test_without_mu_err_the_stated_default_is_used():
    V0 = np.geomspace(0.1, 1.0, 4)
    predicted = _known(V0, errors=np.zeros(4))
    offsets = np.array([0.0, 1.9 * DEFAULT_MU_ERR, 2.1 * DEFAULT_MU_ERR, 0.0])
    c = compare_friction(predicted, FrictionCurve(V0, 0.9 + 0.05 * np.log10(V0) + offsets))
    assert c.disagree == pytest.approx((V0[2],))
    assert "assumed mu_err of 0.01" in c.message


def test_a_speed_the_model_could_not_compute_is_not_compared():
    V0 = np.geomspace(0.1, 10.0, 5)
    predicted = _known(V0, failed=(2,))
    v = np.array([0.1, 0.5, 1.0, 10.0])  # 0.5 lies between a good and the failed point
    c = compare_friction(predicted, FrictionCurve(v, 0.9 + 0.05 * np.log10(v) + 0.1))
    assert not c.success and "2 measured speeds not compared" in c.message
    assert np.isnan(c.difference[1:3]).all() and c.n_compared == 2
    assert c.rms == pytest.approx(0.1) and c.disagree == pytest.approx((0.1, 10.0))


@pytest.mark.parametrize("v, kw, words", [
    ([0.05, 0.2, 0.5, 1.0], {}, "v = 0.05 m/s lies outside the predicted speeds"),
    ([0.2, 0.5, 1.0, 20.0], {}, "measured point 3"),
    ([0.2, 0.5, 1.0, 2.0], {"n_sigma": -1}, "n_sigma=-1"),
    ([0.2, 0.5, 1.0, 2.0], {"mu_err": math.nan}, "mu_err=nan")])
def test_bad_inputs_are_refused(v, kw, words):
    with pytest.raises(ValueError, match=words.replace("(", r"\(")):
        compare_friction(_known(np.geomspace(0.1, 10, 4)), FrictionCurve(v, np.ones(4)), **kw)


def test_a_zero_speed_in_the_measured_file_is_refused_naming_its_line(tmp_path):
    path = tmp_path / "s.csv"
    path.write_text("# run 3\nv [m/s],mu\n0.1,1\n0.2,1\n\n0,1\n0.3,1\n")
    with pytest.raises(CurveFileError, match=r"s\.csv line 6: v = 0"):
        read_measured(path)


def test_the_shipped_example_is_what_its_header_says():
    shipped, again = EXAMPLE.read_text(), structured_text()
    head = [line for line in shipped.splitlines() if not line[:1].isdigit()]
    assert head == [line for line in again.splitlines() if not line[:1].isdigit()]
    assert "not a measurement" in head[0]

    def numbers(text):
        return np.array([[float(x) for x in line.split(",")] for line in text.splitlines()
                         if line[:1].isdigit()])
    np.testing.assert_allclose(numbers(shipped), numbers(again), atol=2e-5)
    np.testing.assert_allclose(numbers(shipped)[:, 0], STRUCTURED_SPEEDS, rtol=1e-5)


def _run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_cli_round_trip_agrees_with_the_api(capsys, tmp_path):
    from model.designs.distributions import Fixed
    from model.designs.units import PillarDesign

    design = PillarDesign.example(E="1 MPa", V0="1 m/s", V_s="1 mm/s", L_x="0.1 mm",
                                  F_N="10 uN")
    speeds = np.array([0.1, 0.3, 1.0, 2.0])
    predicted = friction_velocity(design, speeds, Fixed(math.pi / 2)).column("mu_apparent")
    measured = np.round(predicted + [0.0, 0.1, -0.005, 0.015], 6)
    path = tmp_path / "structured.csv"
    path.write_text("v [mm/s],mu\n" + "".join(f"{v * 1e3:g},{float(m)!r}\n"
                                               for v, m in zip(speeds, measured)))
    code, out, err = _run(capsys, *ARGS, "--compare", str(path), "--orientation", "fixed",
                          "--json")
    assert code == 0, err
    record = json.loads(out)
    c = record["comparison"]
    assert c["v_m_per_s"] == pytest.approx(speeds.tolist(), rel=1e-12)
    assert record["prediction"]["V0_m_per_s"] == pytest.approx(c["v_m_per_s"], rel=1e-12)
    assert c["predicted"] == pytest.approx(predicted.tolist(), rel=1e-9)
    assert c["difference"] == pytest.approx((measured - predicted).tolist(), abs=1e-9)
    assert c["rms"] == pytest.approx(float(np.sqrt(np.mean((measured - predicted) ** 2))))
    # a fixed array has no quadrature error: allowed 2 x the default mu_err = 0.02
    assert c["measured_error"] == [DEFAULT_MU_ERR] * 4
    assert c["disagree_m_per_s"] == pytest.approx([0.3])
    code, out, _ = _run(capsys, *ARGS, "--compare", str(path), "--orientation", "fixed")
    assert code == 0 and "disagree beyond the allowed error at V0 [m/s]: 0.3" in out
    assert out.count("disagrees") == 1


@pytest.mark.parametrize("extra, flag", [
    (["--compare", "EXAMPLE", "--speeds", "0.1m/s..1m/s"], "--compare"),
    (["--mu-err", "0.01"], "--mu-err"), (["--v-unit", "mm/s"], "--v-unit"),
    (["--compare", "EXAMPLE", "--mu-err", "-1"], "--mu-err")])
def test_cli_bad_flags_are_one_line(capsys, extra, flag):
    extra = [str(EXAMPLE) if e == "EXAMPLE" else e for e in extra]
    code, out, err = _run(capsys, *ARGS, *extra)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1
    assert f"error: {flag}:" in err, err


@pytest.mark.parametrize("text, words", [
    ("0.1,1\n0.2,1\n", "line 1: no header"),
    ("v [m/s],mu\n0.1,1\n0.2,abc\n0.3,1\n1,1\n", "non-numeric value 'abc' on line 3"),
    ("v [m/s],mu\n0.1,1\n0,1\n0.3,1\n1,1\n", "line 3: v = 0")])
def test_cli_bad_files_are_one_line_naming_the_line(capsys, tmp_path, text, words):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    code, out, err = _run(capsys, *ARGS, "--compare", str(path))
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1
    assert words in err, err
