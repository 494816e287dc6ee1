"""Speed against error for one support: the compiled solvers against scipy.

    python benchmarks/bench_support.py [--quick] [--out DIR]

For each case the exit state (x, y, v_x, v_y, theta at tau_out) is compared with a
tight scipy reference (DOP853; Radau for the stiff case; cached in DIR/reference_cache.json). Every method runs
over a sweep of rtol (atol = rtol/100); each time is the median over repeated runs,
reported with its min and max, and the time needed for a target error is found by
log-log interpolation along the sweep. A scipy run is aborted past ABORT seconds, and
once one takes more than CAP seconds the tighter tolerances of that sweep are skipped
(tighter takes no less time); the report lists every such cut. Writes DIR/support.md,
DIR/support.json and the work-precision plots against the exit-state error and against
the energy-balance residual (DIR/work_precision.html with bokeh, screenshot to
DIR/work_precision.png; or the PNG with matplotlib) and prints the headline table.
"""
from __future__ import annotations

import argparse
import functools
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numba
import numpy as np


from model import REGIMES, Params, SolverOptions, simulate_support
from model.contact.options import REFERENCE_METHODS
from model import _kernel

from machine import machine
from plots import plot
from scipy_baselines import CUT, score, sweep_scipy
from spread import cell, repeats_for, spread

OURS = ("auto", "explicit", "implicit")
# "-lean": the researcher's script (scalar RHS, math functions); plain: 11-state numpy RHS.
SCIPY = {"full": ("RK45-lean", "RK45", "DOP853-lean", "DOP853", "LSODA-lean", "LSODA", "Radau"),
         "quick": ("RK45-lean", "RK45", "DOP853")}
RTOLS = {"full": [10.0**-k for k in range(3, 11)], "quick": [1e-4, 1e-6, 1e-8]}
REF_RTOL = {"full": 1e-13, "quick": 1e-12}
# Seconds per scipy run: past ABORT a run is aborted; after a run over CAP the tighter
# tolerances of its sweep are skipped. Both cuts are listed in the report.
CAP = {"full": 0.5, "quick": 0.25}
ABORT = {"full": 3.0, "quick": 1.0}
MIN_TOTAL = {"full": 0.1, "quick": 0.05}  # repeat a scipy run until about this many seconds, >= 3 times
TAU_MAX = SolverOptions().tau_max
STARTUP = "from model import REGIMES, simulate_support; simulate_support(REGIMES['pendulum'])"


def cases(mode: str) -> dict:
    """name -> (Params, target error)."""
    out = {"pendulum pi/2": (REGIMES["pendulum"], 1e-6),
           "hard F_N=10": (Params(k_r=0.01, k_theta=0.01, F_N=10, theta0=math.pi / 2), 1e-5)}
    if mode == "full":
        out.update({f"{n} pi/2": (REGIMES[n], 1e-6) for n in ("slider", "stiff", "soft")})
        # docs/model.md hard case: driven into the pivot region (theta0 near pi, slider springs).
        out["slider pi-1e-3"] = (REGIMES["slider"].replace(theta0=math.pi - 1e-3), 1e-5)
    return out


#: The cases whose contacts are stiff (large load): their reference is scipy's Radau, as
#: DOP853's steps are bound by stability there.
STIFF = ("hard F_N=10",)


def reference(name: str, params: Params, rtol: float, cache_file: Path) -> dict:
    """Exit time and state of a tight scipy run (DOP853; Radau for the stiff cases,
    ``STIFF``), cached by case and parameters.

    A cached entry at rtol or tighter is reused; otherwise the run is made and stored.
    """
    cache = json.loads(cache_file.read_text()) if cache_file.exists() else {}
    key = f"{name} | {json.dumps(params.as_dict(), sort_keys=True)}"
    if key in cache and cache[key]["rtol"] <= rtol:
        return cache[key]
    start = time.perf_counter()
    method = "reference-radau" if name in STIFF else "reference"
    res = simulate_support(params, rtol=rtol, atol=1e-15, method=method, max_steps=2_000_000)
    if not res.success:
        raise RuntimeError(f"reference for {name} failed: {res.message}")
    cache[key] = {"rtol": rtol, "method": REFERENCE_METHODS[method], "t_out": res.t_out,
                  "state_out": [float(v) for v in res.state_out],
                  "seconds": time.perf_counter() - start, "n_rhs": res.stats["n_rhs"]}
    cache_file.write_text(json.dumps(cache, indent=1))
    return cache[key]


def time_calls(fns: list, firsts=None, min_loop=0.02, min_total=0.1, max_repeats=5) -> list:
    """Per-call seconds of each fn (median, min, max, n) over repeated loops of >= min_loop.

    Each fn's loop is repeated until about `min_total` seconds, at least 3 and at most
    `max_repeats` times. `firsts`: seconds of one call already made, to size the loops
    (else one call is made). The loops of the different fns are interleaved, so that a
    burst of other load on the machine hits them alike.
    """
    counts, rounds = [], []
    for i, fn in enumerate(fns):
        one = firsts[i] if firsts else None
        if one is None:
            start = time.perf_counter()
            fn()
            one = time.perf_counter() - start
        counts.append(max(1, math.ceil(min_loop / max(one, 1e-9))))
        rounds.append(repeats_for(counts[-1] * one, min_total, 3, max_repeats))
    per_call = [[] for _ in fns]
    for k in range(max(rounds, default=0)):
        for fn, n, r, out in zip(fns, counts, rounds, per_call):
            if k >= r:
                continue
            start = time.perf_counter()
            for _ in range(n):
                fn()
            out.append((time.perf_counter() - start) / n)
    return [spread(t) for t in per_call]


def sweep_ours(params: Params, rtols: list, ref: dict) -> dict:
    """method -> rows of the rtol sweep of the compiled methods, timed on the uncached path."""
    rows = {m: [] for m in OURS}
    for rtol in rtols:
        calls, firsts = {}, []
        for m in OURS:
            start = time.perf_counter()
            res = simulate_support(params, rtol=rtol, method=m, cache=False)
            first = time.perf_counter() - start
            row = {"method": m, "rtol": rtol, "success": res.success,
                   "status": "ok" if res.success else res.message,
                   "n_rhs": res.stats["n_rhs"], "stats": dict(res.stats)}
            rows[m].append(row)
            if res.success:
                row["rel_energy"] = res.relative_energy_residual
                score(row, res.t_out, res.state_out, ref)
                calls[m] = functools.partial(simulate_support, params, rtol=rtol, method=m,
                                             cache=False)
                firsts.append(first)
        for m, t in zip(calls, time_calls(list(calls.values()), firsts)):
            rows[m][-1].update(seconds=t["median"], min_s=t["min"], max_s=t["max"], n_runs=t["n"])
    return rows


@numba.njit
def _rhs_loop(u, P, out, n):
    """n calls of the kernel's right-hand side at a state with v_R != 0."""
    acc = 0.0
    for i in range(n):
        u[2] = -0.25 + 1e-12 * i  # defeat hoisting of the call out of the loop
        _kernel.rhs(u, P, out)
        acc += out[2]
    return acc


def rhs_cost(params: Params, n=200_000) -> dict:
    """Seconds per compiled right-hand-side evaluation (median, min, max of 5 loops)."""
    u, P, out = _kernel.initial_state(params), _kernel.pack(params), np.zeros(_kernel.N_STATE)
    _rhs_loop(u, P, out, 10)
    t = time_calls([lambda: _rhs_loop(u, P, out, n)], min_total=0.2)[0]
    return {k: (v / n if k != "n" else v) for k, v in t.items()}


def _switches(rtol_a: float, rtol_b: float) -> bool:
    """True when the kernel's explicit pair differs between the two rtols."""
    cut = getattr(_kernel, "DOP853_RTOL", 0.0)
    return (rtol_a <= cut) != (rtol_b <= cut)


def at_error(rows: list, target: float, key="seconds"):
    """(value of `key` at error `target`, note), log-log interpolated along the sweep.

    The first crossing of the target from the loosest rtol on is used. The note is
    "<=" when the loosest run already meets the target, "not reached" when no run does.
    Between two rtols on either side of the kernel's switch of explicit pair
    (``_kernel.DOP853_RTOL``) nothing is interpolated: the first run meeting the target
    is taken.
    """
    ok = [r for r in rows if r["success"]]
    pts = [(max(r["error"], 1e-300), r[key]) for r in ok]
    for i, (e, v) in enumerate(pts):
        if e <= target:
            if i == 0:
                return v, "<="
            if ok[i]["method"] in ("auto", "explicit") and _switches(ok[i - 1]["rtol"], ok[i]["rtol"]):
                return v, ""
            e0, v0 = pts[i - 1]
            f = math.log(e0 / target) / math.log(e0 / e)
            return math.exp(math.log(v0) + f * math.log(v / v0)), ""
    return None, "not reached"


def summarize(rows: dict, target: float, cost: dict) -> dict:
    """Times at the target error (median, min, max), the headline ratios, the RHS bound.

    A method whose sweep was cut by the time cap before reaching the target gets its
    longest run as a lower bound (tighter tolerances take no less time), marked ">".
    """
    at, spreads = {}, {}
    for m, sweep in rows.items():
        at[m] = at_error(sweep, target)
        if at[m][0] is None and any(r["status"].startswith(CUT) for r in sweep):
            at[m] = (max(r.get("seconds") or r.get("elapsed") or 0.0 for r in sweep), ">")
        elif at[m][0] is not None:
            spreads[m] = [at_error(sweep, target, key)[0] * 1e6 for key in ("min_s", "max_s")]
    auto = at["auto"][0]
    best = min((at[m][0] for m in ("explicit", "implicit") if at[m][0] is not None), default=None)
    rk, rk_note = at["RK45"]
    lean, lean_note = at.get("RK45-lean", (None, "not run"))
    n_rhs, _ = at_error(rows["auto"], target, key="n_rhs")
    return {"target": target, "at_target_us": {m: (v * 1e6 if v else None, n) for m, (v, n) in at.items()},
            "at_target_minmax_us": spreads,
            "rk45_over_auto": (rk / auto if rk and auto else None, rk_note),
            "rk45_lean_over_auto": (lean / auto if lean and auto else None, lean_note),
            "auto_over_best_ours": auto / best if auto and best else None,
            "rhs_bound_us": n_rhs * cost["median"] * 1e6 if n_rhs else None}


def findings(case: str, rows: dict) -> list:
    """Failed runs of any method, and every scipy run that beats auto at equal error."""
    out = [f"{case}: {m} failed at rtol={r['rtol']:g}: {r['status']}" for m, sweep in rows.items()
           for r in sweep if not r["success"] and not r["status"].startswith(CUT)]
    for m in (m for m in rows if m not in OURS):
        for r in (r for r in rows[m] if r["success"]):
            auto, _ = at_error(rows["auto"], r["error"])
            if auto is not None and auto > r["seconds"]:
                out.append(f"{case}: auto ({auto * 1e6:.0f} us) slower than {m} ({r['seconds'] * 1e6:.0f}"
                           f" us) at error {r['error']:.2g} (rtol={r['rtol']:g})")
    return out


def cuts(case: str, rows: dict) -> list:
    """The scipy runs left out by the time cap, one line per cut sweep."""
    out = []
    for m, sweep in rows.items():
        aborted = [r for r in sweep if r["status"].startswith("aborted")]
        skipped = [r for r in sweep if r["status"].startswith("skipped")]
        if not aborted and not skipped:
            continue
        parts = [f"run at rtol {r['rtol']:g} stopped after {r['elapsed']:.2g} s" for r in aborted]
        if skipped:
            span = f"{skipped[0]['rtol']:g}" + (f" ... {skipped[-1]['rtol']:g}" if len(skipped) > 1 else "")
            parts.append(f"rtol {span} {skipped[0]['status']}")
        out.append(f"{case}: {m}: " + "; ".join(parts))
    return out


def startup(repeats: int, cold: bool = True) -> dict:
    """Seconds from process start to the first trajectory: warm cache, and cold compile
    (``cold=False``: not measured, as in ``--quick``; it compiles every kernel anew, a
    minute on two cores).

    An untimed first run brings the compile cache up to date with the sources.
    """
    def run(env):
        start = time.perf_counter()
        subprocess.run([sys.executable, "-c", STARTUP], env=env, check=True)
        return time.perf_counter() - start
    warm = [run(os.environ.copy()) for _ in range(repeats + 1)][1:]
    compile_s = None
    if cold:
        with tempfile.TemporaryDirectory() as empty:
            compile_s = run({**os.environ, "NUMBA_CACHE_DIR": empty})
    w = spread(warm)
    return {"warm_median_s": w["median"], "warm_min_s": w["min"], "warm_max_s": w["max"],
            "warm_s": warm, "cold_compile_s": compile_s}


def fmt(v, digits=3) -> str:
    """A number for a table cell: thousands separated, else `digits` significant digits."""
    if v is None:
        return "-"
    return f"{v:,.0f}" if abs(v) >= 1e3 else f"{v:.{digits}g}"


def headline(results: dict, methods: list) -> str:
    """One row per case: times at the target error and the headline ratios."""
    cols = ["case", "target err"] + [f"{m} us [min–max]" for m in methods] + [
        "RK45-lean/auto (goal >= 100)", "RK45/auto (numpy RHS)", "auto/best ours (goal <= 1.2)",
        "RHS bound us"]
    lines = ["| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    for case, res in results.items():
        s = res["summary"]
        cells = [case, f"{s['target']:g}"]
        for m in methods:
            v, note = s["at_target_us"][m]
            mark = {"<=": " (loosest rtol)", ">": " (cap)"}.get(note, "")
            if v and m in s["at_target_minmax_us"]:
                cells.append(cell(v, *s["at_target_minmax_us"][m], fmt=fmt) + mark)
            else:
                cells.append((">" if note == ">" else "") + fmt(v) + mark if v else note)
        lean, lean_note = s["rk45_lean_over_auto"]
        rk, note = s["rk45_over_auto"]
        cells += [(">" if lean_note == ">" else "") + fmt(lean), (">" if note == ">" else "") + fmt(rk),
                  fmt(s["auto_over_best_ours"]), fmt(s["rhs_bound_us"])]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def sweep_table(rows: dict) -> str:
    """Every run of one case: time, errors, energy residual, RHS calls, status."""
    lines = ["| method | rtol | us median [min–max] | runs | error | t_out error | rel. energy | n_rhs "
             "| status |", "|---|---|---|---|---|---|---|---|---|"]
    for m, sweep in rows.items():
        for r in sweep:
            sec = r.get("seconds")
            us = cell(sec * 1e6, r["min_s"] * 1e6, r["max_s"] * 1e6, fmt) if sec else "-"
            lines.append(f"| {m} | {r['rtol']:g} | {us} | {r.get('n_runs', '-')} | "
                         f"{fmt(r.get('error'), 2)} | {fmt(r.get('t_error'), 2)} | "
                         f"{fmt(r.get('rel_energy'), 2)} | {r.get('n_rhs', '-')} | {r['status'][:80]} |")
    return "\n".join(lines)


def report(info, results, methods, start, notes, cut_notes, cost, cap, abort) -> tuple[str, str]:
    """(headline printed to stdout, full markdown report)."""
    head = summary(results, methods, start, notes, cut_notes, cost, cap, abort)
    machine_lines = [f"- {k}: {v}" for k, v in info.items()]
    body = [f"## {case}\n\nReference: {r['reference'].get('method', 'DOP853')} rtol={r['reference']['rtol']:g}, atol=1e-15, "
            f"tau_out={r['reference']['t_out']:.12g}.\n\n{sweep_table(r['rows'])}"
            for case, r in results.items()]
    return head, "\n\n".join(["# One support: speed against error", "\n".join(machine_lines), head,
                              *body]) + "\n"


def summary(results, methods, start, notes, cut_notes, cost, cap, abort) -> str:
    """The headline table, the RHS cost, the start-up times and every cut or failed run."""
    ns = lambda v: f"{v * 1e9:.0f}"  # noqa: E731
    head = "\n".join([
        "Times per trajectory (us) at the target error: median [min–max] over repeated runs,",
        "each log-log interpolated over the rtol sweep.", "", headline(results, methods), "",
        f"A scipy run is aborted after {abort:g} s; once a run takes more than {cap:g} s, the tighter",
        "rtols of its sweep are skipped (a tighter rtol takes no less time). '>' (cap) marks a lower",
        "bound from the longest run of a sweep so cut before reaching the target.",
        f"RHS cost {cell(cost['median'], cost['min'], cost['max'], ns)} ns per call (compiled, median "
        f"[min–max] of {cost['n']} loops); RHS bound = median cost x auto's n_rhs at target.",
        f"Process start to first trajectory: {start['warm_median_s']:.2f} s [{start['warm_min_s']:.2f}–"
        f"{start['warm_max_s']:.2f}] with the compile cache (median [min–max] of {len(start['warm_s'])}), "
        + (f"{start['cold_compile_s']:.2f} s cold (one run, empty NUMBA_CACHE_DIR)."
         if start["cold_compile_s"] is not None else "cold start not measured (--quick)."),
        "", "Scipy runs cut by the time cap:", *(f"- {n}" for n in cut_notes or ["none"]),
        "", "Failed runs, and scipy runs faster than auto at equal error:",
        *(f"- {n}" for n in notes or ["none"])])
    return head


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="two cases, three tolerances, RK45/DOP853 only")
    ap.add_argument("--out", type=Path, default=Path("bench-out"), help="output directory")
    args = ap.parse_args(argv)
    mode = "quick" if args.quick else "full"
    args.out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    for m in OURS:  # load (or compile) the kernel once per method before timing
        simulate_support(REGIMES["pendulum"], method=m, cache=False)
    cost = rhs_cost(REGIMES["pendulum"])
    methods = list(OURS) + list(SCIPY[mode])
    results, notes, cut_notes, phases = {}, [], [], {}

    def lap(what, since):  # wall and CPU seconds of each part, for the JSON
        phases[what] = {"wall_s": time.perf_counter() - since[0], "cpu_s": time.process_time() - since[1]}
        return time.perf_counter(), time.process_time()

    for case, (params, target) in cases(mode).items():
        t = time.perf_counter(), time.process_time()
        ref = reference(case, params, REF_RTOL[mode], args.out / "reference_cache.json")
        t = lap(f"{case} | reference", t)
        rows = sweep_ours(params, RTOLS[mode], ref)
        t = lap(f"{case} | ours", t)
        for m in SCIPY[mode]:
            rows[m] = sweep_scipy(params, m, RTOLS[mode], ref, cap=CAP[mode], abort=ABORT[mode],
                                  min_total=MIN_TOTAL[mode])
            t = lap(f"{case} | {m}", t)
        results[case] = {"params": params.as_dict(), "reference": ref, "rows": rows,
                         "summary": summarize(rows, target, cost)}
        notes += findings(case, rows)
        cut_notes += cuts(case, rows)
        print(f"[{time.perf_counter() - t0:5.1f} s] {case} done", file=sys.stderr, flush=True)
    t = time.perf_counter(), time.process_time()
    start = startup(repeats=3, cold=mode == "full")
    lap("startup (subprocesses)", t)
    info = machine()
    head, full = report(info, results, methods, start, notes, cut_notes, cost, CAP[mode], ABORT[mode])
    print(head)
    (args.out / "support.md").write_text(full)
    info.update(mode=mode, rhs_cost_s=cost, startup=start, findings=notes, cuts=cut_notes,
                cap_s=CAP[mode], abort_s=ABORT[mode], phases_s=phases,
                wall_s=time.perf_counter() - t0, cases=results)
    (args.out / "support.json").write_text(json.dumps(info, indent=1, default=str))
    for note in plot(results, args.out):
        print(f"note: {note}")
    print(f"\nwrote {args.out}/support.md, support.json ({time.perf_counter() - t0:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
