"""The offline explorer: one self-contained HTML file that computes in the browser.

``write(path)`` (the CLI's ``micropillar pack --out explorer.html``) lays out the page with
Bokeh's Python API -- the sliders k_r, k_theta, F_N, theta0, the regime presets, projector
mode, the headline, and three tabs of the dashboard's figures (``figures.py``: the
support with Fig. 7, Fig. 3, the energy bars of Eq. 12 and the player; the polar
diagrams of Fig. 11; the shipped regime maps of Fig. 5: these two packed apart from the
opening document and added when first shown, ``tabs.py``) -- and saves it with BokehJS
inlined (``bokeh.resources.INLINE``: no CDN, no font, no request). In the page the
JavaScript port of the kernel (``kernel.js`` and its ``kernel_*.js``) recomputes in Web
Workers whenever a control moves, ``views.js`` turns its results into the figures' data
and ``page.js`` holds the state, also in the URL fragment (``#k_r=3&k_theta=0.01&F_N=1&theta0_deg=90&tab=polar``).
docs/offline.md documents the page and its JavaScript API.

The ranges, defaults, regimes and their titles are read here from ``model.controls``,
``model.contact.params.REGIMES``, ``app.texts`` and ``app.urlstate`` and handed to the page as JSON:
defined once, in Python.
"""
from __future__ import annotations

import json
import math
import re
from functools import lru_cache
from importlib import resources
from pathlib import Path
from urllib.parse import urlencode

from bokeh.document import Document
from bokeh.embed import file_html
from bokeh.layouts import column, row
from bokeh.models import (Button, CustomJS, CustomJSTickFormatter, Div, Select, Slider,
                          TabPanel, Tabs, Toggle)
from bokeh.resources import INLINE

from model.controls import CONTROLS, DEFAULT_REGIME
from model.contact.friction import mu0
from model.contact.params import REGIMES

from ..figures.access_js import PAGE_SCRIPT, mark_figures
from ..figures.arrays import AVERAGE_COLUMNS
from ..texts import AVERAGE_NAMES, FELT_AVERAGE, MECHANISMS
from ..defaults import TABS
from ..edge import TESTED
from ..worker import UNIFORM_TOL
from . import figures as views
from .tabs import LATER_ID, later_json, later_tab, map_tab, polar_tab

__all__ = ["page_html", "page_bytes", "write", "config", "initial_fragment", "MAX_BYTES",
           "OFFLINE_TABS", "FRAGMENT_KEYS"]

#: The page's size bound (the issue's target): BokehJS inlined is most of it.
MAX_BYTES = 5 * 1024 * 1024
#: The tabs of the dashboard the offline page shows (the others say they are not in it yet).
OFFLINE_TABS = ("support", "polar", "map")
TITLE = "Micropillar friction explorer (offline)"
#: The page's scripts (app/offline/*.js), in loading order.
SCRIPTS = ("bokeh_fix", "kernel_inputs", "kernel_rhs", "kernel_dopri5", "kernel", "solvers",
           "arrays", "fragment", "jobs", "first", "views", "support", "paint", "models",
           "readouts", "polarview", "mapview", "tabs", "open", "page")

_SLIDERS = (  # (control, fragment key, title, log scale or the linear step)
    ("k_r", "k_r", "k_r: radial stiffness (Eq. 5)", True),
    ("k_theta", "k_theta", "k_θ: torsional stiffness (Eq. 5)", True),
    ("F_N", "F_N", "F_N: normal load", True),
    ("theta0_deg", "theta0_deg", "θ₀: rest orientation [deg]", 1),
    ("beta", "beta", "β: the fixed load factor N_c0/N_c (with “fixed β”)", 0.001),
)
#: The load factor's modes (``beta_mode``, the dashboard's): label of each.
BETA_MODES = {"self": "self-consistent β = L0/⟨τ_out⟩ (the dashboard's default)",
              "fixed": "fixed β (the slider below)"}
#: A dashboard tab the page does not have: the tab it opens instead, and what that shows.
CLOSEST_TABS = {
    "array": ("polar", "the polar tab (fixed arrays, Fig. 11), with the uniform array's "
                       "readout beside the controls; the array under the slab needs the server"),
    "load": ("map", "the regime maps (uniform arrays) at the shipped loads; the load curves "
                    "(Fig. 6) need the server"),
}


#: What the page leaves to the server (docs/offline.md says why).
MISSING = ("Not in this offline page: the array view, the load curves (Fig. 6), regime "
           "maps at new loads, the equations, the design tab, pinning a state, animation "
           "export. Run <code>panel serve app</code> for the full explorer.")
#: The headline's clause for a uniform array that could not be computed.
UNIFORM_FAILED_NOTE = "not computed (see the uniform array's readout)"


def config() -> dict:
    """What the page needs from the model: controls, regimes, mu0, tabs (as JSON)."""
    controls = {}
    for name, key, title, scale in _SLIDERS:
        control = CONTROLS[name]
        interval = control.interval
        controls[key] = dict(lo=interval.lo, hi=interval.hi, hi_open=interval.hi_open,
                             default=control.default, log=scale is True,
                             step=None if scale is True else scale, title=title,
                             meaning=control.meaning, expected=control.expected())
    mode = CONTROLS["beta_mode"]
    regimes = {name: dict(k_r=p.k_r, k_theta=p.k_theta, title=MECHANISMS[name][0])
               for name, p in REGIMES.items()}
    return dict(controls=controls, regimes=regimes, default_regime=DEFAULT_REGIME,
                mu0=mu0(), tabs=list(TABS), offline_tabs=list(OFFLINE_TABS),
                closest_tabs={k: dict(tab=t, why=w) for k, (t, w) in CLOSEST_TABS.items()},
                beta_mode=dict(default=mode.default, choices=list(mode.choices),
                               expected=mode.expected()),
                uniform_tol=UNIFORM_TOL, uniform_failed_note=UNIFORM_FAILED_NOTE,
                felt_average=FELT_AVERAGE, average_names=AVERAGE_NAMES,
                average_columns=AVERAGE_COLUMNS, **views.constants())


def _slider(key: str, title: str, spec: dict) -> Slider:
    """A slider over the control's interval; a log control slides over log10 of it."""
    if spec["log"]:
        lo, hi = math.log10(spec["lo"]), math.log10(spec["hi"])
        fmt = CustomJSTickFormatter(code="return Number(Math.pow(10, tick).toPrecision(3)).toString();")
        slider = Slider(start=lo, end=hi, value=math.log10(spec["default"]), step=0.01,
                        title=title, format=fmt, name=f"slider-{key}")
    else:  # theta0 in [0, 360): the slider stops at 359
        step = spec["step"]
        slider = Slider(start=spec["lo"], end=spec["hi"] - step if spec["hi_open"] else spec["hi"],
                        value=spec["default"], step=step, title=title, name=f"slider-{key}")
    slider.js_on_change("value", CustomJS(
        args=dict(key=key), code="if (window.explorer) window.explorer._slider(key, cb_obj.value);"))
    slider.sizing_mode = "stretch_width"
    return slider


def _support_tab(figs):
    """The dashboard's Support tab: scene and Fig. 7, the player, Fig. 3 and the energy."""
    for key in ("scene", "forces", "law"):
        figs[key].sizing_mode = "stretch_width"
        figs[key].min_width = 300
    energy = figs["energy"]
    energy.sizing_mode = figs["energy_fig"].sizing_mode = "stretch_width"
    energy.min_width = figs["energy_fig"].min_width = 300
    wrap = dict(sizing_mode="stretch_width", styles={"flex-wrap": "wrap"})
    return column([row([figs["scene"], figs["forces"]], **wrap), figs["player"].layout,
                   row([figs["law"], energy], **wrap)], sizing_mode="stretch_width",
                  name="support-tab")


def _layout(cfg: dict, figs: dict, polar: dict, regime_map):
    controls = cfg["controls"]
    sliders = [_slider(key, title, controls[key]) for _, key, title, _ in _SLIDERS]
    beta_mode = Select(title="load factor β = N_c0/N_c", value=cfg["beta_mode"]["default"],
                       options=list(BETA_MODES.items()), name="beta-mode",
                       sizing_mode="stretch_width")
    beta_mode.js_on_change("value", CustomJS(
        code="if (window.explorer) window.explorer._betaMode(cb_obj.value);"))
    uniform = Div(text="", name="uniform-readout", sizing_mode="stretch_width",
                  styles={"font-size": "0.9em"})
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
    headline = Div(text="computing…", name="headline", sizing_mode="stretch_width",
                   styles={"font-size": "1.15em", "font-weight": "600"})
    number = Div(text="", name="headline-number", styles={"font-size": "1.0em"})
    status = Div(text="", name="status", styles={"color": "#555555", "font-size": "0.9em"})
    projector = Toggle(label="Projector mode", name="projector", active=False, width=160,
                       html_attributes={"title": "Larger text and thicker lines for a "
                                                 "projected screen (projector=1 in the link)"})
    projector.js_on_change("active", CustomJS(
        code="if (window.explorer) window.explorer._projector(cb_obj.active);"))
    missing = Div(text=MISSING, name="missing", styles={"color": "#555555", "font-size": "0.85em"})
    side = column([number, uniform, notice, row(presets, sizing_mode="stretch_width",
                                                          styles={"flex-wrap": "wrap"}),
                   *sliders[:4], beta_mode, sliders[4], status, projector, missing],
                  sizing_mode="stretch_width", name="side")
    polar_panel, polar_content = later_tab(polar_tab(polar), "Polar (Fig. 11)", "polar")
    map_panel, map_content = later_tab(map_tab(regime_map), "Regime map (Fig. 5)", "map")
    tabs = Tabs(tabs=[TabPanel(child=_support_tab(figs), title="Support", name="tab-support"),
                      polar_panel, map_panel],
                name="tabs", sizing_mode="stretch_width", min_width=300)
    tabs.js_on_change("active", CustomJS(
        code="if (window.explorer) window.explorer._tab(cb_obj.active);"))
    roots = dict(heading=heading, headline=headline, side=side, tabs=tabs)
    return roots, dict(polar=polar_content, map=map_content)


#: Where each root goes (``_layout``'s, by name): separate roots, so that a new text in
#: the side column or the headline lays out that root alone, not the tabs' figures (Bokeh
#: lays out a root whole whenever a Div in it changes).
PAGE_TEMPLATE = """{% block contents %}
<div class="mp-page">
{{ embed(roots.heading) }}
{{ embed(roots.headline) }}
<div class="mp-body">
<div class="mp-side">{{ embed(roots.side) }}</div>
<div class="mp-main">{{ embed(roots.tabs) }}</div>
</div>
</div>
{% endblock %}
{% block postamble %}<style>
.mp-page { overflow-x: hidden; }
.mp-body { display: flex; flex-wrap: wrap; gap: 8px; }
.mp-side { flex: 1 1 280px; min-width: 280px; max-width: 400px; }
.mp-main { flex: 1000 1 300px; min-width: 300px; }
</style>{% endblock %}
"""


def _script(element_id: str, source: str, kind: str = "") -> str:
    """A ``<script>`` element whose source cannot end the element early."""
    if "</script" in source.lower():
        raise ValueError(f"{element_id}: the source contains '</script'")
    type_attr = f' type="{kind}"' if kind else ""
    return f'<script id="{element_id}"{type_attr}>\n{source}\n</script>\n'


#: A script or stylesheet loaded by address. Bokeh's inline resources add one for every
#: ``__javascript__``/``__css__`` of every model class registered in the process (Panel's
#: models once Panel is imported, e.g. es-module-shims), whether the page uses them or
#: not; this page uses Bokeh's own models only and loads nothing.
_FETCH = re.compile(r'<script\b[^>]*\bsrc="[^"]*"[^>]*>\s*</script>\s*'
                    r'|<link\b[^>]*\brel="stylesheet"[^>]*>\s*')


def _without_fetches(html: str) -> str:
    """``html`` without the script and stylesheet tags that load by address."""
    return _FETCH.sub("", html)


#: The keys of a dashboard link the offline page reads (its fragment, fragment.js); a
#: session's other settings (rtol, the averages, the Design tab's inputs...) need the server.
FRAGMENT_KEYS = ("regime", "k_r", "k_theta", "F_N", "theta0_deg", "beta", "tab", "projector",
                 "play")


def initial_fragment(query: dict) -> str:
    """The fragment the page opens in for a dashboard link's ``query`` (app.urlstate's keys):
    the keys it reads, in order (``#k_r=3&k_theta=0.01&...``); "" for none."""
    kept = [(k, str(query[k])) for k in FRAGMENT_KEYS if k in query]
    return "#" + urlencode(kept) if kept else ""


def page_html(fragment: str = "") -> str:
    """The whole page: Bokeh's document with BokehJS inlined, the kernel and the page code;
    it opens in the state of ``fragment`` (``#k_r=3&...``: a link's own fragment wins)."""
    if fragment and not fragment.startswith("#"):
        raise ValueError(f"fragment={fragment[:40]!r} must start with '#' (e.g. '#k_r=3')")
    html = _base_page()
    at = html.rfind('<script id="mp-config"')  # before the page's scripts, which read it
    return (html[:at] + _script("mp-initial", json.dumps(fragment).replace("</", "<\\/"),
                                "application/json") + html[at:])


@lru_cache(maxsize=1)
def _base_page() -> str:
    """The page without its initial state (built once per process: ~1 s)."""
    cfg = config()
    figs, polar, regime_map = views.support_figures(), views.polar_figures(), views.map_figure()
    cfg["maps"] = views.maps()
    cfg["projector"] = views.projector_styles(
        [figs["scene"], figs["forces"], figs["law"], figs["energy_fig"], *polar.values(),
         regime_map])
    doc = Document()
    roots, later = _layout(cfg, figs, polar, regime_map)
    for root in roots.values():
        doc.add_root(root)
    doc.title = TITLE
    mark_figures(doc)  # named and described for screen readers (PAGE_SCRIPT)
    figs["player"].install(doc)  # the player's keyboard shortcuts (no autoplay)
    html = _without_fetches(file_html(doc, resources=INLINE, title=TITLE,
                                      template=PAGE_TEMPLATE))
    here = resources.files(__package__)
    extra = (_script("mp-config", json.dumps(cfg).replace("</", "<\\/"), "application/json")
             + _script(LATER_ID, later_json(later, doc), "application/json")
             + "".join(_script(f"mp-{name}", (here / f"{name}.js").read_text(encoding="utf-8"))
                       for name in SCRIPTS)
             + _script("mp-bokeh-fix-apply", "MicropillarBokehFix.apply(window.Bokeh, "
                       f"{json.dumps(TESTED['bokeh'])});")  # before the first paint
             + PAGE_SCRIPT)  # slider handles and figures named for screen readers
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


def page_bytes(fragment: str = "") -> bytes:
    """``page_html(fragment)`` as UTF-8; ``ValueError`` when over ``MAX_BYTES``."""
    html = page_html(fragment).encode("utf-8")
    if len(html) > MAX_BYTES:
        raise ValueError(f"the offline page is {len(html):,} bytes, over the bound of "
                         f"{MAX_BYTES:,}")
    return html


def write(path, fragment: str = "") -> int:
    """Write the offline explorer to ``path`` (opening in ``fragment``'s state); returns
    its size in bytes.

    Raises ``ValueError`` when the page would exceed ``MAX_BYTES``."""
    html = page_bytes(fragment)
    Path(path).write_bytes(html)
    return len(html)
