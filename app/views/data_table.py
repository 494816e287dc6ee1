"""The numbers behind a tab's plots as a table on the page ("Data as a table"), so nothing
is only in a picture (WCAG 1.1.1).

``DataTable`` is a toggle button under a tab's figures; pressed, it shows the rows of the
tab's CSV download (the same text, read back with ``model.csvfile.read_text``) as an HTML
table with a caption and column headers that carry units (``column_header``: the
registered quantities' labels and units, ``model.arrays.quantities``). The table is written only
while it is shown, and again when the owner says the result changed (``refresh``).
A long file (a trajectory, the array's frames) is shown every k-th row, first and last
kept, and the caption says so: the download has every row.
"""
from __future__ import annotations

import html
import math
from typing import Callable

import numpy as np
import panel as pn

from model import csvfile
from model.arrays.quantities import QUANTITIES, format_value, label

from .layout import BUTTON_CSS
from .widgets import caption, look

#: Rows shown at most (a screen reader's table, not the whole file).
MAX_ROWS = 120
#: The dashboard's dimensionless units (Eq. 5) as a header writes them.
UNIT_WORDS = {"1": "–", "r0": "r₀", "r0/V0": "r₀/V₀", "m V0^2": "m V₀²", "rad": "rad",
              "V0": "V₀", "s": "s"}
#: Columns of the downloads that are not registered quantities: (label, unit).
OTHER_COLUMNS = {"theta0_deg": ("θ₀", "°"), "theta_deg": ("θ", "°"), "t": ("t", "r₀/V₀"),
                 "slab_lead": ("slab's leading edge", "r₀"), "N_c": ("N_c", "supports"),
                 "N_c0": ("N_c0", "supports"), "FTx": ("F_T,x/(μ₀F_N) now", "–"),
                 "FTx_running": ("F_T,x/(μ₀F_N) running mean", "–"), "curve": ("curve", "")}
TABLE_CSS = """
.data-table { max-height: 320px; overflow: auto; }
.data-table table { border-collapse: collapse; font-size: 0.85em; }
.data-table caption { text-align: left; padding: 2px 0 4px; }
.data-table th, .data-table td { border: 1px solid #999; padding: 1px 5px; text-align: right; }
.data-table th { background: #F0F0F0; position: sticky; top: 0; }
"""


def column_header(name: str) -> str:
    """A column's header with its unit, e.g. "τ [r₀/V₀]", "F_T,x/(μ₀F_N) [–]"."""
    if name in QUANTITIES:
        text, unit = label(name), UNIT_WORDS.get(QUANTITIES[name].units, QUANTITIES[name].units)
    else:
        text, unit = OTHER_COLUMNS.get(name, (name, ""))
    return f"{text} [{unit}]" if unit else text


def _cell(name: str, value) -> str:
    if name in QUANTITIES:
        return format_value(name, value.item() if hasattr(value, "item") else value, 4)
    if isinstance(value, (float, np.floating)):
        return "–" if not math.isfinite(value) else f"{value:.4g}"
    return str(value)


def shown_rows(n: int, limit: int = MAX_ROWS) -> np.ndarray:
    """Indices of the rows shown of ``n``: all, or every k-th with the last kept."""
    if n <= limit:
        return np.arange(n)
    step = math.ceil((n - 1) / (limit - 1))
    rows = np.arange(0, n, step)
    return rows if rows[-1] == n - 1 else np.append(rows, n - 1)


def table_html(csv_text: str, what: str, limit: int = MAX_ROWS) -> str:
    """``csv_text`` (a download of ``model.csvfile``) as an HTML table captioned ``what``."""
    _, columns = csvfile.read_text(csv_text)
    if not columns:
        note = " ".join(line[2:] for line in csv_text.splitlines() if line.startswith("# "))
        note = note or "no data yet"
        return f"<p>{html.escape(what)}: {html.escape(note)}.</p>"
    names = list(columns)
    n = len(columns[names[0]])
    rows = shown_rows(n, limit)
    some = (f"one row in {rows[1] - rows[0]} of {n} (the CSV download has all)"
            if len(rows) < n else f"{n} rows")
    head = "".join(f'<th scope="col">{html.escape(column_header(c))}</th>' for c in names)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(_cell(c, columns[c][i]))}</td>"
                                    for c in names) + "</tr>" for i in rows)
    return (f'<div class="data-table" role="region" tabindex="0" aria-label="{html.escape(what)}">'
            f"<table><caption>{html.escape(what)}: {some}; [–] a ratio without unit, lengths "
            f"in r₀, times in r₀/V₀ (Eq. 5).</caption><thead><tr>{head}</tr></thead>"
            f"<tbody>{body}</tbody></table></div>")


class DataTable(pn.viewable.Viewer):
    """A toggle button "Data as a table" that shows the CSV ``csv_text()`` returns as a table
    (a button, not a card: its name is its own text, there as soon as it is drawn)."""

    def __init__(self, csv_text: Callable[[], str], what: str, css: str, **params):
        super().__init__(**params)
        self._csv_text, self.what = csv_text, what
        self.toggle = pn.widgets.Toggle(**caption("Data as a table"),
                                        **look("default", "outline"),
                                        margin=(4, 10), stylesheets=[BUTTON_CSS],
                                        css_classes=["data-table-button"])
        self.pane = pn.pane.HTML("", stylesheets=[TABLE_CSS], sizing_mode="stretch_width",
                                 margin=(0, 10), visible=False)
        self.toggle.param.watch(self._on_toggle, "value")
        self._layout = pn.Column(self.toggle, self.pane, sizing_mode="stretch_width", margin=0,
                                 css_classes=["data-table-card", css])

    @property
    def collapsed(self) -> bool:
        return not self.toggle.value

    def _on_toggle(self, _) -> None:
        self.pane.visible = self.toggle.value
        self.refresh()

    def refresh(self) -> None:
        """Write the table again from the current result (only while it is shown)."""
        if self.toggle.value:
            self.pane.object = table_html(self._csv_text(), self.what)

    def __panel__(self):
        return self._layout
