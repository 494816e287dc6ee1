"""Panel: a widget change made in a browser reaches Python 50 ms after its message arrived,
although nothing arrives meanwhile to merge it with.

Panel 1.9.4 (Bokeh 3.9.2). In a served session, Panel's handler of a change from the
browser (``Syncable._server_change``) schedules the widget's update as a timeout callback
of ``Syncable._debounce`` = 50 ms, unless the property is one of the class's
``_priority_changes`` (only the Tabulator's ``data`` and ``filters``). Every slider key
press therefore waits 50 ms on an idle server before any computation can start; changes
arriving meanwhile are merged, which a drag may want, but a key press or a click does not.
Expected: no wait when nothing is pending (or a public setting for it), e.g. the widget
updated at the next tick, as for ``_priority_changes``.

Run: ``python docs/upstream/widget_change_debounce.py``. It builds a ``FloatSlider`` in a
document with a session (as a server's), applies a browser's change to its Bokeh model as
Bokeh's server does, and prints whether the widget saw it at once and the timeout the
update was scheduled with. No browser or server needed.
Workaround in this project (public API: Bokeh's ``Model.on_change`` on the slider's model,
which Bokeh calls as the message is applied): ``app/views/at_once.py``; in headless
Chromium on a 2-core machine a key press -> new orbit data went from ~128 to ~90 ms median.
"""
import threading
from types import SimpleNamespace

import panel as pn
from bokeh.document import Document
from panel.io.state import set_curdoc


def main() -> bool:
    request = SimpleNamespace(arguments={}, headers={}, cookies={})
    context = SimpleNamespace(id="a served session", request=request)
    doc = Document()
    doc._session_context = lambda: context  # as a server's session has it
    with set_curdoc(doc):
        pn.state._thread_id = threading.get_ident()  # the event loop's thread
        slider = pn.widgets.FloatSlider(start=0, end=10, value=1)
        model = slider.get_root(doc)
        doc.add_root(model)
        model.set_from_json("value", 7.0, setter=object())  # the browser's message
    waits = [cb.timeout for cb in doc.session_callbacks if hasattr(cb, "timeout")]
    print(f"panel {pn.__version__}: widget value right after the message: {slider.value} "
          f"(the browser sent 7.0); update scheduled in {waits} ms")
    reproduced = slider.value != 7.0 and any(w > 0 for w in waits)
    print("REPRODUCED" if reproduced else "not reproduced")
    return reproduced


if __name__ == "__main__":
    main()
