"""Micropillar friction explorer: one contact of one support, live.

A first page of the dashboard: sliders for the support and the load, and a readout of
``simulate_support`` for the current values. Serve it with ``panel serve app``; the page
is at ``/app``.
"""
import math

import panel as pn
from bokeh.models import CustomJSTickFormatter

from model import Params, mu0, simulate_support

pn.extension()

K_MIN, K_MAX = 0.01, 3.0


def log_slider(name: str, value: float) -> pn.widgets.FloatSlider:
    """A slider over log10 of a stiffness in [K_MIN, K_MAX] that displays the stiffness."""
    return pn.widgets.FloatSlider(
        name=f"{name} (log scale)", start=math.log10(K_MIN), end=math.log10(K_MAX), step=0.01,
        value=math.log10(value),
        format=CustomJSTickFormatter(code="return Math.pow(10, tick).toPrecision(3)"))


def readout(log_k_r: float, log_k_theta: float, F_N: float, theta0_deg: float) -> str:
    """Markdown with the results of one contact; a model error is shown as text."""
    try:
        params = Params(k_r=10**log_k_r, k_theta=10**log_k_theta, F_N=F_N,
                        theta0=math.radians(theta0_deg))
        result = simulate_support(params)
    except Exception as error:  # the page must show any failure, never a traceback
        return f"**Error:** `{type(error).__name__}: {error}`"
    rows = [
        ("k_r, k_theta", f"{params.k_r:.4g}, {params.k_theta:.4g}", "radial and torsional stiffness"),
        ("F_mean_x", f"{result.F_mean[0]:.6g}", "time-averaged friction on the support along x, over f_N"),
        ("F_mean_y", f"{result.F_mean[1]:.6g}", "the same along y"),
        ("F_mean_x / mu0", f"{result.F_mean[0] / mu0(params):.6g}",
         "apparent friction of a fixed-orientation array, F_T,x/(mu0 F_N)"),
        ("t_out", f"{result.t_out:.6g}", "contact duration [r0/V0]"),
        ("energy_residual", f"{result.energy_residual:.3g}",
         "W - (D_x + D_y + U_el + K), the integration error"),
    ]
    table = "\n".join(f"| `{name}` | {value} | {meaning} |" for name, value, meaning in rows)
    verdict = "Success" if result.success else f"Did not succeed (status {result.status})"
    return (f"| quantity | value | meaning |\n|---|---|---|\n{table}\n\n"
            f"**{verdict}:** `{result.message}`")


k_r = log_slider("k_r", 3.0)
k_theta = log_slider("k_theta", 0.01)
F_N = pn.widgets.FloatSlider(name="F_N", start=0.1, end=10.0, step=0.1, value=1.0)
theta0 = pn.widgets.FloatSlider(name="theta0 [deg]", start=0.0, end=360.0, step=1.0, value=90.0)

results = pn.panel(
    pn.bind(readout, k_r.param.value_throttled, k_theta.param.value_throttled,
            F_N.param.value_throttled, theta0.param.value_throttled),
    loading_indicator=True)

pn.Column(
    "# Micropillar friction explorer",
    "One support dragged through one contact by the sliding slab (dimensionless units).",
    pn.Row(pn.Column(k_r, k_theta, F_N, theta0), results),
).servable(title="Micropillar friction explorer")
