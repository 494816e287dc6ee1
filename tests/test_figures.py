"""Each figure function of ``app.figures`` on its data: axes, ranges, the right curves."""
import math

import numpy as np
import pytest
from bokeh.models import LogScale

from model import REGIMES, mu0, orientation_table, simulate_support
from app import figures as F
from model.runs.shipped_map import load_regime_map


@pytest.fixture(scope="module")
def series():
    return {t: simulate_support(REGIMES["slider"].replace(theta0=t), samples=200).series
            for t in (math.pi / 4, math.pi / 2)}


def _stiffness_columns():
    k_r = np.array([0.01, 0.1, 1.0, 3.0])
    rows = [(kt, kr) for kt in (0.03, 3.0) for kr in k_r[::-1]]  # unsorted k_r on purpose
    cols = {"k_theta": np.array([r[0] for r in rows]), "k_r": np.array([r[1] for r in rows])}
    cols["Nc_over_Nc0"] = 1 + 0.1 / cols["k_r"] / cols["k_theta"]
    split = np.array([0.5, 0.1, 0.3, 0.1])
    for name, share in zip(("Dx_over_W", "Dy_over_W", "Uel_over_W", "K_over_W"), split):
        cols[name] = np.full(len(rows), share) * cols["k_theta"]
    return cols


def test_friction_law_fig3():
    fig = F.friction_law_figure()
    law = F.sources(fig)["friction_law"].data
    assert law["v"][0] == 0 and law["v"][-1] == pytest.approx(2.0)
    i = int(np.argmin(np.abs(np.asarray(law["v"]) - 1.0)))
    assert law["mu"][i] == pytest.approx(mu0(), abs=2e-3)
    assert max(law["mu"]) > 1.2  # the static peak near v_R = V_s


def test_forces_fig7(series):
    s = series[math.pi / 2]
    fig = F.forces_figure(s, REGIMES["slider"])
    data = F.sources(fig)["forces"].data
    assert set(data) == {"tau", "F_x", "F_y", "F_abs"}
    assert np.array_equal(data["F_abs"], s.F_abs)
    assert F.annotation(fig, "forces_mu0").location == pytest.approx(mu0())
    assert {item.label["value"] for item in fig.legend[0].items} == {
        "|F_f|", "F_f,x", "F_f,y"}
    # mu0's label: at the right end of the range, above its line, clear of the contact's
    # early peaks.
    label = F.annotation(fig, "forces_mu0_label")
    assert label.x == fig.x_range.end and label.y == pytest.approx(mu0())
    assert (label.text_align, label.text_baseline) == ("right", "bottom")


def test_the_support_tabs_mu0_label_follows_each_new_range(pool):
    from app.state import ExplorerState
    from app.results import SessionResults
    from app.views.support import SupportView

    state = ExplorerState()
    results = SessionResults(state)
    view = SupportView(state=state, results=results)
    results.start()
    label = F.annotation(view.forces, "forces_mu0_label")
    for k_r in (0.05, 2.0):
        state.k_r = k_r
        assert label.x == view.forces.x_range.end, (k_r, label.x, view.forces.x_range.end)
    assert view.forces.x_range.end != F.forces_figure(None).x_range.end


@pytest.mark.parametrize("key, parity", [("FTx", 1), ("FTy", -1)])
def test_polar_fig11_closes_the_circle_by_symmetry(key, parity):
    theta = np.linspace(0.1, math.pi - 0.1, 9)
    values = 0.2 + np.sin(theta)
    fig = F.polar_figure(key, theta, values)
    curve = F.sources(fig)[f"polar_{key}"].data
    deg = np.asarray(curve["theta0_deg"])
    assert deg.min() < 10 and deg.max() > 350  # both halves of the circle
    v = np.asarray(curve["value"])
    assert np.allclose(v[9:18], parity * values[::-1])  # mirror image, even or odd
    assert v[0] == v[-1]  # closed loop


def test_regime_map_fig5():
    m = load_regime_map()
    for quantity, column in (("5a", "FTx_over_mu0FN"), ("5b", "Dy_over_Dx")):
        fig = F.regime_map_figure(m, quantity)
        cells = F.sources(fig)["regime_map"].data
        assert len(cells["value"]) == m.k_r.size * m.k_theta.size
        assert np.nanmax(cells["value"]) == pytest.approx(np.nanmax(getattr(m, column)))
        assert isinstance(fig.x_scale, LogScale) and isinstance(fig.y_scale, LogScale)
        assert "Fig. 5" in fig.title.text


def test_load_fig6():
    rows = {r: {f: {"FTx_over_mu0FN": 1 - 0.01 * f, "quadrature_error_FTx": 1e-4}
                for f in (0.1, 1.0, 10.0)} for r in REGIMES}
    fig = F.load_figure(regimes=rows)
    reg = F.sources(fig)["load_regimes"].data
    assert reg["regime"] == list(REGIMES)
    assert all(xs == [0.1, 1.0, 10.0] for xs in reg["xs"])
    assert isinstance(fig.x_scale, LogScale)


def test_contact_count_fig8a():
    cols = _stiffness_columns()
    fig = F.contact_count_figure(cols)
    lines = F.sources(fig)["contact_count"].data
    assert lines["k_theta"] == ["k_θ = 0.03", "k_θ = 3"]
    for xs, ys in zip(lines["xs"], lines["ys"]):
        assert np.all(np.diff(xs) > 0)  # sorted by k_r
        assert np.all(np.diff(ys) < 0)  # this data falls with k_r
    assert isinstance(fig.x_scale, LogScale) and "Fig. 8a" in fig.title.text


def test_work_split_fig8b_takes_one_k_theta():
    cols = _stiffness_columns()
    fig = F.work_split_figure(cols, k_theta=0.03)
    data = F.sources(fig)["work_split"].data
    assert list(data["k_r"]) == [0.01, 0.1, 1.0, 3.0]
    assert np.allclose(data["Dx_over_W"], 0.5 * 0.03)
    assert {"Dx_over_W", "Dy_over_W", "Uel_over_W", "K_over_W"} <= set(data)
    assert fig.y_range.start == 0 and "Fig. 8b" in fig.title.text


def test_components_fig10a_to_d(series):
    curves = {f"θ₀ = {t:.2f}": s for t, s in series.items()}
    fig = F.components_figure(curves, ("v_x", "v_y"), "Velocities (Fig. 10b)")
    src = F.sources(fig)
    assert set(src) == {"v_x_0", "v_y_0", "v_x_1", "v_y_1"}
    assert np.array_equal(src["v_y_1"].data["value"], series[math.pi / 2].v_y)
    assert fig.xaxis[0].axis_label == "τ" and "ṽ_x" in fig.yaxis[0].axis_label


def test_radius_fig10e(series):
    curves = {("slider", f"{t:.2f}"): s for t, s in series.items()}
    fig = F.radius_figure(curves)
    src = F.sources(fig)
    assert len(src) == 2 and isinstance(fig.y_scale, LogScale)
    assert np.array_equal(src["radius_0"].data["r"], series[math.pi / 4].r)


def test_rms_fig10f():
    table = orientation_table("slider", n=6, beta=1.0).columns
    fig = F.rms_figure({"slider": table})
    data = F.sources(fig)["rms_slider"].data
    assert np.allclose(data["theta0_deg"], np.degrees(table["theta0"]))
    assert 0 < min(data["theta0_deg"]) and max(data["theta0_deg"]) < 180
    assert np.all(np.asarray(data["dr_rms"]) > np.asarray(data["dtheta_rms"]))  # slider
    assert isinstance(fig.y_scale, LogScale)


def test_model_imports_no_plotting_or_app_code():
    """The reproduction's computing half stays free of Bokeh, Panel and the app."""
    import subprocess
    import sys

    code = ("import sys, model, model.reproduce, model.cli; "
            "print(sorted({m.split('.')[0] for m in sys.modules} & "
            "{'bokeh', 'panel', 'holoviews', 'param', 'app'}))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "[]"


def test_arrow_labels_part_and_stay_in_view():
    """v_R and the friction point opposite ways from the mass: their labels run outwards,
    away from each other; the slab's sits above its arrow, the friction's below its tip;
    near the view's border a label turns back inside."""
    from app.figures.scene import FORCE_COLOR, SLAB_COLOR, VREL_COLOR, _arrow_labels

    view = (-2.0, 2.0, -2.0, 2.0)
    arrows = [((0.0, 0.3), (0.5, 0.3), SLAB_COLOR, "slab V₀"),
              ((0.0, 0.0), (-0.5, 0.0), VREL_COLOR, "v_R"),
              ((0.0, 0.0), (0.5, 0.0), FORCE_COLOR, "friction")]
    labels = _arrow_labels(arrows, *view)
    assert labels["align"] == ["left", "right", "left"]
    assert labels["baseline"] == ["bottom", "top", "top"]
    edge = _arrow_labels([((1.0, 1.9), (1.9, 1.9), SLAB_COLOR, "slab V₀"),
                          ((-1.0, -1.9), (-1.9, -1.9), FORCE_COLOR, "friction")], *view)
    assert edge["align"] == ["right", "left"] and edge["baseline"] == ["top", "bottom"]


@pytest.mark.parametrize("projector", [False, True])
def test_styling_keeps_a_horizontal_colour_scale_long_and_a_frameless_key_frameless(projector):
    """The Array tab's colour scale lies across its own figure: styling (projector or
    not) sets its thickness, never its length, and adds no frame around the empty plot
    area under it; a vertical colour bar beside a plot gets the thickness as its width."""
    from bokeh.models import ColorBar, LinearColorMapper

    from app.figures.array_key import colorbar_figure
    from app.figures.common import new_figure, style

    key = colorbar_figure(LinearColorMapper(palette=["#000000", "#ffffff"], low=-90, high=90),
                          400)
    bar = key.select_one({"type": ColorBar})
    length = bar.width
    style(key, projector)
    assert bar.width == length >= 120
    assert bar.height == (14 if projector else 8)
    assert key.outline_line_color is None

    fig = new_figure("with_bar", "t", 300, 300)
    side = ColorBar(color_mapper=LinearColorMapper(palette=["#000000", "#ffffff"]))
    fig.add_layout(side, "right")
    style(fig, projector)
    assert side.width == (14 if projector else 8)
    assert fig.outline_line_color is not None


def test_the_support_figures_legends_name_only_still_stand_ins():
    """A legend entry naming a glyph redrawn every frame would rebuild the legend every
    frame (``legend_stand_ins``): after the figures are built, every entry of every legend
    names renderers that are not animated, and each animated glyph a legend shows has its
    still stand-in in the plot."""
    from bokeh.models import GlyphRenderer

    from app.figures import forces_figure, friction_law_figure, scene_figure
    from app.figures.common import ANIMATED
    from model.contact.params import Params

    p = Params(k_r=3.0, k_theta=0.01)
    checked = 0
    for fig in (scene_figure(None, p, 0), forces_figure(None, p, 0),
                friction_law_figure(None, p, 0)):
        for legend in fig.legend:
            for item in legend.items:
                for r in item.renderers:
                    assert isinstance(r, GlyphRenderer) and r.level != ANIMATED, (fig.name, r)
                    assert r in fig.renderers
                    checked += 1
    assert checked >= 5
