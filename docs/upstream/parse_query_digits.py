"""Panel: an address with a 4301-digit value breaks the session's sync.

Panel 1.9.4 parses the address of every served session: ``Location.from_request`` sets
``search``, which ``Location`` watches (``_update_synced``) and reads with
``panel.util.parse_query``, even when nothing is synced with the address. ``parse_query``
converts any all-digit value with ``int()``: Python refuses more than 4300 digits
(``sys.int_info``, CVE-2020-10735) and raises ``ValueError``. With ``pn.serve`` of a
function the page is not built at all (the traceback below, from ``server_doc`` ->
``_add_location``); in a ``panel serve`` script this project saw the page drawn without its
address model, and the widgets stopped syncing (``UnknownReferenceError`` in the log).
Expected: the value kept as a string (or left out) and the page working; the app never
asked for the address to be parsed.

Run: ``python docs/upstream/parse_query_digits.py``: opens the page with and without
``?x=`` + 4301 digits, moves a slider in the browser, and reports whether the page drew,
whether the server saw the move, and the errors logged.
Workaround in this project: none needed. The dashboard keeps the address itself
(``app/views/browser.py``) and is served with ``servable(location=False)`` (``app/main.py``),
Panel's public switch for its ``Location``: Panel then never parses the address.
"""
import logging
import time

import panel as pn

from harness import browser_page, served

SEEN = []
LOGGED = []


class Collect(logging.Handler):
    def emit(self, record):
        LOGGED.append(record.getMessage().splitlines()[0][:160])


def page():
    slider = pn.widgets.IntSlider(start=0, end=10, value=0, css_classes=["probe"])
    slider.param.watch(lambda e: SEEN.append(e.new), "value")
    return slider


MOVE = """() => { for (const m of Bokeh.documents[0].all_models)
  if (m.css_classes && m.css_classes.includes("probe")) { m.value = 7; return true; }
  return false; }"""

if __name__ == "__main__":
    for name in ("panel", "bokeh", "tornado"):
        logging.getLogger(name).addHandler(Collect(level=logging.ERROR))
    with served(page) as url, browser_page() as browser:
        for query in ("", "?x=" + "1" * 4301):
            SEEN.clear()
            LOGGED.clear()
            browser.goto(url + query)
            time.sleep(3.0)
            drawn = browser.evaluate("() => !!(window.Bokeh && Bokeh.documents.length)")
            if drawn:
                browser.evaluate(MOVE)
                time.sleep(1.5)
            print(f"address {'?x=<4301 digits>' if query else '(plain)'}: page drawn {drawn}; "
                  f"server saw {SEEN}; errors logged: {LOGGED[:2]}")
    print("REPRODUCED" if not SEEN or LOGGED else "not reproduced")
