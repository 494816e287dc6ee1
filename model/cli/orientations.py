"""``python -m model array --orientation pair|vonmises|mixture|csv``: arrays whose
orientations follow a distribution (``model.designs.distributions``), p-weighted as in Eq. (10).

Flags: ``--theta0`` (pair, radians), ``--mean-deg`` and ``--kappa`` (von Mises),
``--component FAMILY[:key=value,...]`` (repeated) with ``--weights w1,w2,...`` (mixture),
``--histogram PATH`` (csv), ``--psi-deg`` (sliding angle to the array, any orientation).
"""
from __future__ import annotations

import json
import math
import re

from ..contact.params import Params
from ..designs.distribution_array import distribution_array
from ..designs.distribution_result import error_words
from ..designs.distributions import Histogram, Mixture, Pair, VonMises, from_dict, rotated
from ._common import FIELD_FLAGS, UsageError, jsonable, real, stiffness, table

ORIENTATIONS = ("pair", "vonmises", "mixture", "csv")
#: Each distribution flag and the orientations that take it.
_OWN = {"--mean-deg": ("vonmises",), "--kappa": ("vonmises",), "--component": ("mixture",),
        "--weights": ("mixture",), "--histogram": ("csv",)}
_DEST = {"--mean-deg": "mean_deg", "--kappa": "kappa", "--component": "component",
         "--weights": "weights", "--histogram": "histogram"}
#: Names in the model's ValueError messages -> flags (beyond FIELD_FLAGS).
_FLAGS = {"mean": "--mean-deg", "mean_deg": "--mean-deg", "kappa": "--kappa",
          "weights": "--weights", "components": "--component", "psi": "--psi-deg",
          "theta0_deg": "--component", "family": "--component", "edges": "--histogram",
          "histogram": "--histogram", "max_intervals": "--tol"}


def add_arguments(parser) -> None:
    g = parser.add_argument_group(
        "orientation distribution",
        "theta0 from the sliding direction; arrays are p-weighted averages (Eq. 10)")
    g.add_argument("--mean-deg", type=real, metavar="M",
                   help="vonmises: mean direction in degrees")
    g.add_argument("--kappa", type=real, metavar="K",
                   help="vonmises: concentration kappa >= 0 (0 uniform; large: all at the mean)")
    g.add_argument("--component", action="append", metavar="FAMILY[:k=v,...]",
                   help="mixture: one component, e.g. vonmises:mean_deg=60,kappa=4, "
                        "fixed:theta0_deg=30, pair:theta0_deg=45, uniform (repeat the flag)")
    g.add_argument("--weights", metavar="W1,W2,...",
                   help="mixture: one weight per --component (normalised)")
    g.add_argument("--histogram", metavar="PATH",
                   help="csv: histogram file with header theta0_deg,weight (bin centres) or "
                        "lower_deg,upper_deg,weight")
    g.add_argument("--psi-deg", type=real, default=0.0, metavar="PSI",
                   help="sliding direction at PSI degrees to the array (the distribution is "
                        "rotated by -PSI; default 0)")


def reject_foreign(args, orientation: str) -> None:
    """A distribution flag given with an orientation that does not take it."""
    for flag, owners in _OWN.items():
        if getattr(args, _DEST[flag]) is not None and orientation not in owners:
            raise UsageError(flag, f"only with --orientation {' or '.join(owners)}")
    if args.theta0 is not None and orientation in ORIENTATIONS and orientation != "pair":
        raise UsageError("--theta0", "only with --orientation fixed or pair")
    if args.psi_deg != 0 and orientation not in ORIENTATIONS:
        raise UsageError("--psi-deg", f"only with --orientation {', '.join(ORIENTATIONS)} (a "
                                      f"uniform array looks the same from every direction; for "
                                      f"a fixed one, subtract psi from --theta0)")


def _usage(error: ValueError) -> UsageError:
    match = re.match(r"(\w+)=", str(error))
    name = match.group(1) if match else None
    flag = _FLAGS.get(name) or FIELD_FLAGS.get(name)
    return UsageError(flag, str(error))


def _component(text: str):
    family, _, rest = text.partition(":")
    d = {"family": family.strip()}
    for item in filter(None, (s.strip() for s in rest.split(","))):
        key, eq, value = item.partition("=")
        if not eq:
            raise UsageError("--component", f"{item!r} must be key=value (in {text!r})")
        try:
            d[key.strip()] = float(value)
        except ValueError:
            raise UsageError("--component", f"{value!r} is not a number (in {text!r})") from None
    return from_dict(d)


def distribution(args, orientation: str):
    """The distribution the flags describe; ``UsageError`` naming the flag otherwise."""
    reject_foreign(args, orientation)
    try:
        if orientation == "pair":
            dist = Pair(math.pi / 2 if args.theta0 is None else args.theta0)
        elif orientation == "vonmises":
            for flag in ("--mean-deg", "--kappa"):
                if getattr(args, _DEST[flag]) is None:
                    raise UsageError(flag, "required with --orientation vonmises")
            dist = VonMises(math.radians(args.mean_deg), args.kappa)
        elif orientation == "mixture":
            if not args.component:
                raise UsageError("--component", "required (at least once) with --orientation "
                                                "mixture")
            comps = tuple(_component(c) for c in args.component)
            if args.weights is None:
                weights = (1.0,) * len(comps)
            else:
                try:
                    weights = tuple(float(w) for w in args.weights.split(","))
                except ValueError:
                    raise UsageError("--weights", f"{args.weights!r} must be numbers separated "
                                                  f"by commas") from None
            dist = Mixture(comps, weights)
        else:
            if args.histogram is None:
                raise UsageError("--histogram", "required with --orientation csv")
            try:
                dist = Histogram.from_csv(args.histogram)
            except ValueError as error:
                raise UsageError("--histogram", str(error)) from None
        if not math.isfinite(args.psi_deg):
            raise ValueError(f"psi={args.psi_deg!r} must be a finite angle in degrees")
        return rotated(dist, math.radians(args.psi_deg))
    except ValueError as error:
        raise _usage(error) from None


def run(args, orientation: str) -> int:
    """Compute and print one distribution array; 0 on success, 1 if it did not succeed."""
    if orientation == "pair" and args.tol is not None:
        raise UsageError("--tol", "only with a continuous distribution (a pair has no "
                                  "quadrature over theta0)")
    dist = distribution(args, orientation)
    k_r, k_theta = stiffness(args)
    try:
        params = Params(k_r=k_r, k_theta=k_theta, F_N=args.F_N)
        result = distribution_array(params, dist, beta=args.beta,
                                    tol=1e-3 if args.tol is None else args.tol,
                                    rtol=args.rtol, atol=args.atol, method=args.method)
    except ValueError as error:
        raise _usage(error) from None
    record = {"orientation": orientation, **result.to_dict()}
    print(json.dumps(jsonable(record)) if args.json else summary(record))
    return 0 if record["success"] else 1


def summary(r: dict) -> str:
    """A readable report of a distribution array."""
    p = r["params"]

    def pm(key):
        words = error_words(r, key)
        return f" ({words})" if words.startswith("±") else f" {words}".rstrip()

    params = [("orientation", r["orientation"], json.dumps(r["distribution"])),
              ("k_r", p["k_r"], "radial stiffness"),
              ("k_theta", p["k_theta"], "torsional stiffness"),
              ("F_N", p["F_N"], "normal load per support at rest"),
              ("beta", r["beta"], f"load factor N_c0/N_c, residual {r['beta_residual']:.2g}")]
    results = [
        ("success", r["success"], r["message"]),
        ("FTx_over_mu0FN", r["FTx_over_mu0FN"],
         "apparent friction F_T,x/(mu0 F_N), p-weighted paper average (Eq. 10)"
         + pm("FTx_over_mu0FN")),
        ("FTx_over_mu0FN_duration", r["FTx_over_mu0FN_duration"],
         "duration-weighted: sum int F_f,x dtau / (f_N sum tau_out)"
         + pm("FTx_over_mu0FN_duration")),
        ("FTy_over_mu0FN", r["FTy_over_mu0FN"], "transverse force F_T,y/(mu0 F_N)"
         + pm("FTy_over_mu0FN")),
        ("Dy_over_Dx", r["Dy_over_Dx"], "transverse over longitudinal dissipation"
         + pm("Dy_over_Dx")),
        ("Nc_over_Nc0", r["Nc_over_Nc0"], "contact count <tau_out>_p/L0" + pm("Nc_over_Nc0")),
    ]
    results += [(f"{k}/W", v, "share of the slab work (Eq. 12)")
                for k, v in r["work_split"].items()]
    checks = [("n_members", r["n_members"], "orientations integrated (point masses included)"),
              ("n_failed", r["n_failed"], "members that did not finish their contact"),
              ("n_pivot", r["n_pivot"], "members driven into the region of their pivot"),
              ("integration_error", r["integration_error"], "largest |energy residual|/W"),
              ("seconds", r["seconds"], "wall time")]
    return table([("Parameters (dimensionless)", params), ("Array", results),
                  ("Checks", checks)])
