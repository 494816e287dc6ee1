"""The Design tab's figures in words, for screen readers (``app.views.access.LiveDescription``),
written from the computed design result, as ``app.plot_words`` does for the other tabs.

Each function reads the data its figure draws (the figure modules' ``*_data``) and says what
is drawn, the values that matter now, with units, and what they mean:

* ``design_map_description``: the design's point on Fig. 5a (k~_r, k~_theta, F~_N, Eq. 5),
  its regime, where the map's status puts it, its speed line and its friction
  (``model.designs.design_table.headline``: F_T,x/(mu0 F_N) against a rigid surface, Eq. 10);
* ``design_polar_description``: Fig. 11a of the design's springs, its extremes, the
  orientation distribution drawn over it and the array's friction with it (Eq. 10);
* ``law_description``: the friction law mu(v) of Eq. (4) (Fig. 3 in m/s), mu at V0 and
  the fit and measured points when a curve was uploaded;
* ``speeds_description``: friction against sliding speed, the structured surface's
  F_T,x/F_N (Eqs. 10, 11) beside the flat mu(V0), where it is lowest, and measured -
  predicted (its RMS) when a measured curve is there.

A value not computed yet is said to be computing, never guessed.
"""
from __future__ import annotations

import math

import numpy as np

from model.designs.design_table import headline
from model.contact.regimes import EXPLORED_MAP

from ..figures.design import design_map_data
from ..figures.law import law_data
from ..figures.speeds import speeds_data
from ..plot_words import extreme, minus
from ..speed_results import speed_words
from .compare_tables import distribution_words

_LO, _HI = EXPLORED_MAP
#: Where a design lies (``model.designs.design_point.POINT_STATUS``), in words.
STATUS_WORDS = {"in_map": "inside the paper's explored map",
                "outside_map": f"outside the paper's explored map [{_LO:g}, {_HI:g}]² (same "
                               "model, beyond the paper's figures)",
                "scaled": "beyond the model range: computed scaled along its speed line",
                "unusable": "not computable"}


def _friction(array: dict | None) -> str:
    """The array's friction in one sentence, or that it is being computed."""
    if array is None:
        return "Its friction is being computed."
    return headline(array).replace("This design: friction", "Its friction F_T,x/(μ₀F_N)", 1)


def design_map_description(point: dict | None, array: dict | None = None) -> str:
    """The design's point on Fig. 5a (``point``: ``SessionResults.design_point``) and its
    friction (``array``: ``SessionResults.design_array`` when up to date, else None)."""
    if point is None:
        return "The design's point on the regime map is being computed."
    p, c = point["point"], point["computed"]
    data, xr, yr = design_map_data(point)
    speeds = point["speed_line"]["V0_m_per_s"]
    text = (f"Regime map (Fig. 5a, friction of uniform arrays at F_N = 1) with this design as "
            f"a star at k̃_r = {p['k_r']:.3g}, k̃_θ = {p['k_theta']:.3g} (F̃_N = "
            f"{p['F_N']:.3g}, at V₀ = {point['V0_m_per_s']:.3g} m/s): {point['regime']} "
            f"regime, {STATUS_WORDS[point['status']]}.")
    if data["design_point"]["note"][0]:
        text += " It lies beyond the map's axes and is drawn at their edge."
    if speeds:
        text += (f" A dashed line shows its path as V₀ changes, from {min(speeds):.3g} to "
                 f"{max(speeds):.3g} m/s.")
    if point["status"] == "scaled" and c is not None:
        text += (f" The model computes it at k̃_r = {c['k_r']:.3g}, k̃_θ = "
                 f"{c['k_theta']:.3g} (a square).")
    if point["error"]:
        return minus(f"{text} Not computable: {point['error']}")
    return minus(f"{text} {_friction(array)}")


def design_polar_description(sweep, distribution: dict | None, psi_deg: float,
                             array: dict | None = None) -> str:
    """Fig. 11a of the design's springs (``sweep``: ``SessionResults.design_polar``) with
    the orientation ``distribution`` seen at ``psi_deg`` over it, and the array's friction
    with that distribution (``array`` as in ``design_map_description``)."""
    if sweep is None:
        return "The polar diagram of the design's springs is being computed."
    theta = np.degrees(np.asarray(sweep.columns["theta0"], float))
    ftx = np.asarray(sweep.columns["FTx_over_mu0FN"], float)
    if not np.isfinite(ftx).any():
        return "The polar diagram of the design's springs has no finished orientation."
    s = sweep.settings
    low, at_low = extreme(theta, ftx, np.argmin)
    high, at_high = extreme(theta, ftx, np.argmax)
    text = (f"Polar diagram (Fig. 11a) of the friction F_T,x/(μ₀F_N) of arrays whose supports "
            f"all share one orientation θ₀, for the design's springs k̃_r = {s['k_r']:.3g}, "
            f"k̃_θ = {s['k_theta']:.3g}, F̃_N = {s['F_N']:.3g}: lowest, {low:.3g}, at "
            f"θ₀ = {at_low:.0f}° and highest, {high:.3g}, at θ₀ = {at_high:.0f}°. Drawn over "
            f"it in orange: the orientation distribution, "
            f"{distribution_words(distribution, psi_deg)}.")
    if array is not None and math.isfinite(array["array"]["FTx_over_mu0FN"]):
        text += (f" With it the array's F_T,x/(μ₀F_N) = "
                 f"{array['array']['FTx_over_mu0FN']:.3g}.")
    else:
        text += " The array's friction with it is being computed."
    return minus(text)


def law_description(law, fit=None, curve=None, V0: float | None = None,
                    problem: str = "") -> str:
    """The friction law's figure (``app.figures.law``): the law ``law`` (a ``FrictionLaw``,
    None when not usable, ``problem`` saying why), a fit ``fit`` of the measured ``curve``
    and the design's sliding speed ``V0`` (m/s)."""
    data, (v_lo, v_hi), _ = law_data(law, fit, curve, V0)
    if not len(data["law"]["v"]):
        why = f": {problem}" if problem else ""
        return f"The friction law μ(v) is not drawn{why}."
    mu = np.asarray(data["law"]["mu"], float)
    v = np.asarray(data["law"]["v"], float)
    text = (f"Friction law μ(v), Eq. (4), against the sliding speed v on a log axis from "
            f"{v_lo:.3g} to {v_hi:.3g} m/s: μ_s = {law.mu_s:.3g}, A = {law.A:.3g}, "
            f"B = {law.B:.3g}" + (f", V_s = {law.V_s:.3g} m/s" if law.V_s is not None else "")
            + f". μ goes from {mu[0]:.3g} at {v[0]:.3g} m/s to {mu[-1]:.3g} at "
            f"{v[-1]:.3g} m/s, lowest {mu.min():.3g} at {v[mu.argmin()]:.3g} m/s, highest "
            f"{mu.max():.3g} at {v[mu.argmax()]:.3g} m/s.")
    if len(data["law_V0"]["v"]):
        text += (f" At the design's V₀ = {data['law_V0']['v'][0]:.3g} m/s (a square): "
                 f"μ = {data['law_V0']['mu'][0]:.3g}.")
    if fit is not None and fit.success:
        n = len(data["law_measured"]["v"])
        text += (f" Fitted to {n} measured points (circles with their error bars), rms "
                 f"residual {fit.rms_residual:.3g}; the shaded band is the fit's 95 % band.")
    return minus(text)


def speeds_description(points, law=None, measured=None, comparison=None,
                       running: bool = False) -> str:
    """The friction against sliding speed (``app.figures.speeds``): the arrived ``points``
    (``SpeedPoint`` or None), the flat ``law``, the ``measured`` curve and the
    ``comparison`` (a ``FrictionComparison``) of measured and predicted; while ``running``,
    only that it is being computed (said once, not at each speed)."""
    if running:
        return "The friction against sliding speed is being computed, speed by speed."
    data, (v_lo, v_hi), _ = speeds_data(points, law, measured)
    model = data["speeds_model"]
    text = (f"Friction against the sliding speed V₀ on a log axis from {v_lo:.3g} to "
            f"{v_hi:.3g} m/s.")
    if len(data["speeds_flat"]["v"]):
        flat = np.asarray(data["speeds_flat"]["mu"], float)
        text += (f" Dashed: the flat material's μ(V₀), from {flat[0]:.3g} to "
                 f"{flat[-1]:.3g}.")
    if model["v"]:
        mu = np.asarray(model["mu"], float)
        i = int(mu.argmin())
        text += (f" Dots: the pillars' predicted F_T,x/F_N at {len(mu)} speeds, from "
                 f"{mu[0]:.3g} at {model['v'][0]:.3g} m/s to {mu[-1]:.3g} at "
                 f"{model['v'][-1]:.3g} m/s, lowest {mu[i]:.3g} at {model['v'][i]:.3g} m/s.")
    else:
        text += " No prediction yet: Predict computes the pillars' friction at each speed."
    if measured is not None:
        text += f" Diamonds: the measured curve, {len(data['speeds_measured']['v'])} points."
    if comparison is not None:
        text += (f" Below, measured − predicted: RMS {comparison.rms:.3g} over "
                 f"{comparison.n_compared} speeds; "
                 + (f"they disagree beyond the model's error at "
                    f"{speed_words(comparison.disagree)}." if len(comparison.disagree) else
                    "they agree within the model's error at every measured speed."))
    return minus(text)
