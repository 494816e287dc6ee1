"""Live energy and the single-support scene on the browser-side player.

* ``live_energy_figure(energies, player)``: the slab work W(tau) so far beside its split
  D_x + D_y + U_el + K (Eq. 12 at every tau, not only at exit), as bars that follow the
  player;
* ``energy_frames(series, n_frames)``: those histories from a ``model.TimeSeries`` that
  carries them (W, D_x, D_y, U_el, K arrays), resampled on the player's frames;
* ``support_frames_callback(...)``: a ``CustomJS`` that draws the existing support scene
  (``scene_figure``), the marker of Fig. 7 (``forces_figure``) and the friction-law marker
  (``friction_law_figure``) at the player's frame, from data sent once.
"""
from __future__ import annotations

import math

import numpy as np
from bokeh.models import CustomJS, Range1d

from model.contact.friction import mu

from .common import (BLACK, animated, annotation, legend_stand_ins, new_figure, source,
                     sources)
from .live_text import live_div, live_html
from .histories import ENERGY_COLORS, ENERGY_LABELS, ENERGY_TERMS
from .player import UI_MS
from .scene import (ARROW_SCALE, FORCE_COLOR, LABEL_ROOM_X, LABEL_ROOM_Y, SLAB_COLOR,
                    SLAB_REACH, STRIPES, VREL_COLOR, _extent, view_box)

__all__ = ["energy_frames", "live_energy_figure", "support_frames", "support_frames_callback",
           "ENERGY_KEYS"]

ENERGY_KEYS = ("W", *ENERGY_TERMS)


def energy_frames(series, n_frames: int) -> dict:
    """tau, W, D_x, D_y, U_el, K on ``n_frames`` evenly spaced instants of the contact.

    ``series`` must carry the energy histories (``model.TimeSeries`` with W, D_x, D_y,
    U_el and K arrays, Eq. 12 at every tau).
    """
    missing = [k for k in ENERGY_KEYS if getattr(series, k, None) is None]
    if missing:
        raise ValueError(f"the time series has no {', '.join(missing)} histories; they come "
                         f"with model.TimeSeries of simulate_support(..., samples=N)")
    tau = np.linspace(0.0, float(series.tau[-1]), n_frames)
    out = {"tau": tau}
    for k in ENERGY_KEYS:
        out[k] = np.interp(tau, series.tau, getattr(series, k))
    return out


def _bars(e: dict, i: int) -> dict:
    """Quads: W on the left, its split stacked on the right (order of ENERGY_TERMS)."""
    left, right, bottom, top, color, label = [0.15], [0.85], [0.0], [float(e["W"][i])], \
        ["#555555"], ["slab work W"]
    base = 0.0
    for k, c, name in zip(ENERGY_TERMS, ENERGY_COLORS, ENERGY_LABELS):
        v = float(e[k][i])
        left.append(1.15)
        right.append(1.85)
        bottom.append(base)
        top.append(base + v)
        color.append(c)
        label.append(name)
        base += v
    return {"left": left, "right": right, "bottom": bottom, "top": top, "color": color,
            "label": label}


def _energy_text(e, i) -> str:
    parts = " + ".join(f"{k} {float(e[k][i]):.3f}" for k in ENERGY_TERMS)
    return f"τ = {float(e['tau'][i]):.2f}: W = {float(e['W'][i]):.3f} = {parts}  (m V₀²)"


def energy_live_range(energies: dict) -> tuple[float, float]:
    """The y range that holds every frame's bars."""
    values = np.array([energies[k] for k in ENERGY_KEYS])
    lo = min(0.0, float(values.min()))
    hi = max(float(values[0].max()), float(np.sum(values[1:], axis=0).max()), 1e-12)
    return lo - 0.05 * hi, 1.1 * hi


def energy_live_data(energies: dict, frame: int = 0) -> dict:
    """Source data of ``live_energy_figure`` for new histories: the frames and the bars."""
    return {"energy_live_frames": {k: np.asarray(v, float) for k, v in energies.items()},
            "energy_live_bars": _bars(energies, frame)}


def live_energy_figure(energies: dict, player, width: int = 420, height: int = 320,
                       frames=None):
    """Bars of W(tau) and D_x, D_y, U_el, K(tau) at the player's frame (Eq. 12).

    ``frames``: the ``ColumnDataSource`` of the histories the bars follow (made here if
    None); give it ``energy_live_data(...)`` of new histories to redraw."""
    n = len(energies["tau"])
    if n != player.n_frames:
        raise ValueError(f"{n} energy samples for a player of {player.n_frames} frames; "
                         f"use energy_frames(series, player.n_frames)")
    fig = new_figure("energy_live", "The slab's work, now (Eq. 12)", width, height,
                     # the bars' width: the legend stands beside the plot, not over it
                     x_range=Range1d(0, 2), y_range=Range1d(*energy_live_range(energies)),
                     y_axis_label="energy / (m V₀²)")
    fig.tools = [t for t in fig.tools if type(t).__name__ in ("SaveTool",)]
    bars = source("energy_live_bars", _bars(energies, 0))
    animated(fig.quad("left", "right", "bottom", "top", source=bars, fill_color="color",
                      line_color=BLACK, legend_field="label"))
    legend_stand_ins(fig)  # the legend's colours and labels, which never change
    fig.xaxis.ticker = [0.5, 1.5]
    fig.xaxis.major_label_overrides = {0.5: "W so far", 1.5: "its split"}
    fig.xgrid.visible = False
    legend = fig.legend[0]  # beside the plot: it hides no bar
    legend.label_text_font_size = "11px"
    legend.padding = 2
    legend.spacing = 1
    legend.glyph_height = 12
    legend.glyph_width = 12
    fig.center = [m for m in fig.center if m is not legend]
    fig.add_layout(legend, "right")
    readout_box = live_div(_energy_text(energies, 0), name="energy_live_readout", width=width,
                           styles={"font-size": "max(14px, var(--bokeh-font-size, 14px))"})
    readout = live_html(readout_box)
    data = frames if frames is not None else source(
        "energy_live_frames", energy_live_data(energies)["energy_live_frames"])
    # Drawn when the frame changes and when new histories arrive (at the current frame).
    draw = CustomJS(args=dict(bars=bars, data=data, readout=readout, frame=player.frame,
                              terms=list(ENERGY_TERMS), ui_ms=float(UI_MS)), code="""
        const e = data.data, b = bars.data, i = Math.min(frame.value, e.tau.length - 1);
        b.top[0] = e.W[i];
        let base = 0;
        terms.forEach((k, j) => { b.bottom[j + 1] = base; base += e[k][i]; b.top[j + 1] = base; });
        bars.change.emit();
        // The readout is DOM (a text node, app.figures.live_text): while playing it is
        // written at most every ui_ms, and once more when it settles.
        const write = () => readout.setv({html: `τ = ${e.tau[i].toFixed(2)}: W = ` +
          `${e.W[i].toFixed(3)} = ` + terms.map((k) => `${k} ${e[k][i].toFixed(3)}`).join(" + ")
          + "  (m V₀²)"}, {sync: false});
        const now = performance.now();
        clearTimeout(readout.__later);
        if (!(now - (readout.__t || 0) < ui_ms)) { readout.__t = now; write(); }
        else readout.__later = setTimeout(write, ui_ms);""")
    player.on_frame(draw)
    data.js_on_change("data", draw)
    from bokeh.layouts import column

    return column(fig, readout_box, name="energy_live_layout")


#: The columns of ``support_frames`` (time, the series interpolated, then v_R and mu) and
#: of the trajectory's constants.
FRAME_COLUMNS = ("tau", "x", "y", "theta", "v_x", "v_y", "F_x", "F_y", "F_abs", "v_R", "mu")
FRAME_PARAMS = ("theta0", "L0", "x_start", "amp", "rho0", "tau_out", "vx0", "vx1", "vy0", "vy1")


def support_frames(series, params, n_frames: int) -> dict:
    """The support's history on the player's frames: tau, x, y, theta, v_x, v_y, F_x, F_y,
    F_abs, v_R and mu(v_R)."""
    tau = np.linspace(0.0, float(series.tau[-1]), n_frames)
    out = {"tau": tau}
    for k in FRAME_COLUMNS[1:-2]:
        out[k] = np.interp(tau, series.tau, getattr(series, k))
    out["v_R"] = np.hypot(out["v_x"] - 1.0, out["v_y"])
    out["mu"] = mu(out["v_R"], params)
    return out


def support_frames_data(series, params, n_frames: int) -> dict:
    """The data of the sources ``support_frames_callback`` reads: the frames and one row of
    the trajectory's constants (the drawing of ``app.figures.scene``); with ``series``
    None, the same columns empty (the callback then draws nothing)."""
    if series is None:
        return {"support_frames": {k: np.zeros(0) for k in FRAME_COLUMNS},
                "support_frame_params": {k: [] for k in FRAME_PARAMS}}
    ext = _extent(series)
    x0, x1, y0, y1, _ = view_box(series, params)
    return {"support_frames": support_frames(series, params, n_frames),
            "support_frame_params": {
                "theta0": [float(params.theta0)], "L0": [float(params.L0)],
                "x_start": [float(series.x[0])], "amp": [0.05 * math.sqrt(ext)],
                "rho0": [0.3 * ext ** 0.25], "tau_out": [float(series.tau[-1])],
                "vx0": [x0], "vx1": [x1], "vy0": [y0], "vy1": [y1]}}


def support_frames_callback(series, params, n_frames: int, scene=None, forces=None, law=None,
                            frame=None, frames_source=None):
    """A ``CustomJS`` for ``player.on_frame`` drawing the existing figures at the frame
    (``series`` None: made before the first trajectory, with empty sources).

    ``scene``, ``forces``, ``law``: figures made by ``scene_figure``, ``forces_figure`` and
    ``friction_law_figure`` (any may be None). It updates the named sources they already
    have (mass, spring, twist, slab and its stripes and edges, the arrows, forces_now,
    friction_now), the time line of Fig. 7 and the time label, as ``scene_frame`` does on
    the server. Its own data are two named sources, ``support_frames`` and
    ``support_frame_params`` (``callback.args``): give them ``support_frames_data`` of a
    new trajectory and the figures follow it, with no new callback. Every change it makes
    stays in the browser (``sync: false``): no message to the server per frame.
    With ``frame`` (the player's ``PlayerFrame``) it also draws the current frame when new
    data arrive (attach it to the sources' ``data`` as well) and when Fig. 7 or Fig. 3 is
    zoomed (it is attached to their ranges here): their markers are drawn only inside the
    plots' ranges, as they are not clipped (``app.figures.common.animated``).
    ``frames_source``: an existing ``support_frames`` source to fill and read (one that
    other callbacks, such as the sound's, read too), else a new one.
    """
    data = support_frames_data(series, params, n_frames)
    if frames_source is not None:
        frames_source.data = data["support_frames"]
    named = {}
    for fig in (scene, forces, law):
        if fig is not None:
            named.update(sources(fig))
    # Fig. 7's and Fig. 3's x and y ranges: their markers are drawn only inside them.
    ranges = [r for fig in (forces, law)
              for r in ((fig.x_range, fig.y_range) if fig is not None else (None, None))]
    args = dict(
        data=(frames_source if frames_source is not None
              else source("support_frames", data["support_frames"])),
        fp=source("support_frame_params", data["support_frame_params"]),
        stripes_n=STRIPES, reach=SLAB_REACH, arrow_scale=ARROW_SCALE,
        room=[LABEL_ROOM_X, LABEL_ROOM_Y],
        colors=[SLAB_COLOR, VREL_COLOR, FORCE_COLOR],
        **{key: named.get(name) for key, name in (
            ("mass", "scene_mass"), ("spring", "scene_spring"), ("twist", "scene_twist"),
            ("slab", "scene_slab"), ("stripes", "scene_stripes"), ("edges", "scene_edges"),
            ("arrows", "scene_arrows"), ("arrow_labels", "scene_arrow_labels"),
            ("forces_now", "forces_now"), ("friction_now", "friction_now"))},
        ranges=ranges,
        time_line=annotation(forces, "forces_time") if forces is not None else None,
        time_label=annotation(scene, "scene_time") if scene is not None else None,
        frame=frame)
    callback = CustomJS(args=args, code=_SUPPORT_JS)
    if frame is not None:  # a zoomed plot: its markers drawn again, inside or not
        for r in ranges:
            if r is not None:
                r.js_on_change("start", callback)
                r.js_on_change("end", callback)
    return callback


# The same drawing as app.figures.scene.scene_frame (zigzag spring, twist spiral, slab,
# its stripes and out-of-view edges, the three arrows at the mass).
_SUPPORT_JS = """
const d = data.data, p = fp.data;
if (!d.tau || d.tau.length === 0) return;
const i = Math.min(frame ? frame.value : cb_obj.value, d.tau.length - 1);
const quiet = (m, attrs) => { if (m) m.setv(attrs, {sync: false}); };
const theta0 = p.theta0[0], L0 = p.L0[0], x_start = p.x_start[0], amp = p.amp[0];
const rho0 = p.rho0[0], tau_out = p.tau_out[0];
const vx0 = p.vx0[0], vx1 = p.vx1[0], vy0 = p.vy0[0], vy1 = p.vy1[0];
const x = d.x[i], y = d.y[i], tau = d.tau[i], theta = d.theta[i];
quiet(mass, {data: {x: [x], y: [y], tau: [tau]}});
if (spring) {
  const r = Math.hypot(x, y), coils = 7;
  const sx = [], sy = [];
  if (r > 0) {
    const ex = x / r, ey = y / r, u = [0, 0.15], w = [0, 0];
    for (let k = 1; k < 2 * coils; k++) { u.push(0.15 + 0.7 * k / (2 * coils)); w.push(amp * ((k - 1) % 2 === 0 ? 1 : -1)); }
    u.push(0.85, 1); w.push(0, 0);
    for (let k = 0; k < u.length; k++) { sx.push(u[k] * r * ex - w[k] * ey); sy.push(u[k] * r * ey + w[k] * ex); }
  } else { sx.push(0); sy.push(0); }
  quiet(spring, {data: {x: sx, y: sy}});
}
if (twist) {
  const span = theta - theta0, m = Math.max(2, Math.floor(Math.abs(span) / 0.05) + 2);
  const tx = [], ty = [];
  for (let k = 0; k < m; k++) {
    const phi = theta0 + span * k / (m - 1);
    const rho = rho0 * (1 + 0.08 * Math.abs(phi - theta0) / (2 * Math.PI));
    tx.push(rho * Math.cos(phi)); ty.push(rho * Math.sin(phi));
  }
  quiet(twist, {data: {x: tx, y: ty}});
}
const left = x_start - L0 + tau, right = x_start + tau;
if (slab) quiet(slab, {data: {y: [-reach, reach], left: [left, left], right: [right, right]}});
if (stripes) {
  const spacing = (vx1 - vx0) / stripes_n;
  const first = left < vx0 ? left + Math.ceil((vx0 - left) / spacing) * spacing : left;
  const xs = [], ys = [];
  for (let v = first; v <= Math.min(right, vx1) + 1e-12; v += spacing) { xs.push([v, v]); ys.push([vy0, vy1]); }
  quiet(stripes, {data: {xs, ys}});
}
if (edges) {
  const e = {x: [], y: [], text: [], align: []}, ye = vy0 + 0.93 * (vy1 - vy0);
  const g = (v) => Number(v.toPrecision(2));
  if (left < vx0 && right > vx0) { e.x.push(vx0); e.y.push(ye); e.text.push(`◀ trailing edge ${g(vx0 - left)} r₀`); e.align.push("left"); }
  if (right > vx1 && left < vx1) { e.x.push(vx1); e.y.push(ye); e.text.push(`leading edge ${g(right - vx1)} r₀ ▶`); e.align.push("right"); }
  quiet(edges, {data: e});
}
if (arrows) {
  const sx = arrow_scale * 0.5 * (vx1 - vx0), sy = arrow_scale * 0.5 * (vy1 - vy0);
  const ys = y + 0.12 * (vy1 - vy0);
  const all = [[x, ys, x + sx, ys, colors[0], "slab V₀"],
               [x, y, x + sx * (d.v_x[i] - 1), y + sy * d.v_y[i], colors[1], "v_R"],
               [x, y, x + sx * d.F_x[i], y + sy * d.F_y[i], colors[2], "friction"]];
  const keep = all.filter((a) => Math.hypot(a[2] - a[0], a[3] - a[1]) > 1e-9);
  quiet(arrows, {data: {x0: keep.map((a) => a[0]), y0: keep.map((a) => a[1]),
                        x1: keep.map((a) => a[2]), y1: keep.map((a) => a[3]),
                        color: keep.map((a) => a[4])}});
  // Labels inside the view, as app.figures.scene._arrow_labels places them.
  const lx = keep.map((a) => Math.min(Math.max(a[2], vx0), vx1));
  const ly = keep.map((a) => Math.min(Math.max(a[3], vy0), vy1));
  const rx = room[0] * (vx1 - vx0), ry = room[1] * (vy1 - vy0);
  quiet(arrow_labels, {data: {x: lx, y: ly, text: keep.map((a) => a[5]), color: keep.map((a) => a[4]),
                              align: lx.map((v, k) => (v >= keep[k][0] ? v < vx1 - rx : v < vx0 + rx) ? "left" : "right"),
                              baseline: ly.map((v, k) => (keep[k][4] === colors[0] ? v < vy1 - ry : v < vy0 + ry) ? "bottom" : "top")}});
}
// The markers are not clipped to their plots (app.figures.common.animated): only those
// inside the plot's ranges are drawn (a zoomed plot).
const inside = (r, v) => !r || (v >= Math.min(r.start, r.end) && v <= Math.max(r.start, r.end));
const shown = (xr, yr, xs, ys) => {
  const keep = xs.map((x, k) => inside(xr, x) && inside(yr, ys[k]));
  return [xs.filter((_, k) => keep[k]), ys.filter((_, k) => keep[k])];
};
if (forces_now) {
  const [ts, Fs] = shown(ranges[0], ranges[1], [tau, tau, tau], [d.F_x[i], d.F_y[i], d.F_abs[i]]);
  quiet(forces_now, {data: {tau: ts, F: Fs}});
}
if (friction_now) {
  const [vs, mus] = shown(ranges[2], ranges[3], [d.v_R[i]], [d.mu[i]]);
  quiet(friction_now, {data: {v: vs, mu: mus}});
}
quiet(time_line, {location: tau});
quiet(time_label, {text: `τ = ${tau.toPrecision(3)} of τ_out = ${tau_out.toPrecision(4)}`});
"""
