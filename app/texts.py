"""Words on the page: the regimes' mechanisms (Figs. 5-7), the model's equations
(Eqs. 3-6, 8-13, as LaTeX; the constants quoted from ``model.params.DEFAULTS``) and short
help. Labels of quantities come from ``model.quantities.label``."""
from __future__ import annotations

from model.params import DEFAULTS as _D

_LAW = (f"μ_s = {_D['mu_s']:g}, A = {_D['A']:g}, B = {_D['B']:g}".replace("-", "−")
        + f", ζ = {_D['zeta']:g}")

#: regime -> (title, what the model does at theta0 = 90 deg, F_N = 1): numbers from
#: ``app.lesson.facts`` (tests/test_lesson.py); where the motion differs from the paper's
#: wording, the text says so.
MECHANISMS = {
    "pendulum": (
        "Pendulum (stiff radial, soft torsional spring)",
        "The support swings about its pivot: dragged forward, it turns from 90° through 0° to "
        "about −24° and back, and its stiff radial spring still stretches (r from 1 up to "
        "1.8 r₀ at F_N = 1), so it is not a rigid pendulum. The swing drives the mass "
        "sideways: the friction turns away from the sliding direction (F_f,y ≠ 0, "
        "D_y/D_x ≈ 0.08) and the slab needs about 5 % less force than on a rigid surface."),
    "slider": (
        "Slider (soft radial, stiff torsional spring)",
        "The soft radial spring lets the slab pull the mass far out: at θ₀ = 90° it stretches "
        "to about 10 r₀ while turning from 90° to 26° (the stiff torsional spring resists "
        "but does not keep the orientation, unlike the paper's picture). Supports leaning "
        "backwards (θ₀ ≫ 90°) are compressed instead. Contacts last up to six times longer "
        "than L₀, transverse dissipation is D_y/D_x ≈ 0.15 for θ₀ = 90°, and the force drops "
        "by 9-16 % (16 % for a fixed array at θ₀ = 90°)."),
    "stiff": (
        "Stiff (both springs stiff)",
        "The support is pushed forward -- at θ₀ = 90° it turns by about 35° and stretches to "
        "1.3 r₀ within two time units -- then rocks back and forth between about 60° and "
        "80°. It never slides slowly against the slab: the friction stays at μ₀ and along "
        "x, so there is no significant friction reduction (under 0.3 %) and almost no "
        "transverse dissipation (D_y/D_x < 0.01)."),
    "soft": (
        "Soft (both springs soft)",
        "The compliant support sticks to the slab (|v_R| < 0.1 V₀ for about 60 % of the "
        "contact) and is carried along, stretched to about 20 r₀, until the slab has passed. "
        "More than half of the slab's work ends up stored in the springs (U_el/W ≈ 0.55) "
        "rather than dissipated, the contact lasts almost three times L₀, and the force drops "
        "by about 16 %."),
}

EQUATIONS_INTRO = (
    "### The model (dimensionless; Sci. Rep. 11, 8093, 2021)\n"
    "Lengths in r₀, time τ = t V₀/r₀, forces in m V₀²/r₀. The slab slides at unit "
    "speed along +x; a support is a unit mass at **x** = (x, y) from its pivot, r = |**x**|, "
    "ê_r = **x**/r, ê_θ = (−y, x)/r, relative velocity **v**_R = **v** − î, load per "
    "support f_N = β F_N with β = N_c0/N_c.")

#: (caption, LaTeX) for each equation shown on the Equations tab.
EQUATIONS = [
    (f"**Repulsion near the pivot (Eq. 3)**, λ = {_D['lam']:g}",
     r"\phi(r) = \frac{e^{-r/\lambda}}{2\lambda}"),
    (f"**Friction law (Eq. 4)**, {_LAW} (V₀ = {_D['zeta']:g} V_s); μ₀ = μ(1)",
     r"\mu(v) = \mu_s \sin\Big(A \arctan\big\{\zeta v"
     r" - B\,[\zeta v - \arctan(\zeta v)]\big\}\Big)"),
    ("**Motion (Eq. 5)**",
     r"\begin{aligned}\mathbf{a} = &-\big[k_r (r - 1) - \phi(r)\big]\hat e_r"
     r" - \frac{k_\theta}{r}(\theta - \theta_0)\,\hat e_\theta \\"
     r" &- f_N\,\mu(|\mathbf{v}_R|)\,\frac{\mathbf{v}_R}{|\mathbf{v}_R|}\end{aligned}"),
    ("**Orientation (Eq. 6)**, unwrapped; the support starts at rest at (cos θ₀, sin θ₀)",
     r"\frac{d\theta}{d\tau} = \frac{x v_y - y v_x}{r^2}"),
    ("**Mean friction of a contact (Eq. 8)**; **its end (Eq. 9)**, "
     f"slab length L₀ = {_D['L0']:g}",
     r"\bar{\mathbf{F}}_f = \frac{1}{\tau_{out}}\int_0^{\tau_{out}} \mathbf{F}_f\, d\tau,"
     r"\qquad L_0 = -\int_0^{\tau_{out}} \mathbf{v}_R\cdot\hat{i}\; d\tau"),
    ("**Force on the slab (Eqs. 10, 11)**: mean over the supports (uniform θ₀, or one θ₀ "
     "for a fixed-orientation array)",
     r"\frac{F_{T,x}}{F_N} = \Big\langle \frac{\bar{\mathbf{F}}_f\cdot\hat{i}}{f_N}\Big\rangle,"
     r"\qquad \frac{F_{T,y}}{F_N}"
     r" = \Big\langle \frac{\bar{\mathbf{F}}_f\cdot\hat{j}}{f_N}\Big\rangle"),
    ("**Energy balance (Eq. 12)**: the slab's work is dissipated along x and y, stored in "
     "the springs, or left as kinetic energy",
     r"W = D_x + D_y + U_{el} + K"),
    ("**Dissipation (Eq. 13)**",
     r"\begin{aligned}D_x &= "
     r"-\Big\langle\int_0^{\tau_{out}} F_{f,x}\, v_{R,x}\, d\tau\Big\rangle \\"
     r" D_y &= -\Big\langle\int_0^{\tau_{out}} F_{f,y}\, v_{R,y}\, d\tau\Big\rangle\end{aligned}"),
]

EQUATIONS_NOTES = (
    "**Contact count**: dragged supports stay longer, N_c/N_c0 = ⟨τ_out⟩/L₀, so β = "
    "L₀/⟨τ_out⟩(β) is solved self-consistently unless fixed (Advanced options). "
    "**Averages of a uniform array**: *paper* (Eq. 10: the mean over supports of "
    "F̄_f,x/f_N) or *duration-weighted* (Σ∫F_f,x dτ / (f_N Σ τ_out), the steady force when "
    "contacts last different times).")

HELP = (
    "One elastic support dragged by a sliding slab (Sci. Rep. 11, 8093, 2021), in "
    "dimensionless units. Move the sliders or press a regime button; the support tab updates live. "
    "Click a polar plot to set θ₀, click the regime map to set k_r and k_θ. "
    "Pin as A keeps this state, drawn dashed beside the next one you explore. "
    "The address bar always holds the current view: copy it to share.")
