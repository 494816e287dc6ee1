"""The load test's browser stand-in (``benchmarks/load_client.py``): how much of the
server's patches its copy of the page applies (``REPLICAS``)."""
from __future__ import annotations

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture
def lc(monkeypatch):
    monkeypatch.syspath_prepend(str(ROOT / "benchmarks"))
    import load_client

    return load_client


def _patch(lc, replica: str):
    """A client's copy of a two-text page, and the server's patch changing both texts."""
    from bokeh.document import Document
    from bokeh.models import Div

    server = Document()
    head, other = Div(text="θ₀ = 90°"), Div(text="unchanged")
    server.add_root(head)
    server.add_root(other)
    client = Document.from_json(server.to_json())
    events = []

    class Recorder:
        def _document_patched(self, event):
            events.append(event)

    server.callbacks.on_change_dispatch_to(Recorder())
    head.text, other.text = "θ₀ = 33°", "changed"
    message = lc.Session(0, "http://127.0.0.1:1", replica=replica).protocol.create(
        "PATCH-DOC", events)
    session = lc.Session(0, "http://127.0.0.1:1", replica=replica)
    session.doc = client
    session.watched = {head.id}
    session._apply(message, message.content["events"])
    return client.get_model_by_id(head.id).text, client.get_model_by_id(other.id).text


def test_a_watched_copy_applies_the_changes_it_reads_and_skips_the_rest(lc):
    assert _patch(lc, "watched") == ("θ₀ = 33°", "unchanged")


def test_a_full_copy_applies_every_change_as_bokehjs_does(lc):
    assert _patch(lc, "full") == ("θ₀ = 33°", "changed")


def test_an_unknown_replica_is_refused_with_the_choices(lc):
    with pytest.raises(ValueError, match=r"replica='half'.*full.*watched"):
        lc.Session(0, "http://127.0.0.1:1", replica="half")


def test_a_move_or_a_drag_never_ends_where_the_slider_already_was(lc):
    """A drag that ends where it began changes nothing on the server, which then sends
    nothing: the client would wait for an update that never comes. ``_position`` avoids
    the slider's current value and the drag's starting one."""
    from bokeh.models import Slider

    session = lc.Session(0, "http://127.0.0.1:1")
    session.sliders = {"theta0": Slider(start=0, end=3, step=1, value=1)}
    seen = {session._position("theta0", avoid=(2.0,)) for _ in range(200)}
    assert seen == {0.0, 3.0}


def test_in_the_drags_profile_every_move_is_a_theta0_drag(lc):
    """``--profiles class,drags``: each move drags theta0 over ``DRAG_STEPS`` positions and
    is timed from its last one, so a last position that never reaches the page is seen; only
    the last is sent as a drag's end."""
    import asyncio

    from bokeh.models import Slider

    session = lc.Session(0, "http://127.0.0.1:1")
    session.sliders = {name: Slider(start=0, end=359, step=1, value=90)
                       for name in ("theta0", "k_r", "k_theta", "F_N")}
    sent = []

    async def set_slider(name, value, end=True):
        sent.append((name, end))
        session.sliders[name].value = value
        return 0.0

    session._set = set_slider
    session._arrived = lambda name, value, pushes: True

    async def moves():
        for _ in range(5):
            await session.move(only_drags=True)
    asyncio.run(moves())
    assert "drags" in lc.PROFILES
    # As BokehJS: a drag's positions on the way without ``value_throttled``, its end with it.
    one_drag = [("theta0", False)] * (lc.DRAG_STEPS - 1) + [("theta0", True)]
    assert sent == one_drag * 5
    assert len(session.drag_latencies) == 5 and session.latencies == []
