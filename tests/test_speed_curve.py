"""The structured surface's friction against sliding speed (``model.lab.speed_curve``,
``micropillar pillar --speeds``): at every speed it is the design's own evaluation,
beside the flat material's mu(V0) of Eq. (4); a speed out of reach is named, not fatal."""
import json
import math

import numpy as np
import pytest

from model.cli import main
from model.designs.design_point import evaluate, model_params
from model.designs.distributions import Fixed, VonMises
from model.contact.friction import mu0
from model.lab.friction_law import FrictionLaw
from model.lab.speed_curve import friction_velocity, parse_speeds, speed_range
from model.designs.units import PillarDesign, ureg

#: Soft LDPE-like pillars on a short slab: cheap arrays near the paper's map at 0.1-1 m/s.
DESIGN = PillarDesign.example(E="1 MPa", V0="1 m/s", V_s="1 mm/s", L_x="0.1 mm",
                              F_N="10 uN")
ARGS = ["pillar", "--D", "5 um", "--h", "50 um", "--E", "1 MPa", "--nu", "0.4", "--rho",
        "920 kg/m^3", "--r0", "10 um", "--d-x", "20 um", "--d-y", "20 um", "--L-x", "0.1 mm",
        "--L-y", "1 mm", "--F-N", "10 uN", "--V0", "1 cm/s"]
VM = VonMises(math.radians(60), 4.0)


def test_each_speed_is_the_design_evaluated_at_that_speed_with_the_paper_law():
    speeds = [0.1, 0.3, 1.0]
    curve = friction_velocity(DESIGN, speeds, VM)
    assert curve.success and DESIGN.friction_law == FrictionLaw(V_s="1 mm/s")
    for V0, p in zip(speeds, curve.points):
        at = DESIGN.replace(V0=ureg.Quantity(V0, "m/s"))
        r = evaluate(at, VM)
        assert p.V0 == V0 and p.status == r.status
        assert p.mu_flat == mu0(model_params(at))  # the rigid-contact mu0 is the flat mu(V0)
        assert p.mu_apparent == pytest.approx(r.FTx_N / at.F_N, rel=1e-14)
        assert p.quadrature_error == pytest.approx(r.errors["FTx_N"] / at.F_N, rel=1e-14)
        assert p.integration_error == r.array.integration_error


def test_the_flat_curve_is_eq4_of_the_speed():
    law = FrictionLaw(mu_s=0.8, A=1.6, B=-3.0, V_s="0.2 m/s")
    speeds = np.geomspace(0.05, 1.0, 4)
    curve = friction_velocity(DESIGN.with_friction(law), speeds, Fixed(math.pi / 2))
    assert np.allclose(curve.column("mu_flat"), law.mu(speeds), rtol=1e-14, atol=0)
    assert curve.law == law.to_dict() and curve.success


def test_a_speed_out_of_reach_is_a_named_point_and_the_rest_is_computed():
    curve = friction_velocity(DESIGN, [1.0, 1e3], Fixed(math.pi / 2))
    ok, far = curve.points
    assert ok.success and math.isfinite(ok.mu_apparent)
    assert not far.success and far.status == "outside_range" and "too fast" in far.message
    assert math.isnan(far.mu_apparent) and math.isfinite(far.mu_flat)
    assert not curve.success


def test_a_law_without_its_own_V_s_is_refused():
    with pytest.raises(ValueError, match="V_s=None"):
        friction_velocity(DESIGN.replace(V_s=None), [0.1, 1.0])


@pytest.mark.parametrize("text, lo, hi", [("0.1mm/s..1m/s", 1e-4, 1.0),
                                          (" 1 cm/s .. 2 m/s ", 0.01, 2.0)])
def test_speed_ranges_read_with_units(text, lo, hi):
    assert parse_speeds(text) == pytest.approx((lo, hi), rel=1e-12)
    assert speed_range(lo, hi, 30)[[0, -1]] == pytest.approx([lo, hi], rel=1e-12)


@pytest.mark.parametrize("text, words", [("1m/s..0.1mm/s", "below the high"),
                                         ("fast", "not a range"), ("1 kg..2 kg", "V0=")])
def test_bad_speed_ranges_are_refused(text, words):
    with pytest.raises(ValueError, match=words):
        parse_speeds(text)


def _run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_cli_prints_the_curve_and_its_json_agrees_with_the_api(capsys):
    code, out, _ = _run(capsys, *ARGS, "--V-s", "1 mm/s", "--speeds", "0.1m/s..1m/s",
                        "--n", "3", "--orientation", "fixed", "--json")
    record = json.loads(out)
    assert code == 0 and record["all_success"]
    api = friction_velocity(DESIGN, speed_range(0.1, 1.0, 3), Fixed(math.pi / 2))
    assert record["V0_m_per_s"] == pytest.approx(api.column("V0").tolist(), rel=1e-12)
    assert record["mu_apparent"] == pytest.approx(api.column("mu_apparent").tolist(), rel=1e-9)
    code, out, _ = _run(capsys, *ARGS, "--V-s", "1 mm/s", "--speeds", "0.1m/s..1m/s", "--n",
                        "3", "--orientation", "fixed")
    rows = [line for line in out.splitlines() if line.strip()[:1].isdigit()]
    assert code == 0 and len(rows) == 3 and "mu flat" in out


def test_two_processes_give_every_point_of_one_and_report_each_as_it_finishes():
    speeds = speed_range(0.1, 1.0, 4)
    serial = friction_velocity(DESIGN, speeds, VM)
    seen = []
    parallel = friction_velocity(DESIGN, speeds[::-1], VM, workers=2,
                                 on_point=lambda i, p: seen.append((i, p)))
    assert parallel.points == serial.points  # bit for bit, in increasing speed
    assert sorted(i for i, _ in seen) == [0, 1, 2, 3]
    assert all(parallel.points[i] == p for i, p in seen)


def test_cli_rows_come_in_increasing_speed_with_two_processes(capsys):
    code, out, _ = _run(capsys, *ARGS, "--V-s", "1 mm/s", "--speeds", "0.1m/s..1m/s",
                        "--n", "4", "--orientation", "fixed", "--workers", "2")
    speeds = [float(line.split()[0]) for line in out.splitlines()
              if line.strip()[:1].isdigit()]
    assert code == 0 and speeds == sorted(speeds) and len(speeds) == 4


@pytest.mark.parametrize("extra, flag", [
    (["--speeds", "1m/s..0.1m/s"], "--speeds"), (["--speeds", "0.1m/s..1m/s", "--n", "1"], "--n"),
    (["--n", "3"], "--n"), (["--speeds", "0.1m/s..1m/s"], "--V-s"), (["--workers", "2"], "--workers"),
    (["--V-s", "1mm/s", "--speeds", "0.1m/s..1m/s", "--workers", "0"], "--workers")])
def test_cli_bad_speed_flags_are_one_line(capsys, extra, flag):
    code, out, err = _run(capsys, *ARGS, *extra)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1
    assert f"error: {flag}:" in err, err
