"""A matplotlib figure laid out to fit its frame, for files of a fixed size (the slides'
animations, ``app.animation_export``): every title, label, legend and tick label inside the
picture, at any size a user asks for."""
from __future__ import annotations

import warnings

__all__ = ["outside", "fit_layout"]

#: Smallest font (pt) a text is shrunk to so that it fits the frame.
_MIN_FONT = 6.0


def outside(fig) -> list:
    """The visible texts of ``fig`` (titles, labels, ticks, legends) that cross its edge."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    frame = fig.bbox
    out, undrawn = [], set()
    for ax in fig.axes:  # tick labels beyond an axis' limits are not drawn
        for axis in (ax.xaxis, ax.yaxis):
            lo, hi = sorted(axis.get_view_interval())
            slack = 1e-9 * (hi - lo)
            undrawn.update(id(label) for tick in axis.get_major_ticks() + axis.get_minor_ticks()
                           if not lo - slack <= tick.get_loc() <= hi + slack
                           for label in (tick.label1, tick.label2))
    for text in fig.findobj(lambda a: hasattr(a, "get_text") and hasattr(a, "get_fontsize")):
        if not text.get_visible() or not text.get_text().strip() or id(text) in undrawn:
            continue
        box = text.get_window_extent(renderer)
        if box.x0 < frame.x0 - 0.5 or box.y0 < frame.y0 - 0.5 or \
                box.x1 > frame.x1 + 0.5 or box.y1 > frame.y1 + 0.5:
            out.append(text)
    return out


def fit_layout(fig) -> None:
    """Lay ``fig`` out once (matplotlib's constrained layout: titles, labels, legends and
    the colour bar inside the frame), shrinking a text that still crosses the edge (a
    title longer than a small frame is wide), then freeze it: the frames that follow
    change data only, so nothing jumps."""
    with warnings.catch_warnings():
        # A frame too small for the layout: the loop below shrinks the texts instead.
        warnings.filterwarnings("ignore", "constrained_layout not applied")
        _shrink_to_fit(fig)
        fig.canvas.draw()
    fig.set_layout_engine("none")


def _shrink_to_fit(fig) -> None:
    for _ in range(8):
        wide = outside(fig)
        if not wide:
            break
        for text in wide:
            text.set_fontsize(max(_MIN_FONT, 0.88 * text.get_fontsize()))
