"""Speed of the design tools: distribution arrays and the optimiser (issue 16).

    python benchmarks/bench_design.py [--quick] [--corners] [--out DIR]

Reports medians over cold-cache repeats with their min and max, against the best honest
alternatives run in the same process on the same compiled kernel:

* a von Mises array (mean 60 deg, kappa 4, self-consistent beta) at tol 1e-3 in each
  regime (target <= 100 ms), its error against a tol 1e-6 reference; the alternatives:
  the paper's method (200 random supports, Eq. 10, with its own beta solve) and the
  midpoint rule on the circle with as many orientations as the adaptive rule used;
* the pair-family optimisation in each regime (target <= 5 s), its gap to a dense scan
  (720 orientations, the brute-force alternative, timed too);
* with --corners, one run each of the uniform array at the corners of the model range
  [1e-3, 1e6]^2 (bounded cost, not a target);
* with --tab, the Design tab's array for the notes' LDPE pillars at three sliding speeds
  (one run each, under the tab's budget), and where its time goes: the cost of each
  member of the first partition at beta = 1 (stiff springs ring; a few members near
  theta0 = 0, pi/2, pi take most of the steps).
"""
from __future__ import annotations

import argparse
import json
import math
import platform
import time
from pathlib import Path

import numpy as np

from model import REGIMES, Params, orientation_sweep
from model.designs import design as design_module
from model._kernel import warmup
from model.arrays.beta import solve_beta_scalar
from model.arrays.contacts import run_contacts
from model.designs.design import optimise
from model.designs.distribution_array import _cached_array, distribution_array
from model.designs.distributions import Uniform, VonMises
from model.contact.friction import mu0
from model.contact.options import SolverOptions
from model.contact.support import _simulate

from spread import cell, cold_runs

VM = VonMises(math.radians(60), 4.0)


def _clear():
    _simulate.cache_clear()
    _cached_array.cache_clear()
    design_module._CACHE.clear()


def timed(fn, min_total, lo=3, hi=15):
    return cold_runs(fn, _clear, min_total, lo, hi)


def monte_carlo(params, n=200, seed=0):
    """The paper's estimate: n supports with theta0 drawn from the distribution, beta
    solved on them; returns (F_T,x/(mu0 F_N), its standard error)."""
    theta = np.random.default_rng(seed).vonmises(VM.mean, VM.kappa, n)
    options = SolverOptions(rtol=1e-5)

    def tau(b):
        return float(np.mean(run_contacts(params, theta, options, beta=np.full(n, b))[0].t_out))

    beta = solve_beta_scalar(tau, params.L0, xtol=1e-5).beta
    fx = run_contacts(params, theta, options, beta=np.full(n, beta))[0].F_x / mu0(params)
    return float(np.mean(fx)), float(np.std(fx, ddof=1) / math.sqrt(n))


def midpoint(params, n):
    """The midpoint rule on the circle with n orientations, beta solved on them."""
    theta = (np.arange(n) + 0.5) * 2 * math.pi / n - math.pi
    w = VM.density(theta) * 2 * math.pi / n
    options = SolverOptions(rtol=1e-5)

    def tau(b):
        return float(w @ run_contacts(params, theta, options, beta=np.full(n, b))[0].t_out)

    beta = solve_beta_scalar(tau, params.L0, xtol=1e-5).beta
    fx = run_contacts(params, theta, options, beta=np.full(n, beta))[0].F_x
    return float(w @ fx) / mu0(params)


def bench_vonmises(min_total):
    rows = []
    for name, p in REGIMES.items():
        ref = distribution_array(p, VM, tol=1e-6)
        t, r = timed(lambda: distribution_array(p, VM, tol=1e-3), min_total)
        tm, (mc, mc_se) = timed(lambda: monte_carlo(p), min_total)
        n_nodes = int(r.n_members)
        tq, mid = timed(lambda: midpoint(p, 2 * n_nodes), min_total)
        rows.append(dict(regime=name, adaptive=t,
                         adaptive_error=abs(r.FTx_over_mu0FN - ref.FTx_over_mu0FN),
                         adaptive_estimate=r.quadrature_error["FTx_over_mu0FN"],
                         trajectories=r.stats["trajectories"], nodes=n_nodes,
                         monte_carlo=tm, mc_error=abs(mc - ref.FTx_over_mu0FN), mc_se=mc_se,
                         midpoint=tq, midpoint_n=2 * n_nodes,
                         midpoint_error=abs(mid - ref.FTx_over_mu0FN),
                         FTx_over_mu0FN=r.FTx_over_mu0FN))
    return rows


def bench_pair(min_total):
    rows = []
    grid = (np.arange(720) + 0.5) * math.pi / 720
    for name, p in REGIMES.items():
        t, r = timed(lambda: optimise(p, "pair"), min_total, lo=3, hi=5)
        td, s = timed(lambda: orientation_sweep(p, grid, rtol=1e-6), min_total, lo=1, hi=3)
        best = float(np.min(s.FTx_over_mu0FN))
        rows.append(dict(regime=name, optimise=t, FTx_over_mu0FN=r.FTx_over_mu0FN,
                         error_estimate=r.error_estimate, evaluations=r.evaluations,
                         dense=td, dense_best=best, gap=r.FTx_over_mu0FN - best, gain=r.gain))
    return rows


def bench_corners():
    rows = []
    for k_r, k_theta in ((1e6, 1e6), (1e6, 1e-3), (1e-3, 1e6), (1e-3, 1e-3)):
        _clear()
        start = time.perf_counter()
        r = distribution_array(Params(k_r, k_theta), Uniform(), tol=1e-3)
        rows.append(dict(k_r=k_r, k_theta=k_theta, seconds=time.perf_counter() - start,
                         FTx_over_mu0FN=r.FTx_over_mu0FN, success=r.success,
                         trajectories=r.stats["trajectories"], n_rhs=r.stats["n_rhs"]))
    return rows


TAB_SPEEDS = ("1 cm/s", "10 cm/s", "1 m/s")


def bench_tab():
    """The Design tab's uniform array at each of ``TAB_SPEEDS`` (its tol and budget), and
    the step cost of the 60 members of its first partition at beta = 1."""
    from app.worker import DESIGN_REFINE_S, DESIGN_TOL
    from model.designs.design_point import evaluate, model_params
    from model.designs.distribution_nodes import initial_edges, nodes
    from model.designs.units import PillarDesign

    rows = []
    for speed in TAB_SPEEDS:
        design = PillarDesign.example(V0=speed)
        p = model_params(design)
        theta = nodes(initial_edges(Uniform()))
        start = time.perf_counter()
        c = run_contacts(p.replace(theta0=0.0), theta, SolverOptions(rtol=DESIGN_TOL / 100),
                         beta=np.ones(theta.size))[0]
        members_s = time.perf_counter() - start
        steps = np.sort(c.stats[:, 0] + c.stats[:, 1])[::-1]
        _clear()
        start = time.perf_counter()
        r = evaluate(design, Uniform(), tol=DESIGN_TOL, budget=DESIGN_REFINE_S)
        a = r.array
        rows.append(dict(V0=speed, k_r=p.k_r, k_theta=p.k_theta, status=r.status,
                         seconds=time.perf_counter() - start, budget=DESIGN_REFINE_S,
                         outcome=a.outcome, trajectories=a.stats["trajectories"],
                         beta_iterations=a.beta_iterations, n_failed=a.n_failed,
                         FTx_over_mu0FN=a.FTx_over_mu0FN, members=int(theta.size),
                         members_s=members_s, steps=int(steps.sum()), max_steps=int(steps[0]),
                         top6_share=float(steps[:6].sum() / steps.sum()),
                         median_steps=float(np.median(steps))))
    return rows


def tab_report(rows) -> list:
    lines = ["", "## Design tab: the notes' LDPE pillars (uniform array, tol and budget of "
             "the tab; one run each)", "",
             "| V0 | computed k~_r, k~_theta | array s (budget) | outcome | trajectories "
             "| F_T,x/(mu0 F_N) | 60 members at beta=1: s | steps: total, max, median "
             "| share of the 6 costliest |", "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['V0']} | {r['k_r']:.3g}, {r['k_theta']:.3g} ({r['status']}) | "
                     f"{r['seconds']:.1f} ({r['budget']:g}) | {r['outcome']} | "
                     f"{r['trajectories']} | {r['FTx_over_mu0FN']:.5f} | {r['members_s']:.2f} | "
                     f"{r['steps']:.3g}, {r['max_steps']:.3g}, {r['median_steps']:.3g} | "
                     f"{r['top6_share']:.0%} |")
    return lines


def ms(s):
    return cell(s["median"] * 1e3, s["min"] * 1e3, s["max"] * 1e3)


def report(vm, pair, corners, tab=()) -> str:
    cpu = platform.processor() or platform.machine()
    lines = [f"# Design benchmarks ({platform.node()}, {cpu})",
             "", "## Von Mises array (mean 60 deg, kappa 4, beta self-consistent, tol 1e-3)", "",
             "| regime | adaptive ms | error (estimate) | paper: 200 random ms | its error (s.e.) "
             "| midpoint rule (n) ms | its error |", "|---|---|---|---|---|---|---|"]
    for r in vm:
        lines.append(f"| {r['regime']} | {ms(r['adaptive'])} | {r['adaptive_error']:.1e} "
                     f"({r['adaptive_estimate']:.1e}) | {ms(r['monte_carlo'])} | "
                     f"{r['mc_error']:.1e} ({r['mc_se']:.1e}) | {ms(r['midpoint'])} "
                     f"({r['midpoint_n']}) | {r['midpoint_error']:.1e} |")
    lines += ["", "## Pair-family optimisation (min F_T,x, beta self-consistent)", "",
              "| regime | optimise s | F_T,x/(mu0 F_N) | gap to dense scan | gain over uniform "
              "| evaluations | dense scan (720) s |", "|---|---|---|---|---|---|---|"]
    for r in pair:
        o, d = r["optimise"], r["dense"]
        lines.append(f"| {r['regime']} | {cell(o['median'], o['min'], o['max'])} | "
                     f"{r['FTx_over_mu0FN']:.6f} | {r['gap']:+.1e} | {r['gain']:.3f} | "
                     f"{r['evaluations']} | {cell(d['median'], d['min'], d['max'])} |")
    if corners:
        lines += ["", "## Uniform array at the corners of the model range (one run each)", "",
                  "| k_r | k_theta | s | trajectories | RHS evaluations | F_T,x/(mu0 F_N) "
                  "| success |",
                  "|---|---|---|---|---|---|---|"]
        for r in corners:
            lines.append(f"| {r['k_r']:g} | {r['k_theta']:g} | {r['seconds']:.2f} | "
                         f"{r['trajectories']} | {r['n_rhs']} | {r['FTx_over_mu0FN']:.6f} | "
                         f"{r['success']} |")
    if tab:
        lines += tab_report(tab)
    return "\n".join(lines) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer repeats")
    parser.add_argument("--corners", action="store_true",
                        help="also the corners of the model range (slow: minutes)")
    parser.add_argument("--tab", action="store_true",
                        help="also the Design tab's pillars at three speeds (about 2 min)")
    parser.add_argument("--only-tab", action="store_true", help="only the --tab part")
    parser.add_argument("--out", type=Path, help="write design.md and design.json here")
    args = parser.parse_args(argv)
    warmup()
    min_total = 0.05 if args.quick else 0.5
    vm, pair = ([], []) if args.only_tab else (bench_vonmises(min_total),
                                                bench_pair(min_total))
    corners = bench_corners() if args.corners else []
    tab = bench_tab() if (args.tab or args.only_tab) else []
    text = report(vm, pair, corners, tab)
    print(text)
    if args.out:
        args.out.mkdir(parents=True, exist_ok=True)
        (args.out / "design.md").write_text(text)
        (args.out / "design.json").write_text(json.dumps(
            {"vonmises": vm, "pair": pair, "corners": corners, "tab": tab}, indent=1,
            default=float))


if __name__ == "__main__":
    main()
