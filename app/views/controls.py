"""The controls (the issue's list, item 1): log-scale sliders for k_r, k_theta and F_N,
theta0 in degrees, the four regime presets (the one matching the current springs drawn
solid), reset, advanced options folded away, and the comparison: pin the current state
as "A" (drawn muted beside the current "B"), swap A and B, clear A.

Keys on a slider: the arrows step 0.05 decade on the log sliders (about 50 presses
across k_r) and 1° on θ₀; PageUp/PageDown a tenth of the range (``browser.PageBehaviour``).

Every widget carries a CSS class ``ctl-<name>`` (e.g. ``ctl-k_r``, ``preset-soft``,
``ctl-reset``) so tests and stylesheets can find it. Sliders follow ``value`` (not
``value_throttled``), so dragging and the arrow keys both update the page; the views
drop stale work.
"""
from __future__ import annotations

import math

import panel as pn
from bokeh.models import CustomJSTickFormatter

from ..state import PRESETS, ExplorerState, clamp
from .layout import BUTTON_CSS, SLIDER_CSS
from .widgets import caption, look

_LOG_FORMAT = "return Math.pow(10, tick).toPrecision(3)"
#: Arrow-key step of the log sliders, in decades.
LOG_STEP = 0.05


class LogLink:
    """A slider over log10 of a state parameter, kept in step with it both ways."""

    def __init__(self, state: ExplorerState, name: str, label: str, step: float = LOG_STEP):
        self.state, self.name = state, name
        lo, hi = state.param[name].bounds
        self.widget = pn.widgets.FloatSlider(
            **caption(label), start=math.log10(lo), end=math.log10(hi), step=step,
            value=math.log10(getattr(state, name)), format=CustomJSTickFormatter(code=_LOG_FORMAT),
            css_classes=[f"ctl-{name}"], sizing_mode="stretch_width", margin=(2, 10),
            stylesheets=[SLIDER_CSS])
        self._bounds = (lo, hi)
        self.widget.param.watch(self._to_state, "value")
        state.param.watch(self._to_widget, name)

    def _to_state(self, event) -> None:
        if abs(math.log10(getattr(self.state, self.name)) - event.new) > 1e-9:
            setattr(self.state, self.name, clamp(10 ** event.new, self._bounds))

    def _to_widget(self, event) -> None:
        if abs(self.widget.value - math.log10(event.new)) > 1e-9:
            self.widget.value = math.log10(event.new)


class Controls(pn.viewable.Viewer):
    """Sidebar: sliders, presets, reset, advanced options, projector mode."""

    def __init__(self, state: ExplorerState, extra=(), **params):
        super().__init__(**params)
        self.state = state
        self.k_r = LogLink(state, "k_r", "k_r  radial stiffness (log)")
        self.k_theta = LogLink(state, "k_theta", "k_θ  torsional stiffness (log)")
        self.F_N = LogLink(state, "F_N", "F_N  normal load (log)")
        self.theta0 = pn.widgets.FloatSlider.from_param(
            state.param.theta0, **caption("θ₀  rest orientation [°]"), start=0, end=359, step=1,
            css_classes=["ctl-theta0"], sizing_mode="stretch_width", margin=(2, 10),
            stylesheets=[SLIDER_CSS])
        self.presets = {
            name: pn.widgets.Button(**caption(name.capitalize()), css_classes=[f"preset-{name}"],
                                    **look("primary", "outline"),
                                    description=f"k_r = {k_r:g}, k_θ = {k_t:g}",
                                    sizing_mode="stretch_width", margin=(2, 3),
                                    stylesheets=[BUTTON_CSS])
            for name, (k_r, k_t) in PRESETS.items()}
        for name, button in self.presets.items():
            button.on_click(lambda _event, name=name: state.apply_preset(name))
        self._marked = ()  # the preset drawn solid (None: none); () before the first
        state.param.watch(self._mark_preset, ["k_r", "k_theta"])
        self.reset = pn.widgets.Button(**caption("Reset"), css_classes=["ctl-reset"],
                                       **look("warning", "outline"),
                                       description="the physics back to its defaults (the tab and projector mode stay)",
                                       sizing_mode="stretch_width", margin=(2, 3),
            stylesheets=[BUTTON_CSS])
        self.reset.on_click(lambda _event: state.reset())
        self.projector = pn.widgets.Toggle.from_param(
            state.param.projector, **caption("Projector mode"), css_classes=["ctl-projector"],
            **look("default"), sizing_mode="stretch_width", margin=(2, 3),
            stylesheets=[BUTTON_CSS])
        self.rtol = pn.widgets.Select.from_param(
            state.param.rtol, **caption("Solver tolerance rtol"), css_classes=["ctl-rtol"],
            sizing_mode="stretch_width", margin=(2, 10))
        self.beta_mode = pn.widgets.RadioButtonGroup.from_param(
            state.param.beta_mode, css_classes=["ctl-beta_mode"],
            options={"β self-consistent": "self", "β fixed": "fixed"},
            sizing_mode="stretch_width", margin=(2, 10))
        self.beta = pn.widgets.FloatSlider.from_param(
            state.param.beta, **caption("fixed β = N_c0/N_c"), start=0.05, end=1.0, step=0.01,
            css_classes=["ctl-beta"], sizing_mode="stretch_width", margin=(2, 10),
            disabled=state.beta_mode == "self")
        state.param.watch(lambda e: setattr(self.beta, "disabled", e.new == "self"), "beta_mode")
        self.average = pn.widgets.RadioButtonGroup.from_param(
            state.param.average, css_classes=["ctl-average"],
            options={"paper (Eq. 10)": "paper", "duration-weighted": "duration"},
            sizing_mode="stretch_width", margin=(2, 10))
        self.advanced = pn.Card(  # one column: see ReadoutsView.details
            pn.Column(self.rtol, pn.pane.Markdown("Load factor β = N_c0/N_c", margin=(0, 10)),
                      self.beta_mode, self.beta,
                      pn.pane.Markdown("Uniform-array average", margin=(0, 10)), self.average,
                      sizing_mode="stretch_width", margin=0),
            title="Advanced options", collapsed=True, css_classes=["ctl-advanced"],
            sizing_mode="stretch_width", margin=(4, 3))
        self.pin = self._button("Pin as A", "ctl-pin", "primary",
                                "keep the current state as A, drawn muted beside what "
                                "you explore next (B)", state.pin)
        self.swap = self._button("Swap A↔B", "ctl-swap", "default",
                                 "exchange the pinned state A and the current state B",
                                 state.swap_pin)
        self.clear = self._button("Clear A", "ctl-clear", "default", "stop comparing",
                                  state.clear_pin)
        self.pinned_text = pn.pane.Markdown("", css_classes=["ctl-pinned"], margin=(0, 10),
                                            styles={"font-size": "0.85em"})
        state.param.watch(self._show_pinned, "pinned")
        self._extra = list(extra)
        self._mark_preset()
        self._show_pinned()

    @staticmethod
    def _button(label, css, color, description, action):
        button = pn.widgets.Button(**caption(label), css_classes=[css], **look(color, "outline"),
                                   description=description, sizing_mode="stretch_width",
                                   margin=(2, 3), stylesheets=[BUTTON_CSS])
        button.on_click(lambda _event: action())
        return button

    def _show_pinned(self, *_events) -> None:
        a = self.state.pinned
        self.swap.disabled = self.clear.disabled = a is None
        self.pinned_text.object = (
            "Nothing pinned: pin a state to compare it with the next." if a is None else
            f"**A**: k_r = {a['k_r']:.3g}, k_θ = {a['k_theta']:.3g}, F_N = {a['F_N']:.3g}, "
            f"θ₀ = {a['theta0']:g}° (dashed, grey)")

    @property
    def sliders(self) -> list:
        """The physics' sliders (Panel widgets), each with its own ``ctl-`` CSS class."""
        return [self.theta0, self.k_r.widget, self.k_theta.widget, self.F_N.widget]

    def _mark_preset(self, *_events) -> None:
        """Draw the preset of the current springs solid, the others as outlines (the
        buttons are restyled only when the preset matched changes, not at every move)."""
        active = self.state.matching_preset()
        if active == self._marked:
            return
        self._marked = active
        for name, button in self.presets.items():
            button.param.update(**look("primary", "solid" if name == active else "outline"))

    def __panel__(self):
        names = list(self.presets)
        return pn.Column(
            self.k_r.widget, self.k_theta.widget, self.F_N.widget, self.theta0,
            pn.pane.Markdown("**Regimes** (Fig. 6)", margin=(0, 10)),
            pn.Row(*(self.presets[n] for n in names[:2]), sizing_mode="stretch_width"),
            pn.Row(*(self.presets[n] for n in names[2:]), sizing_mode="stretch_width"),
            pn.Row(self.reset, self.projector, sizing_mode="stretch_width"),
            pn.pane.Markdown("**Compare** two states", margin=(4, 10, 0, 10)),
            pn.Row(self.pin, self.swap, self.clear, sizing_mode="stretch_width"),
            self.pinned_text,
            self.advanced, *self._extra,
            sizing_mode="stretch_width", css_classes=["controls"])
