"""The dashboard's controls: each one's bounds or choices and its default, defined once.

The physics' ranges and defaults are the model's (``model.controls``: the paper's map, the
loads of Fig. 6, the tolerances, the orientation distribution of a design); only the
page's own choices (tabs, averages, projector mode) and the Design tab's inputs (their
URL keys, labels and the example pillars' values) are defined here. The state
(``app.state``), the sliders, the URL (``app.urlstate``) and the pinned state of a
comparison (``app.pinned_state``) read them from here.
"""
from __future__ import annotations

from model.controls import CONTROLS
from model.lab.friction_law import COEFFICIENTS
from model.arrays.quantities import AVERAGES as _AVERAGES, MAP_FIGURES
from model.designs.units import PillarDesign, quantity

K_BOUNDS = CONTROLS["k_r"].bounds
F_N_BOUNDS = CONTROLS["F_N"].bounds
#: The fixed load factor beta = N_c0/N_c, bounded below by the physical limit of the model
#: (``model.validation.BETA``).
BETA_BOUNDS = CONTROLS["beta"].bounds
THETA0_DEG = CONTROLS["theta0_deg"].interval
RTOLS = CONTROLS["rtol"].choices
TABS = ("support", "array", "polar", "map", "load", "equations", "design")
ORIENTATIONS = ("uniform", "fixed")
AVERAGES = tuple(_AVERAGES)
MAP_QUANTITIES = tuple(MAP_FIGURES)

#: The default view: the pendulum support of Fig. 7a (theta0 = 90 deg, F_N = 1).
DEFAULTS = dict(k_r=CONTROLS["k_r"].default, k_theta=CONTROLS["k_theta"].default,
                F_N=CONTROLS["F_N"].default, theta0=CONTROLS["theta0_deg"].default,
                rtol=CONTROLS["rtol"].default, beta_mode=CONTROLS["beta_mode"].default,
                beta=CONTROLS["beta"].default, average=AVERAGES[0],
                map_quantity=MAP_QUANTITIES[0], tab="support", projector=False,
                orientation="uniform", play=False, pinned=None)

# ---------------------------------------------------------------- Design tab
#: The default pillars: the LDPE example of the notes (``PillarDesign.example``) at V0 = 1
#: m/s, not 1 cm/s, where k~ ~ 5e6 lies beyond the model range, is computed scaled to 1e6
#: and its array costs minutes; at 1 m/s k~_r ~ 550, k~_theta ~ 4900 (outside the paper's
#: map, stiff) compute in seconds. The speed line on the map shows both.
_EXAMPLE = PillarDesign.example(V0="1 m/s").to_dict()
#: The display unit of each velocity input (the example's cm/s reads badly at 1 m/s).
_SHOWN_UNIT = {"V0": "m/s"}


def _example_text(field: str) -> str:
    value, unit = _EXAMPLE.get(field), _SHOWN_UNIT.get(field, _EXAMPLE["units"].get(field, ""))
    if value is None:
        return ""
    if field in _SHOWN_UNIT:
        value = quantity(field, f"{value} {_EXAMPLE['units'][field]}").to(unit).magnitude
    return f"{value:.6g} {unit}".strip()


#: Design inputs: state parameter -> (URL key, ``PillarDesign`` field, label, what it is).
#: The text of each is a quantity with its unit, parsed by ``model.designs.units`` (pint).
DESIGN_INPUTS = {
    "design_D": ("d_D", "D", "D", "pillar diameter D"),
    "design_h": ("d_h", "h", "h", "pillar height h"),
    "design_E": ("d_E", "E", "E", "Young's modulus E"),
    "design_G": ("d_G", "G", "G (or ν)", "shear modulus G (empty: G = E/(2(1+ν)))"),
    "design_nu": ("d_nu", "nu", "ν", "Poisson's ratio ν (used when G is empty)"),
    "design_rho": ("d_rho", "rho", "ρ", "density ρ of the pillar"),
    "design_r0": ("d_r0", "r0", "r₀", "radial rest length r₀"),
    "design_d_x": ("d_dx", "d_x", "d_x", "pillar spacing along x"),
    "design_d_y": ("d_dy", "d_y", "d_y", "pillar spacing along y"),
    "design_L_x": ("d_Lx", "L_x", "L_x", "slab length L_x along the sliding direction"),
    "design_L_y": ("d_Ly", "L_y", "L_y", "slab width L_y"),
    "design_F_N": ("d_FN", "F_N", "F_N (total)", "total normal load F_N on the slab"),
    "design_V0": ("d_V0", "V0", "V₀", "sliding speed V₀"),
    "design_V_s": ("d_Vs", "V_s", "V_s", "velocity scale V_s of the friction law (ζ = V₀/V_s)"),
    "design_mu_s": ("d_mus", "mu_s", "μ_s", "static friction coefficient μ_s of the friction "
                                          "law (Eq. 4)"),
    "design_A": ("d_A", "A", "A", "shape A of the friction law (Eq. 4)"),
    "design_B": ("d_B", "B", "B", "shape B of the friction law (Eq. 4)"),
}
#: The design inputs that make its friction law, Eq. (4) (``model.FrictionLaw``).
LAW_INPUTS = tuple(name for name, v in DESIGN_INPUTS.items() if v[1] in COEFFICIENTS)
DESIGN_DEFAULTS = {name: _example_text(v[1]) for name, v in DESIGN_INPUTS.items()}
#: Orientation distributions the Design tab edits (``model.controls``).
DIST_FAMILIES = CONTROLS["dist_family"].choices
KAPPA_BOUNDS = CONTROLS["kappa"].bounds
PSI_BOUNDS = CONTROLS["psi_deg"].bounds
DIST_DEG = CONTROLS["dist_deg"].interval
MIX_BOUNDS = CONTROLS["mix_weight"].bounds
BOUND_BOUNDS = CONTROLS["bound"].bounds
DEFAULTS.update(DESIGN_DEFAULTS, dist_family=CONTROLS["dist_family"].default,
                dist_deg=CONTROLS["dist_deg"].default, dist_kappa=CONTROLS["kappa"].default,
                dist_psi=CONTROLS["psi_deg"].default, mix_weight=CONTROLS["mix_weight"].default,
                dist2_family=CONTROLS["dist2_family"].default,
                dist2_deg=CONTROLS["dist2_deg"].default, dist2_kappa=CONTROLS["kappa"].default,
                dist_hist=None, opt_objective=CONTROLS["objective"].default,
                opt_bound=CONTROLS["bound"].default)
