"""This view as code: the Python snippet (public ``model`` API) that reproduces the numbers
on the page for the current controls and tab (``app.snippet.view_as_python``: the
Orientation, Regime map, Load and Array tabs get their own calls; with a pinned state A,
A's numbers too, and on the Design tab the design's array), folded in a card, and the
software's version and how to cite it."""
from __future__ import annotations

import panel as pn
import param

from ..about import version_text
from ..results import SessionResults
from ..snippet import view_as_python
from ..state import DESIGN_KEYS, DIST_KEYS, ExplorerState


class CodeView(pn.viewable.Viewer):
    """A folded card with the snippet of the current view; the version line below it."""

    state = param.ClassSelector(class_=ExplorerState, constant=True)
    results = param.ClassSelector(class_=SessionResults, constant=True)

    def __init__(self, **params):
        super().__init__(**params)
        self.code = pn.pane.Markdown("", css_classes=["view-as-code"],
                                     sizing_mode="stretch_width", styles={"font-size": "0.8em"})
        self.card = pn.Card(self.code, title="This view as Python", collapsed=True,
                            css_classes=["ctl-code"], sizing_mode="stretch_width",
                            margin=(4, 3))
        # Folded, the snippet is not written (rendering and highlighting it took ~15 % of
        # the server's time per slider move); it is written when the card opens.
        self._stale = True
        self.card.param.watch(self._on_open, "collapsed")
        self.version = pn.pane.Markdown(
            f"{version_text()} · cite with `CITATION.cff`", css_classes=["version"],
            margin=(0, 10), styles={"font-size": "0.8em", "color": "#555"})
        self._write()

    @param.depends("state.k_r", "state.k_theta", "state.F_N", "state.theta0", "state.rtol",
                   "state.beta_mode", "state.beta", "state.average", "state.pinned",
                   "state.tab", "state.map_quantity", "state.orientation",
                   *(f"state.{name}" for name in DESIGN_KEYS + DIST_KEYS),
                   watch=True)
    def _write(self) -> None:
        if self.card.collapsed:
            self._stale = True
            return
        self._stale = False
        try:
            self.code.object = f"```python\n{view_as_python(self.state)}```"
        except ValueError as exc:  # a state the model refuses: say so
            self.code.object = f"*No snippet for these controls: {exc}*"

    def _on_open(self, event) -> None:
        if not event.new and self._stale:
            self._write()

    def __panel__(self):
        return pn.Column(self.card, self.version, sizing_mode="stretch_width", margin=0)
