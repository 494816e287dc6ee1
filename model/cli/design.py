"""``python -m model design``: the orientation distribution with the least friction.

Searches a family (fixed, pair, vonmises, mixture) for the smallest F_T,x/(mu0 F_N)
under a bound on |F_T,y|/(mu0 F_N) (``--objective min-FTx``), or the largest
|F_T,y|/(mu0 F_N) under a bound on F_T,x/(mu0 F_N) (``--objective max-FTy``), and
compares it with the uniform array (``model.designs.design.optimise``).

``python -m model pillar`` (registered with ``design``): a real pillar array in physical
units (``model.designs.units``): its dimensionless point, regime and, with ``--evaluate``, its
array's drive force, power, contact time and excursion.
"""
from __future__ import annotations

import json
import math
import re

from ..contact.params import DEFAULTS, Params
from ..designs.design import FAMILIES, OBJECTIVES, OptimisationCancelled, optimise
from ..designs.design_table import headline, rows as design_rows
from .sweep import POINT_BYTES
from ._common import (FIELD_FLAGS, UsageError, add_stiffness, beta_value, check_memory,
                      jsonable, real, stiffness, table, whole)

_FLAGS = {"bound": None, "n_scan": "--n-scan", "max_evaluations": "--max-evaluations",
          "family": "--family", "objective": "--objective"}


def add_command(commands) -> None:
    p = commands.add_parser(
        "design", help="the orientation distribution with the least friction",
        description="Find the orientation distribution of a family that minimises the "
                    "apparent friction F_T,x/(mu0 F_N) under a bound on |F_T,y|/(mu0 F_N) "
                    "(or maximises |F_T,y| under a bound on F_T,x), with the gain over the "
                    "uniform array. A global search: a scan over theta0, then scipy.optimize.")
    model = p.add_argument_group("array")
    add_stiffness(model)
    model.add_argument("--F-N", type=real, default=1.0, metavar="F",
                       help="normal load F_N per support at rest (default 1)")
    model.add_argument("--beta", type=beta_value, default="self", metavar="self|B",
                       help="load factor: 'self' (default) or a number in (0, 1]")
    search = p.add_argument_group("search")
    search.add_argument("--objective", choices=OBJECTIVES, default="min-FTx",
                        help="min-FTx (default): least F_T,x; max-FTy: largest |F_T,y|")
    search.add_argument("--family", choices=FAMILIES, default="pair",
                        help="distributions searched (default pair: +-theta0, F_T,y = 0)")
    search.add_argument("--max-abs-FTy", type=real, metavar="B",
                        help="min-FTx: bound on |F_T,y|/(mu0 F_N) (default none)")
    search.add_argument("--max-FTx", type=real, metavar="B",
                        help="max-FTy: bound on F_T,x/(mu0 F_N) (default none)")
    search.add_argument("--tol", type=real, default=1e-3, metavar="T",
                        help="quadrature tolerance of each array (default 1e-3)")
    search.add_argument("--n-scan", type=whole, default=90, metavar="N",
                        help="theta0 grid on [0, pi] for the scan (default 90)")
    search.add_argument("--max-evaluations", type=whole, default=200, metavar="N",
                        help="model evaluations allowed in the refinement (default 200)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=run)
    add_pillar_command(commands)


def _usage(error: ValueError) -> UsageError:
    match = re.match(r"(\w+)=", str(error))
    name = match.group(1) if match else None
    flag = _FLAGS.get(name) or FIELD_FLAGS.get(name)
    return UsageError(flag, str(error))


def run(args) -> int:
    """``design``: search and print the optimum; 0 on success, 1 if it did not succeed."""
    if args.objective == "min-FTx" and args.max_FTx is not None:
        raise UsageError("--max-FTx", "only with --objective max-FTy")
    if args.objective == "max-FTy" and args.max_abs_FTy is not None:
        raise UsageError("--max-abs-FTy", "only with --objective min-FTx")
    bound, flag = ((args.max_abs_FTy, "--max-abs-FTy") if args.objective == "min-FTx"
                   else (args.max_FTx, "--max-FTx"))
    if bound is not None and not (math.isfinite(bound) and bound >= 0):
        raise UsageError(flag, f"{bound!r} must be a finite number >= 0")
    k_r, k_theta = stiffness(args)
    if args.n_scan >= 1:  # below the minimum: named by optimise itself
        check_memory("--n-scan", args.n_scan * POINT_BYTES["orientation"],
                     f"{args.n_scan:,} scanned orientations")
    try:
        params = Params(k_r=k_r, k_theta=k_theta, F_N=args.F_N)
        result = optimise(params, family=args.family, objective=args.objective, bound=bound,
                          beta=args.beta, tol=args.tol, n_scan=args.n_scan,
                          max_evaluations=args.max_evaluations)
    except OptimisationCancelled as error:  # pragma: no cover - no cancel event here
        raise UsageError(None, str(error)) from None
    except ValueError as error:
        if str(error).startswith("family="):
            raise UsageError("--family", str(error)) from None
        raise _usage(error) from None
    record = result.to_dict()
    print(json.dumps(jsonable(record)) if args.json else _summary(record))
    return 0 if record["success"] else 1


def _summary(r: dict) -> str:
    p = r["params"]
    bound_key = "max_abs_FTy" if r["objective"] == "min-FTx" else "max_FTx"
    setup = [("k_r", p["k_r"], "radial stiffness"),
             ("k_theta", p["k_theta"], "torsional stiffness"),
             ("F_N", p["F_N"], "normal load per support at rest"),
             ("objective", r["objective"], "min-FTx: least F_T,x; max-FTy: largest |F_T,y|"),
             ("family", r["family"], "distributions searched"),
             (bound_key, "none" if r[bound_key] is None else r[bound_key], "bound")]
    found = [("success", r["success"], r["message"]),
             ("distribution", json.dumps(r["distribution"]), "the optimum"),
             ("FTx_over_mu0FN", r["FTx_over_mu0FN"],
              f"apparent friction (+- {r['error_estimate']:.2g})"),
             ("FTy_over_mu0FN", r["FTy_over_mu0FN"], "transverse force"),
             ("uniform_FTx_over_mu0FN", r["uniform_FTx_over_mu0FN"], "the uniform array"),
             ("gain", r["gain"], "1 - F_T,x(optimum)/F_T,x(uniform)"),
             ("beta", r["beta"], "load factor of the optimum"),
             ("evaluations", r["evaluations"], "model evaluations"),
             ("seconds", r["seconds"], "wall time")]
    return table([("Search", setup), ("Optimum", found)])


# --------------------------------------------------------------------------- pillar

#: ``pillar`` flags -> PillarDesign fields (values with units, e.g. "5 um").
_PILLAR = {"--D": "D", "--h": "h", "--E": "E", "--G": "G", "--nu": "nu", "--rho": "rho",
           "--mass-fraction": "mass_fraction", "--r0": "r0", "--d-x": "d_x", "--d-y": "d_y",
           "--L-x": "L_x", "--L-y": "L_y", "--F-N": "F_N", "--V0": "V0", "--V-s": "V_s",
           "--mu-s": "mu_s", "--A": "A", "--B": "B"}
_PILLAR_HELP = {"D": "pillar diameter, e.g. '5 um'", "h": "pillar height, e.g. '50 um'",
                "E": "Young's modulus, e.g. '1 GPa'", "G": "shear modulus (or --nu)",
                "nu": "Poisson's ratio (or --G)", "rho": "density, e.g. '920 kg/m^3'",
                "mass_fraction": "share of the pillar's mass moving with its tip (default 1)",
                "r0": "radial rest length r0, e.g. '10 um'", "d_x": "pillar spacing along x",
                "d_y": "pillar spacing along y", "L_x": "slab length along x",
                "L_y": "slab width", "F_N": "total normal load, e.g. '1 mN'",
                "V0": "sliding speed, e.g. '1 cm/s'",
                "V_s": "friction law's velocity scale (default: zeta = V0/V_s = 10)",
                **{name: f"friction law {name} (default {DEFAULTS[name]:g})"
                   for name in ("mu_s", "A", "B")}}


def add_pillar_command(commands) -> None:
    from . import compare, orientations, speeds

    p = commands.add_parser(
        "pillar", help="a real pillar array in physical units: its point on the map",
        description="A micropillar array in physical units (values with units, e.g. '5 um', "
                    "'1.2 GPa'): its dimensionless point (k~_r, k~_theta, F~_N), its regime, "
                    "the speeds and heights of the other regimes; with --evaluate its array "
                    "and the drive force (N), power (W), contact time (s) and excursion (um).")
    g = p.add_argument_group("design (with units)")
    for flag, name in _PILLAR.items():
        g.add_argument(flag, dest=f"pillar_{name}", metavar="Q", help=_PILLAR_HELP[name])
    g.add_argument("--friction", metavar="FILE.json",
                   help="the friction law (mu_s, A, B, V_s in m/s) from a JSON file, such as "
                        "the one 'friction fit --out' writes; instead of --mu-s/--A/--B/--V-s")
    g.add_argument("--prefactors", choices=("paper", "beam"), default="paper",
                   help="stiffness prefactors: paper (1, 1) or beam theory (3 pi/64, pi/32)")
    run_group = p.add_argument_group("evaluation")
    run_group.add_argument("--evaluate", action="store_true",
                           help="compute the array and its physical results")
    run_group.add_argument("--orientation", choices=("uniform", "fixed",
                                                     *orientations.ORIENTATIONS),
                           default="uniform", help="orientation distribution (default uniform)")
    run_group.add_argument("--theta0", type=real, metavar="T",
                           help="fixed or pair: orientation in radians (default pi/2)")
    run_group.add_argument("--beta", type=beta_value, default="self", metavar="self|B",
                           help="load factor: 'self' (default) or a number in (0, 1]")
    run_group.add_argument("--tol", type=real, metavar="T",
                           help="quadrature tolerance (default 1e-3)")
    run_group.add_argument("--budget", type=real, metavar="S",
                           help="time budget of the evaluation in seconds (default none); "
                                "running out prints the result with success false, its "
                                "outcome and remedy, and exits with 1")
    speeds.add_arguments(run_group)
    compare.add_arguments(run_group)
    orientations.add_arguments(p)
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=run_pillar)


def _pillar_design(args):
    from ..designs.units import BEAM_PREFACTORS, PillarDesign

    values = {name: getattr(args, f"pillar_{name}") for name in _PILLAR.values()}
    missing = [flag for flag, name in _PILLAR.items()
               if values[name] is None and name in ("D", "h", "E", "rho", "r0", "d_x", "d_y",
                                                    "L_x", "L_y", "F_N", "V0")]
    if missing:  # all at once, not one per attempt
        raise UsageError(", ".join(missing), "required (values with units, e.g. --h '50 um'; "
                         "each is described by --help)")
    kwargs = {k: v for k, v in values.items() if v is not None}
    if args.friction is not None:
        kwargs.update(_friction_fields(args.friction, kwargs))
    if args.prefactors == "beam":
        kwargs.update(prefactor_r=BEAM_PREFACTORS["k_r"],
                      prefactor_theta=BEAM_PREFACTORS["k_theta"])
    try:
        return PillarDesign(**kwargs)
    except ValueError as error:
        match = re.match(r"(\w+)=", str(error))
        flags = {name: flag for flag, name in _PILLAR.items()}
        raise UsageError(flags.get(match.group(1)) if match else None, str(error)) from None


#: The flags a friction-law file replaces.
_LAW_FLAGS = ("--mu-s", "--A", "--B", "--V-s")


def _friction_fields(path: str, given: dict) -> dict:
    """The ``PillarDesign`` friction inputs from the JSON file ``path``; ``UsageError``
    naming --friction for a file that cannot be read or a law flag given as well."""
    from ..lab.friction_law import FrictionLaw

    both = [flag for flag in _LAW_FLAGS if _PILLAR[flag] in given]
    if both:
        raise UsageError("--friction", f"give the friction law as a file or as {both[0]}, "
                                       f"not both")
    try:
        return FrictionLaw.from_json(path).design_fields()
    except ValueError as error:
        raise UsageError("--friction", str(error)) from None


def _distribution(args):
    """The orientation distribution of --orientation and its flags (None: uniform)."""
    from ..designs.distributions import Fixed
    from . import orientations

    if args.orientation in orientations.ORIENTATIONS:
        return orientations.distribution(args, args.orientation)
    orientations.reject_foreign(args, args.orientation)
    return Fixed(math.pi / 2 if args.theta0 is None else args.theta0) \
        if args.orientation == "fixed" else None


def run_pillar(args) -> int:
    """``pillar``: where a real design sits; with --evaluate its array in physical units;
    with --speeds its friction against sliding speed."""
    from ..designs.design_point import evaluate, model_point, regime_intervals
    from . import compare, speeds

    compare.check(args)
    if args.budget is not None and not (args.evaluate or args.speeds or args.compare):
        raise UsageError("--budget", "only with --evaluate, --speeds or --compare (the point "
                                     "itself costs no time)")
    if args.budget is not None and not (math.isfinite(args.budget) and args.budget > 0):
        raise UsageError("--budget", f"{args.budget!r} must be a finite number of seconds > 0")
    values = speeds.speeds(args)
    design = _pillar_design(args)
    if values is not None:
        return speeds.run(args, design, _distribution(args), values)
    if args.compare is not None:
        return compare.run(args, design, _distribution(args))
    record = {"design": design.to_dict(), "point": design.dimensionless(),
              "regime": design.regime(), "intervals": regime_intervals(design)}
    try:
        computed, status, message = model_point(design)
        record.update(computed=computed, status=status, status_message=message)
    except ValueError as error:
        record.update(status="outside_range", status_message=str(error))
        if args.evaluate:
            raise UsageError(None, str(error)) from None
    code = 0
    if args.evaluate:
        dist = _distribution(args)
        try:
            result = evaluate(design, dist, beta=args.beta,
                              tol=1e-3 if args.tol is None else args.tol, budget=args.budget)
        except ValueError as error:
            # The dimensionless numbers the model checks, named by the input that sets them.
            match = re.match(r"(\w+)=", str(error))
            flag = {"zeta": "--V-s", "L0": "--L-x", "mu_s": "--mu-s", "A": "--A", "B": "--B",
                    "beta": "--beta", "tol": "--tol",
                    "budget": "--budget"}.get(match.group(1) if match else None)
            raise UsageError(flag, str(error)) from None
        record = result.to_dict()
        code = 0 if result.success else 1
    print(json.dumps(jsonable(record)) if args.json else _pillar_summary(record))
    return code


def _law_text(design: dict) -> str:
    """mu_s, A, B (and V_s with its unit) of a design's ``to_dict``."""
    text = ", ".join(f"{name} {design[name]:.4g}" for name in ("mu_s", "A", "B"))
    if "V_s" in design:
        text += f", V_s {design['V_s']:.4g} {design['units']['V_s']}"
    return text


def _pillar_summary(r: dict) -> str:
    p = r["point"]
    rows = [("k_r", p["k_r"], "k~_r = r0^2 k_r / (m V0^2)"),
            ("k_theta", p["k_theta"], "k~_theta = k_theta / (m V0^2)"),
            ("F_N", p["F_N"], "F~_N = r0 F_N / (N_c0 m V0^2)"),
            ("zeta", p["zeta"], "V0 / V_s"), ("L0", p["L0"], "L_x / r0"),
            ("friction", _law_text(r["design"]), "friction law, Eq. (4)"),
            ("regime", r["regime"], "quadrant of the map"),
            ("status", r["status"], r["status_message"])]
    for regime, span in r["intervals"]["V0_m_per_s"].items():
        rows.append((f"V0 {regime}", "unreachable" if span is None else
                     f"{span[0]:.3g} .. {span[1]:.3g}", "m/s"))
    sections = [("Dimensionless point", rows)]
    if "FTx_N" in r:
        sections.append(("Array in physical units", [
            ("success", r["success"], r["message"]),
            ("outcome", r["array"]["outcome"], "ok, or what ran out"),
            ("headline", "", headline(r)),
            *((row["key"], row["text"], row["what"]) for row in design_rows(r))]))
    return table(sections)
