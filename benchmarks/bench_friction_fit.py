"""Speed of the friction-law fit (issue 27) and of a friction-velocity curve.

    python benchmarks/bench_friction_fit.py [--quick] [--out DIR]

* The fit of Eq. (4) to 1 000 synthetic points (the paper's law with V_s = 1 mm/s,
  speeds 0.01 to 100 V_s, Gaussian noise 0.02; target <= 1 s): ``model.fit_friction``
  (a few starts read off the curve, analytic Jacobian, intervals and warnings included)
  against the best honest alternative, ``scipy.optimize.curve_fit`` with the same bounds
  from the same first guess (the best of fit_friction's starts; finite-difference Jacobian,
  covariance only, no warnings). Median [min-max] over repeats, and each one's distance to the true coefficients.
* A 30-speed friction-velocity curve (``model.lab.speed_curve``) of a von Mises array (mean
  60 deg, kappa 4) for soft pillars at 0.1-1 m/s, each run with the model's caches
  cleared: on two processes (``workers=2``, the command line's default: the speeds are
  independent, the slowest handed out first) against the best honest alternative, one
  process (``workers=1``, the serial path), and the slowest single speed (the floor two
  processes cannot go below). Median [min-max] over ``--repeats`` runs (default 3; target
  <= 10 s on 2 cores; 5 speeds twice with --quick). Both give the same points, bit for bit
  (checked here). Where the time goes: the stiffest pillars, at the lowest speeds, cost
  the most (at 0.1 m/s a few hundred quadrature members, each integrated at every load
  factor the self-consistent beta iteration tries; 0.1 m/s alone is about half the
  serial time), so one slow speed bounds what two processes gain.

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
from model.designs.distributions import VonMises
from model.contact.friction import law
from model.lab.friction_fit import _bounds, _starts
from model.lab.speed_curve import friction_velocity, speed_range
from model.designs.units import PillarDesign

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
    """``repeats`` runs of an ``n``-speed curve on 2 processes and on 1, and of its slowest
    speed alone, each with the model's caches cleared."""
    from model.designs.distribution_array import _cached_array
    from model.contact.support import _simulate

    design = PillarDesign.example(E="1 MPa", V0="1 m/s", V_s="1 mm/s", L_x="0.1 mm",
                                  F_N="10 uN")
    dist = VonMises(math.radians(60), 4.0)
    friction_velocity(design, [1.0], dist)  # kernel loaded
    speeds = speed_range(0.1, 1.0, n)

    def clear():
        _cached_array.cache_clear()
        _simulate.cache_clear()

    out, curves = {"n": n}, {}
    for name, workers, values in (("two_processes", 2, speeds), ("one_process", 1, speeds),
                                  ("slowest_speed", 1, speeds[:1])):
        seconds, curves[name] = cold_runs(
            lambda: friction_velocity(design, values, dist, workers=workers), clear,
            min_total=0.0, lo=repeats, hi=repeats)
        out[name] = seconds
    out["seconds"] = out["two_processes"]
    out["success"] = curves["two_processes"].success
    out["same_points"] = curves["two_processes"].points == curves["one_process"].points
    return out


def fit_lines(fit: dict) -> list[str]:
    """The fit's table: each method's seconds, error and convergence."""
    lines = [f"{N_POINTS} points, noise {NOISE}; seconds median [min–max] over "
             f"{fit['fit_friction']['runs']} draws (target <= 1 s).", "",
             "| method | seconds | largest relative error | converged |", "|---|---|---|---|"]
    for name, r in fit.items():
        s, e = r["seconds"], r["max_rel_error"]
        lines.append(f"| {name} | {cell(s['median'], s['min'], s['max'])} | "
                     f"{cell(e['median'], e['min'], e['max'], lambda x: f'{x:.2g}')} | "
                     f"{r['converged']}/{r['runs']} |")
    return lines


def speeds_lines(speeds: dict) -> list[str]:
    """The friction-velocity curve's table: 2 processes, 1 process, the slowest speed."""
    lines = [f"Friction-velocity curve, von Mises array, {speeds['n']} speeds, cold caches; "
             f"seconds median [min–max] over {speeds['seconds']['n']} runs (target <= 10 s "
             f"for 30 on 2 cores):", "", "| path | seconds |", "|---|---|"]
    for name, words in (("two_processes", "2 processes (workers=2, the default)"),
                        ("one_process", "1 process (workers=1, serial)"),
                        ("slowest_speed", "the slowest speed alone (the floor of 2)")):
        t = speeds[name]
        lines.append(f"| {words} | {cell(t['median'], t['min'], t['max'], lambda x: f'{x:.2f}')} |")
    return lines + ["", f"All speeds succeeded: {speeds['success']}; the same points on 1 "
                        f"and 2 processes: {speeds['same_points']}."]


def report(fit: dict, speeds: dict) -> str:
    cpu = platform.processor() or platform.machine()
    lines = [f"# Friction-law fit ({platform.node()}, {cpu})", "", *fit_lines(fit), "",
             *speeds_lines(speeds), "",
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
