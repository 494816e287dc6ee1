"""``python -m model array``: one fixed- or uniform-orientation array (Figs. 5, 6, 8-11)."""
from __future__ import annotations

import json
import math

from ..arrays.fixed import fixed_orientation
from ..arrays.uniform import uniform_array
from ..contact.params import Params
from . import orientations
from ._common import (UsageError, add_atol_method, add_stiffness, as_usage_error, beta_value,
                      jsonable, real, stiffness, table)

#: Error estimates of a uniform array; a fixed array has no quadrature, so all are 0.
QUADRATURE_KEYS = ("FTx_over_mu0FN", "FTx_over_mu0FN_duration", "FTy_over_mu0FN", "Dy_over_Dx",
                   "Nc_over_Nc0", "work_split.D_x", "work_split.D_y", "work_split.U_el",
                   "work_split.K")


def add_command(commands) -> None:
    p = commands.add_parser(
        "array", help="a fixed- or uniform-orientation array of supports",
        description="Apparent friction F_T,x/(mu0 F_N), D_y/D_x, contact count N_c/N_c0 and the "
                    "split of the slab work of an array of supports: all sharing theta0 "
                    "(fixed, Figs. 9-11) or theta0 uniform on [0, 2 pi) (uniform, Figs. 5, 6, 8).")
    model = p.add_argument_group("array")
    add_stiffness(model)
    model.add_argument("--F-N", type=real, default=1.0, metavar="F",
                       help="normal load F_N per support at rest (default 1)")
    model.add_argument("--orientation", choices=("uniform", "fixed", *orientations.ORIENTATIONS),
                       help="uniform (default), fixed, or a distribution: pair (+-theta0), "
                            "vonmises, mixture, csv (histogram); --theta0 alone implies fixed")
    model.add_argument("--theta0", type=real, metavar="T",
                       help="common rest orientation of a fixed array in radians (default pi/2)")
    model.add_argument("--beta", type=beta_value, default="self", metavar="self|B",
                       help="load factor N_c0/N_c: 'self' solves beta = L0/<tau_out>(beta) "
                            "(default), a number in (0, 1] fixes it")
    solver = p.add_argument_group("solver")
    solver.add_argument("--tol", type=real, metavar="T",
                        help="uniform only: quadrature tolerance on F_T,x/(mu0 F_N) and "
                             "N_c/N_c0 (default 1e-3)")
    solver.add_argument("--rtol", type=real, metavar="R",
                        help="relative tolerance per contact (default: tol/100, at most 1e-5, "
                             "for uniform arrays; 1e-6 for fixed)")
    add_atol_method(solver)
    orientations.add_arguments(p)
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=run)


def _orientation(args) -> str:
    orientation = args.orientation or ("fixed" if args.theta0 is not None else "uniform")
    if orientation == "uniform" and args.theta0 is not None:
        raise UsageError("--theta0", "only with --orientation fixed (a uniform array covers "
                                     "every theta0)")
    if orientation == "fixed" and args.tol is not None:
        raise UsageError("--tol", "only with --orientation uniform (a fixed array has no "
                                  "quadrature over theta0)")
    return orientation


def run(args) -> int:
    """``array``: compute one array and print it; 0 on success, 1 if it did not succeed."""
    orientation = _orientation(args)
    if orientation in orientations.ORIENTATIONS:
        return orientations.run(args, orientation)
    orientations.reject_foreign(args, orientation)
    k_r, k_theta = stiffness(args)
    theta0 = math.pi / 2 if args.theta0 is None else args.theta0
    try:
        params = Params(k_r=k_r, k_theta=k_theta, F_N=args.F_N, theta0=theta0)
        if orientation == "fixed":
            rtol = 1e-6 if args.rtol is None else args.rtol
            result = fixed_orientation(params, beta=args.beta, rtol=rtol, atol=args.atol,
                                       method=args.method)
        else:
            tol = 1e-3 if args.tol is None else args.tol
            result = uniform_array(params, beta=args.beta, tol=tol, rtol=args.rtol,
                                   atol=args.atol, method=args.method)
    except ValueError as error:
        raise as_usage_error(error) from None
    record = _record(result, orientation)
    print(json.dumps(jsonable(record)) if args.json else _summary(record))
    return 0 if record["success"] else 1


def _record(result, orientation: str) -> dict:
    """``result.to_dict()`` with the keys shared by both orientations."""
    record = {"orientation": orientation, **result.to_dict()}
    if orientation == "fixed":
        # All contacts of a fixed array last equally long: both averages coincide.
        record["FTx_over_mu0FN_duration"] = record["FTx_over_mu0FN"]
        record["quadrature_error"] = dict.fromkeys(QUADRATURE_KEYS, 0.0)
    return record


def _summary(r: dict) -> str:
    """A readable report saying which average is which (Eq. 10 vs duration-weighted)."""
    p, uniform = r["params"], r["orientation"] == "uniform"
    err = r["quadrature_error"]

    def pm(key):
        return f" (+- {err[key]:.2g})" if uniform else ""

    where = ("theta0 uniform on [0, 2 pi) (Figs. 5, 6, 8)" if uniform else
             f"every support at theta0 = {p['theta0']:.6g} rad (Figs. 9-11)")
    params = [("orientation", r["orientation"], where),
              ("k_r", p["k_r"], "radial stiffness"),
              ("k_theta", p["k_theta"], "torsional stiffness"),
              ("F_N", p["F_N"], "normal load per support at rest"),
              ("beta", r["beta"], f"load factor N_c0/N_c, residual {r['beta_residual']:.2g}")]
    same = "" if uniform else "; equal to the paper average: every contact lasts as long"
    results = [
        ("success", r["success"], r["message"]),
        ("FTx_over_mu0FN", r["FTx_over_mu0FN"], "apparent friction F_T,x/(mu0 F_N), "
         + ("paper average over supports (Eq. 10)" if uniform else "F_x/(f_N mu0) (Eq. 8)")
         + pm("FTx_over_mu0FN")),
        ("FTx_over_mu0FN_duration", r["FTx_over_mu0FN_duration"],
         "duration-weighted: sum int F_f,x dtau / (f_N sum tau_out)" + same
         + pm("FTx_over_mu0FN_duration")),
        ("FTy_over_mu0FN", r["FTy_over_mu0FN"], "transverse force F_T,y/(mu0 F_N)"
         + (" (0 by mirror symmetry)" if uniform else "")),
        ("Dy_over_Dx", r["Dy_over_Dx"],
         "transverse over longitudinal dissipation" + pm("Dy_over_Dx")),
        ("Nc_over_Nc0", r["Nc_over_Nc0"],
         "contact count <tau_out>/L0 (Fig. 8a)" + pm("Nc_over_Nc0")),
    ]
    results += [(f"{k}/W", v, "share of the slab work (Eq. 12, Fig. 8b)")
                for k, v in r["work_split"].items()]
    results += [("dtheta_rms", r["dtheta_rms"], "orientation fluctuation [rad] (Fig. 10f)"),
                ("dr_rms", r["dr_rms"], "length fluctuation [r0] (Fig. 10f)")]
    return table([("Parameters (dimensionless)", params), ("Array", results),
                  ("Checks", _checks(r, uniform))])


def _checks(r: dict, uniform: bool) -> list:
    if not uniform:
        return [("energy_residual", r["energy_residual"], "W - (D_x + D_y + U_el + K)"),
                ("r_min", r["r_min"], "closest approach of the mass to its pivot [r0]"),
                ("beta_iterations", r["beta_iterations"], "root-finder iterations for beta")]
    stats = r["stats"]
    return [("n_members", r["n_members"], "orientations integrated (adaptive Gauss-Kronrod)"),
            ("n_failed", r["n_failed"], "members that did not finish their contact"),
            ("n_pivot", r["n_pivot"], "members driven into the region of their pivot"),
            ("integration_error", r["integration_error"], "largest |energy residual|/W"),
            ("intervals", stats.get("intervals", 0), "quadrature intervals over theta0"),
            ("rtol", stats.get("rtol", 0.0), "relative tolerance per contact"),
            ("seconds", r["seconds"], "wall time")]
