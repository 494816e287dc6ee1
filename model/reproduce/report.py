"""The reproduction report: ``report.md`` and ``index.html`` (the same content, with the
figures linked and, where PNGs exist, shown)."""
from __future__ import annotations

import html
import platform
from pathlib import Path

from ..contact.params import REGIMES
from ..files import write_text_atomic


def _md_table(header: list, rows: list) -> list:
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(str(c).replace("|", "\\|") for c in row) + " |" for row in rows]
    return out


def findings_rows(checks) -> list:
    return [[c.finding, c.quantity, c.value, c.error, c.criterion, f"**{c.verdict}**",
             c.figure, c.basis] for c in checks]


FINDINGS_HEADER = ["#", "computed quantity", "value", "error estimate", "criterion",
                   "verdict", "fig.", "β, averaging"]


def sensitivity_rows(variants) -> list:
    return [[v.name, *[f"{v.FTx[r]:.4f} ({v.error[r]})" for r in REGIMES],
             *[f"{v.DyDx[r]:.4f}" for r in REGIMES]] for v in variants]


SENSITIVITY_HEADER = ["choice", *[f"F_T,x/(μ₀F_N) {r}" for r in REGIMES],
                      *[f"D_y/D_x {r}" for r in REGIMES]]


def markdown(rep) -> str:
    """The report as Markdown; ``rep`` is a ``Reproduction``."""
    claims = []
    for c in rep.checks:
        if not claims or claims[-1][:2] != (c.finding, c.claim):
            claims.append((c.finding, c.claim, []))
        claims[-1][2].append(c)
    lines = [f"# Reproduction of Sci. Rep. 11, 8093 (2021): {rep.resolution.name} resolution",
             "", f"Package version {rep.version}; Python {platform.python_version()}; "
             f"{rep.seconds:.0f} s (computing {sum(rep.data.seconds.values()):.0f} s).", "",
             f"**{sum(c.agrees for c in rep.checks)} of {len(rep.checks)} checks agree with "
             f"the paper; {sum(not c.agrees for c in rep.checks)} differ** (listed below with "
             "their numbers: they are results of the model as specified, not hidden).", "",
             "## Findings", ""]
    for finding, claim, checks in claims:
        lines += [f"**{'Finding ' + finding if finding != 'extra' else 'Other result'}**: "
                  f"{claim}", ""]
        lines += _md_table(FINDINGS_HEADER, findings_rows(checks)) + [""]
    differ = [c for c in rep.checks if not c.agrees]
    if differ:
        lines += ["## Where the model and the paper differ", ""]
        lines += [f"- Finding {c.finding}: {c.quantity} = {c.value} ({c.error}); the paper's "
                  f"claim needs {c.criterion}." for c in differ] + [""]
    lines += ["## Sensitivity to the choices the paper left open", "",
              "Uniform arrays of the four regimes at F_N = 1; the value in brackets is the "
              "quadrature error estimate, or the spread over repeated random draws.", ""]
    lines += _md_table(["choice", "meaning"], [[v.name, v.description] for v in rep.variants])
    lines += [""] + _md_table(SENSITIVITY_HEADER, sensitivity_rows(rep.variants)) + [""]
    lines += ["## Figures", ""]
    for f in rep.figures:
        links = [f"[{kind}]({path.name})" for kind, path in
                 (("HTML", f.html), ("CSV", f.csv), ("PNG", f.png), ("SVG", f.svg),
                  ("PDF", f.pdf)) if path is not None]
        lines.append(f"- Fig. {f.spec.number}: {f.spec.caption} — {', '.join(links)}")
    if rep.png_note:
        lines += ["", f"Pictures missing: {rep.png_note}."]
    lines += ["", "## Time per stage", ""]
    lines += _md_table(["stage", "seconds"], [[k, f"{v:.1f}"] for k, v in
                                              {**rep.data.seconds, **rep.extra_seconds}.items()])
    return "\n".join(lines) + "\n"


def _html_table(header, rows, verdicts=None) -> str:
    head = "".join(f"<th>{html.escape(h)}</th>" for h in header)
    body = []
    for i, row in enumerate(rows):
        cls = f' class="{verdicts[i]}"' if verdicts else ""
        cells = "".join(f"<td>{html.escape(str(c)).replace('**', '')}</td>" for c in row)
        body.append(f"<tr{cls}>{cells}</tr>")
    return f"<table><tr>{head}</tr>{''.join(body)}</table>"


STYLE = """body{font-family:system-ui,sans-serif;margin:2em;max-width:1400px}
table{border-collapse:collapse;margin:1em 0;font-size:14px}td,th{border:1px solid #ccc;
padding:4px 8px;text-align:left}tr.differs td{background:#fde8e0}tr.agrees td{background:#e6f4ea}
figure{display:inline-block;margin:1em;vertical-align:top}img{max-width:640px;border:1px solid #eee}"""


def index_html(rep) -> str:
    """The report as one HTML page linking (and showing) every figure."""
    parts = ["<!doctype html><html lang='en'><meta charset='utf-8'>"
             "<title>Reproduction report</title>"
             f"<style>{STYLE}</style><h1>Reproduction of Sci. Rep. 11, 8093 (2021)</h1>",
             f"<p>{rep.resolution.name} resolution, version {rep.version}, {rep.seconds:.0f} s. "
             f"<b>{sum(c.agrees for c in rep.checks)} of {len(rep.checks)} checks agree; "
             f"{sum(not c.agrees for c in rep.checks)} differ.</b> "
             "Full text: <a href='report.md'>report.md</a>.</p><h2>Findings</h2>",
             _html_table(["claim", *FINDINGS_HEADER],
                         [[c.claim, *r] for c, r in zip(rep.checks, findings_rows(rep.checks))],
                         [c.verdict for c in rep.checks]),
             "<h2>Sensitivity</h2>",
             _html_table(SENSITIVITY_HEADER, sensitivity_rows(rep.variants)), "<h2>Figures</h2>"]
    for f in rep.figures:
        picture = f.png or f.svg
        img = f"<img src='{picture.name}' alt='Fig. {f.spec.number}'>" if picture else ""
        parts.append(f"<figure>{img}<figcaption>Fig. {f.spec.number}: "
                     f"{html.escape(f.spec.caption)} — "
                     + (f"<a href='{f.html.name}'>interactive</a>, " if f.html else "")
                     + "".join(f"<a href='{p.name}'>{kind}</a>, " for kind, p in
                               (("SVG", f.svg), ("PDF", f.pdf)) if p is not None)
                     + f"<a href='{f.csv.name}'>data (CSV)</a></figcaption></figure>")
    return "\n".join(parts) + "\n"


def write(rep, out: Path) -> tuple[Path, Path]:
    md, index = out / "report.md", out / "index.html"
    write_text_atomic(md, markdown(rep))
    write_text_atomic(index, index_html(rep))
    return md, index
