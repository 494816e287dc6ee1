"""The offline explorer: one self-contained HTML file that computes in the browser.

``write(path)`` (the CLI's ``micropillar pack --out explorer.html``) builds the page with
Bokeh's Python API -- the top view of the support's orbit, the sliders k_r, k_theta, F_N,
theta0, the regime presets, the headline friction number (Eq. 10 for an array of one
orientation) -- and saves it with BokehJS inlined (``bokeh.resources.INLINE``: no CDN, no
font, no request). The plot's data sources are empty at pack time: the JavaScript port of
the kernel (``kernel.js``) fills them in the page, in a Web Worker, whenever a control
moves (``page.js``). The state lives in the URL fragment (``#k_r=3&k_theta=0.01&F_N=1&
theta0_deg=90``). docs/offline.md documents the page and its JavaScript API.

The ranges, defaults, regimes and their titles are read here from ``model.controls``,
``model.params.REGIMES``, ``app.texts`` and ``app.urlstate`` and handed to the page as JSON:
defined once, in Python.
"""
from __future__ import annotations

import json
import math
from importlib import resources
from pathlib import Path

from bokeh.embed import file_html
from bokeh.layouts import column, row
from bokeh.models import Button, ColumnDataSource, CustomJS, CustomJSTickFormatter, Div, Slider
from bokeh.plotting import figure
from bokeh.resources import INLINE

from model.controls import CONTROLS, DEFAULT_REGIME
from model.friction import mu0
from model.params import REGIMES

from ..texts import MECHANISMS
from ..urlstate import TABS

__all__ = ["page_html", "write", "config", "MAX_BYTES", "OFFLINE_TABS"]

#: The page's size bound (the issue's target): BokehJS inlined is most of it.
MAX_BYTES = 5 * 1024 * 1024
#: The tabs of the dashboard the offline page shows (the others say they are not in it yet).
OFFLINE_TABS = ("support",)
#: Samples of the orbit drawn per contact (uniform in tau).
ORBIT_SAMPLES = 1500
TITLE = "Micropillar friction explorer (offline)"

_SLIDERS = (  # (control, fragment key, title, log scale)
    ("k_r", "k_r", "k_r: radial stiffness (Eq. 5)", True),
    ("k_theta", "k_theta", "k_θ: torsional stiffness (Eq. 5)", True),
    ("F_N", "F_N", "F_N: normal load", True),
    ("theta0_deg", "theta0_deg", "θ₀: rest orientation [deg]", False),
)


def config() -> dict:
    """What the page needs from the model: controls, regimes, mu0, tabs (as JSON)."""
    controls = {}
    for name, key, title, log in _SLIDERS:
        control = CONTROLS[name]
        interval = control.interval
        controls[key] = dict(lo=interval.lo, hi=interval.hi, hi_open=interval.hi_open,
                             default=control.default, log=log, title=title,
                             meaning=control.meaning, expected=control.expected())
    regimes = {name: dict(k_r=p.k_r, k_theta=p.k_theta, title=MECHANISMS[name][0])
               for name, p in REGIMES.items()}
    return dict(controls=controls, regimes=regimes, default_regime=DEFAULT_REGIME,
                mu0=mu0(), tabs=list(TABS), offline_tabs=list(OFFLINE_TABS),
                orbit_samples=ORBIT_SAMPLES)


def _slider(key: str, title: str, spec: dict) -> Slider:
    """A slider over the control's interval; a log control slides over log10 of it."""
    if spec["log"]:
        lo, hi = math.log10(spec["lo"]), math.log10(spec["hi"])
        fmt = CustomJSTickFormatter(code="return Number(Math.pow(10, tick).toPrecision(3)).toString();")
        slider = Slider(start=lo, end=hi, value=math.log10(spec["default"]), step=0.01,
                        title=title, format=fmt, name=f"slider-{key}")
    else:  # theta0 in [0, 360): the slider stops at 359
        slider = Slider(start=spec["lo"], end=spec["hi"] - 1, value=spec["default"], step=1,
                        title=title, name=f"slider-{key}")
    slider.js_on_change("value", CustomJS(
        args=dict(key=key), code="if (window.explorer) window.explorer._slider(key, cb_obj.value);"))
    slider.sizing_mode = "stretch_width"
    return slider


def _orbit_figure() -> figure:
    """The support seen from above: its pivot, rest position and the orbit of the mass."""
    fig = figure(title="The support seen from above (slab slides along +x)", name="orbit-figure",
                 x_axis_label="x [r₀]", y_axis_label="y [r₀]", match_aspect=True,
                 sizing_mode="stretch_both", min_height=320, tools="pan,wheel_zoom,reset",
                 output_backend="canvas")
    orbit = ColumnDataSource(dict(x=[], y=[]), name="orbit-source")
    ends = ColumnDataSource(dict(x=[], y=[], label=[]), name="ends-source")
    spring = ColumnDataSource(dict(x=[], y=[]), name="spring-source")
    fig.line("x", "y", source=spring, line_dash="dashed", line_color="#888888",
             legend_label="spring at rest")
    fig.line("x", "y", source=orbit, line_width=2, line_color="#1f77b4",
             legend_label="path of the mass")
    fig.scatter(x=[0.0], y=[0.0], marker="circle_x", size=12, fill_color="white",
                line_color="black", legend_label="pivot")
    fig.scatter("x", "y", source=ends, marker="circle", size=9, color="#d62728",
                legend_label="rest → exit")
    legend = fig.legend[0]
    legend.orientation = "horizontal"
    fig.add_layout(legend, "below")
    return fig


def _layout(cfg: dict):
    controls = cfg["controls"]
    sliders = [_slider(key, title, controls[key]) for _, key, title, _ in _SLIDERS]
    presets = []
    for name, regime in cfg["regimes"].items():
        button = Button(label=name, name=f"preset-{name}", button_type="default",
                        html_attributes={"title": regime["title"]}, width=90)
        button.js_on_event("button_click", CustomJS(
            args=dict(regime=name), code="if (window.explorer) window.explorer.preset(regime);"))
        presets.append(button)
    heading = Div(text=f"<h1 style='margin:0.2em 0;font-size:1.4em'>{TITLE}</h1>",
                  name="heading")
    notice = Div(text="", name="notice", styles={"color": "#8a4b00"})
    headline = Div(text="computing…", name="headline", styles={"font-size": "1.25em"})
    status = Div(text="", name="status", styles={"color": "#555555", "font-size": "0.9em"})
    missing = Div(text=("Not in this offline page yet: the friction histories, energy bars, "
                        "the array, the polar diagrams, the uniform array with its "
                        "self-consistent β, the regime maps, projector mode. "
                        "Run <code>panel serve app</code> for the full explorer."),
                  name="missing", styles={"color": "#555555", "font-size": "0.85em"})
    side = column([heading, headline, notice, row(presets, sizing_mode="stretch_width"),
                   *sliders, status, missing], sizing_mode="stretch_width", width=360,
                  min_width=280, max_width=420)
    return row([side, _orbit_figure()], sizing_mode="stretch_both", name="layout")


def _script(element_id: str, source: str, kind: str = "") -> str:
    """A ``<script>`` element whose source cannot end the element early."""
    if "</script" in source.lower():
        raise ValueError(f"{element_id}: the source contains '</script'")
    type_attr = f' type="{kind}"' if kind else ""
    return f'<script id="{element_id}"{type_attr}>\n{source}\n</script>\n'


def page_html() -> str:
    """The whole page: Bokeh's document with BokehJS inlined, the kernel and the page code."""
    cfg = config()
    html = file_html(_layout(cfg), resources=INLINE, title=TITLE)
    here = resources.files(__package__)
    extra = (_script("mp-config", json.dumps(cfg).replace("</", "<\\/"), "application/json")
             + _script("mp-kernel", (here / "kernel.js").read_text(encoding="utf-8"))
             + _script("mp-page", (here / "page.js").read_text(encoding="utf-8")))
    head_extra = ('<meta name="viewport" content="width=device-width, initial-scale=1">\n'
                  '<meta http-equiv="Content-Security-Policy" content="default-src \'none\'; '
                  'script-src \'unsafe-inline\' \'unsafe-eval\' blob:; worker-src blob:; '
                  'style-src \'unsafe-inline\'; img-src data: blob:; font-src data:">\n')
    # Bokeh's inlined scripts may hold the text "</head>" or "</body>": add after the
    # first <head> and before the last </body>.
    head, body = html.find("<head>"), html.rfind("</body>")
    if head < 0 or body < 0:
        raise RuntimeError("Bokeh's page template changed: no <head> or </body> to add to")
    head += len("<head>")
    return html[:head] + "\n" + head_extra + html[head:body] + extra + html[body:]


def write(path) -> int:
    """Write the offline explorer to ``path``; returns its size in bytes.

    Raises ``ValueError`` when the page would exceed ``MAX_BYTES``."""
    html = page_html().encode("utf-8")
    if len(html) > MAX_BYTES:
        raise ValueError(f"the offline page is {len(html):,} bytes, over the bound of "
                         f"{MAX_BYTES:,}")
    Path(path).write_bytes(html)
    return len(html)
