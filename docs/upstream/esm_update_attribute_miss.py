"""Panel: every update of a custom component (``JSComponent``, ``ReactiveESM``) reads
attributes its Bokeh model does not have, and Bokeh answers each miss with close-match
suggestions (``difflib``) that nobody reads.

Panel 1.9.4, Bokeh 3.9.2. ``ReactiveESM._update_model`` enters
``freeze_doc(doc, model, msg)``, which reads ``getattr(model, key, None)`` for every key of
the message. A component's own parameters live on ``model.data``, not on ``model``, so each
read misses: ``HasProps.__getattr__`` then calls ``_raise_attribute_error_with_matches``,
which, with Bokeh's ``perform_error_diagnostics`` on (the default), runs
``difflib.get_close_matches`` over the model's property names to word an error that
``getattr``'s default swallows. Expected: the data model's keys looked up on the data
model (or the model's properties checked first), no exception raised.

Run: ``python docs/upstream/esm_update_attribute_miss.py``: a one-parameter
``JSComponent`` in a document, its text changed 200 times, with Bokeh's diagnostics on and
then off (``settings.perform_error_diagnostics``); prints the misses per update and the
median time per update. Here (2026-11-28): reproduced, 1 miss per update; see the numbers
it prints.

Worked around in this project with Bokeh's public setting: the served dashboard turns the
diagnostics off unless ``BOKEH_PERFORM_ERROR_DIAGNOSTICS`` is set (``app/app_hooks.py``,
``quiet_diagnostics``); ``benchmarks/bench_diagnostics.py`` measures what that saves on
the dashboard's page.
"""
import statistics

import panel as pn
from bokeh.core.has_props import HasProps
from bokeh.settings import settings

from harness import live_text, text_updates_ms


def updates(n: int = 200):
    """(misses per update, median ms per update) for ``n`` changes of a text."""
    live, _doc = live_text()
    misses = [0]
    raise_with_matches = HasProps._raise_attribute_error_with_matches

    def counted(self, name, properties):
        misses[0] += 1
        return raise_with_matches(self, name, properties)

    HasProps._raise_attribute_error_with_matches = counted
    try:
        times = text_updates_ms(live, n)
    finally:
        HasProps._raise_attribute_error_with_matches = raise_with_matches
    return misses[0] / n, statistics.median(times)


if __name__ == "__main__":
    import bokeh
    print(f"Panel {pn.__version__}, Bokeh {bokeh.__version__}: a JSComponent's text changed")
    found = {}
    try:
        for on in (True, False, True, False):
            settings.perform_error_diagnostics.set_value(on)
            found.setdefault(on, []).append(updates())
    finally:
        settings.perform_error_diagnostics.unset_value()
    for on, runs in found.items():
        miss = runs[-1][0]
        ms = statistics.median(t for _, t in runs)
        print(f"diagnostics {'on ' if on else 'off'}: {miss:.1f} attribute misses per update, "
              f"{ms:.3f} ms per update")
    print("REPRODUCED: each update reads attributes the model lacks" if found[True][-1][0] >= 1
          else "not reproduced: no attribute read misses")
