"""``micropillar friction fit FILE.csv``: fit the friction law of Eq. (4) to a measured
curve (friction coefficient against sliding speed; ``model.lab.friction_curve`` says the
file's form), reporting mu_s, A, B and V_s with 95 % intervals, their correlations, the
residual and warnings for coefficients the data do not determine (``model.lab.friction_fit``).
``--out fit.json`` writes the law that ``micropillar pillar --friction fit.json`` uses.
"""
from __future__ import annotations

import json
import math

from ..files import write_text_atomic
from ..lab.friction_curve import CurveFileError, read_curve, speed_factor
from ..lab.friction_fit import fit_friction
from ._common import UsageError, jsonable, output_file, table

_MEANING = {"mu_s": "static friction coefficient", "A": "shape A", "B": "shape B",
            "V_s": "velocity scale [m/s]"}


def add_command(commands) -> None:
    p = commands.add_parser(
        "friction", help="the friction law of Eq. (4): fit it to a measured curve",
        description="The friction law of Eq. (4), mu(v) = mu_s sin(A atan(x - B (x - atan x))) "
                    "with x = v/V_s.")
    actions = p.add_subparsers(title="actions", metavar="action", dest="action")
    p.set_defaults(run=_no_action, kernel=False)
    fit = actions.add_parser(
        "fit", help="fit mu_s, A, B and V_s to a measured curve",
        description="Fit mu_s, A, B and V_s of Eq. (4) to friction coefficient against "
                    "sliding speed read from a CSV file whose first row names the columns "
                    "'v [unit]' and 'mu' (and optionally 'mu_err', the standard error of each "
                    "mu, which weights the fit); lines starting with '#' are skipped. Reports "
                    "each coefficient with its 95 %% confidence interval, their correlations, "
                    "the rms residual and warnings for coefficients the data do not determine.",
        epilog="Exit codes: 0 fitted (warnings included), 1 the fit did not converge (results "
               "printed, nothing written), 2 a bad file or flag (one line naming it).")
    fit.add_argument("file", metavar="FILE.csv", help="the measured curve")
    fit.add_argument("--v-unit", metavar="UNIT",
                     help="unit of the v column when its header has none, e.g. mm/s")
    fit.add_argument("--json", action="store_true",
                     help="print one JSON object (SI units: V_s in m/s)")
    fit.add_argument("--out", metavar="FILE.json",
                     help="also write the JSON to this file (only when the fit converged); "
                          "--friction of 'pillar' reads it")
    fit.set_defaults(run=run_fit, kernel=False)


def _no_action(args) -> int:
    raise UsageError(None, "name an action: fit (micropillar friction fit FILE.csv)")


def run_fit(args) -> int:
    """``friction fit``: read, fit, print; 0 fitted, 1 not converged, 2 bad input."""
    out = output_file("--out", args.out) if args.out else None
    try:
        if args.v_unit is not None:
            speed_factor(args.v_unit)
        curve = read_curve(args.file, v_unit=args.v_unit)
    except CurveFileError as error:
        raise UsageError(None, str(error)) from None
    result = fit_friction(curve)
    record = jsonable(result.to_dict())
    print(json.dumps(record) if args.json else _summary(result))
    if out is not None and result.success:
        write_text_atomic(out, json.dumps(record, indent=1) + "\n")
    return 0 if result.success else 1


def _interval(name: str, lo: float, hi: float) -> str:
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return "95 % interval: none"
    return f"95 % interval [{lo:.4g}, {hi:.4g}]"


def _summary(fit) -> str:
    coefficients = [(name, fit.values[name], f"{_MEANING[name]}; {_interval(name, *fit.ci95[name])}")
                    for name in ("mu_s", "A", "B", "V_s")]
    order = ("mu_s", "A", "B", "ln V_s")
    pairs = [(f"corr({order[i]}, {order[j]})", fit.correlation[i, j], "")
             for i in range(4) for j in range(i + 1, 4)]
    quality = [("success", fit.success, fit.message),
               ("rms_residual", fit.rms_residual, "rms of mu(v) - measured mu"),
               ("n_points", fit.n_points, "measured points"
                + (" (weighted by mu_err)" if fit.weighted else ""))]
    if fit.chi2_reduced is not None:
        quality.append(("chi2_reduced", fit.chi2_reduced, "about 1 when mu_err is right"))
    sections = [("Friction law, Eq. (4)", coefficients), ("Correlations", pairs),
                ("Fit", quality)]
    text = table(sections)
    if fit.warnings:
        text += "\n\nWarnings\n" + "\n".join(f"  - {w}" for w in fit.warnings)
    return text
