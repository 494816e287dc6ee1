"""Work-precision plots for the support benchmark (matplotlib PNG or bokeh HTML)."""
from __future__ import annotations

from pathlib import Path


def plot_png(curves: dict, targets: dict, path: Path) -> None:
    """Work-precision plot with matplotlib, one panel per case."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(curves), figsize=(5 * len(curves), 4), squeeze=False)
    for ax, (case, lines) in zip(axes[0], curves.items()):
        for m, pts in ((m, pts) for m, pts in lines.items() if pts):
            ax.loglog(*zip(*sorted(pts)), "o-", label=m)
        ax.axvline(targets[case], color="grey", ls=":")
        ax.set(title=case, xlabel="max abs error of exit state", ylabel="s per trajectory")
    axes[0][0].legend()
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def plot_html(curves: dict, targets: dict, path: Path) -> None:
    """Work-precision plot with bokeh, one figure per case."""
    from bokeh.io import save
    from bokeh.layouts import column
    from bokeh.models import Span
    from bokeh.palettes import Category10
    from bokeh.plotting import figure
    from bokeh.resources import INLINE
    figs = []
    for case, lines in curves.items():
        f = figure(title=case, x_axis_type="log", y_axis_type="log", width=700, height=400,
                   x_axis_label="max abs error of exit state", y_axis_label="s per trajectory")
        for (m, pts), color in ((mp, c) for mp, c in zip(lines.items(), Category10[10]) if mp[1]):
            e, t = zip(*sorted(pts))
            f.line(e, t, color=color, legend_label=m)
            f.scatter(e, t, color=color, legend_label=m)
        f.add_layout(Span(location=targets[case], dimension="height", line_dash="dotted"))
        f.legend.click_policy = "hide"
        figs.append(f)
    save(column(*figs), filename=path, resources=INLINE, title="One support: work-precision")


def html_to_png(html: Path, png: Path) -> None:
    """Screenshot a saved Bokeh page with Debian's headless Chromium (via Playwright)."""
    from playwright.sync_api import sync_playwright

    flags = ["--no-sandbox", "--disable-gpu", "--disable-background-networking",
             "--disable-component-update", "--no-first-run", "--disable-sync"]
    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path="/usr/bin/chromium", args=flags)
        page = browser.new_page(viewport={"width": 760, "height": 600})
        page.goto(html.resolve().as_uri())
        page.wait_for_function("() => window.Bokeh && Bokeh.documents.length > 0")
        page.wait_for_timeout(500)
        page.screenshot(path=str(png), full_page=True)
        browser.close()


def plot(results: dict, out: Path) -> list:
    """Write the plots that the installed libraries allow; return notes on the others."""
    curves = {case: {m: [(r["error"], r["seconds"]) for r in rows if r["success"]]
                     for m, rows in res["rows"].items()} for case, res in results.items()}
    targets = {case: res["summary"]["target"] for case, res in results.items()}
    notes = []
    for name, writer, lib in (("work_precision.png", plot_png, "matplotlib"),
                              ("work_precision.html", plot_html, "bokeh")):
        try:
            writer(curves, targets, out / name)
        except ImportError:
            notes.append(f"{lib} is not installed: no {name}")
    html, png = out / "work_precision.html", out / "work_precision.png"
    if html.exists() and not png.exists():
        try:  # the same figure as a picture, through the browser
            html_to_png(html, png)
            notes = [n for n in notes if "work_precision.png" not in n]
        except Exception as error:  # noqa: BLE001 -- no browser here: the HTML stays
            notes.append(f"no work_precision.png ({type(error).__name__}: {error})"[:200])
    return notes
