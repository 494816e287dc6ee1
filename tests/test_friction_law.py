"""A friction law (Eq. 4) carried into the model: ``model.FrictionLaw`` in the Python API
and ``micropillar pillar --friction fit.json``. The paper's law reproduces every number
of the model as it was, bit for bit; another law reaches the computation."""
import json
import math

import numpy as np
import pytest

from model import DEFAULTS, FrictionLaw, Params, fixed_orientation, mu
from model.cli import main
from model.contact.friction import law
from model.designs.design_point import model_params
from model.designs.units import PillarDesign

PILLAR = ["pillar", "--D", "5 um", "--h", "50 um", "--E", "1 GPa", "--nu", "0.4", "--rho",
          "920 kg/m^3", "--r0", "10 um", "--d-x", "20 um", "--d-y", "20 um", "--L-x", "1 mm",
          "--L-y", "1 mm", "--F-N", "1 mN", "--V0", "1 cm/s"]


def test_the_paper_law_is_the_models_defaults():
    paper = FrictionLaw()
    assert paper.is_paper
    assert (paper.mu_s, paper.A, paper.B) == (DEFAULTS["mu_s"], DEFAULTS["A"], DEFAULTS["B"])
    assert Params(k_r=3.0, k_theta=0.01, **paper.dimensionless()) == Params(k_r=3.0, k_theta=0.01)


def test_eq4_in_physical_units_is_the_models_mu():
    """The model computes Eq. (4) of zeta v (bit for bit the one formula); in physical
    units v/V_s differs from zeta v by rounding only."""
    v = np.geomspace(1e-6, 10.0, 201)
    V0 = 0.01
    assert np.array_equal(law(DEFAULTS["zeta"] * v, 1.3, 1.44, -20.0), mu(v))
    for physical in (FrictionLaw(V_s=V0 / DEFAULTS["zeta"]).mu(v * V0),
                     FrictionLaw().mu(v * V0, V0=V0)):
        assert np.allclose(physical, mu(v), rtol=1e-14, atol=0)


def test_a_design_with_the_paper_law_is_the_same_design():
    example = PillarDesign.example()
    same = example.with_friction(FrictionLaw(V_s="0.1 cm/s"))
    assert same == example and model_params(same) == model_params(example)
    default = PillarDesign.example(V_s=None)
    assert default.with_friction(FrictionLaw()) == default
    assert default.friction_law.is_paper


def test_another_law_reaches_the_array():
    fitted = FrictionLaw(mu_s=0.9, A=1.2, B=-5.0, V_s="2 mm/s")
    params = Params(k_r=3.0, k_theta=0.01, **fitted.dimensionless(V0=0.01))
    assert params.zeta == pytest.approx(5.0) and params.mu_s == 0.9
    base = fixed_orientation(Params(k_r=3.0, k_theta=0.01), rtol=1e-6)
    other = fixed_orientation(params, rtol=1e-6)
    assert other.FTx_over_mu0FN != base.FTx_over_mu0FN
    design = PillarDesign.example().with_friction(fitted)
    assert design.friction_law == fitted and design.dimensionless()["zeta"] == pytest.approx(5.0)


def test_a_law_without_V_s_needs_the_speed():
    with pytest.raises(ValueError, match="V0=None"):
        FrictionLaw().mu([0.001])
    with pytest.raises(ValueError, match="V0=None"):
        FrictionLaw(V_s=1e-3).dimensionless()
    with pytest.raises(ValueError, match="mu_s=-1"):
        FrictionLaw(mu_s=-1)


def _run(capsys, *argv):
    code = main(list(map(str, argv)))
    out, err = capsys.readouterr()
    return code, out, err


def test_cli_friction_file_of_the_paper_law_changes_no_number(capsys, tmp_path):
    path = tmp_path / "paper.json"
    path.write_text(json.dumps({"mu_s": 1.3, "A": 1.44, "B": -20, "V_s": 0.001}))
    code, out, _ = _run(capsys, *PILLAR, "--V-s", "0.1 cm/s", "--json")
    plain = json.loads(out)
    code2, out, _ = _run(capsys, *PILLAR, "--friction", path, "--json")
    assert (code, code2) == (0, 0) and json.loads(out) == plain


def test_cli_friction_file_from_the_fit_sets_the_law(capsys, tmp_path):
    from pathlib import Path

    example = Path(__file__).resolve().parents[1] / "examples" / "flat_friction.csv"
    fit_json = tmp_path / "fit.json"
    code, _, _ = _run(capsys, "friction", "fit", example, "--out", fit_json)
    assert code == 0
    fitted = FrictionLaw.from_json(fit_json)
    code, out, _ = _run(capsys, *PILLAR, "--friction", fit_json, "--json")
    record = json.loads(out)
    assert code == 0 and record["point"]["zeta"] == pytest.approx(0.01 / fitted.V_s, rel=1e-12)
    assert record["design"]["B"] == fitted.B and not math.isclose(fitted.B, DEFAULTS["B"])


@pytest.mark.parametrize("content, words", [
    ("{", "not JSON"),
    ('{"mu_s": 1.3, "A": 1.44}', "no 'B'"),
    ('{"mu_s": 1.3, "A": "x", "B": -20}', "A = 'x' is not a finite number"),
    ('{"mu_s": 1.3, "A": 1.44, "B": -20, "success": false}', "did not converge"),
    ('{"mu_s": 1.3, "A": 1.44, "B": -20, "V_s": -1}', "V_s"),
])
def test_cli_refuses_a_bad_friction_file_in_one_line(capsys, tmp_path, content, words):
    path = tmp_path / "law.json"
    path.write_text(content)
    code, out, err = _run(capsys, *PILLAR, "--friction", path)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1
    assert "--friction: law.json" in err and words in err, err


def test_cli_refuses_a_file_and_a_flag_for_the_law(capsys, tmp_path):
    path = tmp_path / "law.json"
    path.write_text(json.dumps(FrictionLaw().to_dict()))
    code, _, err = _run(capsys, *PILLAR, "--friction", path, "--B", "-10")
    assert code == 2 and "--friction: give the friction law as a file or as --B" in err
