"""Panel: every property update of a component works out its design's parameters again
(``Design.params``), down to resolving the theme's stylesheet paths on disk, although an
update that changes no style cannot change them.

Panel 1.9.4. ``Reactive._update_properties`` starts with ``self._design.params(self, doc)``
at every update, whatever changed; ``Design._get_modifiers`` then reads the theme's
``base_css``/``css`` (``param.Filename``: resolved against the search paths, an
``os.path.isfile`` each time) and builds the stylesheet list anew, which is used only when
``stylesheets`` is among the changes. Expected: the design's parameters worked out when the
model is made and when the design, the theme or the stylesheets change.

Run: ``python docs/upstream/design_params_per_update.py``: a one-parameter ``JSComponent``
(the default design) in a document, its text changed 300 times; prints the median time
per update, the calls of ``Design.params`` and the time in them, and the files looked up
on disk per update. Here (2026-11-28): reproduced, 1 call and 1 file looked up per
update, ~0.1 ms of ~0.33 ms per update.

Worked around in this project through Panel's public setting ``pn.config.design``: the
served dashboard's components use ``app.steady_design.SteadyNative``, Panel's ``Native``
design keeping what ``params`` found per component type and page. A served slider move
updates ~6-7 components (its texts written in place, its address, the downloads);
``benchmarks/bench_steady_design.py`` measures a move and a page build with each design,
``tests/test_steady_design.py`` fails the day Panel keeps the parameters itself.
"""
import os
import statistics
import time

import panel as pn
from panel.theme.base import Design

from harness import live_text, text_updates_ms


def updates(n: int = 300) -> dict:
    """Per update of the text: median ms, ``Design.params`` calls and ms, files looked up."""
    live, _doc = live_text()
    seen = {"calls": 0, "seconds": 0.0, "files": 0}
    design_params, isfile = Design.params, os.path.isfile

    def timed(self, *args, **kwargs):
        start = time.perf_counter()
        try:
            return design_params(self, *args, **kwargs)
        finally:
            seen["calls"] += 1
            seen["seconds"] += time.perf_counter() - start

    def counted(path):
        seen["files"] += 1
        return isfile(path)

    Design.params, os.path.isfile = timed, counted
    try:
        times = text_updates_ms(live, n)
    finally:
        Design.params, os.path.isfile = design_params, isfile
    return {"ms": statistics.median(times), "calls": seen["calls"] / n,
            "design_ms": seen["seconds"] / n * 1e3, "files": seen["files"] / n}


if __name__ == "__main__":
    found = updates()
    print(f"Panel {pn.__version__}: a JSComponent's text changed; per update "
          f"{found['ms']:.3f} ms (median), Design.params {found['calls']:.1f} calls taking "
          f"{found['design_ms']:.3f} ms, {found['files']:.1f} files looked up on disk")
    print("REPRODUCED: the design's parameters are worked out at every update"
          if found["calls"] >= 1 else "not reproduced: no design work per update")
