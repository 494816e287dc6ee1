"""Work-precision plots for the support benchmark (matplotlib PNG or bokeh HTML).

Per case two panels share the time axis: wall time per trajectory against the
exit-state error, and against the relative energy-balance residual.
"""
from __future__ import annotations

from pathlib import Path

# (row key, x axis label, title suffix) of the two panels drawn per case
PANELS = (("error", "max abs error of exit state", ""),
          ("rel_energy", "energy-balance residual |W - (D + U + K)| / |W|", ": energy balance"))


def plot_png(curves: dict, targets: dict, path: Path) -> None:
    """Work-precision plots with matplotlib, one row per case, one column per error measure."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(len(curves), len(PANELS), figsize=(5 * len(PANELS), 4 * len(curves)),
                             squeeze=False)
    for row, (case, panels) in zip(axes, curves.items()):
        for ax, (key, xlabel, suffix) in zip(row, PANELS):
            for m, pts in ((m, pts) for m, pts in panels[key].items() if pts):
                ax.loglog(*zip(*sorted(pts)), "o-", label=m)
            if key == "error":
                ax.axvline(targets[case], color="grey", ls=":")
            ax.set(title=case + suffix, xlabel=xlabel, ylabel="s per trajectory")
    axes[0][0].legend()
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def plot_html(curves: dict, targets: dict, path: Path) -> None:
    """Work-precision plots with bokeh: per case, time against the exit-state error and,
    beside it on the same time axis, against the energy-balance residual."""
    from bokeh.io import save
    from bokeh.layouts import column, row
    from bokeh.models import Span
    from bokeh.palettes import Category10
    from bokeh.plotting import figure
    from bokeh.resources import INLINE
    rows = []
    for case, panels in curves.items():
        figs = []
        for key, xlabel, suffix in PANELS:
            f = figure(title=case + suffix, x_axis_type="log", y_axis_type="log", width=700,
                       height=400, x_axis_label=xlabel, y_axis_label="s per trajectory",
                       name=f"{key}: {case}")
            if figs:
                f.y_range = figs[0].y_range  # the same time axis for both panels
            for (m, pts), color in ((mp, c) for mp, c in zip(panels[key].items(), Category10[10]) if mp[1]):
                e, t = zip(*sorted(pts))
                f.line(e, t, color=color, legend_label=m)
                f.scatter(e, t, color=color, legend_label=m)
            if key == "error":
                f.add_layout(Span(location=targets[case], dimension="height", line_dash="dotted"))
            f.legend.click_policy = "hide"
            figs.append(f)
        rows.append(row(*figs))
    save(column(*rows), filename=path, resources=INLINE, title="One support: work-precision")


def html_to_png(html: Path, png: Path) -> None:
    """Screenshot a saved Bokeh page with Debian's headless Chromium (the reproduction's
    renderer, ``app.reproduce.render``)."""
    from app.reproduce.render import html_to_png as render

    render([(html, png)])


def plot(results: dict, out: Path) -> list:
    """Write the plots that the installed libraries allow; return notes on the others."""
    # Log axes: a residual of exactly 0 (possible at tight rtol) cannot be drawn and is left out.
    curves = {case: {key: {m: [(r[key], r["seconds"]) for r in rows if r["success"] and r.get(key, 0) > 0]
                           for m, rows in res["rows"].items()} for key, _, _ in PANELS}
              for case, res in results.items()}
    targets = {case: res["summary"]["target"] for case, res in results.items()}
    notes, written = [], set()
    for name, writer, lib in (("work_precision.png", plot_png, "matplotlib"),
                              ("work_precision.html", plot_html, "bokeh")):
        (out / name).unlink(missing_ok=True)  # never leave the figure of an earlier run
        try:
            writer(curves, targets, out / name)
            written.add(name)
        except ImportError:
            notes.append(f"{lib} is not installed: no {name}")
    html, png = out / "work_precision.html", out / "work_precision.png"
    if html.name in written and png.name not in written:
        try:  # the same figure as a picture, through the browser
            html_to_png(html, png)
            notes = [n for n in notes if "work_precision.png" not in n]
        except Exception as error:  # noqa: BLE001 -- no browser here: the HTML stays
            notes.append(f"no work_precision.png ({type(error).__name__}: {error})"[:200])
    return notes
