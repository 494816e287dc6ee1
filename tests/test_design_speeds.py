"""The Design tab's friction against sliding speed without a browser
(``app.speed_results``, ``app.views.design_speeds``): the curve the page computes is the
command line's prediction at the same speeds, the comparison with the structured sample's
uploaded curve is ``compare_friction``'s, a bad file is refused in one line, and a change
of the design drops the curve."""
import math
from pathlib import Path

import numpy as np
import pytest

from app.views.page import Dashboard
from app.state import ExplorerState
from model.cli import main
from model.lab.friction_compare import compare_friction, read_measured
from model.lab.friction_example import STRUCTURED_DESIGN

ROOT = Path(__file__).resolve().parents[1]
MEASURED = ROOT / "examples" / "structured_friction.csv"
#: The example's structured design with the example law's V_s (uniform orientations).
QUERY = ("?tab=design&d_E=1%20MPa&d_Lx=0.1%20mm&d_FN=10%20uN&d_V0=1%20m/s&d_Vs=1%20mm/s")
CLI = ["pillar", "--D", "5 um", "--h", "50 um", "--E", "1 MPa", "--nu", "0.4", "--rho",
       "920 kg/m^3", "--r0", "10 um", "--d-x", "20 um", "--d-y", "20 um", "--L-x", "0.1 mm",
       "--L-y", "1 mm", "--F-N", "10 uN", "--V0", "1 m/s", "--V-s", "1 mm/s", "--json",
       "--orientation", "vonmises", "--mean-deg", "90", "--kappa", "4"]  # the page's default


@pytest.fixture
def page(pool):
    state = ExplorerState()
    assert state.load_query(QUERY) == []
    assert {k: state.design_inputs[k] for k in STRUCTURED_DESIGN} == STRUCTURED_DESIGN
    return Dashboard(state)


def _upload(view, path: Path) -> None:
    view.speeds.file.filename = path.name
    view.speeds.file.value = path.read_bytes()


def test_the_page_curve_is_the_command_lines_prediction(page, capsys):
    import json

    s, r = page.state, page.results
    s.param.update(speeds_range="0.1 m/s..3 m/s", speeds_n=4)
    page.design.speeds.predict.clicks += 1
    points = r.speed_points
    assert len(points) == 4 and all(p is not None for p in points) and not r.speed_running
    assert main([*CLI, "--speeds", "0.1m/s..3m/s", "--n", "4"]) == 0
    cli = json.loads(capsys.readouterr().out)
    assert [p.V0 for p in points] == pytest.approx(cli["V0_m_per_s"], rel=1e-14)
    assert [p.mu_apparent for p in points] == cli["mu_apparent"]
    assert [p.quadrature_error for p in points] == cli["quadrature_error"]
    assert [p.mu_flat for p in points] == cli["mu_flat"]
    assert "4 of 4 speeds computed" in r.speed_note
    # The figure shows each point with its error bar, and the flat law.
    data = page.design.speeds._sources["speeds_model"].data
    assert list(data["mu"]) == cli["mu_apparent"]
    assert np.allclose(np.subtract(data["hi"], data["mu"]), cli["quadrature_error"])
    assert len(page.design.speeds._sources["speeds_flat"].data["v"]) > 0


def test_the_comparison_is_compare_frictions_and_names_the_disagreeing_speeds(page):
    s, r = page.state, page.results
    s.param.update(speeds_range="0.1 m/s..3 m/s", speeds_n=6)
    _upload(page.design, MEASURED)
    assert r.speed_comparison is None and "Predict" in r.speed_compare_note
    r.predict_speeds()
    c, reference = r.speed_comparison, compare_friction(r.speed_curve, read_measured(MEASURED))
    assert c is not None and c.rms == reference.rms and c.disagree == reference.disagree
    assert np.array_equal(c.difference, reference.difference)
    text = page.design.speeds.compare.object
    assert f"RMS **{reference.rms:.3g}**" in text
    if reference.disagree:
        assert "disagree beyond the model's error" in text
        assert f"{reference.disagree[0]:.3g}" in text
    else:
        assert "agree within the model's error" in text
    shown = page.design.speeds._sources["speeds_difference"].data
    assert list(shown["d"]) == list(reference.difference)


def test_a_measurement_outside_the_predicted_speeds_is_not_compared(page):
    s, r = page.state, page.results
    s.param.update(speeds_range="0.2 m/s..1 m/s", speeds_n=2)
    r.predict_speeds()
    _upload(page.design, MEASURED)
    assert r.speed_comparison is None and "outside the predicted speeds" in r.speed_compare_note


def test_a_bad_structured_file_is_refused_in_one_line_and_changes_nothing(page):
    _upload_bytes = page.design.speeds.file
    _upload_bytes.filename = "bad.csv"
    _upload_bytes.value = b"v [m/s],mu\n0,0.9\n0.1,0.9\n0.2,0.9\n0.3,0.9\n"
    note = page.design.speeds.compare.object
    assert "**Not loaded:** bad.csv line 2: v = 0" in note
    assert page.state.structured_curve is None


def test_a_change_of_the_design_drops_the_curve_and_a_bad_range_is_named(page):
    s, r = page.state, page.results
    s.param.update(speeds_range="0.5 m/s..1 m/s", speeds_n=2)
    r.predict_speeds()
    assert len(r.speed_points) == 2
    s.design_F_N = "20 uN"
    assert r.speed_points == [] and "dropped" in r.speed_note
    s.speeds_range = "1 m/s..0.1 m/s"
    r.predict_speeds()
    assert r.speed_note.startswith("**Not computed:** speeds='1 m/s..0.1 m/s'")
    assert "low speed must be below" in page.design.speeds.note.object


def test_a_speed_past_its_budget_is_said(page, monkeypatch):
    """The work pool stops a job past its budget with ``OverBudget`` (app.jobs); the page
    names the speed and keeps the others."""
    from app import worker
    from app.jobs import OverBudget
    from model.lab.speed_curve import SpeedPoint

    def slow(design, V0, *args):
        if V0 > 0.7:
            raise OverBudget("this computation needs more than its 20 s of the server's "
                             "time and was stopped")
        return SpeedPoint(V0, 1.0, 0.99, 1e-4, 1e-6, True, "in_map", "ok")
    monkeypatch.setattr(worker, "compute_speed_point", slow)
    page.state.param.update(speeds_range="0.5 m/s..1 m/s", speeds_n=2)
    page.results.predict_speeds()
    assert "ran out at 1 m/s" in page.results.speed_note
    assert "1 of 2 speeds computed" in page.results.speed_note


def test_cancel_drops_the_speeds_not_started_and_ignores_late_ones(page, pool, monkeypatch):
    """As on a server, where speeds arrive later: Cancel cancels the jobs not started, says
    how many had arrived, and a speed that still comes in is not drawn."""
    import concurrent.futures as cf

    from app.speed_results import SpeedResults

    waiting = []

    def later(lane, key, fn, *args, **options):
        future = cf.Future()
        waiting.append((future, fn, args))
        return future
    monkeypatch.setattr(pool, "submit", later)
    monkeypatch.setattr(SpeedResults, "_collect", lambda self, generation, jobs: None)
    r = page.results
    page.state.param.update(speeds_range="0.5 m/s..1 m/s", speeds_n=3)
    r.predict_speeds()
    assert r.speed_running and len(waiting) == 3 and r.speed_points == [None] * 3
    assert page.design.speeds.progress.visible and not page.design.speeds.cancel.disabled
    generation = r._speed_generation
    page.design.speeds.cancel.clicks += 1
    assert not r.speed_running and all(f.cancelled() for f, _, _ in waiting)
    assert r.speed_note.startswith("Cancelled after 0 of 3 speeds")
    assert page.design.speeds.cancel.disabled and not page.design.speeds.predict.disabled
    late = cf.Future()
    late.set_result(waiting[0][1](*waiting[0][2]))
    r._arrive(generation, 0, 0.5, late)
    assert r.speed_points == [None] * 3
