"""The page's stylesheets: sizes that follow the window, projector mode and phones.

Figures fill the window: every tab lays its figures out in a CSS grid whose height is
the window's height less the page's top (header and headline, ``--mp-top``), and each
Bokeh figure stretches over its cell (``sizing_mode="stretch_both"``), so the plots grow
on a 1920 x 1080 projector and still fit a 1280 x 720 laptop without scrolling.

Widgets read their sizes from CSS variables set once on the page's root: projector mode
(``ROOT_PROJECTOR``) and narrow screens (the media query of ``ROOT_CSS``, phones
and small tablets up to ``NARROW_PX``) enlarge text, slider handles and buttons to touch
size (>= 44 px). Below ``NARROW_PX`` the controls fold above the plots and every grid has
one column, one plot per row.
"""
from __future__ import annotations

from ..figures.player import PLAY_FILL
from .browser import NARROW_PX

PHONE = f"@media (max-width: {NARROW_PX}px)"
WIDE = f"@media (min-width: {NARROW_PX + 1}px)"

#: The root's variables on a screen and in projector mode (``styles`` of the root).
ROOT_SCREEN = {"--bokeh-font-size": "13px", "font-size": "13px", "color": "#18191D",
               "--mp-top": "90px", "--mp-handle": "24px", "--mp-track": "8px",
               "--mp-button": "31px"}
ROOT_PROJECTOR = {"--bokeh-font-size": "18px", "font-size": "18px", "color": "#000000",
                  "--mp-top": "98px", "--mp-handle": "30px", "--mp-track": "12px",
                  "--mp-button": "44px", "--mp-side-direction": "column",
                  "--mp-side-width": "calc(100% - 8px)", "--mp-side-wide": "400px",
                  "--mp-card-header": "flex", "--mp-text-width": "clamp(250px, 22vw, 360px)",
                  "--mp-wrap": "1", "--mp-keys": "none"}

#: Colours of the page's text and controls where Bokeh's and Panel's defaults fall below
#: WCAG 2.1 AA contrast (4.5:1 for text; 3:1 for the focus ring against white): the
#: keyboard focus ring, a warning outline's text (the Reset button), a filled green button
#: (Play), an info notice's text and inline code.
UI_COLOURS = {"focus": "#005FCC", "warning_text": "#8A5300", "ok_fill": PLAY_FILL,
              "info_text": "#055160", "code_text": "#1F4E8C"}

#: Given to every shadow root of the page (``app.views.access.PageAccess``): a visible
#: focus ring on whatever the keyboard reaches, and the colours above.
ACCESS_CSS = f"""
:focus-visible {{ outline: 3px solid {UI_COLOURS['focus']} !important;
                  outline-offset: 2px !important; }}
.bk-btn-warning:not(:hover):not(:active):not(.bk-active) {{
  color: {UI_COLOURS['warning_text']} !important; border-color: {UI_COLOURS['warning_text']} !important; }}
.bk-btn-success {{ background-color: {UI_COLOURS['ok_fill']} !important;
                   border-color: {UI_COLOURS['ok_fill']} !important; color: #FFFFFF !important; }}
:host(.alert-info) {{ color: {UI_COLOURS['info_text']} !important; }}
code {{ color: {UI_COLOURS['code_text']} !important; }}
"""

#: Text for screen readers only: in the page, out of sight.
SR_ONLY_CSS = """
.sr-only { position: absolute !important; width: 1px; height: 1px; padding: 0; margin: -1px;
           overflow: hidden; clip: rect(0, 0, 0, 0); white-space: nowrap; border: 0; }
"""

#: On a phone a container may be narrower than its children's desktop sizes (Bokeh sets
#: ``min-width`` from them), so the page never scrolls sideways.
SHRINK_CSS = (f"{PHONE} {{ :host {{ min-width: 0 !important; max-width: 100vw; "
              "height: auto !important; flex: 0 0 auto !important; } }")

#: Projected, the headline (its two results in words) takes two lines, up to 1920 px and
#: beyond (``--mp-wrap`` is 1 in projector mode only).
ROOT_CSS = f"""
:host {{ width: 100%; }}
{WIDE} {{
  :host {{ --mp-top-extra: 30px; }}
}}
{PHONE} {{
  :host {{ max-width: 100vw !important; min-width: 0 !important; box-sizing: border-box;
           height: auto !important;
           --bokeh-font-size: 16px !important; font-size: 16px !important;
           --mp-handle: 44px !important; --mp-track: 12px !important;
           --mp-button: 44px !important; }}
}}
"""

#: The header: title and tab bar side by side; on a phone the tab bar wraps below.
HEADER_CSS = f"""
{PHONE} {{
  :host {{ flex-wrap: wrap !important; height: auto !important; min-width: 0 !important; }}
  .page-title {{ width: 100% !important; }}
  .tab-bar {{ width: calc(100vw - 20px) !important; }}
}}
"""

#: Sidebar and main area side by side; on a phone the controls fold above the plots.
BODY_CSS = f"""
{PHONE} {{
  :host {{ flex-direction: column !important; min-width: 0 !important;
           height: auto !important; flex: 0 0 auto !important; }}
  .sidebar {{ width: calc(100% - 8px) !important; max-height: none !important; }}
  .main-area {{ width: 100% !important; }}
}}
"""

#: The controls' card: a plain column on wide screens, a foldable card on phones and in
#: projector mode (fold the controls away and the plots take the screen).
SIDEBAR_CSS = f"""
{SHRINK_CSS}
{WIDE} {{
  .card-header {{ display: var(--mp-card-header, none) !important; }}
  :host {{ border: none !important; box-shadow: none !important; }}
}}
.card-header {{ min-height: var(--mp-button); font-size: 1.1em; }}
"""

#: Slider handles and tracks sized by the root's variables: at least 24 px (WCAG 2.5.8),
#: touch-size on phones.
SLIDER_CSS = """
.noUi-horizontal { height: var(--mp-track, 8px); }
.noUi-horizontal .noUi-handle {
  width: var(--mp-handle, 24px); height: var(--mp-handle, 24px);
  top: calc((var(--mp-track, 8px) - var(--mp-handle, 24px)) / 2 - 1px);
  right: calc(var(--mp-handle, 24px) / -2); border-radius: 50%;
}
.noUi-handle::before, .noUi-handle::after { display: none; }
.noUi-target {
  width: calc(100% - var(--mp-handle, 24px)) !important;
  margin-left: calc(var(--mp-handle, 24px) / 2) !important;
}
.bk-slider-title { font-size: var(--bokeh-font-size); }
"""

#: The animation player: buttons at least ``--mp-button`` high and sharing the width (its
#: own ``scale_buttons`` only magnifies them in place, so they overlap).
PLAYER_CSS = """
:host { height: auto !important; }
button {
  min-height: var(--mp-button, 31px) !important; max-width: none !important;
  flex: 1 1 0 !important; transform: none !important;
  font-size: var(--bokeh-font-size) !important;
}
"""

#: Buttons (presets, reset, tabs, downloads) at least ``--mp-button`` high; a button
#: group (the tab bar) wraps on a phone instead of running off the screen.
BUTTON_CSS = f"""
.bk-btn {{ min-height: var(--mp-button, 31px); font-size: var(--bokeh-font-size); }}
{PHONE} {{
  .bk-btn-group {{ flex-wrap: wrap; }}
  .bk-btn-group > .bk-btn {{ flex: 1 1 auto; }}
}}
"""


#: A button of a set width grows to hold its caption where the text is larger (projected,
#: 1.5 x) instead of letting it run over its neighbour.
FIT_TEXT_CSS = ":host { min-width: max-content !important; } .bk-btn { white-space: nowrap; }"


#: Text inputs, number inputs and menus touch-sized on a phone.
INPUT_CSS = (f"{PHONE} {{ .bk-input, .bk-btn {{ min-height: 44px !important; }} "
             # the number keypad replaces a number input's 18-px arrows on a phone
             f".bk-spin-wrapper {{ display: none !important; }} }}")


#: The page's top as the grids see it (header, notices, headline; two lines projected).
TOP = "(var(--mp-top, 90px) + var(--mp-wrap, 0) * var(--mp-top-extra, 0px))"


def projector_grid(rows: str, below: int, spans: dict | None = None,
                   columns: str | None = None) -> dict:
    """A grid's layout in projector mode (``grid_css(projector=...)``): ``rows`` whose
    first track(s) fill the window below the page's top, and ``below`` px more under the
    fold for the secondary figures; ``spans`` maps a child's CSS class to its placement
    (CSS declarations, e.g. ``"grid-row: 3;"``)."""
    return {"rows": rows, "below": below, "spans": spans or {}, "columns": columns}


def mode_classes(classes: list, projector: bool) -> list:
    """A view's CSS classes with ``projector`` added (projector mode) or removed."""
    return [c for c in classes if c != "projector"] + (["projector"] if projector else [])


def grid_css(columns: str, rows: str, spans: dict | None = None, phone_height: int = 360,
             min_height: int = 480, projector: dict | None = None) -> str:
    """A grid of figures ``columns`` x ``rows`` (CSS track lists) as tall as the window
    below the page's top; ``spans`` maps a child's CSS class to its ``grid-column``. On a
    phone: one column, every figure ``phone_height`` px high.

    ``projector`` (``projector_grid``) lays the grid out anew when the view carries the
    CSS class ``projector`` (projection on a wide screen): the main figure keeps the
    window's height, secondary figures go below the fold."""
    span = "".join(f".{cls} {{ grid-column: {col}; }}\n" for cls, col in (spans or {}).items())
    if projector:
        area = "".join(f"  :host(.projector) .{cls} {{ {rule} }}\n"
                       for cls, rule in projector["spans"].items())
        cols = (f"grid-template-columns: {projector['columns']};"
                if projector["columns"] else "")
        span += f"""{WIDE} {{
  :host(.projector) {{ {cols} grid-template-rows: {projector['rows']};
    height: calc(100vh - {TOP} + {projector['below']}px) !important;
    min-height: calc(100vh - {TOP} + {projector['below']}px); }}
{area}}}
"""
    return f"""
:host {{
  display: grid !important; grid-template-columns: {columns}; grid-template-rows: {rows};
  height: calc(100vh - {TOP}) !important;
  /* Never shrunk below the window by what follows it (the readouts below the plots in
     projector mode are a scroll away). */
  min-height: max({min_height}px, calc(100vh - {TOP}));
  width: 100% !important; gap: 2px 6px; align-items: stretch;
  flex: 0 1 auto !important;  /* its own height, not the tallest tab's */
}}
{span}
.figure, .bk-Figure {{ min-width: 0; min-height: 0; width: auto !important; height: auto !important; }}
{PHONE} {{
  :host {{ grid-template-columns: 100% !important; grid-template-rows: none !important;
           height: auto !important; min-height: 0; min-width: 0 !important;
           flex: 0 0 auto !important; }}
  .figure, .bk-Figure {{ height: {phone_height}px !important; }}
  .player-row {{ min-width: 0 !important; flex-wrap: wrap !important; height: auto !important;
                 min-height: 80px; }}
  {" ".join(f".{cls} {{ grid-column: 1; }}" for cls in (spans or {}))}
}}
"""


#: Beside a grid: a fixed-width column (the readouts: why the force drops) beside the
#: plots. Projected on a screen narrower than ``SIDE_WIDE_PX`` it moves below the plots
#: (the figures take the screen; the headline above them says the result); on a wider
#: one it stays in view beside them, wider (``--mp-side-wide``). On phones: below.
SIDE_WIDE_PX = 1600
SIDE_ROW_CSS = f"""
:host {{ width: 100% !important; flex-direction: var(--mp-side-direction, row) !important; }}
.side-column {{ width: var(--mp-side-width, 300px) !important; }}
@media (min-width: {SIDE_WIDE_PX}px) {{
  :host {{ flex-direction: row !important; }}
  .side-column {{ width: var(--mp-side-wide, 300px) !important; flex: 0 0 auto !important; }}
}}
{PHONE} {{
  :host {{ flex-direction: column !important; min-width: 0 !important;
           height: auto !important; flex: 0 0 auto !important; }}
  .side-column {{ width: calc(100% - 8px) !important; flex: 0 0 auto !important; }}
}}
"""
