"""Bokeh: every ``PATCH-DOC`` message makes a reference for every model of the document,
whatever the message holds, so a one-event message costs time in proportion to the page.

Bokeh 3.9.2. ``patch_doc.create`` builds ``Serializer(references=doc.models.synced_references)``
and ``Serializer.__init__`` makes ``{id(obj): obj.ref for obj in references}``: a ``Ref``
for each of the document's models, of which a message of property changes uses none
(its events name their models by reference directly). Expected: a reference made when
the encoder meets a model (``get_ref``), the set of synced models only looked up.

Run: ``python docs/upstream/patch_doc_reference_table.py``: documents of 1, 10 and 40
figures; one event (a range's ``start``) encoded into a PATCH-DOC with Bokeh's serializer
and with one that makes each reference when it is met (the two messages checked equal);
prints the median time per message. Here (2026-11-28, Bokeh 3.9.2): reproduced, 35 ->
1 400 models: 0.03 -> 0.70 ms per message with Bokeh's serializer, 0.02 -> 0.21 ms with the
references made as met.

Not worked around in this project: ``benchmarks/bench_messages.py`` measures it on the
dashboard's own page (533 models): ~0.2-0.4 ms of a move's ~0.8 ms message, ~1-4 % of the
~22 ms of server CPU a move costs (``benchmarks/served_moves.py``), too little for a
private touch (``app/edge.py`` keeps three).
"""
import statistics
import sys
import time

from bokeh.core.serialization import Serializer
from bokeh.document import Document
from bokeh.plotting import figure
from bokeh.protocol import Protocol
from bokeh.protocol.messages import patch_doc as _patch_doc_class  # noqa: F401 (loads it)

patch_doc_module = sys.modules["bokeh.protocol.messages.patch_doc"]


class AsMet(Serializer):
    """The same encoder, each synced model's reference made when it is met."""

    def __init__(self, *, references=frozenset(), **kwargs):
        super().__init__(**kwargs)
        self._synced = {id(model): model for model in references}

    def has_ref(self, obj) -> bool:
        return super().has_ref(obj) or id(obj) in self._synced

    def get_ref(self, obj):
        ref = super().get_ref(obj)
        if ref is None and id(obj) in self._synced:
            ref = obj.ref
            super().add_ref(obj, ref)
        return ref


def page(n_figures: int):
    doc = Document()
    figs = []
    for _ in range(n_figures):
        p = figure(width=200, height=150)
        p.line([0, 1, 2], [0, 1, 0])
        figs.append(p)
        doc.add_root(p)
    doc.models.flush_synced()  # as after the page was sent
    return doc, figs


def message_ms(doc, fig, serializer_class, repeats: int = 30):
    events = []
    doc.on_change(lambda event: events.append(event))
    times, contents = [], set()
    patch_doc_module.Serializer = serializer_class
    try:
        for i in range(repeats):
            events.clear()
            fig.x_range.start = float(i)
            start = time.perf_counter()
            msg = Protocol().create("PATCH-DOC", events)
            times.append((time.perf_counter() - start) * 1e3)
            contents.add(msg.content_json.replace(f"{float(i)}", "X"))
    finally:
        patch_doc_module.Serializer = Serializer
    return statistics.median(times), contents


if __name__ == "__main__":
    import bokeh
    print(f"Bokeh {bokeh.__version__}: one event per PATCH-DOC, median ms per message")
    flat = []
    for n in (1, 10, 40):
        doc, figs = page(n)
        plain, plain_json = message_ms(doc, figs[-1], Serializer)
        lazy, lazy_json = message_ms(doc, figs[-1], AsMet)
        assert plain_json == lazy_json, "the two messages differ"
        flat.append((plain, lazy))
        print(f"{len(doc.models):5d} models: Bokeh's serializer {plain:6.3f} ms, "
              f"references as met {lazy:6.3f} ms (same message)")
    grew = flat[-1][0] > 5 * flat[0][0]
    print("REPRODUCED: the time per message grows with the page" if grew
          else "not reproduced: the time per message does not grow with the page")
