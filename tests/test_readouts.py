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
                    "with supports of all orientations the slab feels 5.5 % below a rigid "
                    "surface (each support counted for as long as it touches the slab).")
    assert headline_text(0.9, 45.0, None).endswith(
        "what the slab feels with supports of all orientations: being computed.")
    assert headline_text(0.9, 45.0, None, "not computed (see the notice)").endswith(
        "not computed (see the notice).")
    assert headline_text(None, 45.0, None).startswith("Friction: being computed;")


def test_tables_use_readable_labels():
    row = {"FTx_over_mu0FN": 0.95, "FTx_over_mu0FN_duration": 0.94, "Dy_over_Dx": 0.1,
           "Nc_over_Nc0": 1.1, "quadrature_error_FTx": 1e-4}
    table = uniform_markdown(row, "paper")
    assert "friction F_T,x/(μ₀F_N), paper, Eq. 10: each support counted once | **0.95**" in table
    # The slab's average (the headline's) comes first, named in words.
    assert table.index("duration-weighted: the force the slab feels (headline) | 0.94 |") < \
        table.index("paper, Eq. 10")
    assert "dissipated across / along, D_y/D_x" in table
    assert fixed_markdown(None) == "*No result for these parameters.*"


def test_the_page_headline_follows_the_results():
    from app.state import ExplorerState
    from app.views import Dashboard

    page = Dashboard(ExplorerState())
    text = page.headline.text
    fixed = page.results.support.fixed.FTx_over_mu0FN
    assert change_words(fixed) in text and "θ₀ = 90°" in text
    page.state.theta0 = 30.0
    assert "θ₀ = 30°" in page.headline.text
    assert change_words(page.results.support.fixed.FTx_over_mu0FN) in page.headline.text


def test_the_uniform_readout_shows_a_spinner_while_its_array_is_computed():
    from app.results import SessionResults
    from app.views.readouts import ReadoutsView

    state = ExplorerState()
    results = SessionResults(state)
    view = ReadoutsView(state=state, results=results)
    text = view.uniform_pane.object
    results.busy = ["support", "uniform"]
    # In the folded card nobody sees it: no spinner (Panel's loading overlay, a message).
    assert not view.uniform_holder.loading
    view.details.collapsed = False
    assert view.uniform_holder.loading and view.uniform_pane.object == text
    results.busy = ["support"]
    assert not view.uniform_holder.loading
    results.busy = ["support", "uniform"]
    view.details.collapsed = True
    assert not view.uniform_holder.loading


@pytest.mark.parametrize("tab", ["support", "array", "polar", "map", "load", "equations"])
def test_the_headline_settles_on_every_tab(pool, tab, monkeypatch):
    """The headline stands above every tab (but Design): its uniform array is computed
    whichever tab is on screen, also after the controls move there."""
    from app import worker
    from app.results import SessionResults
    from app.views.page import TAB_RESULTS
    from app.views.readouts import HeadlineView

    # Only the headline's results matter here: the tab's own are not computed.
    for name in ("compute_polar", "compute_map", "compute_array_motion"):
        monkeypatch.setattr(worker, name, lambda *a, **k: None)
    for name in ("compute_load", "compute_load_regimes"):
        monkeypatch.setattr(worker, name, lambda *a, **k: {})
    state = ExplorerState(tab=tab)
    results = SessionResults(state)
    results.show(TAB_RESULTS[tab])
    results.start()
    view = HeadlineView(state=state, results=results)
    state.param.update(k_r=0.01, k_theta=3.0)  # the slider, moved on this tab
    text = view.text
    assert "being computed" not in text
    felt = results.uniform["FTx_over_mu0FN_duration"]
    assert results.uniform is not None and f"the slab feels {change_words(felt)}" in text
    assert change_words(results.support.fixed.FTx_over_mu0FN) in text


def test_the_headline_quotes_the_force_the_slab_feels_whatever_the_plots_average(pool):
    """One number for all orientations: the duration-weighted average (the Array tab's and
    the lesson's 0.845 for the slider), not Eq. 10's, even with the plots set to Eq. 10."""
    from app.results import SessionResults
    from app.views.readouts import HeadlineView

    for average in ("paper", "duration"):
        state = ExplorerState(k_r=0.01, k_theta=3.0, average=average)
        results = SessionResults(state)
        results.start()
        text = HeadlineView(state=state, results=results).text
        assert f"{results.uniform['FTx_over_mu0FN_duration']:.3f}" == "0.845"
        assert "15.5 % below a rigid surface (each support counted for as long" in text
        assert change_words(results.uniform["FTx_over_mu0FN"]) not in text


def test_the_lesson_teaches_the_headline_s_number():
    """docs/teaching.md Q6 quotes the force the slab feels as the headline words it."""
    from pathlib import Path

    from app.lesson import facts

    doc = (Path(__file__).resolve().parents[1] / "docs" / "teaching.md").read_text("utf-8")
    q6 = doc[doc.index("## Q6"):doc.index("## Q7")]
    felt = facts("slider", 90, 1)["uniform_FTx_duration"]
    assert f"*duration-weighted* average ({felt:.3f}, {change_words(felt)})" in q6
    assert "headline" in q6


def test_the_folded_numbers_are_written_when_the_card_is_opened(pool):
    """Folded (the default), the card's tables cost nothing per move: no text is written
    (no Markdown render, no message); opened, they show the current results at once and
    then follow every move."""
    from app.results import SessionResults
    from app.views.readouts import ReadoutsView

    state = ExplorerState()
    results = SessionResults(state)
    results.start()
    view = ReadoutsView(state=state, results=results)
    assert view.details.collapsed
    written = []
    for pane in (view.fixed_pane, view.uniform_pane):
        pane.param.watch(lambda event: written.append(event.obj), "object")
    state.k_r = 0.5
    assert written == []
    view.details.collapsed = False
    assert view.fixed_pane.object == fixed_markdown(results.support)
    assert view.uniform_pane.object == uniform_markdown(results.uniform, state.average)
    assert results.support.params.k_r == 0.5
    state.k_r = 0.7
    assert view.fixed_pane.object == fixed_markdown(results.support)
    assert results.support.params.k_r == 0.7
    # Every column of every table is named: a screen reader reads a header cell out.
    for table in (view.fixed_pane.object, view.uniform_pane.object,
                  uniform_markdown(None, state.average)):
        header = table.splitlines()[0]
        assert all(cell.strip() for cell in header.strip("|").split("|")), header


def test_the_headline_never_quotes_a_result_of_the_controls_before(pool):
    """After a change of the springs, the result that arrives first is not set beside the
    other's number for the springs before: that part of the sentence is "being computed"
    until its own result arrives."""
    from app.results import SessionResults
    from app.views.readouts import HeadlineView

    state = ExplorerState()
    results = SessionResults(state)
    results.start()
    view = HeadlineView(state=state, results=results)
    before = results.uniform["FTx_over_mu0FN_duration"]
    assert f"the slab feels {change_words(before)}" in view.text
    uniform = results.slots["uniform"]
    uniform.set_needed(False)  # its new result held back: the support's comes alone
    state.F_N = 5.0
    assert results.slots["support"].current and not uniform.current
    assert change_words(results.support.fixed.FTx_over_mu0FN) in view.text
    assert change_words(before) not in view.text
    assert "all orientations: being computed." in view.text
    uniform.set_needed(True)  # ... and once it arrives, both numbers are the new state's
    after = results.uniform["FTx_over_mu0FN_duration"]
    assert after != before and f"the slab feels {change_words(after)}" in view.text
