"""Export for slides: a GIF or MP4 of the animation on show, made on the server in the
background (``SessionResults.prepare_animation``) and then offered for download. The
page never waits for it."""
from __future__ import annotations

import io

import panel as pn
import param

from ..results import SessionResults
from ..state import ExplorerState
from .layout import BUTTON_CSS
from .widgets import caption, look


class AnimationExport(pn.viewable.Viewer):
    """Format choice, a "make" button, and the download once the file is ready."""

    state = param.ClassSelector(class_=ExplorerState, constant=True)
    results = param.ClassSelector(class_=SessionResults, constant=True)
    what = param.Selector(default="support", objects=["support", "array"], constant=True)

    def __init__(self, **params):
        super().__init__(**params)
        self.format = pn.widgets.RadioButtonGroup(options={"GIF": "gif", "MP4": "mp4"},
                                                  value="gif", margin=(4, 5),
                                                  stylesheets=[BUTTON_CSS],
                                                  css_classes=[f"export-{self.what}-format"])
        self.make = pn.widgets.Button(**caption("Make animation for slides"),
                                      **look("primary", "outline"), margin=(4, 5),
                                      stylesheets=[BUTTON_CSS],
                                      css_classes=[f"export-{self.what}-make"],
                                      description="renders the animation on the server "
                                                  "(about half a minute)")
        self.make.on_click(self._make)
        self.download = pn.widgets.FileDownload(
            callback=self._file, filename="animation.gif", label="Download", disabled=True,
            **look("success"), margin=(4, 5), css_classes=[f"export-{self.what}-download"],
            stylesheets=[BUTTON_CSS])
        self.status = pn.pane.Markdown("", margin=(0, 5), styles={"font-size": "0.85em"})

    def _make(self, _event=None) -> None:
        self.download.disabled = True
        self.status.object = "Rendering on the server …"
        self.results.prepare_animation(self.what, self.format.value)

    def _mine(self) -> bool:
        a = self.results.animation
        return a is not None and a.get("what") == self.what

    @param.depends("results.animation", "results.errors", watch=True)
    def _ready(self) -> None:
        error = self.results.errors.get("animation", "")
        if self._mine():
            a = self.results.animation
            s = self.state
            self.download.filename = (f"{self.what}_kr{s.k_r:.3g}_kt{s.k_theta:.3g}_"
                                      f"FN{s.F_N:.3g}_theta0_{s.theta0:g}.{a['format']}")
            self.download.disabled = False
            self.status.object = (f"Ready: {a['message']}, {len(a['bytes']) / 1e6:.1f} MB. "
                                  "Press Download.")
        elif error:
            self.status.object = error

    def _file(self):
        return io.BytesIO(self.results.animation["bytes"]) if self._mine() else io.BytesIO()

    def __panel__(self):
        return pn.FlexBox(self.format, self.make, self.download, self.status,
                          flex_wrap="wrap", css_classes=[f"export-{self.what}"],
                          sizing_mode="stretch_width")
