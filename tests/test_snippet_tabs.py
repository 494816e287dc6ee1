"""Each tab's "This view as Python" (app/snippet_tabs.py) reproduces that tab: the snippet
is run in a fresh interpreter (with a smaller grid, where the tab's is large) and what it
computes is compared with what the page's workers give the tab."""
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from app import worker
from app.figures.arrays import map_column
from app.worker import array_params
from app.snippet import view_as_python
from app.state import ExplorerState

ROOT = Path(__file__).resolve().parents[1]


def run(code: str, tail: str, tmp_path) -> dict:
    """Run ``code`` then ``tail`` (which prints one JSON line) in a fresh interpreter."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-c", code + "\nimport json as _j\n" + tail],
                          capture_output=True, text=True, cwd=tmp_path, env=env, timeout=600)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1])


def smaller(code: str, old: str, new: str) -> str:
    assert code.count(old) == 1, old
    return code.replace(old, new)


@pytest.mark.parametrize("tab", ["map", "load", "array", "polar"])
def test_each_tab_has_its_own_snippet(tab):
    support = view_as_python(ExplorerState(tab="support"))
    code = view_as_python(ExplorerState(tab=tab))
    assert code != support and "simulate_support" not in code
    compile(code, "<snippet>", "exec")


@pytest.mark.parametrize("average", ["paper", "duration"])
def test_the_map_snippet_computes_the_tab_s_map(tmp_path, average):
    state = ExplorerState(tab="map", F_N=2.0, average=average)  # no shipped map: computed
    code = smaller(view_as_python(state), f"n = {worker.MAP_FINE_N}\n", "n = 3\n")
    got = run(code, "print(_j.dumps({'shown': shown.tolist(), 'k': list(k_r)}))", tmp_path)
    page = worker.compute_map(2.0, "self", 3)
    assert np.allclose(got["k"], page.k_r, rtol=1e-14)
    np.testing.assert_allclose(got["shown"], getattr(page, map_column("5a", average)),
                               rtol=1e-12)


def test_the_map_snippet_reads_the_shipped_map_where_the_page_does(tmp_path):
    state = ExplorerState(tab="map", F_N=1.0, map_quantity="5b")
    code = view_as_python(state)
    got = run(code, "print(_j.dumps({'shown': shown.tolist()}))", tmp_path)
    np.testing.assert_array_equal(got["shown"], worker.compute_map(1.0).Dy_over_Dx)


def test_the_load_snippet_computes_the_tab_s_curves(tmp_path):
    state = ExplorerState(tab="load", k_r=0.5, k_theta=0.2, average="duration")
    code = smaller(view_as_python(state), f"n = {len(worker.LOAD_F_N)}\n", "n = 2\n")
    code = smaller(code, "for name in ('pendulum', 'slider', 'stiff', 'soft'):",
                   "for name in ('pendulum',):")
    got = run(code, "print(_j.dumps({c: {repr(f): v for f, v in p.items()} "
                    "for c, p in shown.items()}))", tmp_path)
    loads = (0.1, 10.0)
    for curve, (k_r, k_theta) in {"current": (0.5, 0.2), "pendulum": (3.0, 0.01)}.items():
        page = worker.compute_load(k_r, k_theta, "self", loads=loads)
        for F_N in loads:
            assert got[curve][repr(F_N)] == pytest.approx(
                page[F_N]["FTx_over_mu0FN_duration"], rel=1e-12), (curve, F_N)


@pytest.mark.parametrize("orientation", ["uniform", "fixed"])
def test_the_array_snippet_computes_the_tab_s_array(tmp_path, orientation):
    state = ExplorerState(tab="array", k_r=0.5, k_theta=0.2, F_N=2.0, theta0=60.0,
                          orientation=orientation)
    code = smaller(view_as_python(state), f"n_frames = {worker.ARRAY_FRAMES}\n",
                   "n_frames = 20\n")
    got = run(code, "print(_j.dumps({'model': {k: (v if isinstance(v, str) else float(v)) "
                    "for k, v in motion.model.items()}, 'n': motion.n_supports, "
                    "'theta0': motion.theta0.tolist()}))", tmp_path)
    page = worker.compute_array_motion(array_params(state), orientation)
    assert got["n"] == page.n_supports
    np.testing.assert_allclose(got["theta0"], page.theta0, rtol=1e-14)
    for key, value in page.model.items():
        assert got["model"][key] == (value if isinstance(value, str) else
                                     pytest.approx(float(value), rel=1e-12)), key


def test_the_polar_snippet_computes_the_tab_s_sweep(tmp_path):
    state = ExplorerState(tab="polar", k_r=0.5, k_theta=0.2)
    # 8 cells of [0, pi]: their midpoints are every 9th of the page's 72.
    code = smaller(view_as_python(state), f"n = {worker.POLAR_N}\n", "n = 8\n")
    got = run(code, "print(_j.dumps({k: np.asarray(polar.columns[k], float).tolist() "
                    "for k in ('theta0', 'FTx_over_mu0FN', 'Dy_over_Dx')}))", tmp_path)
    page = worker.compute_polar(state.support, state.array_beta, state.rtol).columns
    for key, values in got.items():
        np.testing.assert_allclose(values, np.asarray(page[key], float)[4::9], rtol=1e-9,
                                   err_msg=key)
    assert math.isclose(got["theta0"][0], math.pi / 16)


def test_the_page_s_code_card_follows_the_tab():
    from app.results import SessionResults
    from app.views.code import CodeView

    state = ExplorerState()
    view = CodeView(state=state, results=SessionResults(state))
    view.card.collapsed = False
    for tab, call in (("map", "regime_map("), ("load", "uniform_array("),
                      ("array", "array_motion("), ("support", "simulate_support(")):
        state.tab = tab
        assert call in view.code.object, tab
    state.tab = "map"
    state.map_quantity = "5b"
    assert "Dy_over_Dx" in view.code.object
