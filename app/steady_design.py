"""Panel's default design, its parameters worked out once per component type and page.

Panel (1.9.4) works out a component's design parameters (``Design.params``: the theme's
stylesheets, down to resolving their paths on disk) at every property update, whatever
changed (``docs/upstream/design_params_per_update.py``); they depend only on the type of
the component, the theme, the page's document and whether it is served
(``Design._get_modifiers``). ``SteadyNative`` is Panel's ``Native`` design, the look every
component has by default, that keeps what ``params`` found for a type and a page and hands
out copies: the same parameters, the same stylesheet models of the page.

Installed with Panel's public setting ``pn.config.design`` by the server's start-up hook
(``app/app_hooks.py``, ``use_steady_design``). Each text written in place at a slider move
(the headline, the regime's words, the live description, the page's address) is a
property update; ``benchmarks/bench_steady_design.py`` measures one update and one page
build with Panel's ``Native`` and with this. ``tests/test_steady_design.py`` checks that the
page's models are the same with either, and fails the day Panel keeps the parameters
itself (then this module and its install can go).
"""
from __future__ import annotations

import weakref

import panel as pn
from panel.theme.native import Native


def _is_served() -> bool:
    """Whether the current document is a served session's (``Design._get_modifiers``
    asks the same)."""
    doc = pn.state.curdoc
    return bool(doc is not None and doc.session_context)


def _copy(params: dict) -> dict:
    """A copy a caller may change (Panel adds to the dict and its lists)."""
    return {k: list(v) if isinstance(v, list) else dict(v) if isinstance(v, dict) else v
            for k, v in params.items()}


class SteadyNative(Native):
    """Panel's ``Native`` design; ``params`` worked out once per component type, page
    (document) and served or not, then copied."""

    def __init__(self, **params):
        super().__init__(**params)
        # Per page, held no longer than the page: a session's end detaches its models
        # (Bokeh's ``Document.destroy``), the stylesheet models kept here let go of it.
        self._found: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()

    def params(self, viewable, doc=None):
        if doc is None:  # no page to keep them for (Panel makes new stylesheet models)
            return super().params(viewable, doc)
        key = (type(viewable), _is_served())
        per_page = self._found.setdefault(doc, {})
        if key not in per_page:
            per_page[key] = super().params(viewable, doc)
        modifiers, child_modifiers = per_page[key]
        return _copy(modifiers), _copy(child_modifiers)


def use_steady_design() -> None:
    """Every component of this process made from now on uses ``SteadyNative``, unless
    the app chose another design."""
    if pn.config.design is None:
        pn.config.design = SteadyNative
