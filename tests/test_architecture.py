"""The rules of the code's layout (docs/architecture.md).

* The dashboard's data flows one way: controls -> ``SessionResults`` -> views. A view
  module imports no other view module (only ``page`` composes them), a view is made from
  the state and the results alone, and it declares what it draws from
  (``param.depends`` on ``results.*`` / ``state.*``).
* Ordinary imports: nothing in app/ or tests/ edits the module search path or executes
  source files by path; ``app`` is imported by its installed name.
(``model/`` importing no GUI code is checked in tests/test_figures.py.)
"""
from __future__ import annotations

import ast
import inspect
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
VIEWS = ROOT / "app" / "views"
#: Modules of app/views that hold views (page.py composes them; widgets.py is helpers).
VIEW_MODULES = ("support", "array", "readouts", "polar", "arrays", "controls", "equations",
                "code", "export", "design")


def _python_files(*folders):
    for folder in folders:
        yield from sorted((ROOT / folder).rglob("*.py"))


def _imports(path: Path) -> set[str]:
    """Modules imported by ``path``, relative ones as written (``.support``, ``..state``)."""
    names = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            base = "." * node.level + (node.module or "")
            names.add(base)
            if node.level and not node.module:
                names.update("." * node.level + a.name for a in node.names)
        elif isinstance(node, ast.Import):
            names.update(a.name for a in node.names)
    return names


@pytest.mark.parametrize("path", list(_python_files("app", "tests")), ids=lambda p: str(
    p.relative_to(ROOT)))
def test_no_path_hacks(path):
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and node.attr == "path" and \
                isinstance(node.value, ast.Name) and node.value.id == "sys":
            parent_calls = [n for n in ast.walk(tree) if isinstance(n, ast.Call)
                            and isinstance(n.func, ast.Attribute)
                            and isinstance(n.func.value, ast.Attribute)
                            and n.func.value is node]
            assert not parent_calls, f"{path.name}:{node.lineno} edits the module search path"
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute):
            assert node.func.attr != "spec_from_file_location", (
                f"{path.name}:{node.lineno} loads a module from a source path")
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
            assert node.func.id != "exec", f"{path.name}:{node.lineno} calls exec"


def _module_graph(package: str) -> dict[str, set[str]]:
    """Module of ``package`` -> the modules of ``package`` it imports, anywhere in it
    (inside functions too: an import deferred to break a cycle is still a cycle)."""
    files = {}
    for path in sorted((ROOT / package).rglob("*.py")):
        parts = list(path.relative_to(ROOT).with_suffix("").parts)
        files[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    graph = {}
    for name, path in files.items():
        home = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
        found = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom):
                base = (home[:len(home) - node.level + 1] if node.level else [])
                target = ".".join(base + ([node.module] if node.module else []))
                # ``from package import module`` needs the module; a name, its module
                found |= {f"{target}.{a.name}" if f"{target}.{a.name}" in files else target
                          for a in node.names}
            elif isinstance(node, ast.Import):
                found |= {a.name for a in node.names}
        graph[name] = {m for m in found if m in files and m != name}
    return graph


@pytest.mark.parametrize("package", ["app", "model"])
def test_no_import_cycles(package):
    """Each module can be read after the modules it imports: no two import each other,
    directly or through others (``graphlib`` names the cycle)."""
    import graphlib

    try:
        tuple(graphlib.TopologicalSorter(_module_graph(package)).static_order())
    except graphlib.CycleError as error:
        pytest.fail(f"{package}/ has an import cycle: {' -> '.join(error.args[1])}")


@pytest.mark.parametrize("module", VIEW_MODULES)
def test_views_do_not_import_one_another(module):
    # A view may hold the export controls (``export``), which read only state and results.
    others = {f".{m}" for m in VIEW_MODULES if m not in (module, "export")} | {".page"}
    imported = _imports(VIEWS / f"{module}.py")
    assert not imported & others, f"views/{module}.py imports {imported & others}"


def test_views_are_made_from_state_and_results_only():
    from app import views
    from app.results import SessionResults
    from app.state import ExplorerState

    for name in ("SupportView", "ArrayView", "ReadoutsView", "PolarView", "RegimeMapView",
                 "LoadView", "DesignView"):
        cls = getattr(views, name)
        inputs = {p for p in cls.param if p != "name"}
        assert inputs == {"state", "results"}, (name, inputs)
        assert cls.param["state"].class_ is ExplorerState
        assert cls.param["results"].class_ is SessionResults
        signature = inspect.signature(cls.__init__)
        assert list(signature.parameters) == ["self", "params"], name


def test_views_declare_what_they_draw_from():
    """Every result a view shows reaches it through a declared dependency."""
    from app import views

    expected = {"SupportView": {"results.support", "results.busy", "state.projector"},
                "ReadoutsView": {"results.support", "results.uniform", "state.average"},
                "PolarView": {"results.polar", "results.support"},
                "RegimeMapView": {"results.regime_map", "state.k_r", "state.map_quantity"},
                "LoadView": {"results.load", "results.uniform", "state.F_N"},
                "ArrayView": {"results.array", "results.busy"},
                "DesignView": {"results.design_point", "results.design_array",
                               "results.design_polar", "results.design_optimum",
                               "state.dist_family", "state.dist_deg", "state.dist_kappa",
                               "state.dist_psi"}}
    for name, needed in expected.items():
        cls = getattr(views, name)
        declared = set()
        for attr in dir(cls):
            fn = getattr(cls, attr, None)
            deps = getattr(fn, "_dinfo", None)
            if deps:
                declared |= set(deps.get("dependencies", ()))
        assert needed <= declared, (name, needed - declared)


def test_results_own_every_computation():
    """Only app/results.py hands work to the worker pool; views never submit work."""
    for path in _python_files("app/views"):
        source = path.read_text()
        assert "work_pool" not in source and ".submit(" not in source, path.name


#: The serving layer: how pages reach browsers (the light page, the page gate, the server's
#: hooks and its guards on Panel's internals). The session layer -- state, results, their
#: slots, the views -- imports none of it and knows nothing of sockets or messages.
SERVING = ("edge", "opening", "pages", "app_hooks", "main", "healthcheck")
SESSION = ("app/state.py", "app/results.py", "app/slot.py", "app/compare.py", "app/views")
#: Words of the wire: a session-layer module that uses one reaches below Panel's API.
WIRE = ("PATCH-DOC", "send_message", "_socket", "session_context._session",
        "_subscribed_connections", "_pending_writes", "_held_events", "write_message")


@pytest.mark.parametrize("path", [p for f in SESSION for p in (
    [ROOT / f] if f.endswith(".py") else _python_files(f))], ids=lambda p: str(p.relative_to(ROOT)))
def test_the_session_layer_knows_nothing_of_serving(path):
    imported = _imports(path)
    serving = {name for name in imported
               if name.lstrip(".").split(".")[-1] in SERVING
               or any(name == f"app.{m}" for m in SERVING)}
    assert not serving, f"{path.relative_to(ROOT)} imports the serving layer: {serving}"
    source = path.read_text()
    assert not [w for w in WIRE if w in source], path.relative_to(ROOT)


def test_private_internals_are_touched_in_the_edge_module_only():
    """Panel, Bokeh, Tornado, param and concurrent.futures internals named by the app:
    only ``app/edge.py`` may, behind its version check (tests/test_edge.py)."""
    import re

    private = re.compile(r"_subscribed_connections|_pending_writes|_held_events|"
                         r"_change_callbacks|_set_session|send_message *=|DocHandler|"
                         r"parse_query *=|RequestHandler\.|_remove_control_chars|\._broken|"
                         r"\._processes|\._watch\(|default_view\.prototype|\._socket\b|"
                         r"\._session\b|Bokeh\.index|shadow_el|callbacks\._hold\b")
    # app/reproduce draws the paper's figures offline in a headless page (no server):
    # BokehJS's view index exports them as SVG there.
    found = [f"{p.relative_to(ROOT)}:{n}" for p in _python_files("app")
             if p.name != "edge.py" and p.parent.name != "reproduce"
             for n, line in enumerate(p.read_text().splitlines(), 1) if private.search(line)]
    assert found == []
