"""Where a pillar design (``model.designs.units.PillarDesign``) sits on the paper's map, and its
array in physical units.

* ``regime_intervals``: the sliding speeds V0 (and pillar heights h) at which the design
  lies in each regime; both k~ scale as 1/V0^2, so the speed moves a design along a
  diagonal of the log-log map (``speed_line``);
* ``model_point`` / ``model_params``: the dimensionless point the model computes, which is
  the design's own inside the model range and otherwise the point of its speed line
  where it enters the range (``POINT_STATUS``);
* ``evaluate``: the array for an orientation distribution (Eq. 10), with the drive force,
  power, contact time and excursions back in physical units (``DesignPoint``), each with
  the array's error bar carried over (``PHYSICAL``; ``model.designs.design_table`` says them
  with SI prefixes, as a table, a CSV file and a one-sentence headline).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..contact.params import Params
from ..contact.regimes import EXPLORED_MAP, MAP_NOTE, MODEL_RANGE, REGIME_SPLIT, map_status, regime_of
from .units import F_N_MAX, PillarDesign, to_si

__all__ = ["regime_intervals", "speed_line", "POINT_STATUS", "model_point", "model_params",
           "DesignPoint", "evaluate", "PHYSICAL"]

#: A design's results in physical units: key of ``DesignPoint`` -> (what it is, SI unit).
PHYSICAL = {
    "FTx_N": ("drive force F_T,x", "N"),
    "FTy_N": ("sideways force F_T,y", "N"),
    "power_W": ("power F_T,x V₀", "W"),
    "dissipated_power_W": ("dissipated power", "W"),
    "contact_time_s": ("contact time", "s"),
    "excursion_r_um": ("excursion of r (rms)", "um"),
    "excursion_theta_um": ("excursion of θ (rms, arc at r₀)", "um"),
}


def _intervals(a: float, b: float) -> dict:
    """Regimes against a variable x where k~_r > split for x < a and k~_theta > split for x < b."""
    lo, hi = min(a, b), max(a, b)
    middle = "slider" if a < b else "pendulum"
    other = "pendulum" if middle == "slider" else "slider"
    out = {"stiff": (0.0, lo), middle: (lo, hi), "soft": (hi, math.inf), other: None}
    if a == b:
        out[middle] = None
    return out


def regime_intervals(design: PillarDesign) -> dict:
    """For each regime, the sliding speeds V0 (m/s) and pillar heights h (m) at which the
    design would lie in it, as (low, high) intervals; None when out of reach.

    k~_r and k~_theta both scale as V0^-2 (a diagonal of the log-log map); with the height,
    k~_r ~ h^-4 and k~_theta ~ h^-2 (m ~ h), everything else held.
    """
    d = design.dimensionless()
    speed = _intervals(design.V0 * math.sqrt(d["k_r"] / REGIME_SPLIT),
                       design.V0 * math.sqrt(d["k_theta"] / REGIME_SPLIT))
    height = _intervals(design.h * (d["k_r"] / REGIME_SPLIT) ** 0.25,
                        design.h * (d["k_theta"] / REGIME_SPLIT) ** 0.5)
    lo_map, hi_map = EXPLORED_MAP
    inside = (max(design.V0 * math.sqrt(d[k] / hi_map) for k in ("k_r", "k_theta")),
              min(design.V0 * math.sqrt(d[k] / lo_map) for k in ("k_r", "k_theta")))
    return {"V0_m_per_s": speed, "h_m": height,
            "V0_in_explored_map_m_per_s": inside if inside[0] <= inside[1] else None}


def speed_line(design: PillarDesign, V_min=None, V_max=None, n: int = 61) -> dict:
    """The design's path on the log-log map as the sliding speed changes: arrays of V0
    (m/s) and the k~_r, k~_theta, F~_N it gives (all three scale as V0^-2: a diagonal).

    ``V_min``, ``V_max`` (quantities or text) default to the speeds that span the model
    range [1e-3, 1e6] for the larger and the smaller stiffness."""
    d = design.dimensionless()
    lo_k, hi_k = MODEL_RANGE
    k_max, k_min = max(d["k_r"], d["k_theta"]), min(d["k_r"], d["k_theta"])
    v_lo = design.V0 * math.sqrt(k_max / hi_k) if V_min is None else to_si("V0", V_min)
    v_hi = design.V0 * math.sqrt(k_min / lo_k) if V_max is None else to_si("V0", V_max)
    if isinstance(n, bool) or not isinstance(n, int) or n < 2:
        raise ValueError(f"n={n!r} must be a whole number >= 2")
    if not v_lo < v_hi:
        raise ValueError(f"V_min={V_min!r}, V_max={V_max!r}: the lower speed must be below the "
                         f"upper one")
    V = np.geomspace(v_lo, v_hi, n)
    scale = (design.V0 / V) ** 2
    return {"V0_m_per_s": V, "k_r": d["k_r"] * scale, "k_theta": d["k_theta"] * scale,
            "F_N": d["F_N"] * scale}


#: How a design's dimensionless point relates to what the model covers.
POINT_STATUS = {
    "in_map": f"inside the paper's explored map {list(EXPLORED_MAP)}^2",
    "outside_map": f"{MAP_NOTE} (inside the model range {list(MODEL_RANGE)}^2)",
    "scaled": (f"a stiffness above {MODEL_RANGE[1]:g} or a load F~_N above {F_N_MAX:g}: "
               f"computed at the point of the design's speed line where both enter the model "
               f"range (k~_r, k~_theta and F~_N scaled together, as by a faster slab; zeta "
               f"kept). The deflections F~_N/k~ are kept, so for stiff pillars this is their "
               f"quasi-static (rigid-mass) limit"),
}


def model_point(design: PillarDesign) -> tuple[dict, str, str]:
    """The dimensionless point the model computes for ``design`` (k_r, k_theta, F_N, zeta,
    L0 and the ``scale`` applied), its status (a key of ``POINT_STATUS``) and a message;
    ``ValueError`` naming the remedy when the design cannot be brought into the model
    range."""
    d = design.dimensionless()
    lo, hi = MODEL_RANGE
    k = (d["k_r"], d["k_theta"])
    inside_map = map_status(*k) == "in_map"
    point, status = dict(d), "in_map" if inside_map else "outside_map"
    c = min(1.0, hi / max(k), F_N_MAX / d["F_N"])
    message = POINT_STATUS["in_map" if inside_map else "outside_map"]
    if c < 1.0:
        point.update(k_r=d["k_r"] * c, k_theta=d["k_theta"] * c, F_N=d["F_N"] * c)
        status = "scaled"
        message = (POINT_STATUS[status] + f"; scaled by {c:.3g}, as at V0 = "
                   f"{design.V0 / math.sqrt(c):.3g} m/s")
    if min(point["k_r"], point["k_theta"]) < lo:
        name = "k_r" if point["k_r"] < lo else "k_theta"
        if status == "scaled":
            raise ValueError(f"k_theta={d['k_theta']:.3g}, k_r={d['k_r']:.3g}, F_N={d['F_N']:.3g} "
                             f"(dimensionless): scaled into the model range the smaller "
                             f"stiffness falls below {lo:g}; the stiffnesses and the load per "
                             f"pillar are too far apart for the model (change h, D, r0 or "
                             f"the load)")
        v_max = design.V0 * math.sqrt(d[name] / lo)
        raise ValueError(f"V0={design.V0:g} m/s puts k~_{name[2:]} = {d[name]:.3g} below the "
                         f"model range {lo:g}: the slab is too fast for these pillars; "
                         f"V0 <= {v_max:.3g} m/s brings it in range")
    point["scale"] = c
    return point, status, message


def model_params(design: PillarDesign) -> Params:
    """The model's ``Params`` for ``design``: ``model_point``'s springs, load, zeta and L0
    with the design's friction law (mu_s, A, B); ``ValueError`` as ``model_point``."""
    point = model_point(design)[0]
    return Params(k_r=point["k_r"], k_theta=point["k_theta"], F_N=point["F_N"],
                  zeta=point["zeta"], L0=point["L0"], mu_s=design.mu_s, A=design.A, B=design.B)


@dataclass(frozen=True)
class DesignPoint:
    """A design evaluated: its dimensionless point, regime, array and physical results."""

    design: PillarDesign
    point: dict  # the design's own k~_r, k~_theta, F~_N, zeta, L0
    computed: dict  # the point the model computed (differs when status == "scaled")
    status: str  # a key of POINT_STATUS
    status_message: str
    regime: str
    intervals: dict
    array: object  # DistributionArrayResult
    FTx_N: float  # drive force along the sliding direction
    FTy_N: float
    power_W: float  # F_T,x V0
    dissipated_power_W: float  # F_T,x V0 (D_x + D_y) / W
    contact_time_s: float  # <tau_out>_p r0 / V0
    excursion_r_um: float  # Delta r_rms r0
    excursion_theta_um: float  # Delta theta_rms r0 (arc at the rest radius)
    # The array's error bars carried over to the ``PHYSICAL`` results (NaN: none known),
    # and, when members were filled, the intervals that hold them (``array.bounds``).
    errors: dict = None
    bounds: dict = None

    @property
    def success(self) -> bool:
        return bool(self.array.success)

    def to_dict(self) -> dict:
        a = self.array
        return {"design": self.design.to_dict(), "point": self.point, "computed": self.computed,
                "status": self.status, "status_message": self.status_message,
                "regime": self.regime, "intervals": self.intervals,
                "FTx_over_mu0FN": a.FTx_over_mu0FN, "FTy_over_mu0FN": a.FTy_over_mu0FN,
                "FTx_N": self.FTx_N, "FTy_N": self.FTy_N, "power_W": self.power_W,
                "dissipated_power_W": self.dissipated_power_W,
                "contact_time_s": self.contact_time_s, "excursion_r_um": self.excursion_r_um,
                "excursion_theta_um": self.excursion_theta_um, "array": a.to_dict(),
                "errors": dict(self.errors or {}),
                "bounds": {k: list(v) for k, v in (self.bounds or {}).items()},
                "success": self.success, "message": a.message}


def evaluate(design: PillarDesign, distribution=None, psi: float = 0.0, beta="self",
             tol: float = 1e-3, max_steps: int = 1_000_000,
             budget: float | None = None) -> DesignPoint:
    """The array of ``design`` with orientations from ``distribution`` (default uniform),
    with its results in physical units. Cost per contact grows like L0 sqrt(max k~);
    ``max_steps`` bounds it (a contact that runs out is reported, never hidden) and
    ``budget`` (seconds) the quadrature's refinement (``distribution_array``)."""
    from .distribution_array import distribution_array
    from ..contact.friction import mu0

    point, status, message = model_point(design)
    params = model_params(design)
    a = distribution_array(params, distribution, psi=psi, beta=beta, tol=tol,
                           max_steps=max_steps, budget=budget)
    m0 = mu0(params)
    FTx, FTy = a.FTx_over_mu0FN * m0 * design.F_N, a.FTy_over_mu0FN * m0 * design.F_N
    split = a.work_split
    errors, bounds = _carried(a, m0 * design.F_N, design.V0,
                              point["L0"] * design.r0 / design.V0)
    return DesignPoint(
        design=design, point=design.dimensionless(), computed=point, status=status,
        status_message=message, regime=regime_of(point["k_r"], point["k_theta"]),
        intervals=regime_intervals(design), array=a, FTx_N=FTx, FTy_N=FTy,
        power_W=FTx * design.V0, dissipated_power_W=FTx * design.V0 * (split["D_x"] + split["D_y"]),
        contact_time_s=a.Nc_over_Nc0 * point["L0"] * design.r0 / design.V0,
        excursion_r_um=a.dr_rms * design.r0 * 1e6,
        excursion_theta_um=a.dtheta_rms * design.r0 * 1e6, errors=errors, bounds=bounds)


def _carried(a, force: float, V0: float, time: float) -> tuple[dict, dict]:
    """The array's error bars and bounds (``DistributionArrayResult.quadrature_error``,
    ``.bounds``) in physical units: forces scale by mu0 F_N, power by V0 more, the contact
    time by L0 r0/V0; the dissipated power adds the relative errors of F_T,x and of
    (D_x + D_y)/W. The excursions have no estimate (NaN)."""
    q = a.quadrature_error
    share = a.work_split["D_x"] + a.work_split["D_y"]
    rel_F = q["FTx_over_mu0FN"] / abs(a.FTx_over_mu0FN) if a.FTx_over_mu0FN else math.nan
    rel_D = (q["work_split.D_x"] + q["work_split.D_y"]) / share if share else math.nan
    P = a.FTx_over_mu0FN * force * V0
    errors = {"FTx_N": q["FTx_over_mu0FN"] * force, "FTy_N": q["FTy_over_mu0FN"] * force,
              "power_W": q["FTx_over_mu0FN"] * force * V0,
              "dissipated_power_W": abs(P * share) * (rel_F + rel_D),
              "contact_time_s": q["Nc_over_Nc0"] * time,
              "excursion_r_um": math.nan, "excursion_theta_um": math.nan}
    bounds = {}
    if "FTx_over_mu0FN" in a.bounds:
        lo, hi = a.bounds["FTx_over_mu0FN"]
        bounds.update(FTx_N=(lo * force, hi * force), power_W=(lo * force * V0, hi * force * V0))
    if "FTy_over_mu0FN" in a.bounds:
        lo, hi = a.bounds["FTy_over_mu0FN"]
        bounds["FTy_N"] = (lo * force, hi * force)
    return ({k: float(v) for k, v in errors.items()},
            {k: (float(lo), float(hi)) for k, (lo, hi) in bounds.items()})
