"""The notebooks of ``examples/`` execute (nbclient, a python3 kernel) and are stored
without outputs; the dashboard displays in a notebook.

Each notebook checks its own numbers with ``assert`` cells, so an execution error here is
a wrong result there, not only a crash. The dashboard is a ``pn.viewable.Viewer``: in a
notebook it is displayed through its MIME bundle (Panel's ``_repr_mimebundle_``).
"""
import os
import time
from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "examples").glob("*.ipynb"))
#: Seconds one notebook may take (each runs in a few seconds on a quiet 2-core machine).
BUDGET_S = 120
#: What Bokeh's ``show`` and a displayed HoloViews element leave in a notebook's outputs.
BOKEH_MIME = "application/vnd.bokehjs_exec.v0+json"
HOLOVIEWS_MIME = "application/vnd.holoviews_exec.v0+json"


def test_the_examples_are_there():
    assert {p.name for p in NOTEBOOKS} >= {"api_tour.ipynb", "design_study.ipynb",
                                           "lab_friction.ipynb"}


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_stored_without_outputs(path):
    nb = nbformat.read(path, as_version=4)
    nbformat.validate(nb)
    for cell in nb.cells:
        if cell.cell_type == "code":
            assert cell.outputs == [] and cell.execution_count is None, (
                f"{path.name}: clear the outputs before committing")


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_the_notebook_executes(path, monkeypatch):
    # The kernel imports this tree's model/app (as the suite does), and uses the suite's
    # private disk cache (set in conftest.py) through the inherited environment.
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join(
        [str(ROOT), *filter(None, [os.environ.get("PYTHONPATH")])]))
    nb = nbformat.read(path, as_version=4)
    client = NotebookClient(nb, timeout=BUDGET_S, kernel_name="python3",
                            resources={"metadata": {"path": str(path.parent)}})
    start = time.perf_counter()
    client.execute()
    seconds = time.perf_counter() - start
    assert seconds < BUDGET_S
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    text = "".join(o.get("text", "") for o in outputs if o.output_type == "stream")
    assert "Traceback" not in text and text.strip(), f"{path.name} printed nothing"
    figures = [o for o in outputs if {BOKEH_MIME, HOLOVIEWS_MIME} & set(o.get("data", {}))]
    assert figures, f"{path.name}: no figure was displayed"


# --------------------------------------------------------------------------- the dashboard

@pytest.fixture(scope="module")
def dashboard():
    import panel as pn

    from app.state import ExplorerState
    from app.views import Dashboard

    pn.extension()  # as a notebook's first cell does
    return Dashboard(ExplorerState())


def test_the_dashboard_displays_in_a_notebook(dashboard):
    bundle = dashboard._repr_mimebundle_()
    data, _metadata = bundle if isinstance(bundle, tuple) else (bundle, {})
    assert "text/html" in data or "application/vnd.holoviews_exec.v0+json" in data, data.keys()
    import panel as pn

    from bokeh.models import Plot

    root = pn.panel(dashboard).get_root()
    assert list(root.select({"type": Plot})), "the page's figures are part of what is shown"


@pytest.mark.parametrize("tab, name, plots", [
    (None, "support", 1), (None, "readouts", 0), ("polar", "polar", 1),
    ("map", "regime_map", 1), ("load", "load", 1), ("equations", "equations", 0)])
def test_each_view_displays_on_its_own(dashboard, tab, name, plots):
    import panel as pn
    from bokeh.models import Plot

    if tab is not None:
        dashboard.state.tab = tab  # the page builds a tab's view when it is first shown
    view = getattr(dashboard, name)
    bundle = pn.panel(view)._repr_mimebundle_()
    data = bundle[0] if isinstance(bundle, tuple) else bundle
    assert "text/html" in data or "application/vnd.holoviews_exec.v0+json" in data, name
    root = pn.panel(view).get_root()
    assert len(list(root.select({"type": Plot}))) >= plots, name
    assert dashboard.results.errors == {}, dashboard.results.errors


@pytest.mark.slow
def test_the_dashboard_computes_inside_a_kernel(monkeypatch):
    """In a real notebook kernel the page displays and its worker processes compute."""
    from nbformat.v4 import new_code_cell, new_notebook

    monkeypatch.setenv("PYTHONPATH", os.pathsep.join(
        [str(ROOT), *filter(None, [os.environ.get("PYTHONPATH")])]))
    nb = new_notebook(cells=[
        new_code_cell("import panel as pn\nfrom app.views import Dashboard\n"
                      "pn.extension()\npage = Dashboard()\npage"),
        new_code_cell("r = page.results\nprint(r.support.result.success, "
                      "r.uniform['FTx_over_mu0FN'], r.errors)")])
    NotebookClient(nb, timeout=BUDGET_S, kernel_name="python3").execute()
    shown = nb.cells[0].outputs[-1]
    assert shown.output_type == "execute_result"
    assert "application/vnd.holoviews_exec.v0+json" in shown.data
    success, value, errors = nb.cells[1].outputs[0].text.split(" ", 2)
    # The default springs (pendulum, F_N = 1): F_T,x/(mu0 F_N) = 0.945 (test_app_state).
    assert success == "True" and abs(float(value) - 0.945) < 0.01 and errors.strip() == "{}"


def test_the_page_is_still_servable(dashboard):
    """``app/main.py`` serves the same ``Dashboard`` with ``.servable()`` (the browser tests
    serve it); outside a server ``servable`` hands the page back, displayable as above."""
    import panel as pn

    served = dashboard.servable(title="Micropillar friction explorer")
    assert isinstance(served, pn.viewable.Viewable)
    assert pn.panel(served).get_root() is not None
