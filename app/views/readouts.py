"""Readouts (the issue's list, item 6): the regime and its mechanism, the fixed array at
theta0 (Figs. 9-11) and the uniform array (Figs. 5, 6, 8), computed in a worker process
with a loading indicator; a newer request supersedes an older one.
"""
from __future__ import annotations

import math

import panel as pn
import param

from ..compute import sweep_row, uniform_future
from ..jobs import LatestOnly
from ..state import ARRAY_KEYS, ExplorerState
from ..texts import MECHANISMS
from .support import SupportView


#: The uniform array is requested once the controls have rested this long.
DEBOUNCE_MS = 200
TABLE_CSS = ("table {border-collapse: collapse; width: 100%;} "
             "td, th {padding: 2px 6px; line-height: 1.25;}")


def _fmt(x, digits: int = 4) -> str:
    return "–" if x is None or not math.isfinite(x) else f"{x:.{digits}g}"


def regime_markdown(regime: str) -> str:
    title, text = MECHANISMS[regime]
    return f"**{title}.** {text}"


def fixed_markdown(data) -> str:
    """The fixed-orientation array at theta0 and its one contact, as a Markdown table."""
    if data is None or data.fixed is None:
        return "*No result for these parameters.*"
    f, r = data.fixed, data.result
    theta0_deg = round(math.degrees(data.params.theta0), 6)
    rows = [("F_T,x/(μ₀F_N)", _fmt(f.FTx_over_mu0FN)),
            ("F_T,y/(μ₀F_N)", _fmt(f.FTy_over_mu0FN)),
            ("D_y/D_x", _fmt(f.Dy_over_Dx)), ("N_c/N_c0 = τ_out/L₀", _fmt(f.Nc_over_Nc0)),
            ("β = N_c0/N_c", _fmt(f.beta)),
            ("energy residual / W", _fmt(abs(r.energy_residual / r.W) if r and r.W else None, 2))]
    body = "\n".join(f"| {k} | {v} |" for k, v in rows)
    return f"| Fixed array, θ₀ = {theta0_deg:g}° | |\n|:--|--:|\n{body}"


def uniform_markdown(row: dict | None, average: str, note: str = "") -> str:
    """The uniform array (theta0 uniform on [0, 2 pi)); the chosen average in bold."""
    if row is None:
        return f"| Uniform array | |\n|:--|--:|\n| F_T,x/(μ₀F_N) | {note or '…'} |"
    paper, duration = _fmt(row["FTx_over_mu0FN"]), _fmt(row["FTx_over_mu0FN_duration"])
    if average == "paper":
        paper = f"**{paper}**"
    else:
        duration = f"**{duration}**"
    rows = [("F_T,x/(μ₀F_N), paper (Eq. 10)", paper),
            ("F_T,x/(μ₀F_N), duration-weighted", duration),
            ("D_y/D_x", _fmt(row["Dy_over_Dx"])), ("N_c/N_c0", _fmt(row["Nc_over_Nc0"])),
            ("quadrature error", _fmt(row["quadrature_error_FTx"], 2))]
    body = "\n".join(f"| {k} | {v} |" for k, v in rows)
    warn = "" if row.get("success", True) else (
        f"\n\n⚠ not every member finished its contact ({row.get('n_failed', 0)} failed)")
    return f"| Uniform array (all θ₀) | |\n|:--|--:|\n{body}{warn}"


class ReadoutsView(pn.viewable.Viewer):
    """Regime and mechanism, fixed-array and uniform-array numbers."""

    active = param.Boolean(True, doc="whether the uniform array is on screen (compute only then)")
    uniform = param.Dict(default=None, allow_None=True, doc="the latest uniform-array row")
    error = param.String("")

    def __init__(self, state: ExplorerState, support: SupportView, **params):
        super().__init__(**params)
        self.state, self.support = state, support
        style = {"font-size": "0.92em"}
        compact = [TABLE_CSS]
        self.regime_pane = pn.pane.Markdown(regime_markdown(state.regime), width=290,
                                            css_classes=["readout-regime"], styles=style,
                                            margin=(0, 5))
        self.fixed_pane = pn.pane.Markdown(fixed_markdown(support.data),
                                           width=290, css_classes=["readout-fixed"],
                                           styles=style, stylesheets=compact, margin=(0, 5))
        self.uniform_pane = pn.pane.Markdown(uniform_markdown(None, state.average), width=290,
                                             css_classes=["readout-uniform"], styles=style,
                                             stylesheets=compact, margin=(0, 5))
        self.runner = LatestOnly(self._apply, busy=self._busy)
        support.param.watch(self._on_support, "data")
        state.param.watch(self._on_regime, ["k_r", "k_theta"])
        state.param.watch(self._request, list(ARRAY_KEYS))
        state.param.watch(self._show_uniform, "average")
        self.param.watch(lambda e: e.new and self._stale and self._request(), "active")
        self._stale = True
        self._request()

    def _on_support(self, event) -> None:
        self.fixed_pane.object = fixed_markdown(event.new)

    def _on_regime(self, *_events) -> None:
        self.regime_pane.object = regime_markdown(self.state.regime)

    def _request(self, *_events) -> None:
        self._stale = True
        if not self.active:
            self.runner.cancel()
            return
        self._stale = False
        s = self.state
        self.runner.submit_later(
            lambda: uniform_future(s.k_r, s.k_theta, s.F_N, s.array_beta), DEBOUNCE_MS)

    def _busy(self, flag: bool) -> None:
        self.uniform_pane.loading = flag

    def _apply(self, sweep, error) -> None:
        if error is not None:
            self.error = f"Uniform array failed: {type(error).__name__}: {error}"
            self.uniform = None
            self.uniform_pane.object = uniform_markdown(None, self.state.average, "failed")
            return
        self.error = ""
        self.uniform = sweep_row(sweep)
        self._show_uniform()

    def _show_uniform(self, *_events) -> None:
        self.uniform_pane.object = uniform_markdown(self.uniform, self.state.average)

    def __panel__(self):
        return pn.Column(self.regime_pane, self.fixed_pane, self.uniform_pane,
                         css_classes=["readouts"], width=300)
