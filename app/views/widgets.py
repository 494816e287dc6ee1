"""Widget keyword arguments that work across Panel 1.x: newer releases name a widget's
caption ``label`` and a button's look ``color``/``variant`` (``name``, ``button_type`` and
``button_style`` are deprecated there)."""
from __future__ import annotations

import panel as pn

_NEW = "label" in pn.widgets.FloatSlider.param and "variant" in pn.widgets.Button.param


def caption(text: str) -> dict:
    """The widget's visible caption."""
    return {"label": text} if _NEW else {"name": text}


def look(color: str = "default", variant: str = "solid") -> dict:
    """A button's colour (default, primary, warning, ...) and variant (solid, outline)."""
    return {"color": color, "variant": variant} if _NEW else {
        "button_type": color, "button_style": variant}
