"""Panel: a pane inside a collapsed ``Card`` whose text changes is sent ``visible: true``
with each change; the card hides it again in the browser and sends ``visible: false``
back, and the page is laid out again both times.

Panel 1.9.4 (Bokeh 3.9.2). A folded Card hides its children by setting their model's
``visible`` in the page (``CardView._set_child_visible``); the change goes back to the
server, where the pane's ``visible`` parameter is still True. The next change of the pane's
``object`` updates its model with its parameters, ``visible`` among them, so the browser
gets ``visible: true``, the card hides the child again, and the value travels back: two
extra messages and two layouts of the whole page per change (~0.4 s per update on a
~450-model page in headless Chromium, most of a slider move's time in the browser).
Expected: a folded card's child whose text changes stays hidden without a round trip.

Run: ``python docs/upstream/card_child_visible_round_trip.py``: it changes the pane's text
``CHANGES`` times and counts the ``visible`` changes on the websocket, both ways.
Workaround in this project (public API): a card's content is one ``pn.Column`` that never
changes (``app/views/readouts.py``, ``app/views/controls.py``); the card toggles the
column, and the panes inside it are left alone
(``tests/browser/test_dashboard.py::test_a_slider_move_shows_or_hides_nothing``).
"""
import time

import panel as pn

from harness import browser_page, served

CHANGES = 5


def page():
    text = pn.pane.Markdown("value 0", css_classes=["changing"])
    card = pn.Card(text, title="details", collapsed=True)
    button = pn.widgets.Button(name="change", css_classes=["change"])
    button.on_click(lambda _e: setattr(text, "object", f"value {time.time():.3f}"))
    return pn.Column(button, card)


if __name__ == "__main__":
    frames = []
    with served(page) as url, browser_page() as browser:
        browser.on("websocket", lambda ws: (
            ws.on("framesent", lambda p: frames.append((">", p)) if isinstance(p, str) else None),
            ws.on("framereceived", lambda p: frames.append(("<", p)) if isinstance(p, str) else None)))
        browser.goto(url)
        time.sleep(3.0)
        start = len(frames)
        for _ in range(CHANGES):
            browser.locator(".change button").click()
            time.sleep(1.0)
        toggles = [d for d, f in frames[start:] if '"attr":"visible"' in f.replace(" ", "")]
    print(f"{CHANGES} text changes: {toggles.count('<')} 'visible' sent to the page, "
          f"{toggles.count('>')} sent back")
    print("REPRODUCED" if toggles else "not reproduced")
