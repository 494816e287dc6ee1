"""The Design tab's friction law (Eq. 4) without a browser: a measured curve uploaded and
fitted, or coefficients typed in; the fit's coefficients with their intervals and Fig. 3
(law, band, measured points, in m/s); the design's array computed with the law; the law in
the URL, a pinned state, the design table's CSV and "this view as code". The paper's law
stays the default, bit for bit, and a default view's URL does not change."""
import math
from pathlib import Path

import numpy as np
import pytest

from app import worker
from app.state import ExplorerState
from app.defaults import DEFAULTS, LAW_INPUTS
from app.urlstate import parse, parse_pinned, pinned_text
from app.views.page import Dashboard
from model import FrictionLaw, Params
from model.designs.design_table import table_csv
from model.lab.friction_curve import CurveFileError, read_curve
from model.lab.friction_fit import fit_friction
from model.designs.units import PillarDesign

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "flat_friction.csv"
#: Inside the paper's map, an array in about a second (as tests/test_design_tab.py).
FAST = "?tab=design&d_FN=1%20N&d_V0=100%20m/s&d_Vs=10%20m/s"
#: A law of the model's ranges other than the paper's.
TYPED = {"design_mu_s": "0.8", "design_A": "1.2", "design_B": "-5", "design_V_s": "20 m/s"}


def _upload(view, data: bytes, name: str) -> None:
    """What the browser's FileInput does: the file's name, then its bytes."""
    view.law.file.filename = name
    view.law.file.value = data


@pytest.fixture(scope="module")
def uploaded():
    """The example file uploaded (its V_s ~ 1 mm/s is far below these pillars' 100 m/s,
    an array of minutes: the arrays with a law are the typed law's tests'; the Support tab
    is shown when the file comes)."""
    state = ExplorerState()
    assert state.load_query(FAST) == []
    page = Dashboard(state)
    state.tab = "support"
    _upload(page.design, EXAMPLE.read_bytes(), "flat_friction.csv")
    return page


def test_the_default_law_is_the_papers_bit_for_bit_and_not_in_the_url():
    s = ExplorerState()
    law = s.friction_law
    assert (law.mu_s, law.A, law.B) == (1.3, 1.44, -20.0) == tuple(
        getattr(Params(k_r=1, k_theta=1), k) for k in ("mu_s", "A", "B"))
    assert worker.design_of(s.design_inputs) == PillarDesign.example(V0="1 m/s")
    assert set(s.to_query()) == {"k_r", "k_theta", "F_N", "theta0_deg"}
    assert s.to_search() == "?k_r=3&k_theta=0.01&F_N=1&theta0_deg=90"


def test_an_uploaded_curve_is_fitted_and_the_design_takes_the_fit(uploaded):
    s, r = uploaded.state, uploaded.results
    fit = fit_friction(read_curve(EXAMPLE))  # what `micropillar friction fit` reports
    assert r.friction_fit.values == fit.values and r.fit_in_use
    law = s.friction_law
    for name in ("mu_s", "A", "B", "V_s"):
        assert getattr(law, name) == pytest.approx(fit.values[name], rel=1e-5), name
    note = uploaded.design.law.note.object
    assert "Fitted to flat\\_friction.csv" in note and "40 points" in note
    for name, shown in (("mu_s", "μ_s"), ("A", "A"), ("B", "B")):
        lo, hi = fit.ci95[name]
        assert f"{shown} = {fit.values[name]:.4g} [{lo:.4g}, {hi:.4g}]" in note
    lo, hi = fit.ci95["V_s"]
    assert f"V_s = {fit.values['V_s'] * 1e3:.4g} [{lo * 1e3:.4g}, {hi * 1e3:.4g}] mm/s" in note
    assert "The design uses this fit." in note


def test_fig3_draws_the_law_its_band_and_the_measured_points_in_m_per_s(uploaded):
    view, fit = uploaded.design.law, uploaded.results.friction_fit
    fig, src = view.figure, view._sources
    assert fig.xaxis[0].axis_label == "sliding speed v [m/s]"
    assert fig.yaxis[0].axis_label == "friction coefficient μ"
    curve = read_curve(EXAMPLE)
    measured = src["law_measured"].data
    assert np.allclose(measured["v"], curve.v) and np.allclose(measured["mu"], curve.mu)
    assert np.allclose(np.asarray(measured["hi"]) - measured["lo"], 2 * curve.mu_err)
    band = src["law_band"].data
    lo, hi = fit.band(np.asarray(band["v"]))
    inside = (band["v"] > curve.v.min()) & (band["v"] < curve.v.max())
    assert np.allclose(band["lo"][inside], lo[inside]) and np.allclose(band["hi"][inside],
                                                                        hi[inside])
    law = src["law"].data  # the law in use: the fit to the inputs' 6 digits
    assert np.allclose(law["mu"], fit.predict(np.asarray(law["v"])), atol=1e-4)
    assert np.all((band["lo"] <= law["mu"] + 1e-4) & (law["mu"] - 1e-4 <= band["hi"]))
    assert src["law_V0"].data["v"] == [100.0]  # the design's speed, 100 m/s
    assert fig.x_range.start <= curve.v.min() and fig.x_range.end >= 100.0


def test_the_fitted_law_travels_in_the_url(uploaded):
    s = uploaded.state
    query = s.to_query()
    assert {"d_mus", "d_A", "d_B", "d_Vs"} <= set(query)
    t = ExplorerState()
    assert t.load_query(s.to_search()) == []
    assert t.friction_law == s.friction_law
    assert t.values() == s.values()


@pytest.mark.parametrize("content, named", [
    (b"0.01,0.04\n0.1,0.5\n", "no header"),
    (b"v [mm/s],mu\n0.1,0.5\n1,x\n", "line 3"),
    (b"v [mm/s],mu\n-1,0.5\n1,1\n10,1.2\n100,1.2\n", "line 2"),
    (b"v [mm/s],mu\n1,1\n10,1.2\n", "fewer"),
    (b"", "empty"),
])
def test_a_bad_file_is_named_in_the_command_lines_words_and_changes_nothing(
        tmp_path, content, named):
    state = ExplorerState()
    state.load_query(FAST)
    page = Dashboard(state)
    state.tab = "support"  # the Design tab built; its arrays not needed here
    before = state.values()
    _upload(page.design, content, "bad.csv")
    note = page.design.law.note.object
    assert note.startswith("**Not loaded:**") and "Nothing was changed." in note
    assert named in note
    if content:  # the same one line as `micropillar friction fit bad.csv`
        path = tmp_path / "bad.csv"
        path.write_bytes(content)
        with pytest.raises(CurveFileError) as error:
            read_curve(path)
        assert str(error.value) in note.replace("\\", "")
    assert state.values() == before and page.results.friction_fit is None
    assert state.friction_curve is None


def test_typed_coefficients_are_the_designs_law_and_the_snippet_reproduces_it():
    from test_snippet import execute

    state = ExplorerState()
    state.load_query(FAST)
    state.param.update(**TYPED)
    page = Dashboard(state)
    assert state.friction_law == FrictionLaw(mu_s=0.8, A=1.2, B=-5.0, V_s=20.0)
    note = page.design.law.note.object
    assert "Law in use: μ_s, A, B as typed" in note
    law_mu = page.design.law._sources["law"].data
    assert np.allclose(law_mu["mu"], state.friction_law.mu(np.asarray(law_mu["v"])))
    from app.snippet import view_as_python
    code = view_as_python(state)
    assert "law = FrictionLaw(mu_s=0.8, A=1.2, B=-5.0, V_s='20 m/s')" in code
    assert ".with_friction(law)" in code
    _, printed = execute(code, names=())
    a = page.results.design_array
    assert a is not None and a["success"], a and a["message"]
    value = a["array"]["FTx_over_mu0FN"]
    assert f"design array: F_T,x/(mu0 F_N) = {float(value)!r}," in printed


def test_the_designs_array_and_its_csv_carry_the_law():
    state = ExplorerState()
    state.load_query(FAST)
    state.param.update(**TYPED)
    r = Dashboard(state).results
    a = r.design_array
    assert a is not None and a["success"], a and a["message"]
    design = worker.design_of(state.design_inputs)
    assert design.friction_law == state.friction_law
    expected = worker.compute_design_array(design, state.distribution, state.dist_psi,
                                           state.array_beta)
    assert a["array"]["FTx_over_mu0FN"] == expected["array"]["FTx_over_mu0FN"]
    paper = worker.compute_design_array(design.with_friction(FrictionLaw(V_s="20 m/s")),
                                        state.distribution, state.dist_psi, state.array_beta)
    assert a["FTx_N"] != pytest.approx(paper["FTx_N"], rel=1e-3)  # the law matters
    csv = table_csv(a)
    for line in ("# design mu_s: 0.8", "# design A: 1.2", "# design B: -5", "# design V_s: 2000"):
        assert line in csv, csv[:2000]


def test_an_unusable_coefficient_is_named():
    state = ExplorerState()
    state.load_query(FAST)
    state.design_A = "-1"
    page = Dashboard(state)
    assert "Friction law not usable" in page.design.law.note.object
    assert "A=" in page.design.law.note.object or "A =" in page.design.law.note.object


def test_bad_law_values_in_a_url_keep_the_defaults_with_a_notice():
    values, notices = parse("?d_mus=-1&d_A=abc&d_B=1e5&d_Vs=3")
    assert values == {}
    assert [n.split("=")[0] for n in notices] == ["URL parameter d_mus", "URL parameter d_A",
                                                   "URL parameter d_B", "URL parameter d_Vs"]
    assert "(0, 100]" in notices[0] and "[-10000, 10000]" in notices[2]
    state = ExplorerState()
    state.load_query("?d_mus=-1&d_A=0.9")
    assert state.design_mu_s == DEFAULTS["design_mu_s"] and state.design_A == "0.9"
    assert "d\\_mus" in state.notice or "d_mus" in state.notice


def test_a_pinned_state_keeps_its_law():
    state = ExplorerState()
    state.param.update(**TYPED)
    state.pin()
    state.param.update(**{name: DEFAULTS[name] for name in LAW_INPUTS})
    text = pinned_text(state.pinned)
    assert "d_mus:0.8" in text and "d_B:-5" in text
    a = ExplorerState(**parse_pinned(text))
    assert a.friction_law == FrictionLaw(mu_s=0.8, A=1.2, B=-5.0, V_s=20.0)
    assert state.friction_law.mu_s == 1.3
    w = 1.0 + 5.0 * (1.0 - math.atan(1.0))  # Eq. (4) at v = V_s: x - B (x - atan x), x = 1
    assert math.isclose(a.friction_law.mu(20.0), 0.8 * math.sin(1.2 * math.atan(w)))
