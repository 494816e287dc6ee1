"""The performance report: one Markdown page written from a run of ``run_all.py``.

    python benchmarks/report.py DIR PAGE

reads DIR/run_all.json (the machine, the date, each script's times and the load average
before and after it) and the JSON each benchmark wrote into DIR during that run, and
writes PAGE: the machine, the date and the load, then each benchmark's figures as median
[min–max] with the error each figure buys where the benchmark measures one.
``run_all.py --report PAGE`` runs this at the end. Nothing on the page is typed by hand:
a script that failed, or whose JSON was not written during the run (left over from an
earlier one), is reported as giving no figures.
"""
from __future__ import annotations

import json
import shutil
import sys
from pathlib import Path

#: The file each benchmark of ``run_all.py`` writes, and its section's title.
OUTPUTS = {"bench_support.py": ("support.json", "This run: one support against scipy"),
           "bench_arrays.py": ("arrays.json", "This run: arrays and regime maps"),
           "bench_dashboard.py": ("dashboard.json", "This run: the dashboard"),
           "bench_friction_fit.py": ("friction_fit.json",
                                     "This run: the friction-law fit and a friction-velocity curve")}


def demote(markdown: str, levels: int = 1) -> str:
    """``markdown`` with every heading ``levels`` deeper (a section inside this page)."""
    return "\n".join("#" * levels + line if line.startswith("#") else line
                     for line in markdown.splitlines())


def support_section(data: dict) -> str:
    from bench_support import summary

    methods = list(next(iter(data["cases"].values()))["summary"]["at_target_us"])
    return summary(data["cases"], methods, data["startup"], data["findings"], data["cuts"],
                   data["rhs_cost_s"], data["cap_s"], data["abort_s"])


def arrays_section(data: dict) -> str:
    from bench_arrays import extra_report, map_report, timings_table

    return ("Cold caches; each result's error beside its time.\n\n" + timings_table(data["timings"])
            + demote(extra_report(data["tolerance_costs"], data["throughput"], data["peak_rss_mb"])
                     + map_report(data["regime_maps"])))


def dashboard_section(data: dict) -> str:
    from bench_dashboard import table

    return table(data["server"], data["browser"], data["server_cost"])


def friction_section(data: dict) -> str:
    from bench_friction_fit import fit_lines, speeds_lines
    return "\n".join([*fit_lines(data["fit"]), "", *speeds_lines(data["speeds"])]) + "\n"


SECTIONS = {"bench_support.py": support_section, "bench_arrays.py": arrays_section,
            "bench_dashboard.py": dashboard_section, "bench_friction_fit.py": friction_section}


def load(values) -> str:
    return " / ".join(f"{v:.2f}" for v in values)


def header(run: dict) -> list[str]:
    m = run["machine"]
    versions = ", ".join(f"{k} {m[k]}" for k in ("python", "numpy", "scipy", "numba", "panel",
                                                   "bokeh") if k in m)
    lines = [
        "# Latest benchmark run", "",
        f"Written by `{run['command']}` on {m['date']}"
        + (" in **quick** mode (the reduced runs the tests make: a check that the benchmarks "
           "work, not figures to quote)." if run["mode"] == "quick" else " (full runs)."), "",
        f"- machine: {m['cpu']}, {m['cores']} cores", f"- {versions}",
        f"- load average (1 / 5 / 15 min) {load(run['loadavg_1_5_15_before'])} before the run, "
        f"{load(run['loadavg_1_5_15_after'])} after it; on {m['cores']} cores a load above "
        f"{m['cores']} means other work competed for the CPU", "",
        "| script | wall s | CPU s | load average before | after | exit |", "|---|---:|---:|---|---|---:|"]
    for script, r in run["scripts"].items():
        lines.append(f"| {script} | {r['wall_s']:.1f} | {r['cpu_s']:.1f} | {load(r['loadavg_before'])} | "
                     f"{load(r['loadavg_after'])} | {r['returncode']} |")
    return lines


def fresh(path: Path, since: float) -> bool:
    """``path`` was written at or after ``since`` (epoch seconds): by this run."""
    return path.exists() and path.stat().st_mtime >= since


def plot(out: Path, page: Path, run: dict) -> list[str]:
    """The run's work-precision plot, copied beside the page, as a Markdown image."""
    r, png = run["scripts"].get("bench_support.py"), out / "work_precision.png"
    if not r or r["returncode"] or not fresh(png, r["started"]):
        return []
    name = f"{page.stem}-work_precision.png"
    shutil.copyfile(png, page.parent / name)
    return ["", f"![Work-precision of this run: time per trajectory against the exit-state "
                f"error and the energy-balance residual]({name})"]


def section(out: Path, script: str, run: dict) -> list[str]:
    name, title = OUTPUTS[script]
    r, path = run["scripts"][script], out / name
    lines = ["", f"## {title}", "",
             f"`{script}`, load average {load(r['loadavg_before'])} before and "
             f"{load(r['loadavg_after'])} after it.", ""]
    if r["returncode"]:
        return lines + [f"No figures: `{script}` failed (exit code {r['returncode']})."]
    if not fresh(path, r["started"]):
        return lines + [f"No figures: `{script}` wrote no `{name}` during this run."]
    return lines + [SECTIONS[script](json.loads(path.read_text())).rstrip()]


def write(out: Path, page: Path) -> str:
    """Write ``page`` from the run in ``out`` (its ``run_all.json``); return the text."""
    out = Path(out)
    run = json.loads((out / "run_all.json").read_text())
    page = Path(page)
    page.parent.mkdir(parents=True, exist_ok=True)
    lines = header(run)
    for script in run["scripts"]:
        if script in OUTPUTS:
            lines += section(out, script, run)
            if script == "bench_support.py":
                lines += plot(out, page, run)
    text = "\n".join(lines) + "\n"
    page.write_text(text, encoding="utf-8")
    return text


def main(argv=None) -> int:
    args = sys.argv[1:] if argv is None else argv
    if len(args) != 2:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    write(Path(args[0]), Path(args[1]))
    print(f"wrote {args[1]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
