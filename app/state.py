"""Per-session state of the dashboard: every control, and the ``model.Params`` they make.

``ExplorerState`` holds what the user set: the springs k_r, k_theta and the load F_N
(Eq. 5), the rest orientation theta0 (in degrees, as on the slider), the solver
tolerance, the load factor beta = N_c0/N_c (self-consistent or fixed), which uniform
average is shown (paper, Eq. 10, or duration-weighted), the regime-map quantity
(Fig. 5a or 5b), the visible tab and projector mode, and the pinned state "A" of a
comparison. Views read it and never own it; the URL mirrors it (``app.urlstate``).
"""
from __future__ import annotations

import math

import param

from model import REGIMES, FrictionLaw, Params
from model.controls import OBJECTIVES
from model.designs.units import to_si, ureg

from .pinned_state import PINNED_ALL, PINNED_DIST_KEYS, PINNED_KEYS, complete
from .defaults import (AVERAGES, BETA_BOUNDS, BOUND_BOUNDS, DEFAULTS, DESIGN_INPUTS,
                       DIST_FAMILIES, F_N_BOUNDS, K_BOUNDS, KAPPA_BOUNDS, LAW_INPUTS,
                       MAP_QUANTITIES, MIX_BOUNDS, ORIENTATIONS, PSI_BOUNDS, RTOLS, TABS)
from .urlstate import parse, serialize, to_search

#: Preset buttons: regime -> (k_r, k_theta) (Fig. 6 caption).
PRESETS = {name: (p.k_r, p.k_theta) for name, p in REGIMES.items()}

#: Boundary between "stiff" and "compliant" springs: the log-midpoint of [0.01, 3].
K_MID = math.sqrt(K_BOUNDS[0] * K_BOUNDS[1])

#: Parameters that change a single support (and so the Support tab).
SUPPORT_KEYS = ("k_r", "k_theta", "F_N", "theta0", "rtol", "beta_mode", "beta")
assert set(PINNED_KEYS) == set(SUPPORT_KEYS), "a pinned state keeps what makes a support"
#: Parameters that change the fixed-orientation sweeps (Fig. 11): not theta0.
SWEEP_KEYS = ("k_r", "k_theta", "F_N", "rtol", "beta_mode", "beta")
#: Parameters that change the uniform arrays (Figs. 5, 6).
ARRAY_KEYS = ("k_r", "k_theta", "F_N", "beta_mode", "beta")
#: Parameters carried by the URL.
URL_KEYS = tuple(DEFAULTS)
#: Parameters that change the Design tab's pillar array (its dimensionless point).
DESIGN_KEYS = tuple(DESIGN_INPUTS)
#: Parameters of the Design tab's orientation distribution.
DIST_KEYS = ("dist_family", "dist_deg", "dist_kappa", "dist_psi", "mix_weight", "dist2_family",
             "dist2_deg", "dist2_kappa", "dist_hist")
assert DIST_KEYS == PINNED_DIST_KEYS, "a pinned state keeps the Design tab's distribution"
#: The Design tab's friction-velocity curve: default speeds, their number and the most.
SPEEDS_RANGE, SPEEDS_N, MAX_SPEEDS = "0.1 m/s..1 m/s", 12, 60
#: Parameters of what "Optimise" seeks on the Design tab.
OPTIMUM_KEYS = ("opt_objective", "opt_bound")
#: Parameters of how the page is shown, not of the physics: Reset keeps them.
VIEW_KEYS = ("tab", "projector", "pinned")


def classify(k_r: float, k_theta: float) -> str:
    """The regime of Fig. 5a a pair of stiffnesses falls in (quadrants about ``K_MID``)."""
    stiff_r, stiff_t = k_r >= K_MID, k_theta >= K_MID
    return {(True, True): "stiff", (True, False): "pendulum",
            (False, True): "slider", (False, False): "soft"}[(stiff_r, stiff_t)]


def clamp(value: float, bounds: tuple[float, float]) -> float:
    """``value`` moved into the closed interval ``bounds`` (rounding off log sliders)."""
    return min(max(float(value), bounds[0]), bounds[1])


def _component(family: str, deg: float, kappa: float, hist: dict | None = None) -> dict:
    """One component of the editor as ``model.designs.distributions.from_dict`` reads it (the
    histogram family without an uploaded histogram is uniform)."""
    if family == "histogram" and hist:
        return {"family": "histogram", **hist}
    if family in ("fixed", "pair"):
        return {"family": family, "theta0_deg": float(deg)}
    if family == "vonmises":
        return {"family": family, "mean_deg": float(deg), "kappa": float(kappa)}
    return {"family": "uniform"}


def _editor_values(d: dict, which: str) -> dict:
    """State values of component ``which`` ("" or "2") from a ``to_dict`` form."""
    values = {f"dist{which}_family": d["family"]}
    if d["family"] == "histogram":
        values["dist_hist"] = {"edges_deg": list(d["edges_deg"]), "weights": list(d["weights"])}
    angle = d.get("theta0_deg", d.get("mean_deg"))
    if angle is not None:
        values[f"dist{which}_deg"] = float(angle) % 360.0
    if "kappa" in d:
        values[f"dist{which}_kappa"] = clamp(d["kappa"], KAPPA_BOUNDS)
    return values


def distribution_of(values) -> dict:
    """The orientation distribution of the Design tab's ``values`` (a mapping holding
    ``DIST_KEYS``: the state's, or a pinned state's), as ``model.designs.distributions.from_dict``
    reads it (angles in degrees; psi is separate): one component, or with ``mix_weight``
    > 0 the mixture of two weighted components."""
    hist = values.get("dist_hist")
    first = _component(values["dist_family"], values["dist_deg"], values["dist_kappa"], hist)
    w = float(values["mix_weight"])
    if w <= 0.0:
        return first
    second = _component(values["dist2_family"], values["dist2_deg"], values["dist2_kappa"],
                        hist)
    if w >= 1.0:
        return second
    return {"family": "mixture", "components": [first, second], "weights": [1.0 - w, w]}


def _design_parameters() -> dict:
    return {name: param.String(DEFAULTS[name], doc=f"Design tab: the {what}, a quantity with "
                               f"its unit such as {DEFAULTS[name] or '0.36 GPa'!r}")
            for name, (_, _, _, what) in DESIGN_INPUTS.items()}


class ExplorerState(param.Parameterized):
    """The controls of one browser session (the issue's list "What users see and do", 1)."""

    k_r = param.Number(DEFAULTS["k_r"], bounds=K_BOUNDS, doc="radial stiffness k~_r (Eq. 5)")
    k_theta = param.Number(DEFAULTS["k_theta"], bounds=K_BOUNDS,
                           doc="torsional stiffness k~_theta (Eq. 5)")
    F_N = param.Number(DEFAULTS["F_N"], bounds=F_N_BOUNDS, doc="normal load F~_N on the slab")
    theta0 = param.Number(DEFAULTS["theta0"], bounds=(0.0, 360.0),
                          inclusive_bounds=(True, False),
                          doc="rest orientation theta0 in degrees from the sliding direction +x")
    rtol = param.Selector(default=DEFAULTS["rtol"], objects=list(RTOLS),
                          doc="relative tolerance of the single-support integration")
    beta_mode = param.Selector(default=DEFAULTS["beta_mode"], objects=["self", "fixed"],
                               doc="load factor beta = N_c0/N_c: self-consistent or fixed")
    beta = param.Number(DEFAULTS["beta"], bounds=BETA_BOUNDS, inclusive_bounds=(True, True),
                        doc="the fixed load factor (used when beta_mode is 'fixed')")
    average = param.Selector(default=DEFAULTS["average"], objects=list(AVERAGES),
                             doc="uniform-array average: paper (Eq. 10) or duration-weighted")
    map_quantity = param.Selector(default=DEFAULTS["map_quantity"], objects=list(MAP_QUANTITIES),
                                  doc="regime map of F_T,x/(mu0 F_N) (Fig. 5a) or D_y/D_x (5b)")
    tab = param.Selector(default=DEFAULTS["tab"], objects=list(TABS), doc="the visible tab")
    projector = param.Boolean(DEFAULTS["projector"],
                              doc="large fonts, thick lines, high contrast for projection")
    orientation = param.Selector(default=DEFAULTS["orientation"], objects=list(ORIENTATIONS),
                                 doc="orientations of the array under the slab: theta0 "
                                     "uniform, or every support at theta0")
    play = param.Boolean(DEFAULTS["play"], doc="start the animations when the page opens")
    notice = param.String("", doc="a message for the page (unusable URL values)")
    pinned = param.Dict(None, allow_None=True, doc=(
        "the pinned state A of a comparison ({name: value} of app.pinned_state.PINNED_ALL:"
        " the support's inputs and the Design tab's), or None"))

    # ------------------------------------------------------------------ Design tab
    # A pillar array in physical units (text with units, parsed by model.designs.units): set below
    # from ``DESIGN_INPUTS``, one String parameter per input.
    dist_family = param.Selector(default=DEFAULTS["dist_family"], objects=list(DIST_FAMILIES),
                                 doc="Design tab: the family of the orientation distribution")
    dist_deg = param.Number(DEFAULTS["dist_deg"], bounds=(0.0, 360.0),
                            inclusive_bounds=(True, False),
                            doc="Design tab: theta0 (fixed, pair) or the von Mises mean, degrees")
    dist_kappa = param.Number(DEFAULTS["dist_kappa"], bounds=KAPPA_BOUNDS,
                              doc="Design tab: the von Mises concentration kappa (0: uniform)")
    dist_psi = param.Number(DEFAULTS["dist_psi"], bounds=PSI_BOUNDS,
                            doc="Design tab: the sliding direction psi to the array, degrees")
    mix_weight = param.Number(DEFAULTS["mix_weight"], bounds=MIX_BOUNDS,
                              doc="Design tab: weight of a second component (0: no mixture)")
    dist2_family = param.Selector(default=DEFAULTS["dist2_family"], objects=list(DIST_FAMILIES),
                                  doc="Design tab: the family of the second component")
    dist2_deg = param.Number(DEFAULTS["dist2_deg"], bounds=(0.0, 360.0),
                             inclusive_bounds=(True, False),
                             doc="Design tab: the second component's theta0 or mean, degrees")
    dist2_kappa = param.Number(DEFAULTS["dist2_kappa"], bounds=KAPPA_BOUNDS,
                               doc="Design tab: the second component's concentration kappa")
    dist_hist = param.Dict(None, allow_None=True, doc=(
        "Design tab: the uploaded orientation histogram {'edges_deg': [...], 'weights': "
        "[...]} (app.histogram), used by the 'histogram' family; None: none uploaded"))
    opt_objective = param.Selector(default=DEFAULTS["opt_objective"], objects=list(OBJECTIVES),
                                   doc="Design tab: Optimise seeks the least F_T,x (min-FTx) "
                                       "or the largest |F_T,y| (max-FTy)")
    opt_bound = param.Number(DEFAULTS["opt_bound"], bounds=BOUND_BOUNDS, allow_None=True,
                             doc="Design tab: the bound on |F_T,y|/(mu0 F_N) (min-FTx) or "
                                 "F_T,x/(mu0 F_N) (max-FTy); None: no bound")

    friction_curve = param.Parameter(None, doc=(
        "Design tab: the measured friction curve uploaded (a model.FrictionCurve, speeds in "
        "m/s) that the friction law is fitted to; None: none uploaded. Not in the URL."))
    speeds_range = param.String(SPEEDS_RANGE, doc=(
        "Design tab: the sliding speeds of the structured surface's friction-velocity "
        "curve, 'LO..HI' with units (model.lab.speed_curve.parse_speeds). Not in the URL."))
    speeds_n = param.Integer(SPEEDS_N, bounds=(2, MAX_SPEEDS), doc=(
        "Design tab: how many speeds, evenly spaced in log. Not in the URL."))
    structured_curve = param.Parameter(None, doc=(
        "Design tab: the structured sample's measured friction curve uploaded (a "
        "model.FrictionCurve, speeds in m/s), compared with the prediction; None: none"))

    @property
    def friction_law(self) -> FrictionLaw:
        """The Design tab's friction law, Eq. (4), from its four inputs (``LAW_INPUTS``; an
        empty V_s: V0/zeta); ``ValueError`` naming an unusable coefficient."""
        texts = {DESIGN_INPUTS[name][1]: getattr(self, name).strip() for name in LAW_INPUTS}
        return FrictionLaw(**{k: to_si(k, v) for k, v in texts.items() if k != "V_s"},
                           V_s=texts["V_s"] or None)

    def set_friction_law(self, law: FrictionLaw) -> None:
        """Set the four inputs to ``law`` (e.g. a fit's), 6 significant digits as the URL
        keeps them, V_s with the SI prefix that reads best (``1.06501 mm/s``)."""
        values = {"mu_s": f"{law.mu_s:.6g}", "A": f"{law.A:.6g}", "B": f"{law.B:.6g}",
                  "V_s": ""}
        if law.V_s is not None:
            q = ureg.Quantity(law.V_s, "m/s").to_compact()
            values["V_s"] = f"{q.magnitude:.6g} {q.units:~P}"
        self.param.update(**{name: values[DESIGN_INPUTS[name][1]] for name in LAW_INPUTS})

    @property
    def design_inputs(self) -> dict:
        """The Design tab's ``PillarDesign`` keyword arguments (texts with units): G when
        it is given, else Poisson's ratio nu."""
        out = {v[1]: getattr(self, name) for name, v in DESIGN_INPUTS.items()}
        if out["G"].strip():
            out.pop("nu")
        else:
            out.pop("G")
        return out

    @property
    def distribution(self) -> dict:
        """The Design tab's orientation distribution (``distribution_of`` its values)."""
        return distribution_of({name: getattr(self, name) for name in DIST_KEYS})

    def set_distribution(self, d: dict) -> None:
        """Set the editor from a distribution's ``to_dict`` (e.g. an optimum); a mixture
        of two components fills both, with the second's weight."""
        if d["family"] == "mixture" and len(d["components"]) == 2:
            (a, b), (wa, wb) = d["components"], d["weights"]
            self.param.update(**_editor_values(a, ""), **_editor_values(b, "2"),
                              mix_weight=clamp(wb / (wa + wb), MIX_BOUNDS))
            return
        self.param.update(**_editor_values(d, ""), mix_weight=0.0)

    # ------------------------------------------------------------------ model inputs
    @property
    def support(self) -> Params:
        """The support and its load (k_r, k_theta, F_N): what the array functions take.

        An array covers its own orientations (a sweep's theta0 values, the uniform
        array's circle) and takes its load factor as its ``beta`` argument
        (``array_beta``), so neither is set here.
        """
        return Params(k_r=self.k_r, k_theta=self.k_theta, F_N=self.F_N)

    @property
    def params(self) -> Params:
        """One support at the slider's rest orientation: ``support`` with theta0 (radians).

        Its load factor is the array's (``array_beta``, solved or fixed): the support's
        contact is integrated with the beta its fixed-orientation array returns
        (``worker.compute_support``).
        """
        return self.support.replace(theta0=math.radians(self.theta0))

    @property
    def array_beta(self):
        """The ``beta`` argument of the array functions: ``"self"`` or the fixed value."""
        return "self" if self.beta_mode == "self" else float(self.beta)

    @property
    def regime(self) -> str:
        """The regime (pendulum, slider, stiff, soft) of the current springs."""
        return classify(self.k_r, self.k_theta)

    def values(self) -> dict:
        """The current value of every URL-carried parameter."""
        return {name: getattr(self, name) for name in URL_KEYS}

    # ------------------------------------------------------------------ actions
    def apply_preset(self, name: str) -> None:
        """Set k_r, k_theta to a regime of the paper (pendulum, slider, stiff, soft)."""
        if name not in PRESETS:
            raise ValueError(f"preset={name!r} is unknown; choose one of {sorted(PRESETS)}")
        k_r, k_theta = PRESETS[name]
        self.param.update(k_r=k_r, k_theta=k_theta)

    def set_stiffness(self, k_r: float, k_theta: float) -> None:
        """Set both stiffnesses (clamped into range), e.g. from a click on the regime map."""
        self.param.update(k_r=clamp(k_r, K_BOUNDS), k_theta=clamp(k_theta, K_BOUNDS))

    def set_theta0(self, degrees: float) -> None:
        """Set theta0 from any angle in degrees (wrapped into [0, 360), whole degrees)."""
        self.theta0 = float(round(float(degrees)) % 360)

    def reset(self) -> None:
        """Every control back to its default; the view stays (tab and projector mode: a
        teacher resetting the physics keeps the projected page as it is)."""
        self.param.update(**{k: v for k, v in DEFAULTS.items() if k not in VIEW_KEYS},
                          notice="")

    # ------------------------------------------------------------------ compare
    def snapshot(self) -> dict:
        """The controls a pinned state keeps (``PINNED_ALL``: the support's and the Design
        tab's), as they are now."""
        return {name: getattr(self, name) for name in PINNED_ALL}

    def pin(self) -> None:
        """Pin the current state as "A"; the controls go on as "B"."""
        self.pinned = self.snapshot()

    def clear_pin(self) -> None:
        self.pinned = None

    def swap_pin(self) -> None:
        """Exchange A and B: the controls take the pinned state, which pins the current one."""
        if self.pinned is None:
            return
        a, b = complete(self.pinned), self.snapshot()
        self.param.update(**a, pinned=b)

    # ------------------------------------------------------------------ URL
    def to_query(self) -> dict[str, str]:
        """URL query parameters of the current state (``app.urlstate.serialize``)."""
        return serialize(self.values())

    def to_search(self) -> str:
        """The URL search string of the current state, ``?k_r=...``."""
        return to_search(self.values())

    def load_query(self, query) -> list[str]:
        """Apply URL ``query`` (mapping or search string); unusable values keep defaults.

        Returns the notices, which are also shown on the page through ``notice``.
        """
        values, notices = parse(query)
        self.param.update(**values, notice=" ".join(notices))
        return notices

    def restore_query(self, query) -> list[str]:
        """The state URL ``query`` describes, exactly: what it does not name goes back to
        its default (Back/Forward to an address). Returns the notices, as ``load_query``."""
        values, notices = parse(query)
        self.param.update(**{**DEFAULTS, **values}, notice=" ".join(notices))
        return notices

    def matching_preset(self) -> str | None:
        """The regime preset whose k_r, k_theta are the current springs, if any."""
        for name, (k_r, k_theta) in PRESETS.items():
            if math.isclose(self.k_r, k_r, rel_tol=1e-6) and \
                    math.isclose(self.k_theta, k_theta, rel_tol=1e-6):
                return name
        return None


# One String parameter per design input (``DESIGN_INPUTS``), so the list lives in one place.
for _name, _p in _design_parameters().items():
    ExplorerState.param.add_parameter(_name, _p)
