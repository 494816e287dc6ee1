"""The load test's report (``load_test.py``): the classroom targets, met or not, and the
Markdown page (DIR/load.md)."""
from __future__ import annotations

from load_profile import markdown as profile_markdown

#: The memory checks: after cleanup, at most max(150 MB, 25 %) above the baseline; a
#: second round adds at most max(20 MB, 25 %) of round 1's peak above the baseline.
MEMORY_BOUND_MB, MEMORY_BOUND_FRACTION = 150.0, 0.25
LEAK_BOUND_MB, LEAK_BOUND_FRACTION = 20.0, 0.25
#: What a class of thirty should see (issue 13, item 3): reported as met or not.
TARGET_UPDATE_P95_MS, TARGET_OPEN_P95_MS, TARGET_MEMORY_FACTOR = 500.0, 5000.0, 1.1


def memory_bound(baseline_mb: float) -> float:
    return baseline_mb + max(MEMORY_BOUND_MB, MEMORY_BOUND_FRACTION * baseline_mb)


def leak_bound(baseline_mb: float, peak_mb: float) -> float:
    """How much a second round may add to what the first left: a quarter of what the
    first round's sessions took at their peak (at least 20 MB of allocator noise)."""
    return max(LEAK_BOUND_MB, LEAK_BOUND_FRACTION * (peak_mb - baseline_mb))


def targets(report: dict, rooms: list[dict]) -> dict:
    """The classroom targets (issue 13, item 3), met or not: by every class round."""
    if not rooms:
        return {}
    m = report["memory_mb"]
    return {
        f"class: slider -> new data p95 <= {TARGET_UPDATE_P95_MS:.0f} ms":
            all(r["updates"]["all"]["p95_ms"] <= TARGET_UPDATE_P95_MS for r in rooms),
        f"class: page open p95 <= {TARGET_OPEN_P95_MS / 1e3:.0f} s":
            all(r["open"]["p95_ms"] <= TARGET_OPEN_P95_MS for r in rooms),
        "class: 0 errors": report["n_errors"] == 0,
        f"memory after the class left <= {TARGET_MEMORY_FACTOR:g} x baseline":
            m["after"]["total"] <= m["target_total"],
    }


def markdown(r: dict) -> str:
    s, m = r["settings"], r["memory_mb"]
    peak = m["peak"] or m["baseline"]
    lines = ["# Dashboard load test", "",
             f"{s['sessions']} sessions against one `panel serve app` on {s['cpus']} cores, "
             "in rounds of two profiles:", ""]
    if s.get("replica"):
        lines[-1:-1] = [f"The clients' copies of the page: **{s['replica']}**, "
                        f"{s['replica_description']}.", ""]
    lines += [f"- **{name}**: {text}." for name, text in s["profile_descriptions"].items()]
    lines += ["", "| round | update latency | n | p50 ms | p95 ms | max ms |",
              "|---|---|---:|---:|---:|---:|"]
    for i, rd in enumerate(r["rounds"]):
        u = rd["updates"]
        tag = f"{i + 1}: {rd['profile']}, {rd['elapsed_s']:.0f} s"
        rows = [("slider move -> new data pushed", u["move"])] if u["move"]["n"] else []
        if u["drag"]["n"]:
            rows.append(("drag (last position) -> its data pushed", u["drag"]))
        if u.get("client", {}).get("n"):
            rows.append(("the same, until this Python client applied it", u["client"]))
        rows.append(("page open (GET + websocket + pull)", rd["open"]))
        for step, q in (rd.get("open_steps") or {}).items():
            if q["n"]:
                rows.append((f"... its step: {step}", q))
        for name, p in rows:
            lines.append(f"| {tag} | {name} | {p['n']} | {p['p50_ms']:.0f} | "
                         f"{p['p95_ms']:.0f} | {p['max_ms']:.0f} |")
    b = r.get("browser") or {}
    if b.get("latencies"):
        p = b["latencies"]
        lines.append(f"| 1 | Chromium page: key press -> orbit data changed | {p['n']} | "
                     f"{p['p50_ms']:.0f} | {p['p95_ms']:.0f} | {p['max_ms']:.0f} |")
    lines.append("")
    for i, rd in enumerate(r["rounds"]):
        u, c, cpu = rd["updates"], rd["cleanup"], rd["server_cpu_s"]
        n_updates = max(u["all"]["n"], 1)
        lines += [
            f"Round {i + 1} ({rd['profile']}): {u['rate_per_s']:.1f} updates/s in all, every "
            f"session at least {u['per_session_min']} ({rd['sessions_with_updates']}/"
            f"{s['sessions']} sessions got updates); sessions destroyed {c['destroyed']}/"
            f"{c['sessions']} ({c['seconds']:.1f} s after close), open afterwards "
            f"{c['open_after']}; busy pages reloaded while opening: {rd['busy_pages']}. "
            f"CPU while moving: server process {cpu['server']:.0f} s, "
            f"workers {cpu['workers']:.0f} s ({1e3 * cpu['server'] / n_updates:.0f} and "
            f"{1e3 * cpu['workers'] / n_updates:.0f} ms per update), clients "
            f"{rd['client_cpu_fraction']:.0%} of one core"
            + (f" (applying the server's patches {rd['client_apply_s']:.0f} s; their loop "
               f"woke a 10 ms sleep late by p50 {rd['client_loop_lag']['p50_ms']:.0f}, p95 "
               f"{rd['client_loop_lag']['p95_ms']:.0f} ms)" if "client_loop_lag" in rd else "")
            + ". Load average (1 min): "
            f"{rd['load_average']['start'][0]:.1f} at the start, "
            f"{rd['load_average']['end'][0]:.1f} at the end.", ""]
    lines += ["| server RSS (MB) | server | workers | total | processes |",
              "|---|---:|---:|---:|---:|"]
    rows = [("baseline (server up, one page built)", m["baseline"]), ("peak during the rounds", peak),
            (f"after round 1 ({r['rounds'][0]['profile']}) closed and cleaned up", m["after"]),
            (f"after round 2 ({r['rounds'][1]['profile']})", m["after_second_round"])]
    for name, x in rows:
        x = x if x is not None else peak
        lines.append(f"| {name} | {x['server']:.0f} | {x['workers']:.0f} | {x['total']:.0f} | "
                     f"{x['processes']} |")
    lines += [
        "", f"Memory bound after cleanup: baseline + max({MEMORY_BOUND_MB:.0f} MB, "
        f"{MEMORY_BOUND_FRACTION:.0%}) = {m['bound_total']:.0f} MB (target: "
        f"{TARGET_MEMORY_FACTOR:g} x baseline = {m['target_total']:.0f} MB); round 2 may add "
        f"at most {m['second_round_growth_bound']:.0f} MB (max({LEAK_BOUND_MB:.0f} MB, "
        f"{LEAK_BOUND_FRACTION:.0%} of round 1's peak above the baseline)). Sessions destroyed "
        f"before their websocket connected: {r['destroyed_before_close']}.", "",
        f"Errors: {r['n_errors']}"]
    if b.get("cpu_s") is not None:
        lines[-1:-1] = [f"Chromium ({s['browsers']} pages): {b['cpu_s']:.0f} s of CPU in "
                        f"{b['wall_s']:.0f} s ({b['cpu_s'] / max(b['wall_s'], 1e-9):.0%} of one "
                        f"core), peak RSS {b['peak_rss_mb']:.0f} MB, {b['presses']} key "
                        "presses.", ""]
    lines += [f"- {e}" for e in r["errors"][:50]]
    lines += ["", "| check | result |", "|---|---|"]
    lines += [f"| {k} | {'pass' if v else 'FAIL'} |" for k, v in r["checks"].items()]
    if r.get("targets"):
        lines += ["", "| target (issue 13) | result |", "|---|---|"]
        lines += [f"| {k} | {'met' if v else 'NOT MET'} |" for k, v in r["targets"].items()]
    prof = r["rounds"][0].get("server_profile")
    if prof:
        lines += ["", "## Where the server's time went (round 1's slider moves, py-spy)", "",
                  prof.get("error") or profile_markdown(prof)]
    return "\n".join(lines) + "\n"
