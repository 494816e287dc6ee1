"""The registry of the model's quantities: each named once, with its symbols and meaning.

Every input, output and diagnostic that appears as a field of a result, a CSV column or
a key of the CLI's JSON is a ``Quantity`` in ``QUANTITIES``: its name (the attribute,
column and key), its labels (plain text for terminals and CSV headers, Unicode for the
page, LaTeX), its normalisation, the paper's equation, units and meaning, and the
result types that carry it. What is derived from here:

* the fields of the result types (``tests/test_quantities.py`` checks that every field is
  registered and every registration is a field), ``to_dict`` and so the CLI's JSON;
* the columns of every CSV (``TABLES``: the sweeps, the trajectory download) and the
  column descriptions in their headers (``column_notes``);
* the labels of the dashboard's readouts and the reproduction's tables (``label``,
  ``format_value``).

Adding a quantity computed per contact (``r_max`` is the example): compute it in the
kernel and read it into ``model.arrays.contacts.Contacts``; declare the field on the results that
carry it (``SupportResult`` and ``FixedArrayResult``; the fixed array reads its fields by
name); register it here with ``where`` naming them, and add it to the ``TABLES`` layouts
that show it. The JSON records, CSV columns and headers, and labels follow.

Units are the paper's dimensionless ones (Eq. 5): lengths r0, time r0/V0, energies
m V0^2; forces are quoted over a load (f_N = beta F_N per support, or mu0 F_N).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

__all__ = ["Quantity", "QUANTITIES", "STRUCTURE", "TABLES", "AVERAGES", "MAP_FIGURES",
           "POLAR_FIGURES", "quantity", "label", "format_value", "describe", "carried_by",
           "value_of", "record", "readout", "column_notes"]

# The result types, by name (the registry imports none of them).
SUPPORT, SERIES, CONTACTS = "SupportResult", "TimeSeries", "Contacts"
FIXED, SWEEP = "FixedArrayResult", "OrientationSweep"
UNIFORM, MAP = "UniformArrayResult", "RegimeMap"
ARRAYS = (FIXED, SWEEP, UNIFORM)
PER_CONTACT = (SUPPORT, CONTACTS, FIXED)

#: Fields that hold structure rather than a quantity: inputs, settings, sub-results.
STRUCTURE = ("params", "options", "contacts", "series", "stats", "metadata")


@dataclass(frozen=True)
class Quantity:
    """One named quantity.

    name : attribute, CSV column and JSON key.
    text, unicode, latex : its label as plain text, with Unicode symbols, in LaTeX.
    meaning : one line, what it is.
    equation : where the paper defines it, e.g. "Eq. (10)" (or a figure, "Fig. 10f").
    normalised_by : the scale it is divided by ("mu0 F_N", "f_N", "W", "L0"; "" if none).
    units : "1" (a pure number), "r0", "r0/V0", "rad", "m V0^2", or "" (not a number).
    where : the result types that carry it (as fields or properties).
    digits : significant digits when shown.
    source : how to read it from a result when it is not an attribute of that name (a
        dotted path such as ``"work_split.D_x"``, or a function of the result).
    """

    name: str
    text: str
    unicode: str
    latex: str
    meaning: str
    equation: str = ""
    normalised_by: str = ""
    units: str = "1"
    where: tuple = ()
    digits: int = 4
    source: str | Callable | None = None

    def label(self, style: str = "unicode") -> str:
        return {"unicode": self.unicode, "text": self.text, "latex": self.latex}[style]


def _q(name, text, unicode, latex, meaning, **kw) -> Quantity:
    return Quantity(name, text, unicode, latex, meaning, **kw)


_MISSING = object()


def _attr(result, name: str):
    """Attribute ``name`` of ``result``, else of its per-contact rows ``result.contacts``
    (an ``OrientationSweep`` shows the quantities of its contacts)."""
    value = getattr(result, name, _MISSING)
    if value is _MISSING:
        contacts = getattr(result, "contacts", None)
        if contacts is None:
            raise AttributeError(f"{type(result).__name__} has no quantity {name!r}")
        value = getattr(contacts, name)
    return value


def _ratio(a: str, b: str):
    return lambda r: abs(_attr(r, a)) / abs(_attr(r, b))


_ENTRIES = [
    # ----------------------------------------------------------------- parameters
    _q("regime", "regime", "regime", r"\text{regime}",
       "named springs of Fig. 6: pendulum, slider, stiff or soft", units=""),
    _q("k_r", "k_r", "k_r", r"\tilde k_r", "radial stiffness", equation="Eq. (5)",
       where=(MAP,)),
    _q("k_theta", "k_theta", "k_θ", r"\tilde k_\theta", "torsional stiffness",
       equation="Eq. (5)", where=(MAP,)),
    _q("F_N", "F_N", "F_N", r"\tilde F_N", "normal load on the slab per support at rest",
       equation="Eq. (5)"),
    _q("theta0", "theta0", "θ₀", r"\theta_0", "rest orientation from the sliding direction +x",
       units="rad", where=(SWEEP, CONTACTS)),
    _q("beta", "beta", "β", r"\beta", "load factor N_c0/N_c: each support carries f_N = beta F_N",
       equation="Eq. (9)", where=(*ARRAYS, CONTACTS, MAP)),
    # ----------------------------------------------------------------- one contact
    _q("t_out", "tau_out", "τ_out", r"\tau_{out}",
       "contact duration: the slab slid L0 over the support", equation="Eq. (9)",
       units="r0/V0", where=(SUPPORT, CONTACTS)),
    _q("state_out", "(x, y, v_x, v_y, theta) at tau_out", "(x, y, v_x, v_y, θ) at τ_out",
       r"(x, y, v_x, v_y, \theta)(\tau_{out})", "state of the support at the end of contact",
       units="", where=(SUPPORT, CONTACTS)),
    _q("F_mean", "F_f/f_N (mean)", "F̄_f/f_N", r"\bar{\mathbf{F}}_f/f_N",
       "time-averaged friction on the support over the contact, (x, y)", equation="Eq. (8)",
       normalised_by="f_N", where=(SUPPORT,)),
    _q("F_mean_x", "F_f,x/f_N (mean)", "F̄_f,x/f_N", r"\bar F_{f,x}/f_N",
       "time-averaged friction on the support along x", equation="Eq. (8)",
       normalised_by="f_N", source=lambda r: float(r.F_mean[0])),
    _q("F_mean_y", "F_f,y/f_N (mean)", "F̄_f,y/f_N", r"\bar F_{f,y}/f_N",
       "time-averaged friction on the support along y", equation="Eq. (8)",
       normalised_by="f_N", source=lambda r: float(r.F_mean[1])),
    _q("F_x", "F_f,x/f_N", "F_f,x/f_N", r"F_{f,x}/f_N",
       "friction on the support along x (per contact: its time average, Eq. 8)",
       equation="Eq. (4)", normalised_by="f_N", where=(SERIES, CONTACTS)),
    _q("F_y", "F_f,y/f_N", "F_f,y/f_N", r"F_{f,y}/f_N",
       "friction on the support along y (per contact: its time average, Eq. 8)",
       equation="Eq. (4)", normalised_by="f_N", where=(SERIES, CONTACTS)),
    _q("W", "W", "W", "W", "work of the slab on the support over the contact",
       equation="Eq. (12)", units="m V0^2", where=(SUPPORT, CONTACTS, SERIES)),
    _q("D_x", "D_x", "D_x", "D_x", "friction dissipation along x", equation="Eq. (13)",
       units="m V0^2", where=(SUPPORT, CONTACTS, SERIES)),
    _q("D_y", "D_y", "D_y", "D_y", "friction dissipation along y", equation="Eq. (13)",
       units="m V0^2", where=(SUPPORT, CONTACTS, SERIES)),
    _q("U_el", "U_el", "U_el", "U_{el}", "elastic energy left in the support at exit",
       equation="Eq. (12)", units="m V0^2", where=(SUPPORT, CONTACTS, SERIES)),
    _q("K", "K", "K", "K", "kinetic energy left in the support at exit", equation="Eq. (12)",
       units="m V0^2", where=(SUPPORT, CONTACTS, SERIES)),
    _q("energy_residual", "W - (D_x + D_y + U_el + K)", "W − (D_x + D_y + U_el + K)",
       r"W - (D_x + D_y + U_{el} + K)",
       "miss of the energy balance: zero for the true solution, so the integration error",
       equation="Eq. (12)", units="m V0^2", digits=2, where=(SUPPORT, CONTACTS, FIXED)),
    _q("relative_residual", "|W - (D_x + D_y + U_el + K)|/W", "|W − ΣD − U_el − K|/W",
       r"|W - (D_x + D_y + U_{el} + K)|/W", "relative miss of the energy balance",
       equation="Eq. (12)", normalised_by="W", digits=2,
       source=_ratio("energy_residual", "W")),
    _q("accurate", "accurate", "accurate", r"\text{accurate}",
       "the energy balance holds to a few rtol", units="", where=(SUPPORT,)),
    _q("dtheta_rms", "dtheta_rms", "Δθ_rms", r"\Delta\theta_{rms}",
       "rms of theta - theta0 over the contact", equation="Fig. 10f", units="rad",
       where=(SUPPORT, CONTACTS, *ARRAYS)),
    _q("dr_rms", "dr_rms", "Δr̃_rms", r"\Delta\tilde r_{rms}",
       "rms of r - 1 over the contact", equation="Fig. 10f", units="r0",
       where=(SUPPORT, CONTACTS, *ARRAYS)),
    _q("r_min", "r_min", "r_min", r"r_{min}", "closest approach of the mass to its pivot",
       units="r0", where=PER_CONTACT),
    _q("r_max", "r_max", "r_max", r"r_{max}",
       "largest distance of the mass from its pivot during the contact", units="r0",
       where=PER_CONTACT),
    _q("pivot_approach", "pivot approach", "pivot approach", r"r_{min} < 0.2\lambda",
       "the mass was driven into the region of its pivot (r_min below pivot_radius)",
       units="", where=PER_CONTACT),
    _q("pivot_radius", "0.2 lambda", "0.2 λ", r"0.2\lambda",
       "radius of the pivot region, where the repulsion of Eq. (3) dominates",
       equation="Eq. (3)", units="r0", where=(SUPPORT, CONTACTS)),
    # ----------------------------------------------------------------- arrays
    _q("FTx_over_mu0FN", "F_T,x/(mu0 F_N)", "F_T,x/(μ₀F_N)", r"F_{T,x}/(\mu_0 F_N)",
       "apparent friction: force on the slab along x over the rigid-contact friction "
       "(uniform arrays: the paper's mean over supports)", equation="Eq. (10)",
       normalised_by="mu0 F_N", where=(*ARRAYS, MAP)),
    _q("FTx_over_mu0FN_duration", "F_T,x/(mu0 F_N), duration-weighted",
       "F_T,x/(μ₀F_N), duration-weighted", r"F_{T,x}/(\mu_0 F_N)\ \text{(duration)}",
       "steady force on the slab when contacts last different times: "
       "sum int F_f,x dtau / (f_N sum tau_out)", equation="Eq. (10)",
       normalised_by="mu0 F_N", where=(UNIFORM, MAP)),
    _q("FTy_over_mu0FN", "F_T,y/(mu0 F_N)", "F_T,y/(μ₀F_N)", r"F_{T,y}/(\mu_0 F_N)",
       "transverse force on the slab (0 for a uniform array by mirror symmetry)",
       equation="Eq. (11)", normalised_by="mu0 F_N", where=ARRAYS),
    _q("Dy_over_Dx", "D_y/D_x", "D_y/D_x", "D_y/D_x",
       "transverse over longitudinal friction dissipation", equation="Eq. (13)",
       normalised_by="D_x", where=(*ARRAYS, MAP)),
    _q("Nc_over_Nc0", "N_c/N_c0", "N_c/N_c0", r"N_c/N_{c0}",
       "contact count: <tau_out>/L0, supports dragged beyond L0 stay longer",
       equation="Eq. (9)", normalised_by="L0", where=(*ARRAYS, MAP)),
    _q("work_split", "(D_x, D_y, U_el, K)/W", "(D_x, D_y, U_el, K)/W",
       r"(D_x, D_y, U_{el}, K)/W", "split of the slab work", equation="Eq. (12)",
       normalised_by="W", where=ARRAYS),
    _q("Dx_over_W", "D_x/W", "D_x/W", "D_x/W", "share of the slab work dissipated along x",
       equation="Eq. (12)", normalised_by="W", source="work_split.D_x"),
    _q("Dy_over_W", "D_y/W", "D_y/W", "D_y/W", "share of the slab work dissipated along y",
       equation="Eq. (12)", normalised_by="W", source="work_split.D_y"),
    _q("Uel_over_W", "U_el/W", "U_el/W", "U_{el}/W",
       "share of the slab work left in the springs", equation="Eq. (12)",
       normalised_by="W", source="work_split.U_el"),
    _q("K_over_W", "K/W", "K/W", "K/W", "share of the slab work left as kinetic energy",
       equation="Eq. (12)", normalised_by="W", source="work_split.K"),
    _q("beta_residual", "beta - L0/<tau_out>", "β − L₀/⟨τ_out⟩",
       r"\beta - L_0/\langle\tau_{out}\rangle",
       "residual of the self-consistent load factor (0 when beta is fixed)",
       equation="Eq. (9)", digits=2, where=ARRAYS),
    _q("beta_slope", "dG/dbeta", "dG/dβ", r"dG/d\beta",
       "slope of G(beta) = beta - L0/<tau_out>(beta) at the root: continues the solve at a "
       "neighbouring sweep point", digits=3,
       source=lambda r: r.stats.get("beta_slope", math.nan)),
    _q("beta_iterations", "beta iterations", "β iterations", r"n_\beta",
       "root-finder iterations for the self-consistent beta", units="", where=ARRAYS),
    _q("beta_note", "beta note", "β note", r"\text{note}",
       "why a self-consistent beta is special: capped at 1, or no root", units="",
       where=(SWEEP,)),
    _q("quadrature_error", "quadrature error", "quadrature error", r"\epsilon_Q",
       "error estimate of the average over theta0 (per quantity; on a map, of F_T,x/(mu0 F_N))",
       digits=2, where=(UNIFORM, MAP)),
    _q("quadrature_error_FTx", "quadrature error of F_T,x/(mu0 F_N)",
       "quadrature error of F_T,x/(μ₀F_N)", r"\epsilon_Q(F_{T,x}/\mu_0 F_N)",
       "error estimate of the paper average F_T,x/(mu0 F_N)", digits=2,
       source="quadrature_error.FTx_over_mu0FN"),
    _q("quadrature_error_Nc", "quadrature error of N_c/N_c0", "quadrature error of N_c/N_c0",
       r"\epsilon_Q(N_c/N_{c0})", "error estimate of N_c/N_c0", digits=2,
       source="quadrature_error.Nc_over_Nc0"),
    _q("integration_error", "largest |residual|/W", "largest |residual|/W",
       r"\max |W - \Sigma|/W", "largest relative miss of the energy balance over the members",
       equation="Eq. (12)", digits=2, where=(UNIFORM,)),
    _q("n_members", "members", "members", "n", "orientations integrated by the quadrature",
       units="", where=(UNIFORM,)),
    _q("n_failed", "failed members", "failed members", r"n_{failed}",
       "members that did not finish their contact", units="", where=(UNIFORM, MAP)),
    _q("n_pivot", "members at the pivot", "members at the pivot", r"n_{pivot}",
       "members driven into the region of their pivot", units="", where=(UNIFORM, MAP)),
    _q("failed_theta0", "failed theta0", "failed θ₀", r"\theta_0^{failed}",
       "orientations of the failed members", units="rad", where=(UNIFORM,)),
    # ----------------------------------------------------------------- run records
    _q("success", "success", "success", r"\text{success}", "the computation reached its end "
       "(and, for arrays, met its tolerance)", units="", where=(SUPPORT, *ARRAYS, MAP)),
    _q("status", "status", "status", r"\text{status}", "outcome code of one contact "
       "(model.contact.results.STATUS)", units="", where=(SUPPORT, CONTACTS)),
    _q("message", "message", "message", r"\text{message}", "what happened, and the remedy "
       "when something failed", units="", where=(SUPPORT, FIXED, UNIFORM)),
    _q("seconds", "seconds", "seconds", r"\text{s}", "wall time of the computation", units="s",
       where=(SWEEP, UNIFORM)),
    _q("rtol", "rtol", "rtol", r"\text{rtol}", "relative tolerance of each contact", units=""),
    # ----------------------------------------------------------------- time histories
    _q("tau", "tau", "τ", r"\tau", "time", equation="Eq. (5)", units="r0/V0", where=(SERIES,)),
    _q("x", "x", "x", "x", "position of the mass from its pivot along the sliding direction",
       units="r0", where=(SERIES,)),
    _q("y", "y", "y", "y", "position of the mass from its pivot across the sliding direction",
       units="r0", where=(SERIES,)),
    _q("v_x", "v_x", "v_x", "v_x", "velocity along x", units="V0", where=(SERIES,)),
    _q("v_y", "v_y", "v_y", "v_y", "velocity along y", units="V0", where=(SERIES,)),
    _q("theta", "theta", "θ", r"\theta", "orientation, unwrapped", equation="Eq. (6)",
       units="rad", where=(SERIES,)),
    _q("r", "r", "r̃", r"\tilde r", "length of the support", units="r0", where=(SERIES,)),
    _q("F_abs", "|F_f|/f_N", "|F_f|/f_N", r"|\mathbf{F}_f|/f_N", "magnitude of the friction",
       equation="Eq. (4)", normalised_by="f_N", where=(SERIES,)),
    _q("v_R_abs", "|v_R|", "|v_R|", r"|\mathbf{v}_R|",
       "relative speed of the support and the slab, |v - (1, 0)|", equation="Eq. (4)",
       units="V0", source=lambda s: ((s.v_x - 1.0) ** 2 + s.v_y ** 2) ** 0.5),
    _q("v_over_V0", "v/V0", "v/V₀", "v/V_0", "relative speed", equation="Eq. (4)",
       normalised_by="V0"),
    _q("mu", "mu(v)", "μ(v)", r"\mu(v)", "friction coefficient", equation="Eq. (4)"),
]

#: Every quantity by name.
QUANTITIES: dict[str, Quantity] = {q.name: q for q in _ENTRIES}
assert len(QUANTITIES) == len(_ENTRIES), "a quantity is registered twice"

#: The columns of each CSV table, in order (names of ``QUANTITIES``).
_ARRAY = ("FTx_over_mu0FN", "FTx_over_mu0FN_duration", "Dy_over_Dx", "Nc_over_Nc0", "beta")
_CHECKS = ("quadrature_error_FTx", "n_failed", "n_pivot", "success")
_SPLIT = ("Dx_over_W", "Dy_over_W", "Uel_over_W", "K_over_W")
TABLES: dict[str, tuple] = {
    "regime_map": ("k_r", "k_theta", *_ARRAY, *_CHECKS),
    "load": ("regime", "k_r", "k_theta", "F_N", *_ARRAY, *_CHECKS),
    "stiffness": ("k_theta", "k_r", "Nc_over_Nc0", *_SPLIT, *_ARRAY[:3], "beta",
                  "quadrature_error_Nc", *_CHECKS),
    "orientation": ("theta0", "FTx_over_mu0FN", "FTy_over_mu0FN", "Dy_over_Dx", "Nc_over_Nc0",
                    "dtheta_rms", "dr_rms", "r_max", "beta", "pivot_approach",
                    "relative_residual", "success"),
    "trajectory": ("tau", "x", "y", "v_x", "v_y", "theta", "r", "F_x", "F_y", "F_abs",
                   "v_R_abs"),
    #: The JSON record of one contact (``SupportResult.to_dict``, ``python -m model support``).
    "support": ("t_out", "state_out", "F_mean_x", "F_mean_y", "W", "D_x", "D_y", "U_el", "K",
                "energy_residual", "dtheta_rms", "dr_rms", "r_min", "r_max", "pivot_approach",
                "accurate", "success", "status", "message"),
    #: What one uniform-array point of a sweep keeps (the disk cache stores these).
    "uniform_point": ("k_r", "k_theta", "F_N", *_ARRAY, *_SPLIT, "quadrature_error_FTx",
                      "quadrature_error_Nc", "n_failed", "n_pivot", "success", "rtol",
                      "beta_slope"),
}

#: The two averages of a uniform array (the dashboard's ``avg``) -> their quantity.
AVERAGES = {"paper": "FTx_over_mu0FN", "duration": "FTx_over_mu0FN_duration"}
#: Panels of Fig. 5 (the regime map) -> the quantity shown.
MAP_FIGURES = {"5a": "FTx_over_mu0FN", "5b": "Dy_over_Dx"}
#: Panels of Fig. 11 (polar plots of fixed arrays) -> the quantity shown.
POLAR_FIGURES = {"11a": "FTx_over_mu0FN", "11b": "Dy_over_Dx", "11c": "FTy_over_mu0FN"}


def quantity(name: str) -> Quantity:
    """The registered quantity ``name``; ``KeyError`` naming the known ones otherwise."""
    try:
        return QUANTITIES[name]
    except KeyError:
        raise KeyError(f"{name!r} is not a registered quantity; see model.arrays.quantities.QUANTITIES"
                       ) from None


def label(name: str, style: str = "unicode") -> str:
    """The label of ``name``: ``"unicode"`` (the page), ``"text"`` (terminal, CSV) or
    ``"latex"``."""
    return quantity(name).label(style)


def format_value(name: str, value, digits: int | None = None) -> str:
    """``value`` of quantity ``name`` as shown to a reader: its significant digits,
    "–" for a missing or non-finite number, yes/no for a flag."""
    if value is None:
        return "–"
    if isinstance(value, (bool, np.bool_)):
        return "yes" if value else "no"
    if isinstance(value, str):
        return value
    x = float(value)
    if not math.isfinite(x):
        return "–"
    if float(x).is_integer() and quantity(name).units == "" and abs(x) < 1e15:
        return str(int(x))
    return f"{x:.{digits or quantity(name).digits}g}"


def describe(name: str) -> str:
    """One line for a report: meaning, units and the equation, e.g. "contact duration:
    the slab slid L0 over the support [r0/V0] (Eq. (9))"."""
    q = quantity(name)
    units = f" [{q.units}]" if q.units not in ("", "1") else ""
    where = f" ({q.equation})" if q.equation else ""
    return f"{q.meaning}{units}{where}"


def carried_by(result_type: str) -> tuple:
    """Names of the quantities a result type carries, in registry order."""
    return tuple(q.name for q in _ENTRIES if result_type in q.where)


def value_of(result, name: str):
    """Quantity ``name`` of ``result``: its attribute, or its registered ``source``."""
    q = QUANTITIES.get(name)
    source = quantity(name).source if q is None else q.source
    if source is None:
        return _attr(result, name)
    if callable(source):
        return source(result)
    value = result
    for part in source.split("."):
        value = value[part] if isinstance(value, dict) else getattr(value, part)
    return value


def record(result, layout: str) -> dict:
    """The quantities of ``TABLES[layout]`` read from ``result`` as plain Python values
    (numpy scalars become numbers, arrays lists)."""
    out = {}
    for name in TABLES[layout]:
        value = value_of(result, name)
        out[name] = value.tolist() if hasattr(value, "tolist") else value
    return out


def readout(result, names, style: str = "unicode") -> list:
    """``[(label, formatted value), ...]`` of the quantities ``names`` of ``result``: the
    rows of a readout table (the dashboard) or a report."""
    return [(label(n, style), format_value(n, value_of(result, n))) for n in names]


def column_notes(names) -> dict:
    """``{"column <name>": "<label>: <meaning> [units] (Eq.)"}`` for a CSV header."""
    return {f"column {n}": f"{label(n, 'text')}: {describe(n)}" for n in names}
