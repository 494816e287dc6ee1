"""Readouts: the headline above the plots (the friction change in one plain sentence),
the regime and its mechanism, and behind a disclosure the numbers of the fixed array at
theta0 (Figs. 9-11) and of the uniform array (Figs. 5, 6, 8) with their diagnostics; with
a pinned state "A", its headline numbers beside the current ones and their differences.
Renderers of ``SessionResults.support``, ``.uniform`` and ``.support_A``, ``.uniform_A``.
"""
from __future__ import annotations

import math

import panel as pn
import param

from model.arrays.quantities import readout

from ..figures.arrays import AVERAGE_COLUMNS
from ..results import SessionResults
from ..state import ExplorerState
from ..motion_words import change_words, regime_markdown
from ..texts import AVERAGE_NAMES, FELT_AVERAGE, FELT_WORDS
from .compare_tables import difference
from .shown import WhenShown
from .live_text import LiveHTML, markdown_html

TABLE_CSS = ("table {border-collapse: collapse; width: 100%;} "
             "td, th {padding: 2px 6px; line-height: 1.25;}")


def _fmt(x, digits: int = 4) -> str:
    return "–" if x is None or not math.isfinite(x) else f"{x:.{digits}g}"


def headline_text(fixed: float | None, theta0_deg: float, felt: float | None,
                  felt_note: str = "") -> str:
    """The page's one-line result, e.g. "Friction is 16.2 % below a rigid surface (every
    support at θ₀ = 90°); with supports of all orientations the slab feels 15.5 % below a
    rigid surface (each support counted for as long as it touches the slab)."
    ``fixed`` is F_T,x/(mu0 F_N) of the fixed array, ``felt`` the uniform array's
    duration-weighted average (``app.texts.FELT_AVERAGE``: the force the slab feels; the
    paper's Eq. 10 average is in the folded details); ``felt_note`` stands in for a uniform
    value not (yet) there."""
    first = (f"Friction is {change_words(fixed)} (every support at θ₀ = {theta0_deg:g}°)"
             if fixed is not None else "Friction: being computed")
    if felt is None:
        return (f"{first}; what the slab feels with supports of all orientations: "
                f"{felt_note or 'being computed'}.")
    return (f"{first}; with supports of all orientations the slab feels "
            f"{change_words(felt)} ({FELT_WORDS}).")


def _short_words(ratio: float | None) -> str:
    """``change_words`` without "a rigid surface", for the headline's clause about A."""
    if ratio is None or not math.isfinite(ratio):
        return "being computed"
    percent = 100.0 * (1.0 - ratio)
    return "as rigid" if abs(percent) < 0.05 else \
        f"{abs(percent):.1f} % {'below' if percent > 0 else 'above'}"


def pinned_clause(a_fixed: float | None, a_theta0_deg: float, a_uniform: float | None,
                  fixed: float | None, uniform: float | None) -> str:
    """The headline's clause about a pinned state A: its friction as ``headline_text``
    says B's, and B − A of F_T,x/(mu0 F_N), fixed and averaged, e.g. "A (pinned): 8.1 %
    below at θ₀ = 60°, all orientations: 4.9 % below; B − A = −0.026, −0.011 (F_T,x/μ₀F_N)"."""
    d_fixed, d_uniform = difference(a_fixed, fixed)[0], difference(a_uniform, uniform)[0]
    return (f"A (pinned): {_short_words(a_fixed)} at θ₀ = {a_theta0_deg:g}°, all orientations: "
            f"{_short_words(a_uniform)}; B − A = {d_fixed}, {d_uniform} (F_T,x/μ₀F_N)")


#: The fixed array's readout: quantities of the registry (``model.arrays.quantities``), whose
#: labels and formats the rows take.
FIXED_READOUT = ("FTx_over_mu0FN", "FTy_over_mu0FN", "Dy_over_Dx", "Nc_over_Nc0", "beta",
                 "r_max")
#: Words before the symbols, for students.
PLAIN = {"FTx_over_mu0FN": "friction along x", "FTy_over_mu0FN": "sideways force",
         "Dy_over_Dx": "dissipated across / along", "Nc_over_Nc0": "contacts",
         "beta": "load factor", "r_max": "largest stretch"}


def fixed_markdown(data) -> str:
    """The fixed-orientation array at theta0 and its one contact, as a Markdown table."""
    if data is None or data.fixed is None:
        return "*No result for these parameters.*"
    f, r = data.fixed, data.result
    theta0_deg = round(math.degrees(data.params.theta0), 6)
    rows = [(f"{PLAIN[name]}, {label}" if name in PLAIN else label, value)
            for name, (label, value) in zip(FIXED_READOUT, readout(f, FIXED_READOUT))]
    rows.append(("energy residual / W",
                 _fmt(abs(r.energy_residual / r.W) if r and r.W else None, 2)))
    body = "\n".join(f"| {k} | {v} |" for k, v in rows)
    return f"| Fixed array, θ₀ = {theta0_deg:g}° | value |\n|:--|--:|\n{body}"


def uniform_markdown(row: dict | None, average: str, note: str = "") -> str:
    """The uniform array (theta0 uniform on [0, 2 pi)): both averages of its friction, the
    slab's (the headline's) first; the one the plots use (``average``) in bold."""
    if row is None:
        return f"| Uniform array | value |\n|:--|--:|\n| F_T,x/(μ₀F_N) | {note or '…'} |"
    order = (FELT_AVERAGE, *(a for a in AVERAGE_NAMES if a != FELT_AVERAGE))
    rows = [(f"friction F_T,x/(μ₀F_N), {AVERAGE_NAMES[a]}",
             f"**{_fmt(row[AVERAGE_COLUMNS[a]])}**" if a == average
             else _fmt(row[AVERAGE_COLUMNS[a]])) for a in order]
    rows += [("dissipated across / along, D_y/D_x", _fmt(row["Dy_over_Dx"])),
             ("contacts, N_c/N_c0", _fmt(row["Nc_over_Nc0"])),
             ("quadrature error", _fmt(row["quadrature_error_FTx"], 2))]
    body = "\n".join(f"| {k} | {v} |" for k, v in rows)
    warn = "" if row.get("success", True) else (
        f"\n\n⚠ not every member finished its contact ({row.get('n_failed', 0)} failed)")
    return f"| Uniform array (all θ₀) | value |\n|:--|--:|\n{body}{warn}"


#: The numbers compared between a pinned state A and the current B: (label, fixed-array
#: quantity of the registry, or None for the uniform array's F_T,x the slab feels, as the
#: headline gives it).
COMPARED = (("F_T,x/(μ₀F_N)", "FTx_over_mu0FN"), ("F_T,y/(μ₀F_N)", "FTy_over_mu0FN"),
            ("D_y/D_x", "Dy_over_Dx"), ("N_c/N_c0", "Nc_over_Nc0"),
            ("all θ₀, the slab feels: F_T,x/(μ₀F_N)", None))


def _settings(p) -> str:
    return (f"k_r = {p.k_r:.3g}, k_θ = {p.k_theta:.3g}, F_N = {p.F_N:.3g}, "
            f"θ₀ = {round(math.degrees(p.theta0), 6):g}°")


def compared_values(support, uniform: dict | None, average: str = FELT_AVERAGE) -> list:
    """The ``COMPARED`` numbers of one state (None where not computed)."""
    fixed = support.fixed if support is not None else None
    return [(uniform or {}).get(AVERAGE_COLUMNS[average]) if name is None
            else getattr(fixed, name, None) if fixed is not None else None
            for _, name in COMPARED]


def compare_markdown(a_support, b_support, a_uniform, b_uniform,
                     average: str = FELT_AVERAGE) -> str:
    """A (pinned) and B (current) side by side: the fixed array at each one's theta0 and
    the uniform array, with B - A and, under it, its change relative to A."""
    rows = []
    a_vals = compared_values(a_support, a_uniform, average)
    b_vals = compared_values(b_support, b_uniform, average)
    for (label, _), a, b in zip(COMPARED, a_vals, b_vals):
        diff, rel = difference(a, b)
        rows.append(f"| {label} | {_fmt(a)} | {_fmt(b)} | {diff}<br>{rel} |")
    who = [f"**{side}**: {_settings(d.params)}" for side, d in
           (("A (pinned)", a_support), ("B (current)", b_support)) if d is not None]
    return ("| Compare | A | B | B − A |\n|:--|--:|--:|--:|\n" + "\n".join(rows)
            + "\n\n" + "; ".join(who))


class ReadoutsView(pn.viewable.Viewer):
    """Regime and mechanism, fixed-array and uniform-array numbers."""

    state = param.ClassSelector(class_=ExplorerState, constant=True)
    results = param.ClassSelector(class_=SessionResults, constant=True)

    def __init__(self, **params):
        super().__init__(**params)
        style = {"font-size": "0.92em"}
        compact = [TABLE_CSS]
        wide = dict(sizing_mode="stretch_width", margin=(0, 5))
        self.regime = LiveHTML(html=markdown_html(regime_markdown(self.state.regime,
                                                                  self.results.support)),
                               css_classes=["readout-regime"], styles=style, margin=(0, 5),
                               sizing_mode="stretch_width")
        self.fixed_pane = pn.pane.Markdown(fixed_markdown(self.results.support),
                                           css_classes=["readout-fixed"], styles=style,
                                           stylesheets=compact, **wide)
        self.uniform_pane = pn.pane.Markdown(
            uniform_markdown(self.results.uniform, self.state.average),
            css_classes=["readout-uniform"], styles=style, stylesheets=compact, **wide)
        self.compare_pane = pn.pane.Markdown("", css_classes=["readout-compare"],
                                             styles=style, stylesheets=compact, visible=False,
                                             **wide)
        # The spinner goes on a holder: on a Markdown pane Panel marks loading by
        # rendering the pane's text again (twice per slider move, for a folded card).
        self.uniform_holder = pn.Column(self.uniform_pane, sizing_mode="stretch_width",
                                        margin=0)
        # One column in the card: folded, the card hides its children by setting their
        # ``visible`` in the page; a pane whose text changes each move would be sent
        # ``visible`` again by the server, shown, hidden again and the page laid out
        # twice per move. The column itself never changes.
        self.details = pn.Card(
            pn.Column(self.fixed_pane, self.uniform_holder, sizing_mode="stretch_width",
                      margin=0), title="Numbers and diagnostics",
            collapsed=True, css_classes=["readout-details"], sizing_mode="stretch_width",
            margin=(6, 5))
        # The folded card's tables are written when it is opened: text no reader sees
        # would cost the server a Markdown render and the page a message at every move.
        # Off the One-support tab, nothing here is written until the tab is shown.
        self._stale: set[str] = set()
        self.when_shown = WhenShown(self.state, "support")
        self.details.param.watch(lambda event: self._opened(), "collapsed")
        self._compare()

    def _opened(self) -> None:
        self._mark_busy()
        if not self.details.collapsed:
            stale, self._stale = self._stale, set()
            if "fixed" in stale:
                self._on_support()
            if "uniform" in stale:
                self._show_uniform()

    @param.depends("results.support", watch=True)
    def _on_support(self) -> None:
        if self.details.collapsed:
            self._stale.add("fixed")
            return
        self.when_shown.run(self._write_fixed)

    def _write_fixed(self) -> None:
        self.fixed_pane.object = fixed_markdown(self.results.support)

    @param.depends("results.support", watch=True)
    def _on_regime(self) -> None:
        self.when_shown.run(self._write_regime)

    def _write_regime(self) -> None:
        # Written from the computed support (its own regime): numbers and words agree.
        self.regime.html = markdown_html(regime_markdown(self.state.regime,
                                                         self.results.support))

    @param.depends("results.uniform", "results.errors", "state.average", watch=True)
    def _show_uniform(self) -> None:
        if self.details.collapsed:
            self._stale.add("uniform")
            return
        self.when_shown.run(self._write_uniform)

    def _write_uniform(self) -> None:
        failed = bool(self.results.errors.get("uniform"))
        self.uniform_pane.object = uniform_markdown(
            None if failed else self.results.uniform, self.state.average,
            "failed" if failed else "")

    @param.depends("results.support", "results.uniform", "results.support_A",
                   "results.uniform_A", "state.pinned", watch=True)
    def _compare(self) -> None:
        r = self.results
        on = self.state.pinned is not None
        self.compare_pane.visible = on
        if on:
            self.compare_pane.object = compare_markdown(r.support_A, r.support, r.uniform_A,
                                                        r.uniform)

    @param.depends("results.busy", watch=True)
    def _busy(self) -> None:
        self.when_shown.run(self._mark_busy)

    def _mark_busy(self) -> None:
        # A spinner in a folded card would cost a message (and Panel's loading overlay)
        # at every move for nothing on screen: it shows in the opened card only.
        self.uniform_holder.loading = ("uniform" in self.results.busy
                                       and not self.details.collapsed)

    def __panel__(self):
        return pn.Column(self.regime, self.compare_pane, self.details, css_classes=["readouts", "side-column"],
                         width=300, margin=0)


class HeadlineView(pn.viewable.Viewer):
    """The result in one plain sentence above the plots (``headline_text``)."""

    state = param.ClassSelector(class_=ExplorerState, constant=True)
    results = param.ClassSelector(class_=SessionResults, constant=True)

    def __init__(self, **params):
        super().__init__(**params)
        self.pane = LiveHTML(css_classes=["headline"], margin=(2, 10), sizing_mode="stretch_width",
                             styles={"font-size": "1.15em", "font-weight": "600"})
        self._write()
        self._for_tab()

    @param.depends("state.tab", watch=True)
    def _for_tab(self) -> None:
        # The sentence is about the sidebar's support: the Design tab has its own numbers.
        self.pane.visible = self.state.tab != "design"

    def _numbers(self, data, row, failed: bool = False):
        """F_T,x/(mu0 F_N) of the fixed array and the uniform one (the average the slab
        feels), and theta0 in degrees."""
        fixed = theta0 = None
        if data is not None and data.fixed is not None:
            fixed = data.fixed.FTx_over_mu0FN
            theta0 = round(math.degrees(data.params.theta0), 6)
        uniform = None if failed or row is None else row[AVERAGE_COLUMNS[FELT_AVERAGE]]
        return fixed, theta0, uniform

    @param.depends("results.support", "results.uniform", "results.errors",
                   "results.support_A", "results.uniform_A", "state.pinned", watch=True)
    def _write(self) -> None:
        r = self.results
        failed = bool(r.errors.get("uniform"))
        # One sentence, one state: a result of the controls before the last change (the
        # other one arrived first) is "being computed", not quoted beside the new one.
        # A support that failed keeps its last good numbers (the notice says why).
        support = r.support if r.slots["support"].current or r.errors.get("support") else None
        row = r.uniform if r.slots["uniform"].current else None
        fixed, theta0, uniform = self._numbers(support, row, failed)
        text = headline_text(fixed, theta0 if theta0 is not None else self.state.theta0,
                             uniform, "not computed (see the notice)" if failed else "")
        html = f"<span>{text}</span>"
        a = self.state.pinned
        if a is not None:  # a comparison: A's numbers and B − A in a second, lighter line
            a_fixed, a_theta0, a_uniform = self._numbers(self.results.support_A,
                                                         self.results.uniform_A)
            clause = pinned_clause(a_fixed, a_theta0 if a_theta0 is not None else a["theta0"],
                                   a_uniform, fixed, uniform)
            html += ("<br><span class='headline-compare' style='font-weight: 400; "
                     f"font-size: 0.85em'>{clause}.</span>")
        self.pane.html = html

    @property
    def text(self) -> str:
        """The headline's HTML."""
        return self.pane.html

    def __panel__(self):
        return self.pane
