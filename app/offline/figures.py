"""The offline explorer's figures: the dashboard's own, built at pack time.

Every figure here is made by the dashboard's functions (``app.figures``): the support
scene, the friction histories (Fig. 7), the friction law (Fig. 3), the live split of the
slab work (Eq. 12), the browser-side player, the polar diagrams (Fig. 11) and the regime
map (Fig. 5), with the dashboard's titles, colours, labels and units. They are drawn at
pack time for the default state (computed here by the Python model, so the page shows a
plot before its first computation); in the page the JavaScript port of the kernel
(``kernel.js``) computes new data and ``views.js`` puts it into the same named sources,
as ``app.views.support`` does on the server.

``projector_styles`` records what ``app.figures.common.style`` changes between the screen
and the projector look, so the page can switch with no Python.
"""
from __future__ import annotations

import math

import numpy as np
from bokeh.core.property.dataspec import DataSpec
from bokeh.core.property.vectorization import Value
from bokeh.models import ColumnDataSource, GlyphRenderer, Span

from model import Params, simulate_support
from model.controls import CONTROLS
from model.runs.shipped_map import SHIPPED_LOADS, load_regime_map

from .. import figures as F
from ..figures.arrays import MAP_QUANTITIES, map_data, map_title, value_range
from ..figures.common import legend_above, pass_on_visible
from ..figures.live_energy import (energy_frames, live_energy_figure, support_frames_callback)
from ..figures.player import SPEEDS, browser_player
from ..figures.polar import QUANTITIES as POLAR_QUANTITIES
from ..figures.scene import ARROW_SCALE, MAX_ASPECT, STRETCH_WARNING, STRIPES
from ..texts import FELT_WORDS
from ..worker import POLAR_THETA0

__all__ = ["support_figures", "polar_figures", "map_figure", "projector_styles", "maps",
           "constants", "default_params", "SUPPORT_SAMPLES"]

#: Samples of one contact drawn per trajectory (the dashboard's, app/worker.py).
from ..worker import SAMPLES as SUPPORT_SAMPLES  # noqa: E402

#: Frames of the player. The dashboard's ``app.views.support.N_FRAMES``, which cannot be
#: imported here: that module imports Panel, whose Bokeh extensions would then be
#: written into the page (and blocked there). tests/test_offline_views.py holds them equal.
N_FRAMES = 300


def default_params() -> Params:
    """The page's default state (model/controls.py) as ``Params``."""
    d = {k: CONTROLS[k].default for k in ("k_r", "k_theta", "F_N", "theta0_deg")}
    return Params(k_r=d["k_r"], k_theta=d["k_theta"], F_N=d["F_N"],
                  theta0=math.radians(d["theta0_deg"]))


def support_figures():
    """The Support tab of the dashboard for the default state: scene, Fig. 7, Fig. 3, the
    live energy bars and the player (``app.views.support``), with the player's callback
    that draws a frame (``support_frames_callback``)."""
    p = default_params()
    series = simulate_support(p, samples=SUPPORT_SAMPLES).series
    player = browser_player(N_FRAMES, times=np.linspace(0, series.tau[-1], N_FRAMES),
                            name="support_player", width=680, responsive=True,
                            autoplay=False)
    scene = F.scene_figure(series, p, 0, width=340, height=330)
    forces = F.forces_figure(series, p, 0, width=340, height=330)
    law = F.friction_law_figure(series, p, 0, width=340, height=225)
    energy = live_energy_figure(energy_frames(series, N_FRAMES), player, width=340,
                                height=225)
    frames_js = support_frames_callback(series, p, N_FRAMES, scene=scene, forces=forces,
                                        law=law, frame=player.frame)
    player.on_frame(frames_js)
    frames_js.args["fp"].js_on_change("data", frames_js)
    legend_above(law)
    for fig in (scene, forces):
        legends_of_still_data(fig)
    for fig in (scene, forces, law, energy.children[0]):
        legend_keys_apart(fig)
    energy_fig = energy.children[0]
    energy.children[1].sizing_mode = "stretch_width"
    return dict(scene=scene, forces=forces, law=law, energy=energy, energy_fig=energy_fig,
                player=player, frames_js=frames_js)


def legends_of_still_data(fig) -> None:
    """Legend entries of ``fig`` that name a glyph of a contact's data (a named source: the
    page sets it anew for each contact, e.g. Fig. 7's forces, the scene's rest line) name a
    still stand-in instead, as ``app.figures.common.legend_stand_ins`` does for what the
    player moves: a BokehJS legend draws its entries anew (new elements, a page layout, a
    forced reflow when it is painted) whenever the data of a renderer it names change, i.e.
    at every key press. The stand-in shares the glyph (the same key drawn), has one row of
    NaN, draws nothing in the plot and hides or shows the glyph with it."""
    for legend in fig.legend:
        for item in legend.items:
            item.renderers = [_still(fig, r) if r.data_source.name else r
                              for r in item.renderers]


def _still(fig, renderer: GlyphRenderer) -> GlyphRenderer:
    if any(isinstance(v, str) for col in renderer.data_source.data.values() for v in col):
        raise ValueError(f"{renderer.data_source.name}: a legend of text columns has no "
                         f"one-row stand-in")
    still = GlyphRenderer(data_source=ColumnDataSource(
        {k: [math.nan] for k in renderer.data_source.data}), glyph=renderer.glyph,
        visible=renderer.visible)
    fig.renderers.append(still)
    pass_on_visible(still, renderer)
    return still


def legend_keys_apart(fig) -> None:
    """The renderers that only draw a legend's keys (stand-ins: every number NaN, nothing
    drawn in the plot) go into one hidden group (a ``Span`` without a location, not
    visible, whose ``renderers`` are they): BokehJS still has their views, which the legend
    draws its keys with, but does not paint them with the plot. Each renderer a plot
    paints moves its element and then reads the page's CSS (a style recalculation): with
    every contact a figure's ranges change and all its renderers are painted again."""
    keys = {r.id: r for legend in fig.legend for item in legend.items for r in item.renderers
            if isinstance(r, GlyphRenderer) and _draws_nothing(r)}
    if len(keys) < 2:
        return
    fig.renderers = [r for r in fig.renderers if r.id not in keys]
    fig.renderers.append(Span(location=None, renderers=list(keys.values()), visible=False,
                              name=f"{fig.name}_legend_keys"))


def _draws_nothing(renderer: GlyphRenderer) -> bool:
    columns = renderer.data_source.data.values()
    numbers = [v for col in columns for v in col if not isinstance(v, str)]
    return bool(numbers) and all(isinstance(v, float) and math.isnan(v) for v in numbers)


def polar_figures() -> dict:
    """Fig. 11a-c of the dashboard (``app.views.polar``), empty: the page's worker sweeps
    the orientations."""
    return {key: F.polar_figure(key, width=325, height=340) for key in POLAR_QUANTITIES}


#: The map's columns per load (``map_data``'s); the cells' geometry is shared by all loads.
MAP_COLUMNS = ("FTx", "FTx_duration", "DyDx", "Nc")
MAP_GEOMETRY = ("k_r", "k_theta", "left", "right", "bottom", "top")


def maps(digits: int = 6) -> dict:
    """The shipped regime maps (Fig. 5, model/data, read by ``model.runs.shipped_map``) as the
    source data of the map figure (``app.figures.arrays.map_data``): the cells once, and
    per load its columns with their value ranges (Fig. 5a: F_T,x/(mu0 F_N), paper
    average, the figure's "FTx"; Fig. 5b: D_y/D_x, "DyDx")."""
    geometry, loads = None, {}
    for F_N in SHIPPED_LOADS:
        shipped = load_regime_map(F_N=F_N)
        cols = map_data(shipped, "5a")["regime_map"]
        cells = {k: [_round(v, 12) for v in np.asarray(cols[k], float)] for k in MAP_GEOMETRY}
        if geometry is None:
            geometry = cells
        elif cells != geometry:
            raise ValueError(f"the shipped map at F_N = {F_N:g} is on another grid")
        loads[f"{F_N:g}"] = {
            "titles": {q: map_title(q, shipped, "paper") for q in MAP_QUANTITIES},
            "columns": {k: [_round(v, digits) for v in np.asarray(cols[k], float)]
                        for k in MAP_COLUMNS},
            "range": {q: value_range(cols[MAP_VALUE[q]]) for q in MAP_QUANTITIES}}
    return {"cells": geometry, "loads": loads, "value": dict(MAP_VALUE)}


#: The column each map shows (Fig. 5a: the paper's average, Eq. 10).
MAP_VALUE = {"5a": "FTx", "5b": "DyDx"}


def _round(x: float, digits: int):
    return None if not math.isfinite(x) else float(f"{x:.{digits}g}")


def map_figure():
    """Fig. 5a of the dashboard at the default load, the current springs marked."""
    p = default_params()
    fig = F.regime_map_figure(load_regime_map(F_N=1.0), "5a", current=(p.k_r, p.k_theta),
                              width=560, height=480)
    return fig


def constants() -> dict:
    """The scene's and player's constants the page's drawing code needs (defined once in
    ``app.figures``)."""
    return dict(n_frames=N_FRAMES, support_samples=SUPPORT_SAMPLES, stripes=STRIPES,
                arrow_scale=ARROW_SCALE, max_aspect=MAX_ASPECT,
                stretch_warning=STRETCH_WARNING, speeds=list(SPEEDS),
                polar_theta0=[float(t) for t in POLAR_THETA0],
                polar=dict((k, [v[0], v[1], v[2]]) for k, v in POLAR_QUANTITIES.items()),
                shipped_loads=list(SHIPPED_LOADS), felt_words=FELT_WORDS)


def _snapshot(figs) -> dict:
    out = {}
    for fig in figs:
        for m in fig.references():
            for k, v in m.properties_with_values(include_defaults=True).items():
                if k != "tags":
                    out[(m.id, k)] = (m, v)
    return out


def _plain(model, attr, value):
    """A property value as JSON for BokehJS's ``setv``: a data spec as {value: ...}."""
    if isinstance(value, Value):
        value = value.value
    if not isinstance(value, (str, int, float, bool)) and value is not None:
        return None
    if isinstance(model.lookup(attr).property, DataSpec):
        return {"value": value}
    return value


def projector_styles(figs) -> list:
    """[[model id, property, screen value, projector value], ...]: what
    ``app.figures.common.style`` changes between the screen and projector looks of
    ``figs`` (which are left in the screen look)."""
    for fig in figs:
        F.style(fig, False)  # the screen look, with the base sizes remembered in tags
    screen = _snapshot(figs)
    for fig in figs:
        F.style(fig, True)
    projected = _snapshot(figs)
    for fig in figs:
        F.style(fig, False)
    changes = []
    for key, (model, a) in screen.items():
        b = projected[key][1]
        if a == b or (isinstance(a, float) and isinstance(b, float) and math.isnan(a)
                      and math.isnan(b)):
            continue
        pa, pb = _plain(model, key[1], a), _plain(model, key[1], b)
        if pa is None or pb is None:
            raise TypeError(f"projector style of {model}.{key[1]}: {b!r} is not a plain value")
        changes.append([model.id, key[1], pa, pb])
    return changes


