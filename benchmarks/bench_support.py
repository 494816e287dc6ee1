"""Speed against error for one support: the compiled solvers against scipy.

    python benchmarks/bench_support.py [--quick] [--out DIR]

For each case the exit state (x, y, v_x, v_y, theta at tau_out) is compared with a
tight scipy DOP853 reference (cached in DIR/reference_cache.json). Every method runs
over a sweep of rtol (atol = rtol/100); the time needed for a target error is found
by log-log interpolation along the sweep. Writes DIR/support.md, DIR/support.json and
a work-precision plot (DIR/work_precision.png with matplotlib, DIR/work_precision.html
with bokeh) and prints the headline table.
"""
from __future__ import annotations

import argparse
import datetime
import functools
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numba
import numpy as np
import scipy

from model import REGIMES, Params, SolverOptions, simulate_support
from model import _kernel
from model.support import _simulate

from plots import plot
from scipy_baselines import score, sweep_scipy

OURS = ("auto", "explicit", "implicit")
SCIPY = {"full": ("RK45", "DOP853", "LSODA", "Radau"), "quick": ("RK45", "DOP853")}
RTOLS = {"full": [10.0**-k for k in range(3, 11)], "quick": [1e-4, 1e-6, 1e-8]}
REF_RTOL = {"full": 1e-13, "quick": 1e-12}
TIME_LIMIT = {"full": 15.0, "quick": 2.0}  # seconds of wall time per scipy sweep (case, method)
TAU_MAX = SolverOptions().tau_max
STARTUP = "from model import REGIMES, simulate_support; simulate_support(REGIMES['pendulum'])"


def cases(mode: str) -> dict:
    """name -> (Params, target error)."""
    out = {"pendulum pi/2": (REGIMES["pendulum"], 1e-6),
           "hard F_N=10": (Params(k_r=0.01, k_theta=0.01, F_N=10, theta0=math.pi / 2), 1e-5)}
    if mode == "full":
        out.update({f"{n} pi/2": (REGIMES[n], 1e-6) for n in ("slider", "stiff", "soft")})
        # MODEL.md hard case: driven into the pivot region (theta0 near pi, slider springs).
        out["slider pi-1e-3"] = (REGIMES["slider"].replace(theta0=math.pi - 1e-3), 1e-5)
    return out


def reference(name: str, params: Params, rtol: float, cache_file: Path) -> dict:
    """Exit time and state of a tight DOP853 run, cached by case and parameters.

    A cached entry at rtol or tighter is reused; otherwise the run is made and stored.
    """
    cache = json.loads(cache_file.read_text()) if cache_file.exists() else {}
    key = f"{name} | {json.dumps(params.as_dict(), sort_keys=True)}"
    if key in cache and cache[key]["rtol"] <= rtol:
        return cache[key]
    start = time.perf_counter()
    res = simulate_support(params, rtol=rtol, atol=1e-15, method="reference", max_steps=2_000_000)
    if not res.success:
        raise RuntimeError(f"reference for {name} failed: {res.message}")
    cache[key] = {"rtol": rtol, "t_out": res.t_out, "state_out": [float(v) for v in res.state_out],
                  "seconds": time.perf_counter() - start, "n_rhs": res.stats["n_rhs"]}
    cache_file.write_text(json.dumps(cache, indent=1))
    return cache[key]


def time_calls(fns: list, min_loop=0.02, repeats=5) -> list:
    """Per-call seconds of each fn: the median over `repeats` of a loop lasting >= min_loop.

    The loops of the different fns are interleaved, so that a burst of other load on
    the machine hits them alike.
    """
    counts = []
    for fn in fns:
        start = time.perf_counter()
        fn()
        counts.append(max(1, math.ceil(min_loop / max(time.perf_counter() - start, 1e-9))))
    per_call = [[] for _ in fns]
    for _ in range(repeats):
        for fn, n, out in zip(fns, counts, per_call):
            start = time.perf_counter()
            for _ in range(n):
                fn()
            out.append((time.perf_counter() - start) / n)
    return [statistics.median(t) for t in per_call]


def sweep_ours(params: Params, rtols: list, ref: dict) -> dict:
    """method -> rows of the rtol sweep of the compiled methods, timed on the uncached path."""
    rows = {m: [] for m in OURS}
    for rtol in rtols:
        calls = {}
        for m in OURS:
            options = SolverOptions(rtol=rtol, method=m)
            res = _simulate.__wrapped__(params, options, 0)
            row = {"method": m, "rtol": rtol, "success": res.success,
                   "status": "ok" if res.success else res.message,
                   "n_rhs": res.stats["n_rhs"], "stats": dict(res.stats)}
            rows[m].append(row)
            if res.success:
                row["rel_energy"] = res.relative_energy_residual
                score(row, res.t_out, res.state_out, ref)
                calls[m] = functools.partial(_simulate.__wrapped__, params, options, 0)
        for m, seconds in zip(calls, time_calls(list(calls.values()))):
            rows[m][-1]["seconds"] = seconds
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


def rhs_cost(params: Params, n=200_000) -> float:
    """Seconds per compiled right-hand-side evaluation (median of 5 loops)."""
    u, P, out = _kernel.initial_state(params), _kernel.pack(params), np.zeros(_kernel.N_STATE)
    _rhs_loop(u, P, out, 10)
    return time_calls([lambda: _rhs_loop(u, P, out, n)])[0] / n


def at_error(rows: list, target: float, key="seconds"):
    """(value of `key` at error `target`, note), log-log interpolated along the sweep.

    The first crossing of the target from the loosest rtol on is used. The note is
    "<=" when the loosest run already meets the target, "not reached" when no run does.
    """
    pts = [(max(r["error"], 1e-300), r[key]) for r in rows if r["success"]]
    for i, (e, v) in enumerate(pts):
        if e <= target:
            if i == 0:
                return v, "<="
            e0, v0 = pts[i - 1]
            f = math.log(e0 / target) / math.log(e0 / e)
            return math.exp(math.log(v0) + f * math.log(v / v0)), ""
    return None, "not reached"


def summarize(rows: dict, target: float, cost: float) -> dict:
    """Times at the target error, the headline ratios and the RHS lower bound.

    A method whose sweep was cut by the time budget before reaching the target gets its
    longest run as a lower bound (tighter tolerances take no less time), marked ">".
    """
    at = {}
    for m, sweep in rows.items():
        at[m] = at_error(sweep, target)
        if at[m][0] is None and any("time budget" in r["status"] for r in sweep):
            at[m] = (max(r.get("seconds") or r.get("elapsed") or 0.0 for r in sweep), ">")
    auto = at["auto"][0]
    best = min((at[m][0] for m in ("explicit", "implicit") if at[m][0] is not None), default=None)
    rk, rk_note = at["RK45"]
    n_rhs, _ = at_error(rows["auto"], target, key="n_rhs")
    return {"target": target, "at_target_us": {m: (v * 1e6 if v else None, n) for m, (v, n) in at.items()},
            "rk45_over_auto": (rk / auto if rk and auto else None, rk_note),
            "auto_over_best_ours": auto / best if auto and best else None,
            "rhs_bound_us": n_rhs * cost * 1e6 if n_rhs else None}


def findings(case: str, rows: dict) -> list:
    """Failed runs of any method, and every scipy run that beats auto at equal error."""
    out = [f"{case}: {m} failed at rtol={r['rtol']:g}: {r['status']}" for m, sweep in rows.items()
           for r in sweep if not r["success"] and "time budget" not in r["status"]]
    for m in (m for m in rows if m not in OURS):
        for r in (r for r in rows[m] if r["success"]):
            auto, _ = at_error(rows["auto"], r["error"])
            if auto is not None and auto > r["seconds"]:
                out.append(f"{case}: auto ({auto * 1e6:.0f} us) slower than {m} ({r['seconds'] * 1e6:.0f}"
                           f" us) at error {r['error']:.2g} (rtol={r['rtol']:g})")
    return out


def startup(repeats: int) -> dict:
    """Seconds from process start to the first trajectory: warm cache, and cold compile.

    An untimed first run brings the compile cache up to date with the sources.
    """
    def run(env):
        start = time.perf_counter()
        subprocess.run([sys.executable, "-c", STARTUP], env=env, check=True)
        return time.perf_counter() - start
    warm = [run(os.environ.copy()) for _ in range(repeats + 1)][1:]
    with tempfile.TemporaryDirectory() as empty:
        cold = run({**os.environ, "NUMBA_CACHE_DIR": empty})
    return {"warm_median_s": statistics.median(warm), "warm_s": warm, "cold_compile_s": cold}


def machine() -> dict:
    """CPU, cores, versions and date for the report header."""
    cpu = next((ln.split(":", 1)[1].strip() for ln in Path("/proc/cpuinfo").read_text().splitlines()
                if ln.startswith("model name")), platform.processor() or "unknown")
    return {"cpu": cpu, "cores": os.cpu_count(), "python": platform.python_version(),
            "numpy": np.__version__, "scipy": scipy.__version__, "numba": numba.__version__,
            "date": datetime.datetime.now().isoformat(timespec="seconds")}


def fmt(v, digits=3) -> str:
    """A number for a table cell: thousands separated, else `digits` significant digits."""
    if v is None:
        return "-"
    return f"{v:,.0f}" if abs(v) >= 1e3 else f"{v:.{digits}g}"


def headline(results: dict, methods: list) -> str:
    """One row per case: times at the target error and the headline ratios."""
    cols = ["case", "target err"] + [f"{m} us" for m in methods] + [
        "RK45/auto (goal >= 50)", "auto/best ours (goal <= 1.2)", "RHS bound us"]
    lines = ["| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    for case, res in results.items():
        s = res["summary"]
        cells = [case, f"{s['target']:g}"]
        for m in methods:
            v, note = s["at_target_us"][m]
            mark = {"<=": " (loosest rtol)", ">": " (budget)"}.get(note, "")
            cells.append((">" if note == ">" else "") + fmt(v) + mark if v else note)
        rk, note = s["rk45_over_auto"]
        cells += [(">" if note == ">" else "") + fmt(rk), fmt(s["auto_over_best_ours"]),
                  fmt(s["rhs_bound_us"])]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def sweep_table(rows: dict) -> str:
    """Every run of one case: time, errors, energy residual, RHS calls, status."""
    lines = ["| method | rtol | us | error | t_out error | rel. energy | n_rhs | status |",
             "|---|---|---|---|---|---|---|---|"]
    for m, sweep in rows.items():
        for r in sweep:
            sec = r.get("seconds")
            lines.append(f"| {m} | {r['rtol']:g} | {fmt(sec * 1e6 if sec else None)} | "
                         f"{fmt(r.get('error'), 2)} | {fmt(r.get('t_error'), 2)} | "
                         f"{fmt(r.get('rel_energy'), 2)} | {r.get('n_rhs', '-')} | {r['status'][:80]} |")
    return "\n".join(lines)


def report(info, results, methods, start, notes, cost, limit) -> tuple[str, str]:
    """(headline printed to stdout, full markdown report)."""
    head = "\n".join([
        "Times per trajectory (us) at the target error, log-log interpolated over the rtol sweep.",
        "", headline(results, methods), "",
        f"Each scipy sweep gets {limit:g} s; a run over it is aborted and tighter rtols are skipped;",
        "'>' (budget) marks a lower bound from the longest run of such a sweep.",
        f"RHS cost {cost * 1e9:.0f} ns per call (compiled); RHS bound = cost x auto's n_rhs at target.",
        f"Process start to first trajectory: {start['warm_median_s']:.2f} s with the compile cache "
        f"(median of {len(start['warm_s'])}), {start['cold_compile_s']:.2f} s cold (empty NUMBA_CACHE_DIR).",
        "", "Failed runs, and scipy runs faster than auto at equal error:",
        *(f"- {n}" for n in notes or ["none"])])
    machine_lines = [f"- {k}: {v}" for k, v in info.items()]
    body = [f"## {case}\n\nReference: DOP853 rtol={r['reference']['rtol']:g}, atol=1e-15, "
            f"tau_out={r['reference']['t_out']:.12g}.\n\n{sweep_table(r['rows'])}"
            for case, r in results.items()]
    return head, "\n\n".join(["# One support: speed against error", "\n".join(machine_lines), head,
                              *body]) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="two cases, three tolerances, RK45/DOP853 only")
    ap.add_argument("--out", type=Path, default=Path("bench-out"), help="output directory")
    args = ap.parse_args(argv)
    mode = "quick" if args.quick else "full"
    args.out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    for m in OURS:  # load (or compile) the kernel once per method before timing
        _simulate.__wrapped__(REGIMES["pendulum"], SolverOptions(method=m), 0)
    cost = rhs_cost(REGIMES["pendulum"])
    methods = list(OURS) + list(SCIPY[mode])
    results, notes = {}, []
    for case, (params, target) in cases(mode).items():
        ref = reference(case, params, REF_RTOL[mode], args.out / "reference_cache.json")
        rows = sweep_ours(params, RTOLS[mode], ref)
        for m in SCIPY[mode]:
            rows[m] = sweep_scipy(params, m, RTOLS[mode], ref, TIME_LIMIT[mode],
                                  repeats=1 if mode == "quick" else 3)
        results[case] = {"params": params.as_dict(), "reference": ref, "rows": rows,
                         "summary": summarize(rows, target, cost)}
        notes += findings(case, rows)
        print(f"[{time.perf_counter() - t0:5.1f} s] {case} done", file=sys.stderr, flush=True)
    start = startup(repeats=3)
    info = machine()
    head, full = report(info, results, methods, start, notes, cost, TIME_LIMIT[mode])
    print(head)
    (args.out / "support.md").write_text(full)
    info.update(mode=mode, rhs_cost_s=cost, startup=start, findings=notes,
                wall_s=time.perf_counter() - t0, cases=results)
    (args.out / "support.json").write_text(json.dumps(info, indent=1, default=str))
    for note in plot(results, args.out):
        print(f"note: {note}")
    print(f"\nwrote {args.out}/support.md, support.json ({time.perf_counter() - t0:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
