"""What one slider move sends to the page: only what changed, and nothing for a tab that is
not on screen (app/views/shown.py, app/figures/common.py ``update``). Counted in the
page's Bokeh document (the changes Bokeh would send and the binary arrays they carry),
without a server: every result is computed at once (the ``pool`` fixture)."""
from __future__ import annotations

import numpy as np
import panel as pn
import pytest
from bokeh.document import Document
from bokeh.models import ColumnDataSource, Div
from panel.models.esm import ReactiveESM
from panel.models.markup import HTML as PanelHTML
from bokeh.protocol import Protocol

from app.state import ExplorerState
from app.views import Dashboard

#: The sources of the One-support tab's figures and player (``app.views.support``).
SUPPORT_SOURCES = ("orbit", "forces", "scene_mass", "scene_circle", "support_frames",
                   "energy_live_frames", "support_frame_params")
#: The scene's sources at the frame on show, drawn by the player's callback in the browser.
FRAME_SOURCES = ("scene_mass", "scene_spring", "scene_twist", "scene_slab", "scene_stripes",
                 "scene_edges", "scene_arrows", "scene_arrow_labels")


class Page:
    """A dashboard in a Bokeh document, recording the changes the page would be sent."""

    def __init__(self, **state):
        self.doc = Document()
        self.page = Dashboard(ExplorerState(**state))
        self.doc.add_root(pn.panel(self.page).get_root(self.doc))
        self.events: list = []
        self.doc.callbacks.on_change_dispatch_to(self)

    def _document_patched(self, event) -> None:
        self.events.append(event)

    def move(self, **values) -> list:
        """The changes one move of the controls sends (its results included)."""
        self.events.clear()
        self.page.state.param.update(**values)
        return list(self.events)

    def texts(self) -> dict:
        """The HTML of the texts written in place (``LiveHTML``), by CSS class."""
        return {c: m.data.html for m in self.doc.models if isinstance(m, ReactiveESM)
                and hasattr(m.data, "html") for c in m.css_classes}

    def source(self, name: str):
        return next(m for m in self.doc.models
                    if isinstance(m, ColumnDataSource) and m.name == name)


def _changed_sources(events) -> set[str]:
    return {getattr(e.model, "name", None) for e in events if e.kind == "ColumnDataChanged"}


def _buffers(events) -> int:
    return len(Protocol().create("PATCH-DOC", events).buffers) if events else 0


def test_a_move_sends_only_the_data_that_changed(pool):
    page = Page()
    texts = page.texts()
    events = page.move(theta0=100.0)
    changed = _changed_sources(events)
    assert {"orbit", "forces", "support_frames", "support_frame_params"} <= changed
    # The circle the support's end can reach (its rest length) does not move with theta0.
    assert "scene_circle" not in changed
    # The scene at the frame on show (mass, springs, slab, arrows) is drawn in the browser
    # from the new frames (tests/browser/test_dashboard.py): the server sends none of it.
    assert not changed & set(FRAME_SOURCES), changed & set(FRAME_SOURCES)
    # The files are named when downloaded, not at each move.
    assert not [e for e in events if getattr(e, "attr", None) == "filename"]
    # 31 arrays before the data that did not change was left out, 29 before the scene's
    # frame was left to the browser.
    assert _buffers(events) <= 27
    # The texts that change at each move (headline, regime) are written in place: no
    # Panel text pane renders them again, and no Bokeh Div (whose new text lays the whole
    # page out again in the browser) changes.
    panes = [e for e in events if isinstance(e.model, (PanelHTML, Div))]
    assert not panes, [(e.model.css_classes, e.attr) for e in panes]
    assert "θ₀ = 90°" in texts["headline"] and "θ₀ = 100°" in page.texts()["headline"]
    # ... and what is on the page is the new result's.
    series = page.page.results.support.series
    np.testing.assert_allclose(page.source("forces").data["F_x"], series.F_x)


def test_a_tab_not_on_screen_gets_nothing_until_it_is_shown(pool):
    page = Page(tab="equations")
    events = page.move(theta0=100.0)
    assert not _changed_sources(events) & set(SUPPORT_SOURCES)
    assert not [e for e in events if "readout-regime" in (getattr(e.model, "css_classes", None)
                                                          or ())]
    # The headline above every tab still follows the move.
    assert "θ₀ = 100°" in page.page.headline.text
    events = page.move(tab="support")  # shown: drawn once, with the latest result
    assert {"orbit", "forces", "support_frames"} <= _changed_sources(events)
    series = page.page.results.support.series
    np.testing.assert_allclose(page.source("forces").data["F_x"], series.F_x)
    assert "100" in page.page.readouts.regime.html  # "turned from 100° ..."


def test_the_downloads_are_named_after_the_controls_when_asked_for(pool):
    page = Page()
    page.move(theta0=40.0, k_r=0.5)
    text = page.page._trajectory_csv().getvalue()
    assert page.page.downloads[0].filename == "trajectory_kr0.5_kt0.01_FN1_theta0_40.csv"
    assert text.startswith("#")
    page.page._polar_csv()
    assert page.page.downloads[1].download.filename == "polar_kr0.5_kt0.01_FN1.csv"


def test_the_polar_marks_wait_for_their_tab(pool):
    page = Page(tab="polar")
    page.move(tab="support")
    events = page.move(theta0=120.0)
    assert not [e for e in events if (getattr(e.model, "name", "") or "").startswith("polar_")]
    page.move(tab="polar")  # shown: the spoke points at the latest theta0
    spoke = page.source("polar_FTx_spoke").data
    assert np.degrees(np.arctan2(spoke["y"][1], spoke["x"][1])) == pytest.approx(120.0)


def test_the_first_trajectory_drawn_on_an_open_page_adds_no_callback(pool):
    """The player's drawing exists before the page joins its document: the first trajectory
    (drawn once the page is open, here when its tab is shown) sends data, never a new
    callback (each would send the page's graph of models again)."""
    page = Page(tab="equations")
    events = page.move(tab="support")
    added = [(type(e.model).__name__, e.attr) for e in events
             if getattr(e, "attr", None) == "js_property_callbacks"]
    assert not added, added
    assert {"orbit", "support_frames", "support_frame_params"} <= _changed_sources(events)
