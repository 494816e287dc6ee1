"""Panel's default design with its parameters kept per component type and page
(``app.steady_design``): the page's models are the ones Panel's own design makes, the work
is done once per type and page, and a canary says when Panel keeps them itself."""
from __future__ import annotations

import contextlib
from pathlib import Path

import panel as pn
import pytest
from bokeh.models import ImportedStyleSheet
from panel.io.state import set_curdoc

from app.steady_design import SteadyNative, use_steady_design
from app.views.live_text import LiveHTML
from fakes import served_document


@contextlib.contextmanager
def designed(design):
    """Components made inside use ``design`` (``None``: Panel's default, ``Native``)."""
    before = pn.config.design
    pn.config.design = design
    try:
        yield
    finally:
        pn.config.design = before


ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture
def worked_out(monkeypatch):
    """The benchmark's count of the design parameters worked out (``WorkedOut``)."""
    monkeypatch.syspath_prepend(str(ROOT / "benchmarks"))
    from bench_steady_design import WorkedOut

    return WorkedOut


def page():
    """Components of the kinds the dashboard has, a text written in place among them."""
    live = LiveHTML(html="<p>first</p>", css_classes=["headline"])
    layout = pn.Column(
        pn.pane.Markdown("**a** table", stylesheets=["table { width: 100%; }"]),
        pn.widgets.FloatSlider(label="θ₀", start=0, end=90, value=10),
        live, pn.widgets.Button(label="Reset"),
        pn.Card(pn.pane.HTML("<p>inside</p>"), title="Numbers", collapsed=True),
        pn.Tabs(("One", pn.Row(pn.widgets.Toggle(label="play"))), ("Two", pn.Spacer())),
    )
    return layout, live


def styles(doc):
    """Each model's stylesheets as text (a URL or the CSS), the models in a stable order."""
    def text(sheet):
        return sheet.url if isinstance(sheet, ImportedStyleSheet) else str(sheet)
    return sorted((type(m).__name__, tuple(text(s) for s in m.stylesheets))
                  for m in doc.models if hasattr(m, "stylesheets"))


def built(design, served: bool):
    doc = served_document() if served else None
    with designed(design), set_curdoc(doc):
        layout, live = page()
        if doc is None:
            from bokeh.document import Document
            doc = Document()
        doc.add_root(layout.get_root(doc))
    return doc, layout, live


@pytest.mark.parametrize("served", [False, True], ids=["unserved", "served"])
def test_the_page_has_the_stylesheets_panels_own_design_gives_it(served):
    native, *_ = built(None, served)
    steady, *_ = built(SteadyNative, served)
    assert styles(steady) == styles(native)
    assert len(styles(steady)) > 10


def test_a_text_written_in_place_works_out_no_design_and_keeps_its_styles(worked_out):
    doc, _layout, live = built(SteadyNative, served=True)
    before = styles(doc)
    with set_curdoc(doc), worked_out() as seen:
        for i in range(5):
            live.html = f"<p>update {i}</p>"
    assert seen.count == 0
    assert styles(doc) == before
    assert live._models[doc.roots[0].ref["id"]][0].data.html == "<p>update 4</p>"


def test_new_stylesheets_given_to_a_component_reach_its_model_as_with_panels_design():
    found = {}
    for design in (None, SteadyNative):
        doc, _layout, live = built(design, served=False)
        live.stylesheets = ["p { color: teal; }"]
        model = live._models[doc.roots[0].ref["id"]][0]
        found[design] = [s.url if isinstance(s, ImportedStyleSheet) else str(s)
                         for s in model.stylesheets]
    assert found[SteadyNative] == found[None]
    assert "p { color: teal; }" in found[None]


def test_each_page_has_its_own_stylesheet_models():
    one, *_ = built(SteadyNative, served=True)
    two, *_ = built(SteadyNative, served=True)
    ids = [{s.id for m in doc.models if hasattr(m, "stylesheets")
            for s in m.stylesheets if isinstance(s, ImportedStyleSheet)} for doc in (one, two)]
    assert ids[0] and ids[1] and not ids[0] & ids[1]
    assert all(isinstance(m, ImportedStyleSheet) for m in one.models
               if m.id in ids[0])


def test_canary_panels_design_works_its_parameters_out_at_every_update(worked_out):
    """Fails the day Panel keeps a component's design parameters between updates
    (``docs/upstream/design_params_per_update.py``): then ``app/steady_design.py``, its
    install in ``app/app_hooks.py`` and this file can go."""
    doc, _layout, live = built(None, served=True)
    with set_curdoc(doc), worked_out() as seen:
        for i in range(4):
            live.html = f"<p>update {i}</p>"
    assert seen.count == 4


def test_the_servers_start_up_hook_installs_it(monkeypatch):
    import app.app_hooks as hooks

    monkeypatch.setattr(hooks, "quiet_diagnostics", lambda: False)
    monkeypatch.setattr(hooks, "install", lambda: True)
    monkeypatch.setattr(hooks, "start_warm_up", lambda: True)
    monkeypatch.setattr(pn.config, "authorize_callback", None)
    monkeypatch.setattr(pn.config, "design", None)
    hooks.on_server_loaded(None)
    assert pn.config.design is SteadyNative


def test_the_server_uses_it_unless_the_app_chose_a_design():
    with designed(None):
        use_steady_design()
        assert pn.config.design is SteadyNative
    from panel.theme import Material
    with designed(Material):
        use_steady_design()
        assert pn.config.design is Material
