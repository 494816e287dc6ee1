"""Exports from the page (app/export.py, app/views/export.py): CSVs of the regime map,
the load curves and the array, read back equal to what the tabs draw; a CSV button that
is disabled and says "computing…" until its result exists (never a one-line "being
computed" file); SVG buttons on every figure view."""
import numpy as np
import panel as pn
import pytest

from app import results as results_module
from app import worker
from app.export import array_csv, load_csv, map_csv
from app.state import ExplorerState
from model import csvfile


def _read(text, tmp_path):
    path = tmp_path / "x.csv"
    path.write_text(text, encoding="utf-8")
    return csvfile.read(path)


def test_the_map_csv_is_the_map_on_show(tmp_path):
    m = worker.compute_map(2.0, "self", 3)
    header, cols = _read(map_csv(m), tmp_path)
    assert header["kind"] == "regime_map" and header["F_N"] == 2.0
    assert len(cols["k_r"]) == 9
    np.testing.assert_array_equal(np.reshape(cols["FTx_over_mu0FN_duration"], (3, 3)),
                                  m.FTx_over_mu0FN_duration)
    np.testing.assert_array_equal(np.reshape(cols["k_theta"], (3, 3))[0], m.k_theta)
    assert map_csv(None).startswith("# no regime map computed yet")


def test_the_load_csv_holds_every_curve_of_the_tab(tmp_path):
    curves = {"current": worker.compute_load(0.5, 0.2, "self", loads=(0.1, 1.0)),
              "pendulum": worker.compute_load(3.0, 0.01, "self", loads=(1.0,))}
    header, cols = _read(load_csv(curves), tmp_path)
    assert list(cols["curve"]) == ["current", "current", "pendulum"]
    assert list(cols["F_N"]) == [0.1, 1.0, 1.0]
    assert cols["FTx_over_mu0FN"][1] == curves["current"][1.0]["FTx_over_mu0FN"]
    assert cols["k_r"][2] == 3.0 and header["kind"] == "load"


def test_the_array_csv_is_the_tab_s_live_curves(tmp_path):
    from model import Params
    from model.arrays.array_motion import array_motion

    motion = array_motion(Params(k_r=0.5, k_theta=0.2, F_N=2.0), n_frames=30)
    header, cols = _read(array_csv(motion), tmp_path)
    assert len(cols["t"]) == 30 and header["supports"] == motion.n_supports
    np.testing.assert_array_equal(cols["N_c"], motion.N_c)
    np.testing.assert_array_equal(cols["FTx_running"], motion.FTx_running)  # NaN == NaN
    assert header["model FTx_over_mu0FN_duration"] == motion.model["FTx_over_mu0FN_duration"]


def test_a_csv_button_waits_for_its_result(pool):
    """Clicked before the sweep is there, the polar button gives no "being computed"
    file: it is disabled and says so until the sweep arrives (the issue's one-line file)."""
    from app.export import sweep_csv
    from app.views.export import ResultDownload

    state = ExplorerState()
    r = results_module.SessionResults(state)
    r.start()
    button = ResultDownload(lambda: sweep_csv(r.polar), "p.csv", "polar", results=r,
                            name="polar", label="Polar sweep CSV")
    # Not on its tab and not computed: a button asks for it.
    assert button.compute.visible and not button.download.visible
    r._set_busy("polar", True)  # on its way (a worker computes it)
    assert not button.compute.visible and button.download.visible
    assert button.download.disabled and button.download.label == "Polar sweep CSV: computing…"
    assert button._file().getvalue() == ""
    r._set_busy("polar", False)
    button.compute.clicks += 1  # here the pool computes it at once
    assert "compute_polar" in pool.calls
    assert not button.download.disabled and button.download.label == "Polar sweep CSV"
    assert button._file().getvalue().startswith("# kind: orientation")
    state.k_r = 0.5  # a new sweep is needed: the old one is not offered as the new one
    assert button.compute.visible and button._file().getvalue() == ""


@pytest.mark.parametrize("tab, view", [("map", "regime_map"), ("load", "load"),
                                       ("array", "array")])
def test_every_figure_tab_has_csv_and_svg_exports(pool, tab, view, monkeypatch):
    from app.views import Dashboard

    monkeypatch.setattr(worker, "compute_load_regimes", lambda *a, **k: {})
    monkeypatch.setattr(worker, "LOAD_F_N", (1.0,))
    page = Dashboard(ExplorerState())
    page.state.tab = tab
    v = getattr(page, view)
    assert v.csv.download.label.endswith("CSV") and not v.csv.download.disabled
    text = v.csv._file().getvalue()
    assert text.startswith("# kind: ") and "computed yet" not in text
    assert "SVG" in v.svg.label


def test_the_svg_buttons_are_answered_by_the_page_code_not_a_panel_link(pool, monkeypatch):
    """Each "Figure (SVG)" button carries the class the page's code answers
    (``PageBehaviour.svg_exports``) and no Panel ``js_on_click``: a Panel ``Callback``,
    once registered, makes every layout update of every page in the process walk the
    page's whole model graph (``app.views.export.svg_button``)."""
    from panel.links import Callback

    from app.views import Dashboard
    from app.views.browser import SVG_BUTTON_CLASS
    from app.views.export import svg_button

    monkeypatch.setattr(worker, "compute_load_regimes", lambda *a, **k: {})
    monkeypatch.setattr(worker, "LOAD_F_N", (1.0,))
    page = Dashboard(ExplorerState())
    buttons = [b for b in page.controls.__panel__().select(pn.widgets.Button)
               if SVG_BUTTON_CLASS in b.css_classes]
    for tab, view in (("map", "regime_map"), ("load", "load"), ("array", "array")):
        page.state.tab = tab
        buttons.append(getattr(page, view).svg)
    table = page.behaviour.svg_exports
    assert len(buttons) == 4
    for button in buttons:
        assert SVG_BUTTON_CLASS in button.css_classes and button not in Callback.registry
        assert [c for c in button.css_classes if c in table], button.css_classes
    assert table["export-map-svg"] == ["regime_map"] and table["export-page-svg"] == []
    with pytest.raises(ValueError, match="css='nope'.*SVG_EXPORTS"):
        svg_button("nope")
