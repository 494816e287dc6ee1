"""The Array tab: the slab sliding over a grid of ~100 supports, seen from above (Figs. 2a
and 4 of the paper, live). Supports under the slab move along their own trajectories,
enter contact at the slab's leading edge and are released at their tau_out; each is
coloured by the direction of its friction force; N_c is counted live against N_c0 (so
beta = N_c0/N_c shows) and the running F_T,x/(mu0 F_N) settles as the array does.

A renderer of ``SessionResults.array`` (``model.arrays.array_motion``, computed once per
parameter set in a worker): every frame goes to the browser once and a browser-side
player draws them -- no server round trip per frame.
"""
from __future__ import annotations

import panel as pn
import param
from bokeh.layouts import column
from bokeh.models import Plot

from .. import figures as F
from ..figures.array_scene import array_scene
from ..figures.player import READY_DELAY_MS, browser_player
from ..export import array_csv
from ..plot_words import array_description
from ..results import SessionResults
from ..state import ExplorerState
from ..texts import FELT_WORDS
from .access import LiveDescription, figure_classes
from .data_table import DataTable
from .export import AnimationExport, ResultDownload, svg_button
from .layout import WIDE, mode_classes


#: The tab's figures restyled in projector mode.
FIGURES = ("array_top", "array_live_panel", "array_colorbar_figure")
#: Projected, the top view is this much taller (px): its larger title and ticks take
#: room from the drawing otherwise (it then follows the slab where the travel does not fit).
PROJECTOR_TOP_EXTRA = 80
#: Projected, the result text goes below the figures (the headline above says the result).
PROJECTOR_CSS = f"{WIDE} {{ :host(.projector) .array-status {{ order: 1; }} }}"


def result_text(motion, orientation: str) -> str:
    """The tab's result in words: the steady force on a sliding slab (the array model's
    duration-weighted average, the dashed line the live mean settles to), then the grid."""
    m = motion.model
    return (f"**Result: F_T,x/(μ₀F_N) = {m['FTx_over_mu0FN_duration']:.3f}**, the force "
            f"on the sliding slab once it has settled ({FELT_WORDS}), with N_c/N_c0 = "
            f"{m['Nc_over_Nc0']:.3g} supports in contact per rigid one. Below: {motion.n_supports} supports on a "
            f"{motion.n_rows} × {motion.n_cols} grid, θ₀ "
            f"{'uniform' if orientation == 'uniform' else 'fixed'}; the live values move "
            f"as supports enter and leave, their mean settles on the dashed lines."
            + ("" if motion.success else f" ⚠ {motion.message}"))


class ArrayView(pn.viewable.Viewer):
    """The array under the slab, its player and its live counts."""

    state = param.ClassSelector(class_=ExplorerState, constant=True)
    results = param.ClassSelector(class_=SessionResults, constant=True)

    def __init__(self, **params):
        super().__init__(**params)
        self._doc = pn.state.curdoc
        self.player = None
        self._layout = None  # made by __panel__
        self.toggle = pn.widgets.RadioButtonGroup.from_param(
            self.state.param.orientation, css_classes=["ctl-orientation"],
            options={"θ₀ uniform (all directions)": "uniform",
                     "every support at θ₀ (slider)": "fixed"}, description=None,
            margin=(4, 10), styles={"max-width": "calc(100vw - 20px)"},
            stylesheets=[".bk-btn { white-space: normal; }"])
        self.status = pn.pane.Markdown("", css_classes=["array-status"], margin=(0, 10),
                                       sizing_mode="stretch_width")
        self.pane = pn.pane.Bokeh(None, css_classes=["array-view"], margin=(0, 5),
                                  sizing_mode="stretch_width")
        self.export = AnimationExport(state=self.state, results=self.results, what="array")
        self.csv = ResultDownload(lambda: array_csv(self.results.array), "array.csv", "array",
                                  results=self.results, name="array", label="Array CSV")
        self.svg = svg_button("array-svg", label="Figures (SVG)")
        # The plots in words and in numbers, once per result (never per frame).
        self.description = LiveDescription(text=array_description(None, "uniform"), width=0,
                                           height=0, margin=0,
                                           describes=["figure-array_page"],
                                           label="The array under the slab, live",
                                           css_classes=["array-description"])
        self.table = DataTable(lambda: array_csv(self.results.array),
                               "The array's live curves, frame by frame", "array-table")
        self._draw()
        self._on_busy()

    @param.depends("results.array", watch=True)
    def _draw(self) -> None:
        motion = self.results.array
        if motion is None:
            return
        self.player = browser_player(motion.n_frames, times=motion.t, name="array_player",
                                     autoplay=self.state.play, responsive=True, width=900)
        scene = array_scene(motion, self.player, width=900, responsive=True)
        page = column(self.player.layout, scene, sizing_mode="stretch_width",
                      name="array_page")
        figure_classes(page)  # named and described for screen readers
        self.pane.object = page
        if self._doc is not None:
            # Keys and autoplay start with a change the page sees: once the page has loaded
            # (a result that came before), or once the new models are in a loaded page.
            player = self.player
            pn.state.onload(lambda: pn.state.add_periodic_callback(
                player.ready, period=READY_DELAY_MS, count=1))
        self._restyle()
        self.status.object = result_text(motion, self.state.orientation)
        self.description.text = array_description(motion, motion.orientation)
        self.table.refresh()

    @param.depends("state.projector", watch=True)
    def _restyle(self) -> None:
        """Projector mode: the figures' titles, ticks and labels projector-sized."""
        projector = self.state.projector
        for fig in self._figures():
            F.style(fig, projector)
            if fig.name == "array_top":
                base = next((int(t[2:]) for t in fig.tags if str(t).startswith("h:")), None)
                if base is None:
                    base = fig.height
                    fig.tags = [*fig.tags, f"h:{base}"]
                fig.height = base + (PROJECTOR_TOP_EXTRA if projector else 0)
        if self._layout is not None:
            self._layout.css_classes = mode_classes(self._layout.css_classes, projector)

    def _figures(self) -> list:
        page = self.pane.object
        return [] if page is None else [m for m in page.select({"type": Plot})
                                        if m.name in FIGURES]

    @param.depends("results.busy", "results.errors", watch=True)
    def _on_busy(self) -> None:
        busy = "array" in self.results.busy
        self.pane.loading = busy
        error = self.results.errors.get("array", "")
        if error:
            self.status.object = error
        elif busy and self.results.array is None:
            self.status.object = "Computing the supports' trajectories …"

    def __panel__(self):
        self._layout = pn.Column(
            self.toggle, self.status, self.pane, self.export,
            pn.Row(self.csv, self.svg, margin=0, sizing_mode="stretch_width"),
            self.table, self.description,
            sizing_mode="stretch_width", stylesheets=[PROJECTOR_CSS],
            css_classes=mode_classes(["array-tab"], self.state.projector))
        return self._layout
