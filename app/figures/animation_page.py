"""Standalone pages of the browser-side animations (no server): the array under the slab,
and one support with its live energy. The benchmark and the browser tests load them in
headless Chromium; a teacher can open the saved HTML file offline.
"""
from __future__ import annotations

import math
import re

import numpy as np
from bokeh.document import Document
from bokeh.embed import file_html
from bokeh.layouts import column, row
from bokeh.models import Div, Range1d
from bokeh.resources import INLINE

from model import simulate_support
from model.arrays.array_motion import array_motion

from .access_js import PAGE_SCRIPT, mark_figures
from .array_scene import array_scene
from model.contact.friction import mu0

from .histories import forces_figure, friction_law_data, friction_law_figure
from .live_energy import energy_frames, live_energy_figure, support_frames_callback
from .player import browser_player
from .scene import scene_figure

__all__ = ["array_document", "support_document", "page_html", "SUPPORT_FRAMES"]

SUPPORT_FRAMES = 300


def array_document(params, orientation: str = "uniform", n_supports: int = 100,
                   n_frames: int = 600, autoplay: bool = False, width: int = 1000,
                   ui_ms: float | None = None, responsive: bool = True, **kwargs):
    """The array tab as a standalone document; returns (document, motion, player).

    ``ui_ms``: how often the DOM readouts and the live panel follow playback (None: the
    defaults; 0: every frame, the benchmark's comparison)."""
    motion = array_motion(params, orientation=orientation, n_supports=n_supports,
                          n_frames=n_frames, **kwargs)
    ui = {} if ui_ms is None else {"ui_ms": ui_ms}
    player = browser_player(motion.n_frames, times=motion.t, autoplay=autoplay, width=width,
                            name="array_player", responsive=responsive, **ui)
    scene = array_scene(motion, player, width=width, responsive=responsive,
                        **({} if ui_ms is None else {"ui_ms": ui_ms, "panel_ms": ui_ms}))
    note = Div(text=f"<i>{motion.message}</i>" if not motion.success else "",
               name="array_message")
    doc = Document()
    doc.add_root(column(player.layout, scene, note, name="array_page",
                        sizing_mode="stretch_width" if responsive else None))
    doc.title = "The array under the slab"
    player.install(doc)
    return doc, motion, player


def support_document(params, n_frames: int = SUPPORT_FRAMES, autoplay: bool = False,
                     samples: int = 600):
    """One support (scene, Fig. 7, Fig. 3) with the live energy bars; returns
    (document, result, player). The energy bars need a ``TimeSeries`` with energies."""
    result = simulate_support(params, samples=samples)
    series = result.series
    if series is None:
        raise ValueError(f"no time series to animate: {result.message}")
    player = browser_player(n_frames, times=energy_frames_tau(series, n_frames),
                            autoplay=autoplay, name="support_player")
    scene = scene_figure(series, params)
    freeze_scene_ranges(scene, series, params)
    forces = forces_figure(series, params)
    law = friction_law_figure(series, params)
    # Markers move every frame: fixed ranges spare a bounds computation per frame.
    _freeze(forces, (0.0, float(series.tau[-1])),
            (min(0.0, float(np.min(series.F_y)), float(np.min(series.F_x))),
             max(float(np.max(series.F_abs)), mu0(params))))
    _freeze(law, None, (0.0, float(np.max(law_values(params)))))
    player.on_frame(support_frames_callback(series, params, n_frames, scene=scene,
                                            forces=forces, law=law))
    energy = live_energy_figure(energy_frames(series, n_frames), player)
    doc = Document()
    doc.add_root(column(player.layout, row(scene, forces), row(law, energy),
                        name="support_page"))
    doc.title = "One support"
    player.install(doc)
    return doc, result, player


def energy_frames_tau(series, n_frames):
    return np.linspace(0.0, float(series.tau[-1]), n_frames)


def _freeze(fig, x, y, padding: float = 0.06) -> None:
    """Fixed ranges for a figure whose markers move every frame (see below)."""
    for attr, span in (("x_range", x), ("y_range", y)):
        if span is not None:
            pad = padding * (span[1] - span[0] or 1.0)
            setattr(fig, attr, Range1d(span[0] - pad, span[1] + pad))


def law_values(params):
    return friction_law_data(params)["friction_law"]["mu"]


def freeze_scene_ranges(scene, series, params, padding: float = 0.15) -> None:
    """Fixed, equal-aspect ranges around everything the support scene will draw.

    ``scene_figure``'s data ranges follow the moving mass and spring: in the browser they
    would be recomputed (over the whole path) on every frame, the largest cost of a frame.
    """
    x = np.concatenate([series.x, [0.0, math.cos(params.theta0), -1.0, 1.0]])
    y = np.concatenate([series.y, [0.0, math.sin(params.theta0), -1.0, 1.0]])
    cx, cy = 0.5 * (x.max() + x.min()), 0.5 * (y.max() + y.min())
    half = 0.5 * max(x.max() - x.min(), y.max() - y.min()) * (1 + 2 * padding)
    scene.x_range = Range1d(cx - half, cx + half)
    scene.y_range = Range1d(cy - half, cy + half)


# The page's icon travels inside it: without one, a browser asks for ``favicon.ico`` next to
# the saved file and logs a failed load.
ICON = ("<link rel=\"icon\" href=\"data:image/svg+xml,"
        "%3Csvg xmlns='http://www.w3.org/2000/svg' viewBox='0 0 16 16'%3E"
        "%3Crect x='1' y='2' width='14' height='3' fill='%23555'/%3E"
        "%3Crect x='6' y='5' width='4' height='9' fill='%231f77b4'/%3E%3C/svg%3E\">")


#: A script that a saved file cannot load: a path relative to a server. Bokeh lists the
#: external files declared by every imported model class, so once Panel is imported its
#: module shim (``static/extensions/panel/...``) would be asked for beside the file; the
#: page's own models are Bokeh's and need none of them.
_SERVER_SCRIPT = re.compile(r'<script src="(?![a-z]+:)[^"]*"></script>\n?')


def page_html(doc, title: str | None = None) -> str:
    """Self-contained HTML (Bokeh's JavaScript inline, an inline icon: works offline);
    its figures named for screen readers (``mark_figures``)."""
    mark_figures(doc)
    html = _SERVER_SCRIPT.sub("", file_html(doc, INLINE, title or doc.title))
    html = html.replace("<head>", "<head>\n    " + ICON, 1)
    head, body_end, tail = html.rpartition("</body>")  # the page's own, after BokehJS's
    return head + PAGE_SCRIPT + "\n" + body_end + tail  # named slider handles
