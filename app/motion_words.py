"""The regime panel's words about the state on screen, written from its computed motion.

``motion_facts`` reads one ``worker.SupportData`` (the support at theta0 during one
contact, Eqs. 5-9, and its fixed-orientation array, Eqs. 10-13); ``motion_sentence`` says
those numbers in words: how far the support's length went (r_min...r_max), how far it
turned (the range of theta, Eq. 6), how long it moved with the slab (|v_R| below the static
speed V_s = 0.1 V0, where the friction law of Eq. 4 peaks), how long the contact lasted
against a rigid one (N_c/N_c0 = tau_out/L0), D_y/D_x (Eq. 13), U_el/W (Eq. 12) and the
friction change of the fixed array (Eq. 10). ``regime_markdown`` puts them after the
regime's mechanism (``app.texts.MECHANISMS``). No number is fixed per preset.
"""
from __future__ import annotations

import math

import numpy as np

from .lesson import STICK_SPEED
from .state import classify
from .texts import MECHANISMS


def change_words(ratio: float | None) -> str:
    """F_T,x/(mu0 F_N) in words: how far friction lies below (or above) a rigid surface,
    on which every support would slide at the full speed and F_T,x = mu0 F_N."""
    if ratio is None or not math.isfinite(ratio):
        return "not available"
    percent = 100.0 * (1.0 - ratio)
    if abs(percent) < 0.05:
        return "the same as on a rigid surface"
    return f"{abs(percent):.1f} % {'below' if percent > 0 else 'above'} a rigid surface"


def motion_facts(data) -> dict | None:
    """The numbers the regime panel quotes for ``data`` (a ``SupportData``), or None when
    it has no trajectory or no fixed array."""
    result = getattr(data, "result", None)
    series = getattr(result, "series", None)
    if series is None or data.fixed is None:
        return None
    theta = np.degrees(np.asarray(series.theta, float))
    v_r = np.hypot(np.asarray(series.v_x, float) - 1.0, np.asarray(series.v_y, float))
    p, f = data.params, data.fixed
    return {"theta0_deg": round(math.degrees(p.theta0), 6), "F_N": p.F_N,
            "k_r": p.k_r, "k_theta": p.k_theta,
            "r_min": float(result.r_min), "r_max": float(result.r_max),
            "theta_min": float(theta.min()), "theta_max": float(theta.max()),
            "theta_end": float(theta[-1]),
            "stick_fraction": float(np.mean(v_r < STICK_SPEED)),
            "contact_over_L0": float(f.Nc_over_Nc0), "Dy_over_Dx": float(f.Dy_over_Dx),
            "U_el_over_W": float(f.work_split["U_el"]), "FTx_over_mu0FN": float(f.FTx_over_mu0FN)}


def motion_sentence(facts: dict) -> str:
    """``motion_facts`` in words (no hyphen in them: negative numbers get a minus sign), e.g. "At θ₀ = 90°, F_N = 1 the support's length went from
    r₀ to between 0.93 and 1.8 r₀ and it turned from 90° to between −24° and 90° ..."."""
    f = facts
    return (f"**Here** (θ₀ = {f['theta0_deg']:g}°, F_N = {f['F_N']:.3g}): the support's length "
            f"went from r₀ to between {f['r_min']:.3g} and {f['r_max']:.3g} r₀, and it turned "
            f"from {f['theta0_deg']:g}° to between {f['theta_min']:.0f}° and "
            f"{f['theta_max']:.0f}° (ending at {f['theta_end']:.0f}°). It moved with the slab "
            f"(|v_R| < {STICK_SPEED:g} V₀) for {100 * f['stick_fraction']:.0f} % of a contact "
            f"{f['contact_over_L0']:.3g} times as long as on a rigid surface; "
            f"D_y/D_x = {f['Dy_over_Dx']:.3g}, U_el/W = {f['U_el_over_W']:.2f} when the slab "
            f"leaves. With every support at θ₀ = {f['theta0_deg']:g}° friction is "
            f"{change_words(f['FTx_over_mu0FN'])}.").replace("-", "−")  # minus signs


def regime_markdown(regime: str, data=None) -> str:
    """The regime's title and mechanism, then what the support of ``data`` (the state on
    screen, once computed) did; without it, a line that says it is being computed."""
    facts = motion_facts(data)
    if facts is not None:  # the computed state's own regime, not a newer slider's
        regime = classify(facts["k_r"], facts["k_theta"])
    title, mechanism = MECHANISMS[regime]
    here = motion_sentence(facts) if facts is not None else "*The motion is being computed.*"
    return f"**{title}.** {mechanism}\n\n{here}"


def plots_description(data) -> str:
    """What the One support tab's plots show for ``data`` (a ``SupportData``), in one
    short paragraph for screen readers (``app.views.access.LiveDescription``): the top
    view's swing and stretch (Eqs. 5-6), the time it moved with the slab (Eq. 4) and the
    friction change of the fixed array (Eq. 10)."""
    facts = motion_facts(data)
    if facts is None:
        return "The plots are being computed."
    f, regime = facts, classify(facts["k_r"], facts["k_theta"])
    return (f"Top view and friction histories, {regime} regime (k_r = {f['k_r']:.3g}, "
            f"k_θ = {f['k_theta']:.3g}, F_N = {f['F_N']:.3g}): the support turned from "
            f"{f['theta0_deg']:g}° to between {f['theta_min']:.0f}° and "
            f"{f['theta_max']:.0f}°, ending at {f['theta_end']:.0f}°, and its length went "
            f"from r₀ to between {f['r_min']:.3g} and {f['r_max']:.3g} r₀ while the slab "
            f"slid along +x; it moved with the slab for {100 * f['stick_fraction']:.0f} % of "
            f"the contact. Friction on the slab: {change_words(f['FTx_over_mu0FN'])}."
            ).replace("-", "−")
