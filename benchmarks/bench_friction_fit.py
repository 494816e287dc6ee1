"""Speed of the friction-law fit (issue 27) and of a friction-velocity curve.

    python benchmarks/bench_friction_fit.py [--quick] [--out DIR]

* The fit of Eq. (4) to 1 000 synthetic points (the paper's law with V_s = 1 mm/s,
  speeds 0.01 to 100 V_s, Gaussian noise 0.02; target <= 1 s): ``model.fit_friction``
  (a few starts read off the curve, analytic Jacobian, intervals and warnings included)
  against the best honest alternative, ``scipy.optimize.curve_fit`` with the same bounds
  from the same first guess (the best of fit_friction's starts; finite-difference Jacobian,
  covariance only, no warnings). Median [min-max] over repeats, and each one's distance to the true coefficients.
* A 30-speed friction-velocity curve (``model.speed_curve``) of a von Mises array (mean
  60 deg, kappa 4) for soft pillars at 0.1-1 m/s, in one process, each run with the
  model's caches cleared: median [min-max] over ``--repeats`` runs (default 3; target
  <= 10 s on 2 cores; 5 speeds twice with --quick).

Timings on a shared, loaded machine are not trustworthy: re-measure on a quiet one.
"""
from __future__ import annotations

import argparse
import json
import math
import platform
import time
from pathlib import Path

import numpy as np

from scipy.optimize import curve_fit

from model import FrictionCurve, FrictionLaw, fit_friction
from model.distributions import VonMises
from model.friction import law
from model.friction_fit import _bounds, _starts
from model.speed_curve import friction_velocity, speed_range
from model.units import PillarDesign

from spread import cell, cold_runs, spread

TRUE = FrictionLaw(V_s="1 mm/s")
N_POINTS, NOISE = 1000, 0.02


def _data(seed: int):
    v = np.geomspace(1e-2, 1e2, N_POINTS) * TRUE.V_s
    return v, TRUE.mu(v) + np.random.default_rng(seed).normal(0.0, NOISE, N_POINTS)


def _error(values) -> float:
    """Largest relative distance to the true coefficients (V_s through ln V_s)."""
    t = TRUE.to_dict()
    rel = [abs(values[k] / t[k] - 1) for k in ("mu_s", "A", "B")]
    return max(rel + [abs(math.log(values["V_s"] / t["V_s"]))])


def ours(v, mu):
    fit = fit_friction(FrictionCurve(v, mu))
    return fit.values, fit.success


def scipy_curve_fit(v, mu):
    v_pos = v[v > 0]
    lo, hi = _bounds(v_pos)
    # The same first guess fit_friction starts from (the best of its starts), not the truth.
    p0 = min(_starts(v, mu, v_pos, lo, hi),
             key=lambda p: float(np.sum((law(v * math.exp(-p[3]), *p[:3]) - mu) ** 2)))

    def model(x, mu_s, A, B, ln_V_s):
        return law(x * math.exp(-ln_V_s), mu_s, A, B)

    try:
        p, _ = curve_fit(model, v, mu, p0=p0, bounds=(lo, hi))
    except RuntimeError:
        return {k: math.nan for k in ("mu_s", "A", "B", "V_s")}, False
    return {"mu_s": p[0], "A": p[1], "B": p[2], "V_s": math.exp(p[3])}, True


def bench_fit(repeats: int) -> dict:
    out = {}
    for name, fn in (("fit_friction", ours), ("curve_fit", scipy_curve_fit)):
        fn(*_data(10**6))  # imports (scipy.stats) outside the timing
        times, errors, ok = [], [], 0
        for seed in range(repeats):
            v, mu = _data(seed)
            start = time.perf_counter()
            values, success = fn(v, mu)
            times.append(time.perf_counter() - start)
            errors.append(_error(values) if success else math.inf)
            ok += success
        out[name] = {"seconds": spread(times), "max_rel_error": spread(errors),
                     "converged": ok, "runs": repeats}
    return out


def bench_speeds(n: int, repeats: int) -> dict:
    """``repeats`` runs of an ``n``-speed curve, each with the model's caches cleared."""
    from model.distribution_array import _array
    from model.support import _simulate

    design = PillarDesign.example(E="1 MPa", V0="1 m/s", V_s="1 mm/s", L_x="0.1 mm",
                                  F_N="10 uN")
    dist = VonMises(math.radians(60), 4.0)
    friction_velocity(design, [1.0], dist)  # kernel loaded

    def clear():
        _array.cache_clear()
        _simulate.cache_clear()

    seconds, curve = cold_runs(lambda: friction_velocity(design, speed_range(0.1, 1.0, n), dist),
                               clear, min_total=0.0, lo=repeats, hi=repeats)
    return {"n": n, "seconds": seconds, "success": curve.success}


def report(fit: dict, speeds: dict) -> str:
    cpu = platform.processor() or platform.machine()
    lines = [f"# Friction-law fit ({platform.node()}, {cpu})", "",
             f"{N_POINTS} points, noise {NOISE}; seconds median [min–max] over "
             f"{fit['fit_friction']['runs']} draws (target <= 1 s).", "",
             "| method | seconds | largest relative error | converged |", "|---|---|---|---|"]
    for name, r in fit.items():
        s, e = r["seconds"], r["max_rel_error"]
        lines.append(f"| {name} | {cell(s['median'], s['min'], s['max'])} | "
                     f"{cell(e['median'], e['min'], e['max'], lambda x: f'{x:.2g}')} | "
                     f"{r['converged']}/{r['runs']} |")
    t = speeds["seconds"]
    lines += ["", f"Friction-velocity curve, von Mises array, {speeds['n']} speeds, one "
                  f"process: {cell(t['median'], t['min'], t['max'], lambda x: f'{x:.2f}')} s "
                  f"(median [min–max] over {t['n']} runs, cold caches; target <= 10 s for 30), "
                  f"all speeds succeeded: {speeds['success']}", "",
              "Measured on a shared machine: re-measure on a quiet one before quoting."]
    return "\n".join(lines) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer repeats, 5 speeds")
    parser.add_argument("--out", type=Path, help="write friction_fit.md and .json here")
    parser.add_argument("--repeats", type=int, default=3,
                        help="runs of the 30-speed curve (default 3)")
    args = parser.parse_args(argv)
    fit = bench_fit(3 if args.quick else 15)
    speeds = bench_speeds(5, 2) if args.quick else bench_speeds(30, args.repeats)
    text = report(fit, speeds)
    print(text)
    if args.out:
        args.out.mkdir(parents=True, exist_ok=True)
        (args.out / "friction_fit.md").write_text(text)
        (args.out / "friction_fit.json").write_text(json.dumps(
            {"fit": fit, "speeds": speeds}, indent=1, default=float))


if __name__ == "__main__":
    main()
