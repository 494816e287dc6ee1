"""Animations for slides: one support, or the array under the slab, as GIF or MP4.

Rendered on the server with matplotlib (Agg) and its animation writers: ``PillowWriter``
for GIF, ``FFMpegWriter`` for MP4 with the ffmpeg binary that the ``imageio-ffmpeg``
wheel ships (H.264, yuv420p, so that slide software and browsers play it).

* ``export_animation(what, fmt, path, params, ...)`` writes a file and returns an
  ``ExportResult`` (success, message, frames, size, seconds);
* ``animation_bytes(what, fmt, params, ...)`` returns the file's bytes, for a download
  button.

Both draw what the browser player shows: the support's top view (slab with moving
stripes and its velocity, spring, path so far, the friction force on the mass and the
relative velocity) beside the live energy split of Eq. (12); or the array's top view
(supports coloured by the direction of their friction force) above N_c/N_c0 and
F_T,x/(mu0 F_N).
"""
from __future__ import annotations

import math
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from model import Params, REGIMES, simulate_support
from model.arrays.array_motion import ORIENTATIONS, array_motion

from .figures.array_scene import SLAB_FILL, direction_palette, slab_half_width, view_x
from .figures.common import BLUE, GREEN, GREY, VERMILION
from .figures.histories import ENERGY_COLORS, ENERGY_LABELS, ENERGY_TERMS
from .figures.scene import FORCE_COLOR, SLAB_COLOR, VREL_COLOR
from .frame_fit import fit_layout

__all__ = ["export_animation", "animation_bytes", "ExportResult", "WHAT", "FORMATS",
           "FRAMES_RANGE", "SIZE_RANGE", "FPS_RANGE", "check_request"]

WHAT = ("support", "array")
FORMATS = ("gif", "mp4")
FRAMES_RANGE = (2, 2000)
SIZE_RANGE = ((160, 3840), (120, 2160))
FPS_RANGE = (1, 60)
MIME = {"gif": "image/gif", "mp4": "video/mp4"}
_DPI = 100
# The page's colours (``app.figures``): the same quantity has the same colour on the page
# and in the file.
_BLUE, _GREEN, _GREY = BLUE, GREEN, GREY
_FORCE, _VREL, _SLAB, _MASS = FORCE_COLOR, VREL_COLOR, SLAB_COLOR, VERMILION
_FTX = VERMILION  # F_T,x/(mu0 F_N) on the array's panel, as on the page
_ENERGY = tuple(zip(ENERGY_TERMS, ENERGY_LABELS, ENERGY_COLORS))


@dataclass(frozen=True)
class ExportResult:
    """What was written: ``path`` (None for bytes), frames, size (width, height) in px."""

    success: bool
    message: str
    path: str | None
    what: str
    fmt: str
    frames: int
    size: tuple
    fps: float
    seconds: float
    stats: dict = field(default_factory=dict)


def check_request(what, fmt, frames, size, fps) -> tuple:
    """Validated (what, fmt, frames, (width, height), fps); a ValueError names the value."""
    if what not in WHAT:
        raise ValueError(f"what={what!r} must be one of {', '.join(WHAT)}")
    if fmt not in FORMATS:
        raise ValueError(f"format={fmt!r} must be one of {', '.join(FORMATS)}")
    lo, hi = FRAMES_RANGE
    if isinstance(frames, bool) or not isinstance(frames, (int, np.integer)) \
            or not lo <= frames <= hi:
        raise ValueError(f"frames={frames!r} must be a whole number in [{lo}, {hi}]")
    try:
        width, height = (int(v) for v in size)
    except (TypeError, ValueError):
        raise ValueError(f"size={size!r} must be (width, height) in pixels") from None
    (wlo, whi), (hlo, hhi) = SIZE_RANGE
    if not (wlo <= width <= whi and hlo <= height <= hhi):
        raise ValueError(f"size={width}x{height} must be within {wlo}..{whi} x {hlo}..{hhi} px")
    if fmt == "mp4" and (width % 2 or height % 2):
        raise ValueError(f"size={width}x{height}: MP4 (H.264, yuv420p) needs an even width and "
                         f"height; use {width + width % 2}x{height + height % 2}")
    if isinstance(fps, bool) or not isinstance(fps, (int, float)) or not (
            math.isfinite(fps) and FPS_RANGE[0] <= fps <= FPS_RANGE[1]):
        raise ValueError(f"fps={fps!r} must be a number in [{FPS_RANGE[0]}, {FPS_RANGE[1]}]")
    return what, fmt, int(frames), (width, height), float(fps)


def export_animation(what: str, fmt: str, path, params: Params, frames: int = 120,
                     size=(960, 540), fps: float = 20, orientation: str = "uniform",
                     n_supports: int = 100) -> ExportResult:
    """Write the animation of ``what`` (support or array) as ``fmt`` (gif or mp4) to ``path``.

    ``params``: the support (k_r, k_theta, F_N, theta0); ``orientation`` and
    ``n_supports`` shape the array (see ``model.arrays.array_motion``).
    """
    start = time.perf_counter()
    if not isinstance(params, Params):
        raise TypeError(f"params must be a model.Params, not {type(params).__name__}")
    what, fmt, frames, size, fps = check_request(what, fmt, frames, size, fps)
    if orientation not in ORIENTATIONS:
        raise ValueError(f"orientation={orientation!r} must be one of {ORIENTATIONS}")
    path = Path(path)
    if not path.parent.is_dir():
        raise ValueError(f"out={str(path)!r}: the folder {str(path.parent)!r} does not exist")
    drawer, fig = frame_figure(what, params, frames, size, orientation, n_supports)
    note = "" if what == "support" or drawer.motion.success else drawer.motion.message
    if fig is None:
        return ExportResult(False, drawer.failed, None, what, fmt, 0, size, fps,
                            time.perf_counter() - start)
    writer = _writer(fmt, fps)
    with writer.saving(fig, str(path), dpi=_DPI):
        for i in range(frames):
            drawer.draw(i)
            writer.grab_frame()
    message = f"{frames} frames, {size[0]}x{size[1]} px, {fps:g} frames/s"
    return ExportResult(True, message + (f"; {note}" if note else ""), str(path), what, fmt,
                        frames, size, fps, time.perf_counter() - start,
                        stats={"bytes": path.stat().st_size})


def frame_figure(what: str, params: Params, frames: int, size, orientation: str = "uniform",
                 n_supports: int = 100):
    """(drawer, figure) of the animation, laid out (``fit_layout``) and showing its last
    frame; the figure is None when the model gave nothing to draw (``drawer.failed``)."""
    # A figure with its own Agg canvas: no pyplot, no global backend, safe in a server.
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    drawer = (_SupportDrawer(params, frames) if what == "support"
              else _ArrayDrawer(params, frames, orientation, n_supports))
    if drawer.failed:
        return drawer, None
    fig = Figure(figsize=(size[0] / _DPI, size[1] / _DPI), dpi=_DPI, layout="constrained")
    FigureCanvasAgg(fig)
    drawer.setup(fig)
    drawer.draw(frames - 1)  # the widest texts (the clock) in place for the layout
    fit_layout(fig)
    return drawer, fig


def animation_bytes(what: str, fmt: str, params: Params, **kwargs) -> tuple[bytes, str, ExportResult]:
    """(file bytes, MIME type, result) for a download button; see ``export_animation``."""
    check_request(what, fmt, kwargs.get("frames", 120), kwargs.get("size", (960, 540)),
                  kwargs.get("fps", 20))
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / f"animation.{fmt}"
        result = export_animation(what, fmt, out, params, **kwargs)
        data = out.read_bytes() if result.success else b""
    return data, MIME[fmt], result


def _writer(fmt, fps):
    from matplotlib import animation

    if fmt == "gif":
        return animation.PillowWriter(fps=fps)
    import imageio_ffmpeg
    import matplotlib

    matplotlib.rcParams["animation.ffmpeg_path"] = imageio_ffmpeg.get_ffmpeg_exe()
    return animation.FFMpegWriter(fps=fps, codec="libx264",
                                  extra_args=["-pix_fmt", "yuv420p", "-loglevel", "error"])


def _title(params, extra="") -> str:
    name = next((k for k, p in REGIMES.items()
                 if p.k_r == params.k_r and p.k_theta == params.k_theta), None)
    springs = f"k_r = {params.k_r:g}, k_θ = {params.k_theta:g}, F_N = {params.F_N:g}"
    return (f"{name} regime: " if name else "") + springs + extra


class _SupportDrawer:
    """One support, top view, beside its live energy split (Eq. 12)."""

    def __init__(self, params, frames):
        self.params = params
        res = simulate_support(params, samples=max(400, 4 * frames))
        self.failed = "" if res.series is not None else f"no trajectory: {res.message}"
        if self.failed:
            return
        s = res.series
        self.tau = np.linspace(0.0, float(s.tau[-1]), frames)
        self.d = {k: np.interp(self.tau, s.tau, getattr(s, k))
                  for k in ("x", "y", "v_x", "v_y", "F_x", "F_y", "W", "D_x", "D_y", "U_el", "K")}
        self.path = (np.asarray(s.tau), np.asarray(s.x), np.asarray(s.y))
        self.t_out = float(s.tau[-1])

    def setup(self, fig):
        p, d = self.params, self.d
        gs = fig.add_gridspec(1, 2, width_ratios=(1.5, 1))
        ax = self.ax = fig.add_subplot(gs[0])
        ex = fig.add_subplot(gs[1])
        fig.suptitle(f"One support, top view\n{_title(p)} · θ₀ = {math.degrees(p.theta0):.0f}°",
                     fontsize=11)
        x, y = self.path[1], self.path[2]
        lo = min(x.min(), -1.0) - 0.6, min(y.min(), -1.0) - 0.6
        hi = max(x.max(), 1.0) + 0.6, max(y.max(), 1.0) + 0.6
        half = 0.5 * max(hi[0] - lo[0], hi[1] - lo[1])
        cx, cy = 0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])
        ax.set_xlim(cx - half, cx + half)
        ax.set_ylim(cy - half, cy + half)
        ax.set_aspect("equal")
        ax.set_xlabel("x / r₀ (sliding direction →)")
        ax.set_ylabel("y / r₀")
        ax.text(0.02, 0.97, "TOP VIEW", transform=ax.transAxes, fontweight="bold", va="top",
                bbox=dict(fc="white", ec="none", alpha=0.8))
        self.half, self.cy = half, cy
        self.slab = ax.axvspan(0, 0, color=SLAB_FILL, alpha=0.35, zorder=0)
        self.stripes = [ax.plot([], [], color=_SLAB, alpha=0.25, lw=1.5, zorder=0)[0]
                        for _ in range(int(4 * half + p.L0) + 4)]
        self.edges = [ax.axvline(0, color=_SLAB, lw=2.5) for _ in range(2)]
        ax.plot(np.cos(np.linspace(0, 2 * np.pi, 100)), np.sin(np.linspace(0, 2 * np.pi, 100)),
                ":", color=_GREY, lw=1)
        ax.plot([0], [0], "s", color="black", mfc="white", ms=7, zorder=5)
        ax.plot([math.cos(p.theta0)], [math.sin(p.theta0)], "o", color="black", mfc="white",
                ms=6, zorder=5)
        self.trail, = ax.plot([], [], color=_GREY, lw=1.5)
        self.spring, = ax.plot([], [], color="black", lw=1.3)
        self.mass, = ax.plot([], [], "o", color=_MASS, mec="black", ms=11, zorder=6)
        # The slab's velocity: a fixed arrow (a velocity, not a place) over the view.
        ax.annotate("V₀", xy=(0.95, 0.93), xytext=(0.78, 0.93),
                    xycoords="axes fraction", textcoords="axes fraction", color=_SLAB,
                    ha="right", va="center", fontsize=9,
                    arrowprops=dict(arrowstyle="-|>", color=_SLAB, lw=2.5))
        self.friction = ax.annotate("", xy=(0, 0), xytext=(0, 0),
                                    arrowprops=dict(arrowstyle="-|>", color=_FORCE, lw=2.5))
        self.relvel = ax.annotate("", xy=(0, 0), xytext=(0, 0),
                                  arrowprops=dict(arrowstyle="-|>", color=_VREL, lw=2))
        keys = [ax.plot([], [], color=_SLAB, lw=2.5, label="slab velocity V₀ (slab shaded)")[0],
                ax.plot([], [], color=_FORCE, lw=2.5, label="friction on the mass")[0],
                ax.plot([], [], color=_VREL, lw=2, label="relative velocity v_R")[0]]
        fig.legend(handles=keys, loc="outside lower center", ncol=3, fontsize=8,
                   frameon=False)
        self.clock = ax.text(0.98, 0.03, "", transform=ax.transAxes, ha="right",
                             bbox=dict(fc="white", ec="none", alpha=0.8))
        # Energy bars: W so far beside its split.
        ex.set_title("The slab's work (Eq. 12)", fontsize=10)
        top = max(d["W"].max(), (d["D_x"] + d["D_y"] + d["U_el"] + d["K"]).max(), 1e-12)
        ex.set_ylim(min(0.0, min(d[k].min() for k in ("W", "D_x", "D_y", "U_el", "K"))),
                    1.15 * top)
        ex.set_xlim(-0.6, 1.6)
        ex.set_xticks([0, 1], ["W so far", "D_x + D_y\n+ U_el + K"], fontsize=9)
        ex.set_ylabel("energy / (m V₀²)")
        self.wbar = ex.bar([0], [0], width=0.7, color="#555555")[0]
        self.parts = [ex.bar([1], [0], width=0.7, color=c, label=lab)[0] for _, lab, c in _ENERGY]
        ex.legend(loc="upper left", fontsize=8, frameon=False)

    def draw(self, i):
        p, d = self.params, self.d
        x, y, t = d["x"][i], d["y"][i], self.tau[i]
        x0 = float(self.path[1][0])
        lead, trail = x0 + t, x0 + t - p.L0
        self.slab.set_x(trail)
        self.slab.set_width(p.L0)
        for line, pos in zip(self.edges, (trail, lead)):
            line.set_xdata([pos, pos])
        # Diagonal stripes fixed to the slab, clipped to it: they show it sliding.
        span, y0 = 2 * self.half, self.cy - self.half
        for k, line in enumerate(self.stripes):
            a = trail + k - span
            u0, u1 = max(0.0, (trail - a) / span), min(1.0, (lead - a) / span)
            if u1 > u0:
                line.set_data([a + u0 * span, a + u1 * span], [y0 + u0 * span, y0 + u1 * span])
            else:
                line.set_data([], [])
        tau_p, xp, yp = self.path
        k = np.searchsorted(tau_p, t, side="right")
        self.trail.set_data(xp[:k], yp[:k])
        r = math.hypot(x, y)
        u = np.linspace(0, 1, 31)
        w = np.where((u > 0.15) & (u < 0.85), 0.08 * np.sign(np.sin(u * 14 * np.pi)), 0.0)
        ex_, ey_ = (x / r, y / r) if r > 0 else (1.0, 0.0)
        self.spring.set_data(u * x - w * ey_, u * y + w * ex_)
        self.mass.set_data([x], [y])
        scale = 0.6
        self.friction.set_position((x, y))
        self.friction.xy = (x + scale * d["F_x"][i], y + scale * d["F_y"][i])
        self.relvel.set_position((x, y))
        self.relvel.xy = (x + scale * (d["v_x"][i] - 1.0), y + scale * d["v_y"][i])
        self.clock.set_text(f"τ = {t:.2f} of τ_out = {self.t_out:.2f}")
        self.wbar.set_height(d["W"][i])
        base = 0.0
        for bar, (key, _, _) in zip(self.parts, _ENERGY):
            bar.set_y(base)
            bar.set_height(d[key][i])
            base += d[key][i]


class _ArrayDrawer:
    """The slab over the array (top view) above N_c/N_c0 and F_T,x/(mu0 F_N)."""

    def __init__(self, params, frames, orientation, n_supports):
        self.motion = array_motion(params, orientation=orientation, n_supports=n_supports,
                                   n_frames=frames)
        self.failed = ""

    def setup(self, fig):
        m = self.motion
        from matplotlib.colors import ListedColormap

        # The page's palette of the friction direction (-90 deg ... +90 deg).
        self.cmap = ListedColormap(direction_palette(), name="direction")
        gs = fig.add_gridspec(2, 1, height_ratios=(1.5, 1))
        ax = self.ax = fig.add_subplot(gs[0])
        pn = fig.add_subplot(gs[1])
        fig.suptitle(f"TOP VIEW · the slab slides over {m.n_supports} supports "
                     f"({m.orientation} θ₀)\n{_title(m.params)}", fontsize=10)

        L0 = m.params.L0
        lead0 = float(m.slab_lead[0])
        half = slab_half_width(m)
        ax.set_xlim(*view_x(m))
        ax.set_ylim(-half - 2.0, half + 2.0)
        ax.set_aspect("equal", adjustable="box")
        ax.set_xlabel("x / r₀ (sliding direction →)", fontsize=9)
        ax.tick_params(labelsize=8)
        self.half = half
        from matplotlib.patches import Rectangle

        self.slab = ax.add_patch(Rectangle((lead0 - L0, -half), L0, 2 * half, fc=SLAB_FILL,
                                           alpha=0.35, ec=_SLAB, lw=2.5, hatch="//", zorder=0))
        self.vel = ax.annotate("slab velocity V₀", xy=(0, 0), xytext=(0, 0), color=_SLAB,
                               fontsize=8, va="center", ha="right",
                               arrowprops=dict(arrowstyle="-|>", color=_SLAB, lw=2.5))
        ax.plot(m.pivot_x, m.pivot_y, "s", color=_GREY, ms=2.5)
        from matplotlib.collections import LineCollection

        self.springs = ax.add_collection(LineCollection([], colors=_GREY, linewidths=0.8))
        self.masses = ax.scatter(m.pivot_x, m.pivot_y, s=22, facecolors="#d9d9d9",
                                 edgecolors="black", linewidths=0.5, zorder=4)
        from matplotlib.cm import ScalarMappable
        from matplotlib.colors import Normalize

        scale = ScalarMappable(norm=Normalize(-90, 90), cmap=self.cmap)
        cb = fig.colorbar(scale, ax=ax, fraction=0.025, pad=0.01, ticks=[-90, 0, 90])
        cb.set_label("friction direction [°]", fontsize=7)
        cb.ax.tick_params(labelsize=7)
        pn.set_xlim(0, float(m.t_start.max()) + 0.5)
        # Drawn up to the last entry: then the slab leaves the grid (see array_scene).
        keep = m.t <= m.t_start.max()
        ratio = np.where(keep & (m.N_c0 > 0), m.N_c / np.maximum(m.N_c0, 1), np.nan)
        self.running = np.where(keep, m.FTx_running, np.nan)
        mask = m.steady_mask()
        top = max(1.25, m.model["Nc_over_Nc0"] * 1.25,
                  float(np.nanmax(ratio[mask])) * 1.1 if mask.any() else 0.0)
        pn.set_ylim(0.6, top)
        pn.axvspan(*m.steady, color=_GREEN, alpha=0.08)
        pn.axhline(m.model["Nc_over_Nc0"], color=_BLUE, ls="--", lw=1.5)
        pn.axhline(m.model["FTx_over_mu0FN_duration"], color=_FTX, ls="--", lw=1.5)
        pn.axhline(1.0, color=_GREY, ls=":", lw=1.5)
        self.ratio = ratio
        self.nc, = pn.plot([], [], color=_BLUE, lw=2, label="N_c/N_c0 (dashed: model)")
        self.ftx, = pn.plot([], [], color=_FTX, lw=2,
                            label="F_T,x/(μ₀F_N) running mean (dashed: model)")
        self.cursor = pn.axvline(0, color=_GREY, lw=1)
        pn.set_xlabel("τ (slab travel / r₀)", fontsize=9)
        pn.tick_params(labelsize=8)
        pn.legend(loc="center left", fontsize=7, frameon=False)  # clear of the curves

    def draw(self, i):
        m = self.motion
        L0 = m.params.L0
        lead = float(m.slab_lead[i])
        self.slab.set_x(lead - L0)
        self.vel.set_position((lead - 0.55 * L0, self.half + 1.2))
        self.vel.xy = (lead - 0.15 * L0, self.half + 1.2)
        mx, my = m.pivot_x + m.x[:, i], m.pivot_y + m.y[:, i]
        self.springs.set_segments(np.stack([np.column_stack([m.pivot_x, m.pivot_y]),
                                            np.column_stack([mx, my])], axis=1))
        self.masses.set_offsets(np.column_stack([mx, my]))
        angle = np.degrees(m.F_angle[:, i])
        colors = self.cmap((np.clip(np.nan_to_num(angle), -90, 90) + 90) / 180)
        colors[~np.isfinite(angle)] = (0.85, 0.85, 0.85, 1.0)
        self.masses.set_facecolors(colors)
        self.nc.set_data(m.t[:i + 1], self.ratio[:i + 1])
        self.ftx.set_data(m.t[:i + 1], self.running[:i + 1])
        self.cursor.set_xdata([m.t[i], m.t[i]])


def main_params(k_r=None, k_theta=None, F_N=None, theta0_deg=None, regime=None) -> Params:
    """Params from CLI-style values (theta0 in degrees), starting from ``regime``."""
    base = Params.regime(regime) if regime else REGIMES["pendulum"]
    changes = {k: v for k, v in (("k_r", k_r), ("k_theta", k_theta), ("F_N", F_N)) if v is not None}
    if theta0_deg is not None:
        changes["theta0"] = math.radians(theta0_deg)
    return base.replace(**changes)

