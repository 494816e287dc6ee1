"""``app.plots.plot``: the HoloViews elements of the model's results carry the result's
numbers in named columns, axis labels with units, a hover tool that shows the errors, and
compose with ``*`` and ``+``."""
import math
from pathlib import Path

import numpy as np
import pytest

hv = pytest.importorskip("holoviews")

from bokeh.models import HoverTool, LogScale  # noqa: E402

from app.plots import DISAGREE_COLOR, plot  # noqa: E402
from model import (FrictionCurve, FrictionLaw, Params, compare_friction,  # noqa: E402
                   fit_friction, orientation_sweep, read_curve, regime_map, uniform_array)
from model.lab.speed_curve import SpeedCurve, SpeedPoint  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SPEED_LABEL = "sliding speed V₀ (m/s)"


def _figure(element):
    return hv.render(element, backend="bokeh")


def _hover_text(fig) -> str:
    tools = [t for t in fig.tools if isinstance(t, HoverTool)]
    assert tools, "no hover tool"
    return " ".join(str(t.tooltips) for t in tools)


def _layers(overlay, kind):
    return [el for el in overlay if type(el).__name__ == kind]


@pytest.fixture(scope="module")
def flat():
    return read_curve(ROOT / "examples" / "flat_friction.csv")


@pytest.fixture(scope="module")
def prediction():
    """A friction-velocity curve of known values; its third speed failed."""
    V0 = np.geomspace(0.1, 3.0, 5)
    points = tuple(SpeedPoint(float(v), 1.0017, math.nan if i == 2 else 0.99 + 0.004 * i,
                              math.nan if i == 2 else 1e-4 * (i + 1), 1e-6, i != 2,
                              "outside_range" if i == 2 else "in_map", "")
                   for i, v in enumerate(V0))
    return SpeedCurve(law={}, points=points, seconds=0.0)


def test_a_measured_curve_is_points_with_error_bars(flat):
    element = plot(flat)
    points, = _layers(element, "Scatter")
    assert len(_layers(element, "ErrorBars")) == 1
    np.testing.assert_array_equal(points.dimension_values("v"), flat.v)
    np.testing.assert_array_equal(points.dimension_values("mu"), flat.mu)
    np.testing.assert_array_equal(points.dimension_values("error"), flat.mu_err)
    fig = _figure(element)
    assert fig.xaxis[0].axis_label == SPEED_LABEL and isinstance(fig.x_scale, LogScale)
    assert "friction coefficient" in fig.yaxis[0].axis_label
    assert "error" in _hover_text(fig)
    bare = plot(FrictionCurve(flat.v, flat.mu))  # without mu_err: points alone
    assert type(bare).__name__ == "Scatter"


def test_a_fit_is_its_law_and_composes_with_the_data(flat):
    fit = fit_friction(flat)
    curve = plot(fit, v=flat.v)
    np.testing.assert_allclose(curve.dimension_values("mu"), fit.law.mu(flat.v), rtol=1e-12)
    assert "μ_s 1.3" in curve.label
    both = plot(fit) * plot(flat)
    assert type(both).__name__ == "Overlay" and len(both) == 3
    side = plot(fit) + plot(FrictionLaw(V_s="1 mm/s"))
    assert type(side).__name__ == "Layout" and len(side) == 2
    law = plot(FrictionLaw(V_s="1 mm/s"))
    v = law.dimension_values("v")
    assert v.min() == pytest.approx(1e-5) and v.max() == pytest.approx(0.1)
    fig = _figure(both)
    assert fig.xaxis[0].axis_label == SPEED_LABEL and "mu" in _hover_text(fig)
    with pytest.raises(ValueError, match="v=None: this law has no V_s"):
        plot(FrictionLaw())


def test_a_friction_velocity_curve_shows_flat_and_structured_with_errors(prediction):
    element = plot(prediction)
    flat_line, structured = _layers(element, "Curve")
    np.testing.assert_array_equal(flat_line.dimension_values("flat"),
                                  prediction.column("mu_flat"))
    np.testing.assert_array_equal(structured.dimension_values("mu"),
                                  prediction.column("mu_apparent"))
    np.testing.assert_array_equal(structured.dimension_values("error"),
                                  prediction.column("quadrature_error"))
    assert list(structured.dimension_values("status")).count("outside_range") == 1
    fig = _figure(element)
    assert fig.xaxis[0].axis_label == SPEED_LABEL
    hover = _hover_text(fig)
    assert "status" in hover and "energy residual" in hover and "± error" in hover


def test_the_comparison_marks_the_speeds_that_disagree(prediction):
    V0 = prediction.column("V0")
    v = V0[[0, 1, 3, 4]]
    offsets = np.array([0.0, 0.05, -0.001, 0.03])
    measured = FrictionCurve(v, prediction.column("mu_apparent")[[0, 1, 3, 4]] + offsets,
                             np.full(4, 0.005))
    c = compare_friction(prediction, measured)
    element = plot(c)
    marked = [el for el in _layers(element, "Scatter") if el.label == "disagree"]
    np.testing.assert_allclose(marked[0].dimension_values("v"), c.disagree)
    np.testing.assert_allclose(marked[0].dimension_values("v"), v[[1, 3]])
    predicted, = _layers(element, "Curve")
    np.testing.assert_allclose(predicted.dimension_values("mu"), c.predicted)
    fig = _figure(element)
    assert fig.xaxis[0].axis_label == SPEED_LABEL and "allowed" in _hover_text(fig)
    assert any(getattr(r.glyph, "line_color", None) == DISAGREE_COLOR for r in fig.renderers)
    difference = plot(c, kind="difference")
    points, = _layers(difference, "Scatter")
    np.testing.assert_allclose(points.dimension_values("difference"), offsets, atol=1e-12)
    np.testing.assert_allclose(points.dimension_values("allowed"), c.tolerance)
    fig = _figure(difference)
    assert fig.xaxis[0].axis_label == SPEED_LABEL
    assert fig.yaxis[0].axis_label == "measured − predicted μ"
    with pytest.raises(ValueError, match="kind='bars'"):
        plot(c, kind="bars")


def test_arrays_over_theta0_and_the_uniform_level_share_their_axes():
    params = Params(k_r=1.0, k_theta=1.0)
    theta0 = np.radians([30.0, 60.0, 90.0, 120.0, 150.0])
    sweep = orientation_sweep(params, theta0, beta=1.0)
    uniform = uniform_array(params, beta=1.0, tol=1e-2)
    element = plot(sweep) * plot(uniform)
    fixed, level = _layers(element, "Curve")
    np.testing.assert_allclose(fixed.dimension_values("theta0_deg"), np.degrees(theta0))
    np.testing.assert_allclose(fixed.dimension_values("FTx_over_mu0FN"), sweep.FTx_over_mu0FN)
    assert set(level.dimension_values("FTx_over_mu0FN")) == {uniform.FTx_over_mu0FN}
    fig = _figure(element)
    assert fig.xaxis[0].axis_label == "rest orientation θ₀ (deg)"
    assert fig.yaxis[0].axis_label == "F_T,x/(μ₀F_N)"
    assert "β" in _hover_text(fig)
    y = plot(sweep, quantity="FTy_over_mu0FN")
    np.testing.assert_allclose(y.dimension_values("FTy_over_mu0FN"), sweep.FTy_over_mu0FN)


def test_a_regime_map_is_a_mesh_over_log_stiffness_axes():
    table = regime_map(n=2, tol=1e-2)
    mesh = plot(table)
    assert type(mesh).__name__ == "QuadMesh"
    cols = table.columns
    for k_r, k_theta, value in zip(cols["k_r"], cols["k_theta"], cols["FTx_over_mu0FN"]):
        assert mesh[k_r, k_theta] == pytest.approx(value)
    fig = _figure(mesh)
    assert isinstance(fig.x_scale, LogScale) and isinstance(fig.y_scale, LogScale)
    assert (fig.xaxis[0].axis_label, fig.yaxis[0].axis_label) == ("k_r", "k_θ")
    assert "F_T,x/(μ₀F_N)" in _hover_text(fig)


def test_other_results_and_unknown_options_are_refused_by_name(flat):
    with pytest.raises(TypeError, match="not dict"):
        plot({})
    with pytest.raises(TypeError, match="colour"):
        plot(flat, colour="red")  # nothing is silently ignored
