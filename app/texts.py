"""Words on the page: the regimes' mechanisms (Figs. 5-7), the model's equations
(Eqs. 3-6, 8-13, as LaTeX; the constants quoted from ``model.contact.params.DEFAULTS``) and short
help. Labels of quantities come from ``model.arrays.quantities.label``."""
from __future__ import annotations

from model.contact.params import DEFAULTS as _D

_LAW = (f"μ_s = {_D['mu_s']:g}, A = {_D['A']:g}, B = {_D['B']:g}".replace("-", "−")
        + f", ζ = {_D['zeta']:g}")

#: regime -> (title, mechanism): what the springs of the regime let the support do (the
#: paper's Figs. 5-7), in words true of any state of the regime. The numbers of the state
#: on screen (stretch, swing, sticking, friction change) are written from its computed
#: motion (``app.motion_words``), never fixed per preset.
MECHANISMS = {
    "pendulum": (
        "Pendulum (stiff radial, soft torsional spring)",
        "The soft torsional spring lets the support swing about its pivot, while the stiff "
        "radial spring resists (but does not forbid) stretching. While the mass moves "
        "sideways, the friction turns away from the sliding direction (F_f,y ≠ 0): part of "
        "the work is dissipated across it (D_y) and less force resists the slab."),
    "slider": (
        "Slider (soft radial, stiff torsional spring)",
        "The soft radial spring lets the slab pull the mass out (supports leaning forward "
        "are stretched, those leaning backwards, θ₀ ≫ 90°, are compressed) while the stiff "
        "torsional spring resists turning. A mass carried along rubs at low relative speed, "
        "where μ is smaller, and part of the slab's work is stored in the stretched spring."),
    "stiff": (
        "Stiff (both springs stiff)",
        "Both springs resist the slab: the support is pushed a little and rocks, but hardly "
        "slides slowly against the slab, so the friction stays close to μ₀ and along x."),
    "soft": (
        "Soft (both springs soft)",
        "Both springs give: the support can stick to the slab and be carried along, "
        "stretched, until the slab has passed. Part of the slab's work is stored in the "
        "springs (U_el) rather than dissipated, and while the mass sticks, the small "
        "elastic force, not sliding friction, resists the slab."),
}

#: The average of the uniform array a class sees (headline, Array tab): the force the slab
#: feels when contacts last different times (docs/model.md, "Arrays"), and its words.
FELT_AVERAGE = "duration"
FELT_WORDS = "each support counted for as long as it touches the slab"
#: The two averages of a uniform array as the folded details name them.
AVERAGE_NAMES = {
    "duration": "duration-weighted: the force the slab feels (headline)",
    "paper": "paper, Eq. 10: each support counted once"}

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
