"""What ``model.designs.distribution_array`` returns: the p-weighted array quantities (Eq. 10),
their error bars, and a named outcome with its remedy.

The error bar a result reports (``quadrature_error``) is defined here, once, by its outcome:

* every member finished at the converged (or fixed) beta: the quadrature's error estimate
  (above ``tol`` when the tolerance was not met: still an estimate of the error);
* members did not finish and took their neighbour's values: the filled values are not
  known, so the error of F_T,x and F_T,y is the half-width of ``bounds``, an interval
  that holds whatever the missing members' forces are (each member's mean friction over
  its own load is at most max mu(v) <= mu_s, Eq. 4), widened by the quadrature estimate;
  the other quantities have none (NaN);
* beta did not converge: no error bar (NaN): the members were computed at a load factor
  that is not the array's.

``value_text`` says a value with its error bar in words for the command line and the page.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..arrays.uniform import UniformArrayResult
from ..contact.regimes import MAP_NOTE, map_status
from ..contact.results import ACCURACY_FACTOR
from .distributions import Distribution

__all__ = ["DistributionArrayResult", "QUANTITIES", "OUTCOMES", "outcome_text", "assemble",
           "FILLED", "filled_columns", "BOUNDED", "value_text", "error_words"]

#: Integrand components per orientation (the diagnostics ride along separately).
QUANTITIES = ("F_x", "F_y", "t_out", "W", "D_x", "D_y", "U_el", "K", "dtheta_rms", "dr_rms")

#: Extra integrand columns that track the members filled from a neighbour: their even
#: weight, their |odd| weight and their (filled) weighted F_x and F_y.
FILLED = ("weight_even", "weight_odd", "F_x", "F_y")
#: The quantities whose ``bounds`` are known when members were filled: -> integrand column.
BOUNDED = {"FTx_over_mu0FN": ("F_x", 0, 2), "FTy_over_mu0FN": ("F_y", 1, 3)}


def filled_columns(weighted, even, odd, diag) -> np.ndarray:
    """Per node, the ``FILLED`` columns: zero where the member finished."""
    failed = (diag[:, 2] > 0).astype(float) if diag.size else np.zeros(len(even))
    fx, fy = QUANTITIES.index("F_x"), QUANTITIES.index("F_y")
    return np.column_stack([failed * even, failed * np.abs(odd), failed * weighted[:, fx],
                            failed * weighted[:, fy]])


def error_words(record: dict, key: str) -> str:
    """The error bar ``record[key]`` carries (``record``: a ``to_dict`` of an array), in
    words: ``± 1.6e-04``; ``(not converged: between 0.35 and 1.65)`` when members were
    filled; ``(not converged: no error bar)`` when nothing bounds it; ``± 3e-03
    (tolerance not met)``."""
    error = record.get("quadrature_error", {}).get(key)
    lo_hi = (record.get("bounds") or {}).get(key)
    success = record.get("success", True)
    if lo_hi is not None and all(x is not None and math.isfinite(x) for x in lo_hi):
        return f"(not converged: between {lo_hi[0]:.3g} and {lo_hi[1]:.3g})"
    if error is None or not math.isfinite(error):
        return "" if success else "(not converged: no error bar)"
    return f"± {error:.1e}" + ("" if success else " (tolerance not met)")


def value_text(record: dict, key: str, digits: int = 4) -> str:
    """``record[key]`` with ``error_words``: ``1.0020 ± 1.6e-04``."""
    value = record.get(key)
    if value is None or not math.isfinite(value):
        return "–"
    return f"{value:.{digits}f} {error_words(record, key)}".rstrip()


#: How a distribution array ended: (what happened, the remedy). ``ok`` is the only
#: outcome with ``success=True``; every other result still holds finite values.
OUTCOMES = {
    "ok": ("the quadrature tolerance was met and beta converged", ""),
    "tolerance_not_met": ("quadrature tolerance not met within max_intervals",
                          "raise max_intervals or loosen tol"),
    "refinement_cut": ("quadrature tolerance not met within the time budget",
                       "give a larger budget or a looser tol"),
    "beta_cut": ("time budget ran out before the self-consistent beta converged; the best "
                 "beta so far was used",
                 "give a larger budget, or fix beta (beta=NUMBER)"),
    "contacts_cut": ("time budget ran out inside the contacts: members were cut short",
                     "give a larger budget; stiff springs (large k~) ring fast and cost "
                     "most: a lower k~ (for a design: a faster slab) is cheaper"),
    "members_failed": ("members did not finish their contact (step budget)",
                       "raise max_steps or loosen tol"),
}


def outcome_text(outcome: str, budget: float | None = None) -> str:
    what, remedy = OUTCOMES[outcome]
    if budget and "time budget" in what:
        what = what.replace("time budget", f"time budget of {budget:g} s", 1)
    return what + (f" ({remedy})" if remedy else "")


@dataclass(frozen=True)
class DistributionArrayResult(UniformArrayResult):
    """An array with orientations from ``distribution``; ``quadrature_error`` holds the error
    bars (the module docstring says which, by outcome).

    Every field of a uniform array (``UniformArrayResult``: ``params`` holds the beta used;
    ``FTx_over_mu0FN`` is the p-weighted paper average, Eq. (10)), and the distribution,
    the sliding angle ``psi``, ``map_status`` (``in_map`` or ``outside_map``: the
    springs lie outside the paper's explored map, said in ``message``) and ``outcome``
    (a key of ``OUTCOMES``; ``message`` says it with its remedy). The keys of ``to_dict``
    are those of ``UniformArrayResult.to_dict`` plus ``distribution``, ``psi_deg``,
    ``Uel_over_W``, ``map_status`` and ``outcome``.
    """

    distribution: Distribution | None = None
    psi: float = 0.0
    map_status: str = "in_map"  # or "outside_map" (model.contact.regimes)
    outcome: str = "ok"  # a key of OUTCOMES
    # With members filled from a neighbour: the interval that holds F_T,x/(mu0 F_N) and
    # F_T,y/(mu0 F_N) whatever the missing members' forces are (module docstring).
    bounds: dict = field(default_factory=dict)
    filled_weight: float = 0.0  # the share of the orientations' weight filled

    @property
    def Uel_over_W(self) -> float:
        return self.work_split["U_el"]

    def to_dict(self) -> dict:
        d = {k: getattr(self, k) for k in self.__dataclass_fields__
             if k not in ("params", "distribution", "psi")}
        d["failed_theta0"] = list(self.failed_theta0)
        d["bounds"] = {k: list(v) for k, v in self.bounds.items()}
        d["params"] = self.params.as_dict()
        d["distribution"] = self.distribution.to_dict()
        d["psi_deg"] = math.degrees(self.psi)
        d["Uel_over_W"] = self.Uel_over_W
        return d


def assemble(*args, **kwargs) -> DistributionArrayResult:
    # When every member failed the sums are 0 and the ratios NaN: reported as such
    # (success False, the message says why), without warnings.
    with np.errstate(divide="ignore", invalid="ignore"):
        return _assemble(*args, **kwargs)


def _outcome(converged, budget, beta_cut, n_cut, n_failed) -> str:
    if n_cut:
        return "contacts_cut"
    if beta_cut:
        return "beta_cut"
    if not converged:
        return "refinement_cut" if budget else "tolerance_not_met"
    return "members_failed" if n_failed else "ok"


def _error_bars(errors: dict, values: dict, bounds: dict, n_failed: int, beta_cut: bool):
    """The error bar each quantity reports (the module docstring's rule)."""
    if beta_cut:
        return dict.fromkeys(errors, math.nan)
    if n_failed:
        return {k: max(bounds[k][1] - values[k], values[k] - bounds[k][0]) if k in bounds
                else math.nan for k in errors}
    return errors


def _bounds(mean, e, filled, mu_max, m0) -> tuple[dict, dict]:
    """The intervals of ``BOUNDED`` quantities whatever the filled members' forces are."""
    out, values = {}, {}
    for key, (q, weight, column) in BOUNDED.items():
        known = mean[q] - filled[column]
        half = mu_max * filled[weight] + e[q]
        out[key] = (float((known - half) / m0), float((known + half) / m0))
        values[key] = float(mean[q] / m0)
    return out, values


def _assemble(params, distribution, psi, atom_sum, atom_diag, atoms, quad, m0, counter,
              beta_iter, beta_res, options, seconds, budget=None, beta_cut=False,
              atom_filled=None, self_consistent=False):
    n_q = len(QUANTITIES)
    total = atom_sum.copy()
    err = np.zeros(n_q)
    diag = atom_diag
    filled = np.zeros(len(FILLED)) if atom_filled is None else np.asarray(atom_filled, float)
    theta_all = np.array([t for t, _, _ in atoms])
    converged = True
    if quad is not None:
        total += quad.integral[:n_q]
        err += quad.error[:n_q]
        diag = np.vstack([atom_diag, quad.values[:, n_q:n_q + 3]])
        if quad.integral.size > n_q + 3:
            filled = filled + quad.integral[n_q + 3:n_q + 3 + len(FILLED)]
        theta_all = np.concatenate([theta_all, quad.nodes])
        converged = quad.converged
    failed = diag[:, 2] if diag.size else np.zeros(0)
    nothing = failed.size > 0 and bool(np.all(failed > 0))
    if nothing:  # no member finished: there is no value, only the reason (the message)
        total[:] = np.nan
    mean, fN = dict(zip(QUANTITIES, total)), params.f_N
    e = dict(zip(QUANTITIES, err))

    def ratio(a, b):
        value = mean[a] / mean[b]
        return value, abs(value) * (e[a] / abs(mean[a]) + e[b] / abs(mean[b])) if mean[a] else 0.0

    Dy_Dx, Dy_Dx_err = ratio("D_y", "D_x")
    split = {k: ratio(k, "W") for k in ("D_x", "D_y", "U_el", "K")}
    duration = mean["W"] / (fN * mean["t_out"]) / m0
    pivot, relres, failed = (diag[:, 0], diag[:, 1], diag[:, 2]) if diag.size else (
        np.zeros(0), np.zeros(0), np.zeros(0))
    n_failed = int(np.sum(failed > 0))
    # Members cut short by the time budget (code 2) rather than by max_steps (code 1).
    n_cut = int(np.sum(failed == 2))
    outcome = _outcome(converged, budget, beta_cut, n_cut, n_failed)
    message = "ok" if outcome == "ok" else outcome_text(outcome, budget)
    if outcome == "beta_cut":
        message += f"; residual {beta_res:.1e}" + ("" if converged else
                                                  "; quadrature tolerance not met")
    if nothing:
        message += (f"; none of the {n_failed} members finished its contact "
                    f"({n_cut} cut short by the time budget): the array has no value")
    elif n_failed:
        message += (f"; {n_failed} of {theta_all.size} members did not finish their contact "
                    f"({n_cut} cut short by the time budget) and took the values of their "
                    f"nearest neighbour")
    n_inaccurate = int(np.sum(relres > ACCURACY_FACTOR * options.rtol))
    if n_inaccurate:
        message += (f"; {n_inaccurate} members miss the energy balance by more than "
                    f"{ACCURACY_FACTOR:g} rtol (largest {np.nanmax(relres):.1e} of W)")
    n_pivot = int(np.sum(pivot > 0))
    if n_pivot:
        message += f"; {n_pivot} members were driven into the region of their pivot"
    where = map_status(params.k_r, params.k_theta)
    if where != "in_map":
        message += f"; {MAP_NOTE}"
    errors = {
        "FTx_over_mu0FN": e["F_x"] / m0,
        "FTx_over_mu0FN_duration": duration * (e["W"] / abs(mean["W"])
                                               + e["t_out"] / mean["t_out"]),
        "FTy_over_mu0FN": e["F_y"] / m0,
        "Dy_over_Dx": Dy_Dx_err,
        "Nc_over_Nc0": e["t_out"] / params.L0,
        **{f"work_split.{k}": v for k, (_, v) in split.items()}}
    bounds, values = {}, {}
    if n_failed and not beta_cut and not nothing:
        # Each member's mean friction over its load is at most max mu(v) <= |mu_s| (Eq. 4).
        bounds, values = _bounds(mean, e, filled, abs(params.mu_s), m0)
    if n_failed or beta_cut:
        message += ("; no error bar: beta did not converge" if beta_cut else
                    "; error bars: the bounds that hold whatever the missing members' "
                    "forces are")
    return DistributionArrayResult(
        params=params, distribution=distribution, psi=psi,
        FTx_over_mu0FN=mean["F_x"] / m0, FTx_over_mu0FN_duration=duration,
        FTy_over_mu0FN=mean["F_y"] / m0, Dy_over_Dx=Dy_Dx,
        Nc_over_Nc0=mean["t_out"] / params.L0,
        # A self-consistent beta solved on no finished member is no value either (a given
        # beta is the caller's input, reported as given).
        beta=math.nan if nothing and self_consistent else params.beta,
        work_split={k: v for k, (v, _) in split.items()},
        dtheta_rms=mean["dtheta_rms"], dr_rms=mean["dr_rms"],
        quadrature_error=_error_bars(errors, values, bounds, n_failed, beta_cut),
        integration_error=float(np.nanmax(relres)) if relres.size else 0.0,
        beta_iterations=beta_iter, beta_residual=float(beta_res),
        n_members=int(theta_all.size), n_failed=n_failed, n_pivot=n_pivot,
        failed_theta0=tuple(theta_all[failed > 0].tolist()),
        success=outcome == "ok", message=message, seconds=seconds,
        stats={**counter, "intervals": 0 if quad is None else int(quad.edges.size - 1),
               "rounds": 0 if quad is None else quad.rounds, "atoms": len(atoms),
               "rtol": options.rtol, "method": options.method},
        map_status=where, outcome=outcome, bounds=bounds,
        filled_weight=float(filled[0]) if n_failed else 0.0)
