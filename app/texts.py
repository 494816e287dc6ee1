"""Words on the page: the regimes' mechanisms (Figs. 5-7), the model's equations
(Eqs. 3-6, 8-13, as LaTeX) and short help."""
from __future__ import annotations

#: regime -> (title, two-sentence mechanism), after the paper's discussion of Figs. 5-7.
MECHANISMS = {
    "pendulum": (
        "Pendulum (stiff radial, soft torsional spring)",
        "The support keeps its length and swings about its pivot, so friction drives it "
        "sideways as well as forward. The transverse oscillation turns the relative velocity "
        "away from the sliding direction (F_f,y ≠ 0, D_y > 0), which moderately lowers the "
        "apparent friction."),
    "slider": (
        "Slider (soft radial, stiff torsional spring)",
        "The support keeps its orientation and is stretched (θ₀ ≤ 90°) or compressed "
        "(θ₀ ≫ 90°) along it while the slab drags it. Its radial vibration has a transverse "
        "component, so part of the work is dissipated along y and the apparent friction drops "
        "moderately."),
    "stiff": (
        "Stiff (both springs stiff)",
        "The support barely moves, so the slab slides over it at nearly the full relative "
        "speed, as on a rigid surface. There is no significant friction reduction and "
        "almost no transverse dissipation (D_y/D_x ≈ 0)."),
    "soft": (
        "Soft (both springs soft)",
        "The compliant support is carried along with the slab in long sticky phases "
        "(|v_R| ≈ 0) where only the small elastic force opposes the slab. Much of the slab's "
        "work is stored in the springs rather than dissipated, which gives the lowest "
        "apparent friction."),
}

EQUATIONS_INTRO = (
    "### The model (dimensionless; Sci. Rep. 11, 8093, 2021)\n"
    "Lengths in r₀, time τ = t V₀/r₀, forces in m V₀²/r₀. The slab slides at unit "
    "speed along +x; a support is a unit mass at **x** = (x, y) from its pivot, r = |**x**|, "
    "ê_r = **x**/r, ê_θ = (−y, x)/r, relative velocity **v**_R = **v** − î, load per "
    "support f_N = β F_N with β = N_c0/N_c.")

#: (caption, LaTeX) for each equation shown on the Equations tab.
EQUATIONS = [
    ("**Repulsion near the pivot (Eq. 3)**, λ = 0.05",
     r"\phi(r) = \frac{e^{-r/\lambda}}{2\lambda}"),
    ("**Friction law (Eq. 4)**, μ_s = 1.3, A = 1.44, B = −20, ζ = 10 (V₀ = 10 V_s); "
     "μ₀ = μ(1)",
     r"\mu(v) = \mu_s \sin\Big(A \arctan\big\{\zeta v"
     r" - B\,[\zeta v - \arctan(\zeta v)]\big\}\Big)"),
    ("**Motion (Eq. 5)**",
     r"\begin{aligned}\mathbf{a} = &-\big[k_r (r - 1) - \phi(r)\big]\hat e_r"
     r" - \frac{k_\theta}{r}(\theta - \theta_0)\,\hat e_\theta \\"
     r" &- f_N\,\mu(|\mathbf{v}_R|)\,\frac{\mathbf{v}_R}{|\mathbf{v}_R|}\end{aligned}"),
    ("**Orientation (Eq. 6)**, unwrapped; the support starts at rest at (cos θ₀, sin θ₀)",
     r"\frac{d\theta}{d\tau} = \frac{x v_y - y v_x}{r^2}"),
    ("**Mean friction of a contact (Eq. 8)**; **its end (Eq. 9)**, slab length L₀ = 10",
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
    "The address bar always holds the current view: copy it to share.")
