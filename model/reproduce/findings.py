"""The paper's findings (docs/model.md, "What the paper reports", 1-7) checked on the numbers
behind the reproduced figures.

Each ``Check`` states the claim, the computed quantity, its value with the error
estimates (quadrature: the adaptive rule's estimate; integration: the largest relative
energy-balance residual |W - (D_x + D_y + U_el + K)|/W of the trajectories involved), the
criterion, the verdict ("agrees" or "differs") and the beta and averaging used.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..contact.friction import mu0
from ..contact.params import REGIMES
from .datasets import THETA_FIG10, Data, rows_of

UNIFORM = "uniform arrays, self-consistent β, paper average (Eq. 10), F_N = 1"
FIXED = "fixed arrays, self-consistent β, F_N = 1"
SINGLE = "single support, β = 1 (f_N = F_N = 1), rtol 1e-8"


@dataclass(frozen=True)
class Check:
    finding: str  # "1" ... "7", or "extra" for results the paper does not discuss
    claim: str
    quantity: str
    value: str
    error: str
    criterion: str
    agrees: bool
    basis: str
    figure: str

    @property
    def verdict(self) -> str:
        return "agrees" if self.agrees else "differs"


def _u(data, name, q="FTx_over_mu0FN"):
    a = data.headline[name]
    value = a.work_split[q] if q in a.work_split else getattr(a, q)
    err = a.quadrature_error.get(q, a.quadrature_error.get(f"work_split.{q}", np.nan))
    return float(value), float(err), float(a.integration_error)


def _err(quad=None, integ=None) -> str:
    parts = [f"quadrature ±{quad:.1e}" if quad is not None else "",
             f"integration {integ:.1e}" if integ is not None else ""]
    return "; ".join(p for p in parts if p)


def _uniform_check(data, finding, claim, name, q, lo, hi, figure, label=None):
    v, qe, ie = _u(data, name, q)
    return Check(finding, claim, f"{label or q}, {name}", f"{v:.4f}", _err(qe, ie),
                 f"{lo:g} ≤ value ≤ {hi:g}", lo <= v <= hi, UNIFORM, figure)


def finding_1(data):
    c = "Stiff: no significant friction reduction, D_y/D_x ≈ 0"
    return [_uniform_check(data, "1", c, "stiff", "FTx_over_mu0FN", 0.97, 1.03, "5a, 6",
                           "F_T,x/(μ₀F_N)"),
            _uniform_check(data, "1", c, "stiff", "Dy_over_Dx", 0.0, 0.02, "5b", "D_y/D_x")]


def finding_2(data):
    c = "Soft: low apparent friction, D_y/D_x ≈ 0, U_el/W ≈ 0.7, sticky phases"
    ftx = {r: _u(data, r)[0] for r in REGIMES}
    s = data.supports[("soft", "θ₀ = π/2")]
    v_r = np.hypot(s.series.v_x - 1.0, s.series.v_y)
    sticky = float(np.mean(v_r < 0.1))
    return [
        Check("2", c, "F_T,x/(μ₀F_N), soft vs the others",
              ", ".join(f"{r} {v:.4f}" for r, v in ftx.items()),
              _err(max(_u(data, r)[1] for r in REGIMES)), "soft is the lowest of the four",
              min(ftx, key=ftx.get) == "soft", UNIFORM, "5a, 6"),
        _uniform_check(data, "2", c, "soft", "Dy_over_Dx", 0.0, 0.01, "5b", "D_y/D_x"),
        _uniform_check(data, "2", c, "soft, k_r = 0.01", "U_el", 0.6, 0.8, "8b", "U_el/W"),
        Check("2", c, "share of the contact time with |v_R| < 0.1, soft, θ₀ = π/2",
              f"{sticky:.2f}", _err(integ=abs(s.energy_residual / s.W)), "> 0.5",
              sticky > 0.5, SINGLE, "7b"),
    ]


def finding_3(data):
    c = "Pendulum and slider: moderate reduction, D_y/D_x of order 0.1; Fig. 7a F_f,x < |F_f|"
    out = []
    for r in ("pendulum", "slider"):
        out.append(_uniform_check(data, "3", c, r, "FTx_over_mu0FN", 0.85, 0.99, "5a, 6",
                                  "F_T,x/(μ₀F_N)"))
        out.append(_uniform_check(data, "3", c, r, "Dy_over_Dx", 0.05, 0.2, "5b",
                                  "D_y/D_x (paper ≈ 0.1)"))
    dmax = float(np.nanmax(data.regime_map.Dy_over_Dx))
    out.append(Check("3", c, "largest D_y/D_x on the regime map", f"{dmax:.4f}",
                     _err(float(np.max(data.regime_map.quadrature_error))), "0.05 ≤ value ≤ 0.2",
                     0.05 <= dmax <= 0.2, UNIFORM, "5b"))
    s = data.supports[("pendulum", "θ₀ = π/2")]
    excess = float(np.max(s.series.F_x - s.series.F_abs))
    fy = float(np.mean(np.abs(s.series.F_y)))
    out.append(Check("3", c, "max(F_f,x − |F_f|)/f_N and mean |F_f,y|/f_N, pendulum, θ₀ = π/2",
                     f"{excess:.1e}, {fy:.3f}", _err(integ=abs(s.energy_residual / s.W)),
                     "first ≤ 1e-9, second > 0.1", excess <= 1e-9 and fy > 0.1, SINGLE, "7a"))
    return out


def finding_4(data):
    c = "Increasing F_N lowers F_T,x/(μ₀F_N) in every regime"
    out = []
    for r in REGIMES:
        rows = rows_of(data.load, regime=r)
        order = np.argsort(rows["F_N"])
        v, e = rows["FTx_over_mu0FN"][order], rows["quadrature_error_FTx"][order]
        rises = np.diff(v) - 2 * (e[1:] + e[:-1])
        out.append(Check("4", c, f"F_T,x/(μ₀F_N) at F_N = {rows['F_N'][order][0]:g} … "
                         f"{rows['F_N'][order][-1]:g}, {r}",
                         " → ".join(f"{x:.3f}" for x in v), _err(float(e.max())),
                         "never rises by more than twice its errors, falls overall",
                         bool(np.all(rises <= 0) and v[-1] < v[0]), UNIFORM, "6"))
    return out


def finding_5(data):
    c = "N_c/N_c0 ≥ 1, grows as k_r falls (≳ 2 at the smallest k_r); larger k_θ lowers it"
    st = data.stiffness
    k_theta = np.unique(st.columns["k_theta"])
    curves = {kt: rows_of(st, k_theta=kt) for kt in k_theta}
    nc = {kt: v["Nc_over_Nc0"][np.argsort(v["k_r"])] for kt, v in curves.items()}
    err = float(np.max(st.columns["quadrature_error_Nc"]))
    lowest = min(float(v.min()) for v in nc.values())
    at_min = [float(v[0]) for v in nc.values()]
    rising = sum(int(np.sum(np.diff(v) > 2 * err)) for v in nc.values())
    pairs = [(a, b) for a, b in zip(k_theta[:-1], k_theta[1:])]
    lowered = np.mean([np.mean(nc[b] <= nc[a] + 2 * err) for a, b in pairs]) if pairs else 1.0
    kr = np.sort(curves[k_theta[0]]["k_r"])
    return [
        Check("5", c, "smallest N_c/N_c0 over Fig. 8a", f"{lowest:.3f}", _err(err), "≥ 1",
              lowest >= 1.0, UNIFORM, "8a"),
        Check("5", c, f"N_c/N_c0 at k_r = {kr[0]:g}, per k_θ",
              ", ".join(f"{x:.2f}" for x in at_min), _err(err), "all ≥ 2",
              min(at_min) >= 2.0, UNIFORM, "8a"),
        Check("5", c, "increases of N_c/N_c0 as k_r grows (steps beyond 2 errors)",
              f"{rising} of {sum(v.size - 1 for v in nc.values())}", _err(err), "none",
              rising == 0, UNIFORM, "8a"),
        Check("5", c, "share of k_r where a larger k_θ gives a smaller N_c/N_c0",
              f"{lowered:.2f}", _err(err), "1.00", lowered == 1.0, UNIFORM, "8a"),
    ]


def finding_6(data):
    c = ("Pendulum: r̃ oscillates about 1; slider: θ₀ ≫ π/2 shortens, θ₀ ≤ π/2 elongates; "
         "pendulum Δr_rms ≈ 0; slider Δθ_rms ≪ Δr_rms")
    sup = {k: v for k, v in data.supports.items() if k[1] in THETA_FIG10}
    res = lambda keys: max(abs(sup[k].energy_residual / sup[k].W) for k in keys)  # noqa: E731
    pend = [("pendulum", lb) for lb in THETA_FIG10]
    means = [float(np.mean(sup[k].series.r)) for k in pend]
    sl = {lb: sup[("slider", lb)].series.r for lb in THETA_FIG10}
    short = float(sl["θ₀ = 3π/4"].min())
    longs = [float(sl[lb].max()) for lb in ("θ₀ = π/4", "θ₀ = π/2")]
    o = {r: data.orientation[r].columns for r in ("pendulum", "slider")}
    ie = max(float(np.max(o[r]["relative_residual"])) for r in o)
    dr_p = float(np.mean(o["pendulum"]["dr_rms"]))
    ratio = float(np.mean(o["slider"]["dtheta_rms"]) / np.mean(o["slider"]["dr_rms"]))
    return [
        Check("6", c, "mean r̃ over the contact, pendulum, θ₀ = π/4, π/2, 3π/4",
              ", ".join(f"{m:.2f}" for m in means), _err(integ=res(pend)), "|mean − 1| < 0.1",
              max(abs(m - 1) for m in means) < 0.1, SINGLE, "10e"),
        Check("6", c, "slider: min r̃ at 3π/4; max r̃ at π/4, π/2",
              f"{short:.2f}; {longs[0]:.1f}, {longs[1]:.1f}",
              _err(integ=res([("slider", lb) for lb in THETA_FIG10])),
              "first < 1, others > 1", short < 1 and min(longs) > 1, SINGLE, "10a, 10e"),
        Check("6", c, "mean Δr̃_rms over θ₀, pendulum", f"{dr_p:.3f}", _err(integ=ie), "< 0.1",
              dr_p < 0.1, FIXED, "10f"),
        Check("6", c, "mean Δθ_rms / mean Δr̃_rms over θ₀, slider", f"{ratio:.4f}",
              _err(integ=ie), "< 0.05", ratio < 0.05, FIXED, "10f"),
    ]


def finding_7(data):
    c = ("Fixed orientation: F_T,y → 0 as θ₀ → 0, π; pendulum F_T,y ≥ 0; slider F_T,y "
         "changes sign; minima of F_T,x line up with maxima of D_y/D_x")
    out = []
    for r in ("pendulum", "slider"):
        t = data.orientation[r].columns
        th, fy = np.asarray(t["theta0"]), np.asarray(t["FTy_over_mu0FN"])
        ie = _err(integ=float(np.max(t["relative_residual"])))
        edge = float(max(abs(fy[0]), abs(fy[-1])))
        out.append(Check("7", c, f"|F_T,y|/(μ₀F_N) at θ₀ = {th[0]:.3f}, {th[-1]:.3f}, {r}",
                         f"{abs(fy[0]):.4f}, {abs(fy[-1]):.4f}", ie, "both < 0.05",
                         edge < 0.05, FIXED, "11c"))
        if r == "pendulum":
            i = int(np.argmin(fy))
            out.append(Check("7", c, "smallest F_T,y/(μ₀F_N), pendulum",
                             f"{fy[i]:.4f} at θ₀ = {np.degrees(th[i]):.1f}°", ie, "≥ −1e-3",
                             fy[i] >= -1e-3, FIXED, "11c"))
        else:
            out.append(Check("7", c, "range of F_T,y/(μ₀F_N), slider",
                             f"{fy.min():.3f} … {fy.max():.3f}", ie, "min < 0 < max",
                             fy.min() < 0 < fy.max(), FIXED, "11c"))
        gap = abs(th[np.argmin(t["FTx_over_mu0FN"])] - th[np.argmax(t["Dy_over_Dx"])])
        out.append(Check("7", c, f"|θ₀ at min F_T,x − θ₀ at max D_y/D_x|, {r}",
                         f"{np.degrees(gap):.1f}°", ie, "< 15° (0.26 rad)",
                         np.degrees(gap) < 15, FIXED, "11a, 11b"))
    return out


def extra(data):
    m = data.regime_map
    i, j = np.unravel_index(np.nanargmax(m.FTx_over_mu0FN), m.shape)
    jump = float(np.max(np.diff(m.Nc_over_Nc0, axis=0))) if m.k_r.size > 1 else 0.0
    return [
        Check("extra", "μ₀ = μ(V₀) ≈ 1.0085 (the value quoted with the paper's friction constants)", "μ(1) with μ_s = 1.3, A = 1.44, "
              "B = −20, ζ = 10", f"{mu0():.5f}", "exact", "|μ₀ − 1.0085| < 5e-5",
              abs(mu0() - 1.0085) < 5e-5, "friction law (Eq. 4)", "3"),
        Check("extra", "Supports never raise friction above rigid contact (Fig. 5a shows none)",
              "largest F_T,x/(μ₀F_N) on the map",
              f"{m.FTx_over_mu0FN[i, j]:.4f} at k_r = {m.k_r[i]:.2f}, k_θ = {m.k_theta[j]:.2f}",
              _err(float(m.quadrature_error[i, j])), "≤ 1 + 2 × error",
              m.FTx_over_mu0FN[i, j] <= 1 + 2 * m.quadrature_error[i, j], UNIFORM, "5a"),
        Check("extra", "N_c/N_c0 grows as k_r falls (Fig. 8a), on the Fig. 5 grid",
              "largest rise of N_c/N_c0 from one k_r to the next larger", f"{jump:.3f}",
              _err(float(np.max(m.quadrature_error))), "≤ 0.01", jump <= 0.01, UNIFORM, "5"),
    ]


def all_checks(data: Data) -> list:
    """Every check, in the order of the findings in docs/model.md, then the extra results."""
    return [c for fn in (finding_1, finding_2, finding_3, finding_4, finding_5, finding_6,
                         finding_7, extra) for c in fn(data)]
