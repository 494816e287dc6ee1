"""Text of a comparison (helpers of the views, no view): B − A and its change relative to
A, the Design tab's array of A beside B's, and a distribution in words.
"""
from __future__ import annotations

import math

from ..histogram import describe


def _fmt(x, digits: int = 4) -> str:
    return "–" if x is None or not math.isfinite(x) else f"{x:.{digits}g}"


def difference(a: float | None, b: float | None) -> tuple[str, str]:
    """B - A and its change relative to A, as text ("–" where either is missing)."""
    if a is None or b is None or not (math.isfinite(a) and math.isfinite(b)):
        return "–", "–"
    return f"{b - a:+.3g}", f"{100 * (b - a) / abs(a):+.1f} %" if a != 0 else "–"


#: The Design tab's numbers compared between A and B: (label, where in a
#: ``SessionResults.design_array``: a key of its dimensionless ``array`` or of the whole).
DESIGN_COMPARED = (("F_T,x/(μ₀F_N) (Eq. 10)", "array", "FTx_over_mu0FN"),
                   ("… duration-weighted", "array", "FTx_over_mu0FN_duration"),
                   ("F_T,y/(μ₀F_N)", "array", "FTy_over_mu0FN"),
                   ("D_y/D_x", "array", "Dy_over_Dx"),
                   ("N_c/N_c0", "array", "Nc_over_Nc0"),
                   ("β", "array", "beta"),
                   ("drive force F_T,x [N]", "", "FTx_N"),
                   ("power F_T,x V₀ [W]", "", "power_W"),
                   ("contact time [s]", "", "contact_time_s"))


def design_values(design_array: dict | None) -> list:
    """The ``DESIGN_COMPARED`` numbers of one design array (None where not computed)."""
    if design_array is None:
        return [None] * len(DESIGN_COMPARED)
    return [(design_array[part] if part else design_array).get(name)
            for _, part, name in DESIGN_COMPARED]


def distribution_words(d: dict | None, psi_deg: float = 0.0) -> str:
    """An orientation distribution (``ExplorerState.distribution``) in a few words."""
    if d is None:
        return "–"
    family = d["family"]
    if family == "mixture":
        text = " + ".join(f"{w:.2g} × {distribution_words(c)}"
                          for c, w in zip(d["components"], d["weights"]))
    elif family == "vonmises":
        text = f"von Mises about {d['mean_deg']:g}°, κ = {d['kappa']:g}"
    elif family == "pair":
        text = f"pair ±{d['theta0_deg']:g}°"
    elif family == "fixed":
        text = f"fixed θ₀ = {d['theta0_deg']:g}°"
    elif family == "histogram":
        text = "histogram of " + describe(d)
    else:
        text = "uniform"
    return text + (f", ψ = {psi_deg:g}°" if psi_deg else "")


def design_compare_markdown(a: dict | None, b: dict | None, a_words: str,
                            b_words: str) -> str:
    """The Design tab's arrays of A (pinned) and B (current) side by side, with B − A and,
    under it, its change relative to A; then each one's point and distribution."""
    rows = []
    for (label, _, _), x, y in zip(DESIGN_COMPARED, design_values(a), design_values(b)):
        diff, rel = difference(x, y)
        rows.append(f"| {label} | {_fmt(x)} | {_fmt(y)} | {diff}<br>{rel} |")
    who = []
    for side, arr, words in (("A (pinned)", a, a_words), ("B (current)", b, b_words)):
        p = (arr or {}).get("point")
        where = (f"k̃_r = {p['k_r']:.3g}, k̃_θ = {p['k_theta']:.3g}, F̃_N = {p['F_N']:.3g}; "
                 if p else "")
        who.append(f"**{side}**: {where}{words}")
    return ("| Compare the arrays | A | B | B − A |\n|:--|--:|--:|--:|\n" + "\n".join(rows)
            + "\n\n" + "  \n".join(who))
