"""HoloViews elements of the model's results, for notebooks: ``plot(result)``.

    import holoviews as hv
    from app.plots import plot

    hv.extension("bokeh")
    plot(fit) * plot(curve) + plot(comparison, kind="difference")

One function dispatching on the result's type (``functools.singledispatch``), not a
``.plot()`` method on the results: the results live in ``model/``, which imports no
plotting library (it runs in the CLI, in worker processes, without HoloViews installed;
``tests/test_figures.py`` checks it), so a method there would either import HoloViews or
reach back up into ``app``. Here the plotting layer depends on the model, never the other
way, and HoloViews stays an optional extra (``pip install micropillar-friction[notebook]``).

Every element has hover and named dimensions with units, so elements of one kind share
axes: speeds are ``v`` [m/s] (the sliding speed, V0 of a design), friction coefficients
``mu`` (the flat material's mu and the structured surface's F_T,x/F_N alike), orientations
``theta0_deg`` [deg]; ``*`` overlays them and ``+`` lays them side by side.

=====================================  ===============================================
result                                 element
=====================================  ===============================================
``FrictionCurve`` (measured)           points, with error bars when it has ``mu_err``
``FrictionLaw``, ``FrictionFit``       Eq. (4) against speed (``v=``: the speeds)
``SpeedCurve``                         flat mu(V0) and the structured F_T,x/F_N with its
                                       quadrature error
``FrictionComparison``                 measured over predicted, disagreeing speeds
                                       marked; ``kind="difference"``: the difference
                                       and the allowed error
``OrientationSweep``                   a quantity of fixed arrays against theta0
``UniformArrayResult``                 its average, a level line over theta0
``SweepResult`` of ``regime_map``      a quantity over (k_r, k_theta), log axes
=====================================  ===============================================
"""
from __future__ import annotations

import math
from functools import singledispatch

import numpy as np

try:
    import holoviews as hv
    import holoviews.plotting.bokeh  # noqa: F401  (registers the backend the options name)
except ImportError as error:  # pragma: no cover - the extra is installed in the tests
    raise ImportError("app.plots needs HoloViews: pip install 'micropillar-friction[notebook]' "
                      "(or pip install holoviews)") from error

from model import (FrictionComparison, FrictionCurve, FrictionFit, FrictionLaw,
                   OrientationSweep, SweepResult, UniformArrayResult)
from model.arrays.quantities import label
from model.lab.speed_curve import SpeedCurve

__all__ = ["plot", "SPEED", "MU", "THETA0"]

#: The shared dimensions: sliding speed, friction coefficient, rest orientation.
SPEED = hv.Dimension("v", label="sliding speed V₀", unit="m/s")
MU = hv.Dimension("mu", label="friction coefficient μ, F_T,x/F_N")
THETA0 = hv.Dimension("theta0_deg", label="rest orientation θ₀", unit="deg")
_ERROR = hv.Dimension("error", label="± error")
#: The colour of speeds where the model and the measurement disagree.
DISAGREE_COLOR = "#d62728"


def _opts(element, **kw):
    return element.opts(backend="bokeh", tools=["hover"], **kw)


@singledispatch
def plot(result, **kw):
    """A HoloViews element of ``result`` (module doc: which types, which elements)."""
    raise TypeError(f"plot() draws {', '.join(t.__name__ for t in _TYPES)}; not "
                    f"{type(result).__name__}")


@plot.register
def _(curve: FrictionCurve, label_text: str = "measured"):
    data = {"v": curve.v, "mu": curve.mu}
    if curve.mu_err is None:
        return _opts(hv.Scatter(data, SPEED, MU, label=label_text), logx=True, size=6)
    data["error"] = curve.mu_err
    points = _opts(hv.Scatter(data, SPEED, [MU, _ERROR], label=label_text), logx=True, size=6)
    return hv.ErrorBars(data, SPEED, [MU, _ERROR]).opts(backend="bokeh", logx=True) * points


def _law_speeds(law: FrictionLaw, v):
    if v is not None:
        return np.asarray(v, dtype=float)
    if law.V_s is None:
        raise ValueError("v=None: this law has no V_s of its own; give the speeds, "
                         "plot(law, v=np.geomspace(1e-5, 1, 200))")
    return np.geomspace(law.V_s / 100, law.V_s * 100, 200)


def _law_curve(law: FrictionLaw, v, name: str):
    v = _law_speeds(law, v)
    return _opts(hv.Curve({"v": v, "mu": law.mu(v)}, SPEED, MU, label=name), logx=True)


@plot.register
def _(law: FrictionLaw, v=None):
    """Eq. (4) at speeds ``v`` (m/s; default two decades either side of V_s)."""
    return _law_curve(law, v, "friction law, Eq. (4)")


@plot.register
def _(fit: FrictionFit, v=None):
    """The fitted law at speeds ``v``; overlay the data with ``* plot(curve)``."""
    f = fit.values
    name = (f"fit: μ_s {f['mu_s']:.3g}, A {f['A']:.3g}, B {f['B']:.3g}, "
            f"V_s {f['V_s'] * 1e3:.3g} mm/s")
    return _law_curve(fit.law, v, name)


@plot.register
def _(curve: SpeedCurve):
    """The flat material's mu(V0) and the structured surface's F_T,x/F_N (with its
    quadrature error, status and energy-balance residual on hover)."""
    data = {"v": curve.column("V0"), "flat": curve.column("mu_flat"),
            "mu": curve.column("mu_apparent"), "error": curve.column("quadrature_error"),
            "energy": curve.column("integration_error"), "status": curve.column("status")}
    flat = _opts(hv.Curve(data, SPEED, hv.Dimension("flat", label=MU.label),
                          label="flat material μ(V₀)"), logx=True, line_dash="dashed")
    extra = [_ERROR, hv.Dimension("energy", label="energy residual"), "status"]
    structured = _opts(hv.Curve(data, SPEED, [MU, *extra],
                                label="structured surface F_T,x/F_N"), logx=True)
    bars = hv.ErrorBars(data, SPEED, [MU, _ERROR]).opts(backend="bokeh", logx=True)
    return (flat * structured * bars).opts(backend="bokeh", legend_position="bottom_right")


@plot.register
def _(c: FrictionComparison, kind: str = "curves"):
    """``kind="curves"``: measured (with the allowed error as bars) over predicted,
    disagreeing speeds marked; ``kind="difference"``: measured - predicted and the
    allowed error around zero."""
    data = {"v": c.v, "measured": c.measured, "mu": c.predicted,
            "difference": c.difference, "allowed": c.tolerance,
            "model_error": c.model_error, "measured_error": c.measured_error}
    allowed = hv.Dimension("allowed", label="± allowed")
    if kind == "difference":
        diff = hv.Dimension("difference", label="measured − predicted μ")
        points = _opts(hv.Scatter(data, SPEED, [diff, allowed, "measured", "mu"],
                                  label="difference"), logx=True, size=6)
        bars = hv.ErrorBars(data, SPEED, [diff, allowed]).opts(backend="bokeh", logx=True)
        return bars * points * hv.HLine(0.0).opts(backend="bokeh", color="gray")
    if kind != "curves":
        raise ValueError(f"kind={kind!r} must be 'curves' or 'difference'")
    predicted = _opts(hv.Curve(data, SPEED, [MU, hv.Dimension("model_error",
                                                                label="model error")],
                               label="predicted"), logx=True)
    measured = hv.Dimension("measured", label=MU.label)
    bars = hv.ErrorBars(data, SPEED, [measured, allowed]).opts(backend="bokeh", logx=True)
    points = _opts(hv.Scatter(data, SPEED, [measured, allowed, "difference"],
                              label="measured"), logx=True, size=6)
    off = np.isin(c.v, c.disagree)
    marked = _opts(hv.Scatter({k: np.asarray(col)[off] for k, col in data.items()}, SPEED,
                              [measured, "difference", allowed], label="disagree"),
                   logx=True, size=10, color=DISAGREE_COLOR, marker="x")
    return (predicted * bars * points * marked).opts(backend="bokeh",
                                                     legend_position="bottom_right")


def _quantity(name: str) -> hv.Dimension:
    return hv.Dimension(name, label=label(name))


@plot.register
def _(sweep: OrientationSweep, quantity: str = "FTx_over_mu0FN"):
    """``quantity`` of each fixed array against theta0 (hover: beta, N_c/N_c0)."""
    data = {"theta0_deg": np.degrees(sweep.theta0),
            quantity: np.asarray(getattr(sweep, quantity), dtype=float),
            "beta": np.asarray(sweep.beta, dtype=float),
            "Nc_over_Nc0": np.asarray(sweep.Nc_over_Nc0, dtype=float)}
    vdims = [_quantity(quantity)] + [_quantity(k) for k in ("beta", "Nc_over_Nc0")
                                     if k != quantity]
    return _opts(hv.Curve(data, THETA0, vdims, label="fixed arrays"))


@plot.register
def _(array: UniformArrayResult, quantity: str = "FTx_over_mu0FN"):
    """The uniform array's average as a level over theta0 (overlay it on a sweep)."""
    value = float(getattr(array, quantity))
    data = {"theta0_deg": [0.0, 180.0], quantity: [value, value]}
    return _opts(hv.Curve(data, THETA0, _quantity(quantity), label="uniform array"),
                 line_dash="dotted")


@plot.register
def _(table: SweepResult, quantity: str = "FTx_over_mu0FN"):
    """A regime map (``regime_map``): ``quantity`` over (k_r, k_theta), log axes."""
    if table.kind != "regime_map":
        raise ValueError(f"plot() draws the regime map's table, not {table.kind!r}; plot "
                         f"its columns with hv.Curve")
    cols = table.columns
    k_r, k_theta = np.unique(cols["k_r"]), np.unique(cols["k_theta"])
    if k_r.size * k_theta.size != len(table):
        raise ValueError("the table is not a full (k_r, k_theta) grid")
    grid = np.full((k_theta.size, k_r.size), math.nan)
    grid[np.searchsorted(k_theta, cols["k_theta"]), np.searchsorted(k_r, cols["k_r"])] = \
        cols[quantity]
    mesh = hv.QuadMesh((_log_edges(k_r), _log_edges(k_theta), grid),
                       [_quantity("k_r"), _quantity("k_theta")], _quantity(quantity))
    return _opts(mesh, logx=True, logy=True, colorbar=True, cmap="viridis")


def _log_edges(centres):
    """Cell edges halfway between centres in log (the map's axes are log-spaced)."""
    logs = np.log(centres)
    step = np.diff(logs) if logs.size > 1 else np.array([1.0])
    inner = (logs[1:] + logs[:-1]) / 2
    return np.exp(np.concatenate([[logs[0] - step[0] / 2], inner, [logs[-1] + step[-1] / 2]]))


_TYPES = (FrictionCurve, FrictionLaw, FrictionFit, SpeedCurve, FrictionComparison,
          OrientationSweep, UniformArrayResult, SweepResult)
