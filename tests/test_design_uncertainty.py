"""A result that did not converge never carries an error bar that looks like one: members
that did not finish took their neighbour's values, so the error of F_T,x and F_T,y is the
half-width of bounds that hold whatever those members' forces are, and nothing else has
an error bar (``model.designs.distribution_result``). The same everywhere: the result objects,
``to_dict``, the design's physical results, its table and CSV, the command line."""
import csv
import json
import math
import subprocess
import sys

import pytest

from model import Params
from model.designs.design_point import evaluate
from model.designs.design_table import headline, rows, table_csv
from model.designs.distribution_array import distribution_array
from model.designs.distribution_result import value_text
from model.designs.distributions import VonMises
from model.designs.units import PillarDesign, measure_text

STIFF = Params(k_r=3.0, k_theta=3.0, F_N=1.0)
DIST = VonMises(math.pi / 2, 4.0)
#: Explicit steps too few for some orientations of STIFF (a fixed beta keeps it fast).
CUT = dict(tol=1e-3, beta=1.0, method="explicit", max_steps=80)


@pytest.fixture(scope="module")
def cut():
    return distribution_array(STIFF, DIST, **CUT)


@pytest.fixture(scope="module")
def converged():
    return distribution_array(STIFF, DIST, tol=1e-4, beta=1.0, method="explicit")


def test_filled_members_give_bounds_not_a_tiny_error_bar(cut, converged):
    assert not cut.success and 0 < cut.n_failed < cut.n_members
    assert "nearest neighbour" in cut.message
    assert 0 < cut.filled_weight < 1
    truth = converged.FTx_over_mu0FN
    lo, hi = cut.bounds["FTx_over_mu0FN"]
    assert lo <= truth <= hi
    error = cut.quadrature_error["FTx_over_mu0FN"]
    # The error bar covers the converged value, and is at least the filled share times
    # the largest friction a member can have (mu_s over mu0).
    assert error >= abs(cut.FTx_over_mu0FN - truth)
    assert error >= cut.filled_weight * 0.9
    # Quantities without a bound have no error bar at all.
    assert math.isnan(cut.quadrature_error["Nc_over_Nc0"])


def test_the_error_bar_is_the_same_in_to_dict_and_in_words(cut):
    d = json.loads(json.dumps(cut.to_dict(), default=float).replace("NaN", "null"))
    assert d["bounds"]["FTx_over_mu0FN"] == pytest.approx(list(cut.bounds["FTx_over_mu0FN"]))
    text = value_text(cut.to_dict(), "FTx_over_mu0FN")
    assert "not converged: between" in text and "±" not in text
    assert "no error bar" in value_text(cut.to_dict(), "Nc_over_Nc0")


def test_a_converged_result_keeps_its_estimate(converged):
    assert converged.success and converged.bounds == {}
    err = converged.quadrature_error["FTx_over_mu0FN"]
    assert 0 <= err < 1e-3
    assert value_text(converged.to_dict(), "FTx_over_mu0FN").endswith(f"± {err:.1e}")


def test_physical_results_have_si_prefixes_four_figures_and_their_error():
    assert measure_text(0.0010177, "N", 1.6e-7) == "1.018 ± 0.00016 mN"
    assert measure_text(0.001, "W") == "1.000 mW"
    assert measure_text(2.5e-4, "s", None, converged=False) == \
        "250.0 µs (not converged: no error bar)"
    assert measure_text(0.001, "N", None, (-1e-4, 1.2e-3)) == \
        "1.000 mN (not converged: between -0.1 and 1.2 mN)"


@pytest.fixture(scope="module")
def stiff_design():
    """The notes' LDPE pillars at 1 cm/s (k~ ~ 1e6-1e7, computed scaled) with a budget too
    small for their ringing contacts: members are cut short and filled."""
    return evaluate(PillarDesign.example(V0="1 cm/s"), DIST, budget=0.5)


def test_a_design_cut_short_reports_bounds_everywhere(stiff_design):
    r = stiff_design
    assert not r.success and r.array.outcome == "contacts_cut" and r.array.n_failed
    record = r.to_dict()
    # The drive force and power carry the array's bounds, never a small error bar.
    for key in ("FTx_N", "power_W"):
        lo, hi = record["bounds"][key]
        assert lo <= record[key] <= hi and (hi - lo) > 0.1 * abs(record[key])
    table = {row["key"]: row for row in rows(record)}
    assert "±" not in table["FTx_over_mu0FN"]["text"]
    assert "not converged" in table["FTx_over_mu0FN"]["text"]
    assert all("±" not in row["text"] for row in table.values())
    assert "not known yet" in headline(record)
    lines = [x for x in table_csv(record).splitlines() if not x.startswith("#")]
    csv_rows = {row[0]: row for row in csv.reader(lines[1:])}
    assert lines[0] == "key,what,value,error,lower,upper,unit"
    assert csv_rows["Nc_over_Nc0"][3] == ""  # no error bar: an empty cell
    value, error, lo, hi = (float(x) for x in csv_rows["FTx_over_mu0FN"][2:6])
    assert lo <= value <= hi and error > 0.1


PILLAR = ["pillar", "--D", "5 um", "--h", "50 um", "--E", "1 GPa", "--nu", "0.4", "--rho",
          "920 kg/m^3", "--r0", "10 um", "--d-x", "20 um", "--d-y", "20 um", "--L-x", "1 mm",
          "--L-y", "1 mm", "--F-N", "1 mN", "--V0", "1 cm/s", "--V-s", "0.1 cm/s",
          "--evaluate", "--orientation", "vonmises", "--mean-deg", "90", "--kappa", "4",
          "--budget", "0.5"]


def _cli(*extra):
    return subprocess.run([sys.executable, "-m", "model", *PILLAR, *extra], capture_output=True,
                          text=True, timeout=300)


def test_the_command_line_says_not_converged_in_text_and_json():
    out = _cli("--json")
    assert out.returncode == 1, out.stderr
    r = json.loads(out.stdout)
    err = r["array"]["quadrature_error"]
    assert err["FTx_over_mu0FN"] > 0.1 and err["Nc_over_Nc0"] is None
    lo, hi = r["array"]["bounds"]["FTx_over_mu0FN"]
    assert lo <= r["array"]["FTx_over_mu0FN"] <= hi
    assert r["errors"]["FTx_N"] > 0.1 * r["FTx_N"]
    text = _cli()
    assert text.returncode == 1
    line = next(x for x in text.stdout.splitlines() if x.strip().startswith("FTx_over_mu0FN "))
    assert "not converged: between" in line and "±" not in line
    assert "friction not known yet" in text.stdout


def test_the_design_tab_shows_bounds_and_greys_out_stale_numbers(stiff_design):
    """The Design tab's readouts (without a server): the headline, no small error bar on
    a result cut short, and the previous inputs' numbers struck through under a banner
    while a new result computes; the CSV download is the table."""
    from app.results import SessionResults
    from app.state import ExplorerState
    from app.views.design_readouts import DesignReadouts

    results = SessionResults(ExplorerState())
    view = DesignReadouts(state=results.state, results=results)
    record = stiff_design.to_dict()
    results.design_array = record
    text = view.table.object
    header = next(line for line in text.splitlines() if line.startswith("|"))
    assert all(cell.strip() for cell in header.strip("|").split("|")), \
        f"a column without a header, which a screen reader reads out nameless: {header}"
    assert "friction not known yet" in text and "not converged: between" in text
    assert "±" not in text  # no error bar that looks like one
    assert not view.banner.visible and "stale" not in view.table.css_classes
    assert not view.download.disabled
    assert view._csv().getvalue() == table_csv(record)
    results.busy = [*results.busy, "design_array"]  # new inputs: the old numbers stay
    assert view.banner.visible and "previous inputs" in view.banner.object
    assert "up to 30 s" in view.banner.object
    assert "stale" in view.table.css_classes and view.download.disabled


def test_a_real_pillar_off_the_map_is_drawn_at_its_edge_with_its_values():
    from app.figures.design import design_map_data
    from app.worker import compute_design_point

    point = compute_design_point(PillarDesign.example(V0="1 cm/s"))
    assert point["point"]["k_r"] > 1e6 and point["point"]["k_theta"] > 1e7
    data, xr, yr = design_map_data(point)
    star = data["design_point"]
    assert xr[0] < star["k_r"][0] < xr[1] and yr[0] < star["k_theta"][0] < yr[1]
    assert star["note"] == ["off the map →↑\nk̃_r = 5.5e6\nk̃_θ = 4.9e7"]
    inside = compute_design_point(PillarDesign.example(V0="100 m/s", F_N="1 N"))
    data, _, _ = design_map_data(inside)
    assert data["design_point"]["note"] == [""]
    assert data["design_point"]["k_r"] == [inside["point"]["k_r"]]
