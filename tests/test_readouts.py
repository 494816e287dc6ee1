"""The headline sentence and the readout tables (app/views/readouts.py), without a server."""
import math

import pytest

from app.views.readouts import change_words, fixed_markdown, headline_text, uniform_markdown
from app.state import ExplorerState


@pytest.mark.parametrize("ratio, words", [
    (0.945, "5.5 % below a rigid surface"),
    (0.5, "50.0 % below a rigid surface"),
    (1.02, "2.0 % above a rigid surface"),
    (1.0, "the same as on a rigid surface"),
    (0.9996, "the same as on a rigid surface"),  # rounds to 0.0 %
    (None, "not available"),
    (math.nan, "not available"),
])
def test_change_words(ratio, words):
    assert change_words(ratio) == words


def test_headline_names_both_arrays_and_what_is_missing():
    text = headline_text(0.9463, 90.0, 0.9451)
    assert text == ("Friction is 5.4 % below a rigid surface (every support at θ₀ = 90°); "
                    "averaged over all orientations: 5.5 % below a rigid surface.")
    assert headline_text(0.9, 45.0, None).endswith("all orientations: being computed.")
    assert headline_text(0.9, 45.0, None, "not computed (see the notice)").endswith(
        "not computed (see the notice).")
    assert headline_text(None, 45.0, None).startswith("Friction: being computed;")


def test_tables_use_readable_labels():
    row = {"FTx_over_mu0FN": 0.95, "FTx_over_mu0FN_duration": 0.94, "Dy_over_Dx": 0.1,
           "Nc_over_Nc0": 1.1, "quadrature_error_FTx": 1e-4}
    table = uniform_markdown(row, "paper")
    assert "friction F_T,x/(μ₀F_N), paper (Eq. 10) | **0.95**" in table
    assert "dissipated across / along, D_y/D_x" in table
    assert fixed_markdown(None) == "*No result for these parameters.*"


def test_the_page_headline_follows_the_results():
    from app.state import ExplorerState
    from app.views import Dashboard

    page = Dashboard(ExplorerState())
    text = page.headline.pane.object
    fixed = page.results.support.fixed.FTx_over_mu0FN
    assert change_words(fixed) in text and "θ₀ = 90°" in text
    page.state.theta0 = 30.0
    assert "θ₀ = 30°" in page.headline.pane.object
    assert change_words(page.results.support.fixed.FTx_over_mu0FN) in page.headline.pane.object


def test_the_uniform_readout_shows_a_spinner_while_its_array_is_computed():
    from app.results import SessionResults
    from app.views.readouts import ReadoutsView

    state = ExplorerState()
    results = SessionResults(state)
    view = ReadoutsView(state=state, results=results)
    text = view.uniform_pane.object
    results.busy = ["support", "uniform"]
    assert view.uniform_holder.loading and view.uniform_pane.object == text
    results.busy = ["support"]
    assert not view.uniform_holder.loading
