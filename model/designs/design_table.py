"""A design's array as one table, said the same way everywhere (the Design tab, its CSV
download, ``python -m model pillar``): each row a quantity with its value, its error bar
and, when the array did not converge, what is known instead.

The error bars are the array's (``model.designs.distribution_result``: the quadrature estimate; the
bounds that hold whatever the missing members' forces are when members were filled; none
when beta did not converge), carried to physical units by ``model.designs.design_point``.
``headline`` says the friction against a rigid surface (F_T,x/(mu0 F_N) = 1, Eq. 10) in
one sentence.
"""
from __future__ import annotations

import math

from .. import csvfile
from .._version import __version__
from .design_point import PHYSICAL
from .distribution_result import value_text
from .units import measure_text

__all__ = ["ARRAY_ROWS", "rows", "table_csv", "headline"]

#: The array's dimensionless rows: key of ``DistributionArrayResult`` -> what it is.
ARRAY_ROWS = {
    "FTx_over_mu0FN": "F_T,x/(μ₀F_N) (Eq. 10)",
    "FTx_over_mu0FN_duration": "… duration-weighted",
    "FTy_over_mu0FN": "F_T,y/(μ₀F_N)",
    "Dy_over_Dx": "D_y/D_x",
    "Nc_over_Nc0": "N_c/N_c0",
    "beta": "load factor β",
}


def _finite(x) -> bool:
    return x is not None and math.isfinite(x)


def rows(record: dict) -> list[dict]:
    """The table of a ``DesignPoint.to_dict`` record: one dict per quantity with ``key``,
    ``what``, ``value``, ``error`` (NaN: none), ``lower``, ``upper`` (NaN unless the array
    did not converge and a bound is known), ``unit`` (SI; "" dimensionless) and ``text``
    (the value as the page shows it)."""
    a = record["array"]
    out = []
    for key, what in ARRAY_ROWS.items():
        error = a["quadrature_error"].get(key) if key != "beta" else None
        lo, hi = (a.get("bounds") or {}).get(key) or (None, None)
        out.append(_row(key, what, a[key], error, lo, hi, "",
                        value_text(a, key) if key != "beta" else f"{a[key]:.4f}"))
    errors, bounds = record.get("errors") or {}, record.get("bounds") or {}
    for key, (what, unit) in PHYSICAL.items():
        lo, hi = bounds.get(key) or (None, None)
        text = measure_text(record[key], unit, errors.get(key), bounds.get(key),
                            converged=record.get("success", True))
        out.append(_row(key, what, record[key], errors.get(key), lo, hi, unit, text))
    return out


def _row(key, what, value, error, lo, hi, unit, text) -> dict:
    nan = math.nan
    return {"key": key, "what": what, "value": value if _finite(value) else nan,
            "error": error if _finite(error) else nan, "lower": lo if _finite(lo) else nan,
            "upper": hi if _finite(hi) else nan, "unit": unit, "text": text}


def table_csv(record: dict) -> str:
    """The table of ``rows`` as CSV text (``model.csvfile``): the design's inputs, its
    point, the outcome and the headline as ``# key: value`` lines, then one row per
    quantity (an empty error: none known; lower/upper: the bounds of a result that did not
    converge)."""
    table = rows(record)
    # An unknown error or bound is an empty cell, not a number that could pass for one.
    columns = {name: [r[name] if not (isinstance(r[name], float) and math.isnan(r[name]))
                      else "" for r in table]
               for name in ("key", "what", "value", "error", "lower", "upper", "unit")}
    design = record["design"]
    header = {"kind": "design", "version": __version__,
              **{f"design {k}": v for k, v in design.items() if k != "units"},
              "design units": design.get("units", {}),
              **{f"point {k}": v for k, v in record["point"].items()},
              "status": record["status"], "regime": record["regime"],
              "distribution": record["array"]["distribution"],
              "success": bool(record["success"]), "outcome": record["array"]["outcome"],
              "message": record["message"], "headline": headline(record),
              "column error": "the error bar (empty: none known, the result did not "
                              "converge)",
              "column lower/upper": "an interval that holds the value whatever the members "
                                    "that did not finish give (only when some did not)"}
    return csvfile.text(columns, header)


def headline(record: dict) -> str:
    """The design's friction in one plain sentence, from a ``DesignPoint.to_dict`` record:
    F_T,x/(mu0 F_N) against 1, a rigid surface (Eq. 10), with its error bar or bounds."""
    a = record["array"]
    value = a["FTx_over_mu0FN"]
    if not _finite(value):
        return "This design: its friction could not be computed."
    lo_hi = (a.get("bounds") or {}).get("FTx_over_mu0FN")
    if lo_hi is not None:
        lo, hi = (100 * (x - 1) for x in lo_hi)
        return (f"This design: friction not known yet (not converged): between "
                f"{_percent(lo)} and {_percent(hi)} a rigid surface.")
    error = a["quadrature_error"].get("FTx_over_mu0FN")
    change = 100 * (value - 1)
    if not _finite(error):
        return (f"This design: friction ≈ {_percent(change)} a rigid surface "
                f"(not converged: no error bar).")
    if abs(change) <= 100 * error:
        return f"This design: friction as on a rigid surface, within ± {_g2(100 * error)} %."
    return f"This design: friction ≈ {_percent(change)} a rigid surface (± {_g2(100 * error)} %)."


def _g2(x: float) -> str:
    """Two significant figures, without an exponent up to 1e6."""
    return f"{x:.2g}" if abs(x) < 100 or not math.isfinite(x) else f"{x:.0f}"


def _percent(change: float) -> str:
    """A relative change in words: "0.2 % above", "16 % below"."""
    return f"{_g2(abs(change))} % {'above' if change >= 0 else 'below'}"
