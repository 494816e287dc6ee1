"""``python -m model array --orientation pair|vonmises|mixture|csv`` and
``python -m model design``: JSON keys, agreement with the API, one-line errors."""
import json
import math

import pytest

from model.cli import main
from model.cli.array import QUADRATURE_KEYS
from model.designs.design import optimise
from model.designs.distribution_array import distribution_array
from model.designs.distributions import Fixed, Histogram, Mixture, Uniform, VonMises
from model.contact.params import REGIMES

#: The keys ``array --orientation uniform --json`` prints today.
UNIFORM_KEYS = {"FTx_over_mu0FN", "FTx_over_mu0FN_duration", "FTy_over_mu0FN", "Dy_over_Dx",
                "Nc_over_Nc0", "beta", "work_split", "dtheta_rms", "dr_rms", "quadrature_error",
                "integration_error", "beta_iterations", "beta_residual", "n_members", "n_failed",
                "n_pivot", "failed_theta0", "success", "message", "seconds", "stats", "params",
                "orientation"}


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def strict_json(text):
    def reject(constant):
        raise AssertionError(f"{constant} is not JSON")
    return json.loads(text, parse_constant=reject)


def test_uniform_keys_are_what_the_uniform_array_prints(capsys):
    code, out, _ = run(capsys, "array", "--regime", "stiff", "--json")
    assert code == 0 and set(strict_json(out)) == UNIFORM_KEYS


def test_vonmises_json_has_the_uniform_keys_and_matches_the_api(capsys):
    code, out, err = run(capsys, "array", "--orientation", "vonmises", "--mean-deg", "60",
                         "--kappa", "4", "--k-r", "3", "--k-theta", "0.01", "--F-N", "1", "--json")
    assert (code, err) == (0, "")
    r = strict_json(out)
    assert UNIFORM_KEYS <= set(r) and {"Uel_over_W", "distribution", "psi_deg"} <= set(r)
    assert set(QUADRATURE_KEYS) <= set(r["quadrature_error"])
    api = distribution_array(REGIMES["pendulum"], VonMises(math.radians(60), 4.0))
    assert r["FTx_over_mu0FN"] == pytest.approx(api.FTx_over_mu0FN, rel=1e-12)
    assert r["FTy_over_mu0FN"] == pytest.approx(api.FTy_over_mu0FN, rel=1e-12)
    assert r["distribution"] == {"family": "vonmises", "mean_deg": pytest.approx(60),
                                 "kappa": 4.0}


def test_fixed_beta_pair_psi_and_summary(capsys):
    code, out, _ = run(capsys, "array", "--orientation", "pair", "--theta0", "1.0", "--regime",
                       "slider", "--beta", "0.5", "--json")
    r = strict_json(out)
    assert code == 0 and r["beta"] == 0.5 and r["FTy_over_mu0FN"] == 0.0
    code, out, _ = run(capsys, "array", "--orientation", "vonmises", "--mean-deg", "60",
                       "--kappa", "4", "--regime", "soft", "--psi-deg", "20", "--json")
    r = strict_json(out)
    api = distribution_array(REGIMES["soft"], VonMises(math.radians(40), 4.0))
    assert r["FTx_over_mu0FN"] == pytest.approx(api.FTx_over_mu0FN, abs=1e-9)
    code, out, _ = run(capsys, "array", "--orientation", "vonmises", "--mean-deg", "60",
                       "--kappa", "4", "--regime", "soft")
    assert code == 0 and "FTx_over_mu0FN" in out and "p-weighted" in out


def test_mixture_and_csv(capsys, tmp_path):
    code, out, _ = run(capsys, "array", "--orientation", "mixture", "--regime", "pendulum",
                       "--component", "vonmises:mean_deg=60,kappa=4", "--component",
                       "fixed:theta0_deg=30", "--weights", "0.75,0.25", "--json")
    r = strict_json(out)
    api = distribution_array(REGIMES["pendulum"], Mixture(
        (VonMises(math.radians(60), 4.0), Fixed(math.radians(30))), (0.75, 0.25)))
    assert code == 0 and r["FTx_over_mu0FN"] == pytest.approx(api.FTx_over_mu0FN, rel=1e-12)
    path = tmp_path / "h.csv"
    path.write_text("theta0_deg,weight\n" + "".join(f"{10 * i + 5},1\n" for i in range(36)))
    code, out, _ = run(capsys, "array", "--orientation", "csv", "--histogram", str(path),
                       "--regime", "stiff", "--json")
    r = strict_json(out)
    uniform = distribution_array(REGIMES["stiff"], Uniform())
    assert code == 0 and r["distribution"]["family"] == "histogram"
    # A flat histogram over the circle is the uniform array.
    assert r["FTx_over_mu0FN"] == pytest.approx(uniform.FTx_over_mu0FN, abs=2e-6)
    assert isinstance(Histogram.from_csv(path), Histogram)


@pytest.mark.parametrize("argv, flag", [
    (["--orientation", "vonmises", "--mean-deg", "60", "--kappa", "-1"], "--kappa"),
    (["--orientation", "vonmises", "--kappa", "2"], "--mean-deg"),
    (["--kappa", "2"], "--kappa"),
    (["--orientation", "mixture"], "--component"),
    (["--orientation", "mixture", "--component", "gauss"], "--component"),
    (["--orientation", "mixture", "--component", "uniform", "--weights", "x"], "--weights"),
    (["--orientation", "mixture", "--component", "uniform", "--weights", "-1"], "--weights"),
    (["--orientation", "csv"], "--histogram"),
    (["--orientation", "csv", "--histogram", "/no/such/file.csv"], "--histogram"),
    (["--orientation", "fixed", "--psi-deg", "10"], "--psi-deg"),
    (["--orientation", "vonmises", "--mean-deg", "1", "--kappa", "1", "--theta0", "1"],
     "--theta0"),
    (["--orientation", "pair", "--tol", "1e-3"], "--tol"),
    (["--orientation", "pair", "--method", "reference"], "--method"),
    (["--orientation", "uniform", "--method", "reference"], "--method"),
    (["--orientation", "fixed", "--method", "reference"], "--method"),
])
def test_bad_flags_are_one_line_naming_the_flag(capsys, argv, flag):
    code, out, err = run(capsys, "array", "--regime", "pendulum", *argv)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and f"error: {flag}:" in err


@pytest.mark.parametrize("text", ["", "theta0_deg,weight\n", "theta0_deg,weight\n10,abc\n"])
def test_bad_histograms_are_usage_errors(capsys, tmp_path, text):
    path = tmp_path / "h.csv"
    path.write_text(text)
    code, out, err = run(capsys, "array", "--regime", "pendulum", "--orientation", "csv",
                         "--histogram", str(path))
    assert code == 2 and "--histogram:" in err and out == ""


# --------------------------------------------------------------------------- design

DESIGN_KEYS = {"FTx_over_mu0FN", "FTy_over_mu0FN", "family", "distribution",
               "uniform_FTx_over_mu0FN", "quadrature_error", "error_estimate", "success",
               "message", "gain"}


def test_design_json_keys_and_agreement_with_the_api(capsys):
    code, out, err = run(capsys, "design", "--k-r", "3", "--k-theta", "0.01", "--F-N", "1",
                         "--objective", "min-FTx", "--max-abs-FTy", "0.01", "--family", "fixed",
                         "--n-scan", "45", "--json")
    assert (code, err) == (0, "")
    r = strict_json(out)
    assert DESIGN_KEYS | {"theta0_deg", "max_abs_FTy"} <= set(r)
    assert abs(r["FTy_over_mu0FN"]) <= 0.01 + 1e-6
    api = optimise(REGIMES["pendulum"], "fixed", bound=0.01, n_scan=45)
    assert r["FTx_over_mu0FN"] == pytest.approx(api.FTx_over_mu0FN, rel=1e-12)
    assert r["theta0_deg"] == pytest.approx(math.degrees(api.distribution.theta0))


def test_design_vonmises_and_summary(capsys):
    code, out, _ = run(capsys, "design", "--regime", "stiff", "--family", "vonmises",
                       "--n-scan", "30", "--max-evaluations", "15", "--beta", "0.9", "--json")
    r = strict_json(out)
    assert {"mean_deg", "kappa"} <= set(r) and r["distribution"]["family"] == "vonmises"
    assert code in (0, 1) and (code == 0) == r["success"]
    code, out, _ = run(capsys, "design", "--regime", "slider", "--n-scan", "30")
    assert code == 0 and "gain" in out and "pair" in out


@pytest.mark.parametrize("argv, flag", [
    (["--family", "pair", "--objective", "max-FTy"], "--family"),
    (["--max-FTx", "0.9"], "--max-FTx"),
    (["--objective", "max-FTy", "--max-abs-FTy", "0.1", "--family", "fixed"], "--max-abs-FTy"),
    (["--max-abs-FTy", "-1"], "--max-abs-FTy"),
    (["--n-scan", "3"], "--n-scan"),
    (["--tol", "2"], "--tol"),
    (["--family", "gauss"], "--family"),
])
def test_design_bad_flags(capsys, argv, flag):
    code, out, err = run(capsys, "design", "--regime", "pendulum", *argv)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and f"{flag}:" in err


# --------------------------------------------------------------------------- pillar

EXAMPLE = ["--D", "5 um", "--h", "50 um", "--E", "1 GPa", "--nu", "0.4", "--rho", "920 kg/m^3",
           "--r0", "10 um", "--d-x", "20 um", "--d-y", "20 um", "--L-x", "1 mm", "--L-y", "1 mm",
           "--F-N", "1 mN", "--V0", "1 cm/s", "--V-s", "0.1 cm/s"]


def test_pillar_places_the_worked_example(capsys):
    from model.designs.units import PillarDesign

    code, out, err = run(capsys, "pillar", *EXAMPLE, "--json")
    assert (code, err) == (0, "")
    r = strict_json(out)
    x = PillarDesign.example().dimensionless()
    assert r["point"]["k_r"] == pytest.approx(x["k_r"]) and r["regime"] == "stiff"
    assert r["status"] == "scaled" and r["intervals"]["V0_m_per_s"]["pendulum"] is None
    code, out, _ = run(capsys, "pillar", *EXAMPLE, "--prefactors", "beam", "--json")
    assert strict_json(out)["point"]["k_r"] == pytest.approx(x["k_r"] * 3 * math.pi / 64)


def test_pillar_evaluate_in_physical_units(capsys):
    fast = [a if a not in ("1 cm/s", "0.1 cm/s", "1 mm", "1 mN") else
            {"1 cm/s": "100 m/s", "0.1 cm/s": "10 m/s", "1 mm": "0.1 mm", "1 mN": "0.1 mN"}[a]
            for a in EXAMPLE]
    code, out, _ = run(capsys, "pillar", *fast, "--evaluate", "--orientation", "pair",
                       "--theta0", "1.0", "--json")
    r = strict_json(out)
    assert code == 0 and r["status"] == "in_map"
    assert {"FTx_N", "power_W", "contact_time_s", "excursion_r_um"} <= set(r)
    assert r["power_W"] == pytest.approx(r["FTx_N"] * 100.0)


@pytest.mark.parametrize("change, flag", [(("--D", "5 kg"), "--D"), (("--E", "-1 GPa"), "--E"),
                                          (("--V0", "fast"), "--V0")])
def test_pillar_bad_quantities_name_the_flag(capsys, change, flag):
    argv = list(EXAMPLE)
    argv[argv.index(change[0]) + 1] = change[1]
    code, out, err = run(capsys, "pillar", *argv)
    assert code == 2 and out == "" and f"error: {flag}:" in err and err.count("\n") == 1


def test_pillar_names_every_missing_value_at_once(capsys):
    given = EXAMPLE[:EXAMPLE.index("--rho")]  # D, h, E, nu
    code, out, err = run(capsys, "pillar", *given)
    assert code == 2 and out == "" and err.count("\n") == 1
    missing = [f for f in ("--rho", "--r0", "--d-x", "--d-y", "--L-x", "--L-y", "--F-N", "--V0")]
    assert f"error: {', '.join(missing)}: required" in err, err


def test_pillar_budget_that_runs_out_prints_the_result_and_its_outcome(capsys):
    """The worked example at 1 cm/s lies beyond the model range (computed scaled, stiff and
    heavily loaded: minutes of contacts); half a second ends it with a named outcome, finite
    results and exit code 1, as any run that did not succeed."""
    code, out, err = run(capsys, "pillar", *EXAMPLE, "--evaluate", "--budget", "0.5", "--json")
    r = strict_json(out)
    assert (code, err) == (1, "") and r["success"] is False and r["status"] == "scaled"
    assert r["array"]["outcome"] in ("contacts_cut", "beta_cut", "refinement_cut")
    assert "time budget of 0.5 s" in r["message"]
    assert all(math.isfinite(r[k]) for k in ("FTx_over_mu0FN", "FTx_N", "power_W"))
    code, out, err = run(capsys, "pillar", *EXAMPLE, "--evaluate", "--budget", "0.5")
    assert code == 1 and "outcome" in out and "time budget of 0.5 s" in out


@pytest.mark.parametrize("argv", [["--budget", "1"], ["--evaluate", "--budget", "0"],
                                  ["--evaluate", "--budget", "-1"],
                                  ["--evaluate", "--budget", "nan"],
                                  ["--evaluate", "--budget", "soon"]])
def test_pillar_bad_budget_is_named_before_any_work(capsys, monkeypatch, argv):
    import model.designs.design_point as design_point

    def started(*args, **kwargs):
        pytest.fail("the evaluation started although --budget was refused")

    monkeypatch.setattr(design_point, "evaluate", started)
    code, out, err = run(capsys, "pillar", *EXAMPLE, *argv)
    assert code == 2 and out == "" and "error: --budget:" in err and err.count("\n") == 1


# --------------------------------------------------------------------------- fuzzed

from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

VALUES = ["-1", "0", "1", "3", "0.5", "0.01", "nan", "inf", "abc", "", "1e400", "self",
          "fixed", "pair", "vonmises", "mixture", "min-FTx", "max-FTy", "5 um", "1 GPa",
          "5 kg", "1 cm/s", "-2 um", "\x00", "1 2"]
DESIGN_FLAGS = ["--k-r", "--k-theta", "--F-N", "--beta", "--objective", "--family",
                "--max-abs-FTy", "--max-FTx", "--tol", "--n-scan", "--max-evaluations",
                "--regime", "--json", "--bogus"]
PILLAR_FLAGS = list(dict.fromkeys(EXAMPLE[::2])) + ["--prefactors", "--json", "--bogus",
                                                      "--orientation", "--kappa", "--budget"]


def tokens(flags):
    pair = st.tuples(st.sampled_from(flags), st.sampled_from(VALUES)).map(list)
    return st.lists(pair, max_size=4).map(lambda parts: [t for p in parts for t in p])


@settings(max_examples=60, deadline=60_000, database=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(argv=st.one_of(
    # Budgets last (argparse keeps the last value): every design run stays small.
    tokens(DESIGN_FLAGS).map(lambda t: ["design", "--regime", "stiff", *t, "--n-scan", "8",
                                        "--max-evaluations", "2", "--tol", "0.1"]),
    tokens(PILLAR_FLAGS).map(lambda t: ["pillar", *EXAMPLE, *t])))
def test_fuzzed_design_and_pillar_fail_cleanly_or_run(capsys, argv):
    code, out, err = run(capsys, *argv)
    assert "Traceback" not in out + err
    assert code in (0, 1, 2), (code, err)
    if code == 2:
        assert out == "" and err.count("\n") == 1 and ": error: " in err
        return
    assert out.strip()
    if "--json" in argv:
        record = strict_json(out)
        assert "success" not in record or record["success"] is (code == 0)


def test_scan_size_is_checked_against_memory_before_the_search(capsys, monkeypatch):
    """``--n-scan 1e9`` would build a billion fixed arrays: refused before any work."""
    from model.cli import design as design_cli

    def started(*args, **kwargs):
        pytest.fail("the search started although --n-scan was refused")

    monkeypatch.setattr(design_cli, "optimise", started)
    code = main(["design", "--regime", "soft", "--n-scan", "1e9"])
    out, err = capsys.readouterr()
    assert code == 2 and out == "" and err.count("\n") == 1
    assert "error: --n-scan: 1,000,000,000 scanned orientations would need about" in err
