"""Keyboard equivalents of "click to set" on a figure (WCAG 2.1.1): labelled buttons
beside the figure, reached with Tab and pressed with Enter or Space, that do what a
click does.

* ``map_steps``: the regime map (Fig. 5) -- a click there sets (k_r, k_theta); the
  buttons move the current springs (the ⊕) one cell of the map on show along k_r or
  k_theta (``ExplorerState.set_stiffness``, which clamps into the sliders' range);
* ``theta_steps``: the polar diagrams (Fig. 11) -- a click sets theta0 to the clicked
  angle; the buttons turn theta0 by 1° or 15° (``ExplorerState.set_theta0``).
"""
from __future__ import annotations

import panel as pn

from ..state import ExplorerState
from .layout import BUTTON_CSS, FIT_TEXT_CSS
from .widgets import caption, look

#: A map cell when no map is there yet: the shipped maps' 24 cells over [0.01, 3].
DEFAULT_CELL = (3.0 / 0.01) ** (1 / 23)
#: theta0 steps of the polar diagrams' buttons [°].
THETA_STEPS = (-15, -1, 1, 15)


def map_cell(regime_map) -> float:
    """The ratio of neighbouring cells of ``regime_map`` (log grid), or ``DEFAULT_CELL``."""
    k = getattr(regime_map, "k_r", None)
    if k is None or len(k) < 2:
        return DEFAULT_CELL
    return (float(k[-1]) / float(k[0])) ** (1 / (len(k) - 1))


def _button(label: str, css: str, action, tip: str) -> pn.widgets.Button:
    button = pn.widgets.Button(**caption(label), description=tip, **look("default", "outline"),
                               css_classes=["click-key", css], margin=(2, 3), width=64,
                               stylesheets=[BUTTON_CSS, FIT_TEXT_CSS])
    button.on_click(lambda _: action())
    return button


def _wrapping(buttons) -> pn.FlexBox:
    """The buttons in a row that wraps where the column is narrow (projected text is larger)."""
    return pn.FlexBox(*buttons, flex_wrap="wrap", margin=(0, 7), sizing_mode="stretch_width")


def map_steps(state: ExplorerState, cell) -> pn.Column:
    """Buttons that move the springs one map cell (``cell()``: its ratio, read when
    pressed), as a click on the map would set them."""
    def step(d_r: int, d_theta: int):
        factor = cell()
        state.set_stiffness(state.k_r * factor ** d_r, state.k_theta * factor ** d_theta)
    buttons = [_button(label, f"map-key-{name}", lambda d=d: step(*d), tip)
               for label, name, d, tip in (
                   ("k_r −", "kr-down", (-1, 0), "smaller k_r: the ⊕ one cell left"),
                   ("k_r +", "kr-up", (1, 0), "larger k_r: the ⊕ one cell right"),
                   ("k_θ −", "kt-down", (0, -1), "smaller k_θ: the ⊕ one cell down"),
                   ("k_θ +", "kt-up", (0, 1), "larger k_θ: the ⊕ one cell up"))]
    return pn.Column(pn.pane.Markdown("Move ⊕ one cell (as a click on the map):",
                                      margin=(0, 10), styles={"font-size": "0.92em"}),
                     _wrapping(buttons), margin=0, css_classes=["map-keys"])


def theta_steps(state: ExplorerState) -> pn.Column:
    """Buttons that turn theta0, as a click on a polar diagram sets it."""
    buttons = [_button(f"θ₀ {'+' if d > 0 else '−'}{abs(d)}°", f"theta-key-{d}",
                       lambda d=d: state.set_theta0(state.theta0 + d),
                       f"turn θ₀ by {d:+d}° (the marked point moves round the diagrams)")
               for d in THETA_STEPS]
    return pn.Column(pn.pane.Markdown("Turn θ₀ (as a click on a diagram):", margin=(0, 10),
                                      styles={"font-size": "0.92em"}),
                     _wrapping(buttons), margin=0, css_classes=["theta-keys"])
