"""The array under the slab, live (Fig. 2a and Fig. 4 of the paper): a top view of the slab
sliding over a grid of supports, each coloured by the direction of the friction force on
it, with the live count N_c against N_c0 and the force the drive needs, F_T,x/(mu0 F_N).

``array_scene(motion, player)`` draws it from a ``model.arrays.array_motion.ArrayMotion``; all
frames go to the browser once (float32, frame-major) and a ``CustomJS`` attached to the
browser-side player (``app.figures.player``) draws each frame: no server round trip.
What a frame moves is drawn on the plots' overlay layer, clipped to the plot area
(``app.figures.common.animated_group``): the axes, grids, titles and still curves are
not painted again, nor the keys (``app.figures.array_key``).
"""
from __future__ import annotations

import numpy as np
from bokeh.layouts import column
from bokeh.models import (Arrow, BoxAnnotation, CustomJS, Div, Label, LinearColorMapper,
                          Range1d, Span, VeeHead)

from .array_key import colorbar_figure, html_key
from .array_readout import last_counted, readout_text, settled_mean
from .common import (BLACK, BLUE, GREEN, GREY, ORANGE, VERMILION, animated_group, annotation,
                     new_figure, source)
from .live_text import live_div, live_html
from .player import UI_MS

__all__ = ["array_scene", "array_frames", "direction_palette", "slab_half_width", "view_x",
           "html_key", "ARROW_LENGTH"]

ARROW_LENGTH = 0.45  # friction arrows, in r0 (direction only: every support carries f_N)
#: Room above the slab's edge (r0) for its velocity arrow (at 0.9) and the arrow's label.
ARROW_ROOM = 2.6
#: Text beside the canvases: the page's size (13 px, 18 px projected, 16 px on a phone).
TEXT_SIZE = "max(12px, var(--bokeh-font-size, 14px))"
SLAB_FILL = "#9ecae1"
STRIPE_SPACING = 1.5


def direction_palette(n: int = 64) -> list:
    """Friction direction from -90 deg (orange: pushed towards -y) through 0 (dark:
    along the slab's motion) to +90 deg (blue: towards +y); colour-blind safe ends."""
    stops = np.array([[0xE6, 0x9F, 0x00], [0x33, 0x33, 0x33], [0x00, 0x72, 0xB2]], float)
    u = np.linspace(0.0, 2.0, n)
    k = np.minimum(u.astype(int), 1)
    rgb = stops[k] + (stops[k + 1] - stops[k]) * (u - k)[:, None]
    return ["#%02x%02x%02x" % tuple(int(round(c)) for c in col) for col in rgb]


def array_frames(motion) -> dict:
    """The browser's data: frame-major float32 columns x, y (mass relative to its pivot)
    and a (friction direction in degrees, NaN out of contact)."""
    return {"x": np.ascontiguousarray(motion.x.T).ravel(),
            "y": np.ascontiguousarray(motion.y.T).ravel(),
            "a": np.ascontiguousarray(np.degrees(motion.F_angle).T, dtype=np.float32).ravel()}


def _supports_now(motion, f: int) -> dict:
    x = motion.pivot_x + motion.x[:, f]
    y = motion.pivot_y + motion.y[:, f]
    a = np.degrees(motion.F_angle[:, f]).astype(float)
    ok = np.isfinite(a)
    dx = np.where(ok, ARROW_LENGTH * np.cos(np.radians(np.where(ok, a, 0))), 0.0)
    dy = np.where(ok, ARROW_LENGTH * np.sin(np.radians(np.where(ok, a, 0))), 0.0)
    return {"px": motion.pivot_x.astype(float), "py": motion.pivot_y.astype(float),
            "mx": x.astype(float), "my": y.astype(float), "a": a,
            "fx1": (x + dx).astype(float), "fy1": (y + dy).astype(float)}


def slab_half_width(motion) -> float:
    """Half the slab's width in y: the grid, and every mass in contact (all are under it)."""
    in_y = np.abs(motion.pivot_y[:, None] + motion.y)[motion.in_contact]
    return max((motion.n_rows - 1) / 2 * motion.spacing + 0.6,
               float(in_y.max()) + 0.4 if in_y.size else 0.0)


def view_x(motion) -> tuple:
    """The slab's whole travel while any support is in contact (masses in contact are
    always under it), from its start before the grid."""
    lead0 = float(motion.slab_lead[0])
    return lead0 - motion.params.L0 - 0.5, lead0 + float(motion.t_end.max()) + 0.5


def _ranges(motion, width, height_limits=(240, 620), max_half: float = 30.0):
    """Equal scales in x and y: ``view_x`` and the masses' sideways excursions."""
    x0, x1 = view_x(motion)
    y = np.abs(motion.pivot_y[:, None] + motion.y).max()
    # Room above the slab for its velocity arrow and label (ARROW_ROOM r0 over its edge).
    half = min(max((motion.n_rows - 1) / 2 * motion.spacing + 2.5, float(y) + 0.5,
                   slab_half_width(motion) + ARROW_ROOM), max_half)
    height = int(np.clip(width * 2 * half / (x1 - x0) + 60, *height_limits))
    half = max(half, (height - 60) / width * (x1 - x0) / 2)
    return Range1d(x0, x1), Range1d(-half, half), height


def array_scene(motion, player, width: int = 1000, panel_height: int = 220,
                ui_ms: float = UI_MS, responsive: bool = False, panel_ms: float = 100,
                top_height: int | None = None):
    """Top view, N_c/N_c0 and F_T,x panels, and a readout, driven by ``player``.

    ``player`` is a ``BrowserPlayer`` over ``motion.n_frames`` frames; the text readout
    follows it at most every ``ui_ms`` and the live panel every ``panel_ms`` (0: every
    frame). Returns a Bokeh column (top
    view, colour key, readout, live panel). ``responsive``: the figures stretch with the
    page's width; where the slab's whole travel does not fit at equal scales (a phone),
    the top view follows the slab. ``top_height`` fixes the top view's height in px
    (default: from equal scales over the whole travel; at least 300 when responsive).
    """
    if player.n_frames != motion.n_frames:
        raise ValueError(f"the player has {player.n_frames} frames, the motion "
                         f"{motion.n_frames}; make the player with n_frames=motion.n_frames")
    L0 = motion.params.L0
    xr, yr, height = _ranges(motion, width)
    # Two lines: one of ~90 characters runs out of a phone's figure.
    title = (f"TOP VIEW: the slab slides over {motion.n_supports} supports\n"
             f"({motion.orientation} θ₀, k_r = {motion.params.k_r:g}, "
             f"k_θ = {motion.params.k_theta:g}, F_N = {motion.params.F_N:g})")
    fig = new_figure("array_top", title, width, height, x_range=xr, y_range=yr,
                     x_axis_label="x / r₀ (sliding direction →)", y_axis_label="y / r₀")
    fig.tools = [t for t in fig.tools if type(t).__name__ in ("WheelZoomTool", "BoxZoomTool",
                                                               "ResetTool", "SaveTool")]

    # The slab: a band L0 long across the grid, with stripes that move with it.
    lead = float(motion.slab_lead[0])
    half_w = slab_half_width(motion)
    slab = source("array_slab", {"left": [lead - L0], "right": [lead],
                                 "bottom": [-half_w], "top": [half_w]})
    fig.quad("left", "right", "bottom", "top", source=slab, fill_color=SLAB_FILL,
             fill_alpha=0.35, line_color=BLUE, line_width=3)
    offsets = np.arange(-2 * half_w, L0 + 2 * half_w, STRIPE_SPACING)
    stripes = source("array_stripes", _stripes(lead, L0, half_w, offsets))
    fig.segment("x0", "y0", "x1", "y1", source=stripes, line_color=BLUE, line_alpha=0.25,
                line_width=2)
    # The arrow's label starts at its tail (ends at its head once the slab is in the
    # view's right half): it stays inside the view, whose edges the slab reaches.
    arrow = source("array_velocity", {"x0": [lead - 0.8 * L0], "x1": [lead - 0.2 * L0],
                                      "xt": [lead - 0.8 * L0], "align": ["left"],
                                      "y": [half_w + 0.9]})
    velocity = Arrow(end=VeeHead(size=14, fill_color=BLUE, line_color=BLUE), x_start="x0",
                     y_start="y", x_end="x1", y_end="y", source=arrow, line_color=BLUE,
                     line_width=4)
    fig.text(x="xt", y="y", text={"value": "slab velocity V₀"}, source=arrow,
             text_font_size="14px", text_color=BLUE, text_baseline="bottom",
             text_align={"field": "align"}, y_offset=-5, name="array_velocity_label")

    # Supports: pivot, spring line, mass coloured by the friction direction, its arrow.
    now = source("array_supports", _supports_now(motion, 0))
    mapper = LinearColorMapper(palette=direction_palette(), low=-90, high=90,
                               nan_color="#d9d9d9", low_color=ORANGE, high_color=BLUE)
    fig.scatter("px", "py", source=now, marker="square", size=5, color=GREY)
    fig.segment("px", "py", "mx", "my", source=now, line_color=GREY, line_width=1.2)
    fig.segment("mx", "my", "fx1", "fy1", source=now, line_width=2.5,
                line_color={"field": "a", "transform": mapper})
    fig.scatter("mx", "my", source=now, size=9, line_color=BLACK, line_width=0.8,
                fill_color={"field": "a", "transform": mapper})
    # All of it moves (the slab at the bottom, the velocity arrow on top, as before):
    # repainted alone each frame, clipped to the plot area (the slab slides out of view).
    animated_group(fig, *fig.renderers, velocity, name="array_top_moving")
    colorbar = colorbar_figure(mapper, 340 if responsive else width, responsive)

    panel = _panel(motion, width, panel_height)
    # Text only (app.figures.live_text): a change redraws the readout, not the page.
    readout_box = live_div(_readout(motion, 0), name="array_readout", width=width, height=52,
                           styles={"font-size": TEXT_SIZE, "min-height": "2.6em"})
    readout = live_html(readout_box)
    frames = source("array_frames", array_frames(motion))
    series = source("array_series", {"t": motion.t, **_shown_ratios(motion),
                                     "N_c": motion.N_c.astype(float),
                                     "N_c0": motion.N_c0.astype(float),
                                     "last": last_counted(motion).astype(float)})
    live = source("array_live", _live(motion, 0))
    lines = [panel.line("t", "nc", source=live, line_color=BLUE, line_width=3),
             panel.line("t", "ftx", source=live, line_color=VERMILION, line_alpha=0.45,
                        line_width=1.2),
             panel.line("t", "run", source=live, line_color=VERMILION, line_width=3)]
    cursors = [Span(location=0.0, dimension="height", line_color=GREY, line_width=1.5,
                    name="array_cursor")]
    # The growing curves and the cursor, under the steady window's tint and label as the
    # still curves are: repainted alone, clipped to the plot area (F_T,x leaves it).
    animated_group(panel, *lines, *(annotation(panel, n) for n in ("array_steady",
                                                                 "array_steady_label")),
                   *cursors, name="array_live_moving")
    m = motion.model
    panel_key = Div(text=html_key([
        ("line", BLUE, "solid", 3, "N_c/N_c0 live"),
        ("line", BLUE, "dashed", 2, f"array model ⟨τ_out⟩/L₀ = {m['Nc_over_Nc0']:.3f}"),
        ("line", VERMILION, "solid", 1, "F_T,x/(μ₀F_N) instantaneous"),
        ("line", VERMILION, "solid", 3, "F_T,x/(μ₀F_N) mean over the steady window"),
        ("line", VERMILION, "dashed", 2,
         f"array model, steady force = {m['FTx_over_mu0FN_duration']:.3f}"),
        # (the steady window's band is labelled on the panel itself)
        ("line", GREY, "dotted", 2, "rigid supports = 1")]), width=width, name="array_panel_key",
        styles={"font-size": TEXT_SIZE})

    player.on_frame(CustomJS(args=dict(
        frames=frames, now=now, slab=slab, stripes=stripes, arrow=arrow, series=series,
        live=live, cursors=cursors, readout=readout, ui_ms=float(ui_ms),
        panel_ms=float(panel_ms), L0=L0, n=motion.n_supports,
        offsets=offsets.tolist(), half_w=half_w, lead0=float(motion.slab_lead[0]),
        top=fig, full_x=[xr.start, xr.end], follow=bool(responsive),
        arrow_len=ARROW_LENGTH, beta=motion.params.beta,
        model_nc=float(motion.model["Nc_over_Nc0"]),
        model_ftx=float(motion.model["FTx_over_mu0FN_duration"]),
        steady=list(motion.steady)), code=_FRAME_JS))
    key = Div(text=html_key([
        ("box", SLAB_FILL, "solid", 0, "slab (length L₀, moving →)"),
        ("line", BLUE, "solid", 4, "slab velocity V₀"),
        ("square", GREY, "solid", 0, "pivot"), ("line", GREY, "solid", 1, "support (spring)"),
        ("dot", "#333333", "solid", 0, "mass")]) + "<br>" + (
        "Each support is coloured by the direction of the friction force on it "
                    "(arrow): <b>dark</b> along the sliding direction, <b style='color:#0072B2'>"
                    "blue</b> turned towards +y, <b style='color:#9E6600'>orange</b> towards −y, "
                    "<b style='color:#767676'>grey</b> not in contact. Released supports are drawn "
                    "at rest."), width=width, name="array_key", styles={"font-size": TEXT_SIZE})
    parts = [readout_box, fig, colorbar, key, panel, panel_key]
    if responsive:
        # Widths follow the page, heights stay: on a narrow screen the top view keeps
        # equal scales by following the slab (see _FRAME_JS), the panel just narrows.
        for part in parts:
            part.sizing_mode = "stretch_width"
            if isinstance(part, Div):
                part.width = part.height = None
        fig.height = max(fig.height, 300)
    if top_height is not None:
        fig.height = int(top_height)
    return column(*parts, name="array_scene",
                  sizing_mode="stretch_width" if responsive else None)


def _stripes(lead, L0, half_w, offsets):
    """Diagonal stripes clipped to the slab, so its motion is visible inside it too."""
    x0 = lead - L0 + offsets
    x1 = x0 + 2 * half_w
    y0, y1 = np.full(offsets.size, -half_w), np.full(offsets.size, half_w)
    # clip to [lead - L0, lead] along the line x = x0 + (y + half_w)
    lo, hi = lead - L0, lead
    t0 = np.clip((lo - x0) / (x1 - x0), 0, 1)
    t1 = np.clip((hi - x0) / (x1 - x0), 0, 1)
    return {"x0": x0 + t0 * (x1 - x0), "y0": y0 + t0 * (y1 - y0),
            "x1": x0 + t1 * (x1 - x0), "y1": y0 + t1 * (y1 - y0)}


def _ratio(a, b):
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(b > 0, a / np.maximum(b, 1), np.nan)


def _shown_ratios(motion) -> dict:
    """N_c/N_c0 and F_T,x as drawn: up to the last support's entry. After it the slab
    leaves the grid (N_c0 falls to 0 while dragged supports are still in contact), and
    the ratios say nothing about a sliding slab. The mean over the steady window ("run")
    is held at its settled value once the window has closed."""
    keep = motion.t <= motion.t_start.max()
    return {k: np.where(keep, v, np.nan) for k, v in (
        ("nc", _ratio(motion.N_c, motion.N_c0)), ("ftx", motion.FTx),
        ("run", settled_mean(motion)))}


def _live(motion, f):
    k = f + 1
    return {"t": motion.t[:k], **{key: v[:k] for key, v in _shown_ratios(motion).items()}}


def _panel(motion, width, height):
    """N_c/N_c0 and F_T,x/(mu0 F_N) on one axis (both are 1 for rigid supports), with the
    array model's values and the steady window."""
    T = float(motion.t[-1])
    m = motion.model
    fig = new_figure("array_live_panel", "Live: supports in contact N_c/N_c0 (β = N_c0/N_c)\n"
                     "and the force on the slab F_T,x/(μ₀F_N)", width, height,
                     x_range=Range1d(0, float(motion.t_start.max()) + 0.5),
                     x_axis_label="τ (slab travel / r₀)", y_axis_label="ratio to rigid supports")
    mask = motion.steady_mask()
    ratio = _ratio(motion.N_c, motion.N_c0)
    top = max(1.25, m["Nc_over_Nc0"] * 1.25,
              float(np.nanmax(ratio[mask])) * 1.1 if mask.any() else 0.0)
    ftx = motion.FTx[np.isfinite(motion.FTx)]
    low = min(0.75, float(np.percentile(ftx, 2)) - 0.05) if ftx.size else 0.0
    fig.y_range = Range1d(max(0.0, low), top)
    fig.tools = [t for t in fig.tools if type(t).__name__ in ("ResetTool", "SaveTool")]
    fig.add_layout(BoxAnnotation(left=motion.steady[0], right=motion.steady[1],
                                 fill_color=GREEN, fill_alpha=0.08, name="array_steady"))
    fig.add_layout(Label(x=motion.steady[0], y=5, y_units="screen", text="steady window",
                         text_color=GREEN, text_font_size="13px", x_offset=4,
                         name="array_steady_label"))
    fig.line([0, T], [m["Nc_over_Nc0"]] * 2, line_color=BLUE, line_dash="dashed", line_width=2)
    fig.line([0, T], [m["FTx_over_mu0FN_duration"]] * 2, line_color=VERMILION,
             line_dash="dashed", line_width=2)
    fig.line([0, T], [1, 1], line_color=GREY, line_dash="dotted", line_width=2)
    return fig


def _readout(motion, f) -> str:
    series = {"t": motion.t, **_shown_ratios(motion), "N_c": motion.N_c, "N_c0": motion.N_c0,
              "last": last_counted(motion)}
    return readout_text(series, f, motion.steady)


_FRAME_JS = """
const f = cb_obj.value;
const X = frames.data.x, Y = frames.data.y, A = frames.data.a;
const d = now.data, off = f * n;
for (let i = 0; i < n; i++) {
  const x = d.px[i] + X[off + i], y = d.py[i] + Y[off + i], a = A[off + i];
  d.mx[i] = x; d.my[i] = y; d.a[i] = a;
  if (Number.isNaN(a)) { d.fx1[i] = x; d.fy1[i] = y; }
  else { const r = a * Math.PI / 180; d.fx1[i] = x + arrow_len * Math.cos(r); d.fy1[i] = y + arrow_len * Math.sin(r); }
}
now.change.emit();
const t = series.data.t[f], lead = lead0 + t, lo = lead - L0;
// Equal scales on any screen: where the whole travel does not fit, follow the slab. Before
// the top view's first layout its size is unset (reading it throws): follow from then on.
const sized = !top.properties.inner_width.is_unset && !top.properties.inner_height.is_unset;
if (follow && sized && top.inner_width > 0 && top.inner_height > 0) {
  const xr = top.x_range, yr = top.y_range;
  const want = (yr.end - yr.start) * top.inner_width / top.inner_height;
  const [a0, a1] = full_x;
  let a = a0, b = a1;
  if (want < a1 - a0) { a = Math.max(a0, Math.min(a1 - want, lo + L0 / 2 - want / 2)); b = a + want; }
  if (Math.abs(xr.start - a) > 1e-9 || Math.abs(xr.end - b) > 1e-9) xr.setv({start: a, end: b}, {sync: false});
}
slab.setv({data: {left: [lo], right: [lead], bottom: [-half_w], top: [half_w]}}, {sync: false});
const x0 = [], y0 = [], x1 = [], y1 = [];
for (const o of offsets) {
  const a0 = lo + o, a1 = a0 + 2 * half_w;
  const t0 = Math.min(1, Math.max(0, (lo - a0) / (a1 - a0)));
  const t1 = Math.min(1, Math.max(0, (lead - a0) / (a1 - a0)));
  x0.push(a0 + t0 * (a1 - a0)); y0.push(-half_w + t0 * 2 * half_w);
  x1.push(a0 + t1 * (a1 - a0)); y1.push(-half_w + t1 * 2 * half_w);
}
stripes.setv({data: {x0, y0, x1, y1}}, {sync: false});
const right = lead - 0.5 * L0 > (top.x_range.start + top.x_range.end) / 2;
arrow.setv({data: {x0: [lead - 0.8 * L0], x1: [lead - 0.2 * L0], xt: [lead - (right ? 0.2 : 0.8) * L0],
                   align: [right ? "right" : "left"], y: [arrow.data.y[0]]}}, {sync: false});
const s = series.data, k = f + 1;
// The live panel is a second canvas: redrawn at most every panel_ms (and when it settles),
// so the top view gets the frame budget.
const panel = () => {
  live.setv({data: {t: s.t.slice(0, k), nc: s.nc.slice(0, k), ftx: s.ftx.slice(0, k), run: s.run.slice(0, k)}}, {sync: false});
  for (const c of cursors) c.setv({location: t}, {sync: false});
};
const pnow = performance.now();
clearTimeout(live.__later);
if (!(pnow - (live.__t || 0) < panel_ms)) { live.__t = pnow; panel(); }
else live.__later = setTimeout(panel, panel_ms);
// The readout is DOM (a text node): at most every ui_ms, and once more when it settles.
const write = () => {
// As readout_text in Python: after the slab has left the grid, the last counted frame g.
const g = s.last[f], nc = s.N_c[g], nc0 = s.N_c0[g], ftx = s.ftx[g], run = s.run[g];
const fmt = (v, p) => Number.isFinite(v) ? v.toFixed(p) : "–";
const mean = Number.isFinite(run)
  ? `<b>mean over the steady window: ${fmt(run, 3)}</b>` + (t > steady[1] ? " (settled)" : " (so far)")
  : `mean over the steady window: from τ = ${steady[0].toFixed(1)}`;
const now = g === f ? `N_c = ${s.N_c[f]}</b> supports in contact`
  : `N_c = ${s.N_c[f]}</b> still in contact; the slab has left the grid, last values (τ = ${s.t[g].toFixed(1)}): N_c = ${nc}`;
readout.setv({html: `τ = ${t.toFixed(1)} · <b>${now}, N_c0 = ${nc0} under a rigid slab: ` +
  `N_c/N_c0 = ${nc0 ? fmt(nc / nc0, 2) : "–"}, β = N_c0/N_c = ${nc ? fmt(nc0 / nc, 2) : "–"} · ` +
  `F_T,x/(μ₀F_N) instantaneous ${fmt(ftx, 3)}, ${mean}`}, {sync: false});
};
const nowms = performance.now();
clearTimeout(readout.__later);
if (!(nowms - (readout.__t || 0) < ui_ms)) { readout.__t = nowms; write(); }
else readout.__later = setTimeout(write, ui_ms);
"""
