"""The offline explorer's drawing code (app/offline/views.js) against the dashboard's
Python figures it ports (app/figures, app/views/readouts): Node runs the JavaScript, the
Python functions draw the same data, and every source column must agree.

Also: the page's configuration from the model (the shipped maps, the player's frames, the
projector look) is the dashboard's. Node (v18+) is needed; without it the tests skip.
"""
from __future__ import annotations

import json
import math
import subprocess
from importlib import resources

import numpy as np
import pytest

from app.figures import histories, live_energy, polar, scene
from app.offline import figures as offline_figures
from model import Params
from model.contact.friction import mu0
from model.contact.results import TimeSeries
from model.runs.shipped_map import SHIPPED_LOADS, load_regime_map

from test_offline_kernel import _node

VIEWS = resources.files("app.offline") / "views.js"
KERNEL = resources.files("app.offline") / "kernel.js"
RUNNER = """
const V = require(process.argv[1]), K = require(process.argv[2]);
let text = "";
process.stdin.on("data", (c) => { text += c; });
process.stdin.on("end", () => {
  const calls = JSON.parse(text);
  const out = calls.map(([lib, fn, args]) => (lib === "K" ? K : V)[fn](...args));
  process.stdout.write(JSON.stringify(out, (k, v) => (v instanceof Float64Array ? Array.from(v)
    : (typeof v === "number" && !isFinite(v) ? String(v) : v))));
});
"""
CONSTANTS = offline_figures.constants()


def js(calls):
    """Results of [(library "V" or "K", function, args), ...] run in one Node process."""
    done = subprocess.run([_node(), "-e", RUNNER, str(VIEWS), str(KERNEL)],
                          input=json.dumps(calls), text=True, capture_output=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout, parse_constant=float)


def _num(x):
    return float(x) if isinstance(x, str) else x  # "NaN", "Infinity" from JSON


def assert_same(js_cols: dict, py_cols: dict, where: str, rel=1e-12, abs_=1e-12):
    assert set(js_cols) == set(py_cols), (where, set(js_cols) ^ set(py_cols))
    for key, want in py_cols.items():
        got = js_cols[key]
        want = list(want) if not isinstance(want, list) else want
        assert len(got) == len(want), (where, key)
        for g, w in zip(got, want):
            if isinstance(w, (list, np.ndarray)):
                np.testing.assert_allclose(np.asarray(g, float), np.asarray(w, float),
                                           rtol=rel, atol=abs_, err_msg=f"{where}.{key}")
            elif isinstance(w, str):
                assert g == w, (where, key, g, w)
            else:
                g, w = _num(g), float(w)
                if math.isnan(w):
                    assert math.isnan(g), (where, key)
                else:
                    assert g == pytest.approx(w, rel=rel, abs=abs_), (where, key)


STATES = [dict(k_r=3, k_theta=0.01, F_N=1, theta0=math.pi / 2),      # pendulum
          dict(k_r=0.01, k_theta=3, F_N=1, theta0=math.radians(60)),  # slider: stretched
          dict(k_r=0.03, k_theta=0.03, F_N=3, theta0=math.radians(200))]


@pytest.fixture(scope="module")
def contacts():
    """The JavaScript kernel's contacts (with their series) and the views of each."""
    calls = []
    for s in STATES:
        calls.append(("K", "simulate", [{**s, "samples": CONSTANTS["support_samples"]}]))
    results = js(calls)
    views = js([c for r in results for c in (
        ("V", "sceneData", [r["series"], r["params"]["theta0"], CONSTANTS]),
        ("V", "viewBox", [r["series"], CONSTANTS]),
        ("V", "supportFrames", [r["series"], r["params"], CONSTANTS]),
        ("V", "energyFrames", [r["series"], CONSTANTS]),
        ("V", "forceXRange", [r["series"]]),
        ("V", "forceYRange", [r["series"], mu0()]))])
    return [(r, views[6 * i: 6 * i + 6]) for i, r in enumerate(results)]


def _series(r) -> TimeSeries:
    return TimeSeries(**{k: np.asarray(v, float) for k, v in r["series"].items()})


def _params(r) -> Params:
    p = r["params"]
    return Params(k_r=p["k_r"], k_theta=p["k_theta"], F_N=p["F_N"], theta0=p["theta0"])


def test_the_support_views_are_the_dashboards(contacts):
    for r, (scene_js, box_js, frames_js, energy_js, xr_js, yr_js) in contacts:
        s, p = _series(r), _params(r)
        assert_same(scene_js, scene.scene_data(s, p), "scene_data")
        assert box_js == pytest.approx(list(scene.view_box(s, p)), rel=1e-12)
        py_frames = live_energy.support_frames_data(s, p, offline_figures.N_FRAMES)
        for name in py_frames:
            assert_same(frames_js[name], py_frames[name], name, rel=1e-9, abs_=1e-12)
        py_energy = live_energy.energy_frames(s, offline_figures.N_FRAMES)
        assert_same(energy_js["frames"], py_energy, "energy_frames", rel=1e-9, abs_=1e-12)
        assert energy_js["range"] == pytest.approx(live_energy.energy_live_range(py_energy))
        assert xr_js == pytest.approx(list(histories.force_x_range(s)))
        assert yr_js == pytest.approx(list(histories.force_y_range(s, mu0())))
    # The stretched slider gets the dashboard's warning on the scene.
    assert "stretched to" in contacts[1][1][0]["scene_notes"]["text"][0]


#: Radial axes of every kind: (values, parity) for ``polar.radial_axis``.
POLAR_AXES = [([1.1], "even"), ([0.19], "even"), ([23.0], "even"), ([3e-5], "even"),
              ([0.5], "even"), ([4.2], "even"), ([0.0031, -0.0007], "even"), ([145.0], "even"),
              ([-0.14, 0.14], "odd"), ([-0.09, 0.09], "odd"), ([2.2e-7, -1e-7], "odd")]


def test_the_polar_diagrams_are_the_dashboards():
    theta0 = CONSTANTS["polar_theta0"]
    t = np.asarray(theta0)
    cases = {"FTx": 0.9 + 0.05 * np.cos(2 * t), "DyDx": 0.1 + 0.08 * np.sin(t) ** 2,
             "FTy": 0.04 * np.sin(2 * t) - 0.01}
    calls = [("V", "polarData", [k, polar.QUANTITIES[k][2], theta0, list(v)])
             for k, v in cases.items()]
    calls += [("V", "radialAxis", [[0.0031, -0.0007], "even"]),
              ("V", "radialAxis", [[12.5], "even"])]
    got = js(calls)
    for (key, values), (data, axis) in zip(cases.items(), got):
        want, want_axis = polar.polar_data(key, theta0, values)
        want.update(polar.extent_data(key, want_axis))
        assert axis[0] == pytest.approx(want_axis[0]) and axis[1] == pytest.approx(want_axis[1])
        assert_same(data, want, f"polar {key}", rel=1e-12, abs_=1e-12)
        now_js = js([("V", "polarNow", [key, 1.2, float(values[5]), axis])])[0]
        assert_same(now_js, polar.polar_now(key, 1.2, float(values[5]), want_axis), "now")
    for got_axis, values, parity in zip(got[3:], ([0.0031, -0.0007], [12.5]), ("even", "even")):
        want = polar.radial_axis(values, parity)
        assert got_axis[:2] == pytest.approx(list(want[:2]))
        assert got_axis[2] == pytest.approx(list(want[2]))
    # Which rings are labelled, over axes of every kind (tests/test_polar_figure.py).
    axes = [polar.radial_axis(values, parity) for values, parity in POLAR_AXES]
    got = js([("V", "labelledRings", [[a[0], a[1], list(a[2])]]) for a in axes])
    assert got == [polar.labelled_rings(a) for a in axes]


def test_the_headline_is_the_dashboards_sentence():
    readouts = pytest.importorskip("app.views.readouts")  # imports Panel
    cases = [(0.943, 90, None, "needs the server"), (1.0, 45.5, None, ""),
             (1.0004, 0, 0.97, ""), (1.23456, 359, 1.0, ""), (None, 90, None, ""),
             (0.5, 12.25, 1.7, "")]
    from app.texts import FELT_WORDS
    got = js([("V", "headlineText", [*c, FELT_WORDS]) for c in cases])
    for case, text in zip(cases, got):
        assert text == readouts.headline_text(*case), case


def test_uniform_readout_is_the_dashboards_table():
    readouts = pytest.importorskip("app.views.readouts")  # imports Panel
    from app.figures.arrays import AVERAGE_COLUMNS
    from app.texts import AVERAGE_NAMES, FELT_AVERAGE
    row = dict(FTx_over_mu0FN=0.91141693, FTx_over_mu0FN_duration=0.8449153, Dy_over_Dx=0.0499119,
               Nc_over_Nc0=3.01525442, quadrature_error_FTx=3.3e-4, success=True, n_failed=0)
    cases = [(row, "paper", ""), (row, "duration", ""), (None, "paper", "being computed"),
             (None, "duration", ""), ({**row, "success": False, "n_failed": 3, "Dy_over_Dx": None},
                                      "paper", "")]
    extra = [AVERAGE_NAMES, AVERAGE_COLUMNS, FELT_AVERAGE]
    got = js([("V", "uniformMarkdown", [*c, *extra]) for c in cases])
    for case, text in zip(cases, got):
        assert text == readouts.uniform_markdown(*case), case


def test_the_page_holds_the_shipped_maps_and_the_dashboards_player():
    support = pytest.importorskip("app.views.support")  # imports Panel
    assert offline_figures.N_FRAMES == support.N_FRAMES
    maps = offline_figures.maps()
    assert sorted(maps["loads"], key=float) == [f"{f:g}" for f in SHIPPED_LOADS]
    from app.figures.arrays import map_data
    for F_N in (0.3, 10.0):
        want = map_data(load_regime_map(F_N=F_N), "5b")["regime_map"]
        load = maps["loads"][f"{F_N:g}"]
        got = {**maps["cells"], **load["columns"], "value": load["columns"][maps["value"]["5b"]]}
        for key in want:
            np.testing.assert_allclose(np.asarray(got[key], float), np.asarray(want[key], float),
                                       rtol=1e-5, err_msg=key)


def test_projector_styles_are_the_dashboards_switch():
    figs = offline_figures.polar_figures()
    changes = offline_figures.projector_styles(list(figs.values()))
    fig = figs["FTx"]
    title = [c for c in changes if c[0] == fig.title.id and c[1] == "text_font_size"]
    from app.figures.common import MIN_TEXT_PX, PROJECTOR_SCALE
    screen, projector = MIN_TEXT_PX + 1, round((MIN_TEXT_PX + 1) * PROJECTOR_SCALE)
    assert title == [[fig.title.id, "text_font_size", f"{screen}px", f"{projector}px"]]
    assert fig.title.text_font_size == f"{screen}px"  # left in the screen look
    widths = [c for c in changes if c[1] == "line_width"]
    assert widths and all(float(c[3]["value"] if isinstance(c[3], dict) else c[3]) >
                          float(c[2]["value"] if isinstance(c[2], dict) else c[2]) for c in widths)
