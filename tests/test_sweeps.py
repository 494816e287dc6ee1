"""Parameter sweeps (Figs. 5, 6, 8, 10f, 11): columns, CSV, parallel runs, progress, cancel."""
import csv
import math
import threading
import time

import numpy as np
import pytest

from model.runs import parallel
from model.runs import sweeps
from model.arrays.fixed import orientation_sweep
from model.contact.params import REGIMES, Params
from model.runs.sweeps import SweepCancelled, SweepResult
from model.arrays.uniform import _uniform, uniform_array

FAST = dict(n=2, tol=1e-2)
REGIME_MAP_COLUMNS = ["k_r", "k_theta", "FTx_over_mu0FN", "FTx_over_mu0FN_duration", "Dy_over_Dx",
                      "Nc_over_Nc0", "beta", "quadrature_error_FTx", "n_failed", "n_pivot",
                      "success"]


@pytest.fixture(scope="module")
def reference_map():
    """The 2 x 2 regime map computed serially in this process."""
    return sweeps.regime_map(**FAST)


def assert_same(a: SweepResult, b: SweepResult):
    assert a.kind == b.kind and list(a.columns) == list(b.columns)
    for name in a.columns:
        assert a.columns[name].dtype == b.columns[name].dtype, name
        np.testing.assert_array_equal(a.columns[name], b.columns[name], err_msg=name)


def test_regime_map_grid_and_columns(reference_map):
    r = reference_map
    assert r.kind == "regime_map" and list(r.columns) == REGIME_MAP_COLUMNS and len(r) == 4
    assert all(v.shape == (4,) for v in r.columns.values())
    np.testing.assert_array_equal(r.columns["k_r"], [0.01, 0.01, 3.0, 3.0])
    np.testing.assert_array_equal(r.columns["k_theta"], [0.01, 3.0, 0.01, 3.0])
    assert r.columns["success"].dtype == bool and r.columns["success"].all()
    assert r.settings["tol"] == 0.01 and r.settings["beta"] == "self" and r.settings["F_N"] == 1.0
    # Self-consistent load factor: beta = N_c0/N_c (docs/model.md, "Contact count").
    np.testing.assert_allclose(r.columns["beta"] * r.columns["Nc_over_Nc0"], 1.0, rtol=2e-2)
    assert np.all(r.columns["Nc_over_Nc0"] >= 1.0)
    # The first point of each k_theta row starts cold: exactly the uniform array there.
    direct = uniform_array(Params(0.01, 0.01), tol=1e-2)
    assert r.columns["FTx_over_mu0FN"][0] == direct.FTx_over_mu0FN
    assert r.columns["FTx_over_mu0FN_duration"][0] == direct.FTx_over_mu0FN_duration
    assert r.columns["quadrature_error_FTx"][0] == direct.quadrature_error["FTx_over_mu0FN"]
    # The next is continued from its beta: the same array to within the tolerance.
    direct = uniform_array(Params(0.01, 3.0), tol=1e-2)
    assert r.columns["beta"][1] == pytest.approx(direct.beta, rel=1e-3)
    assert r.columns["FTx_over_mu0FN"][1] == pytest.approx(direct.FTx_over_mu0FN, rel=1e-2)
    assert r.columns["Nc_over_Nc0"][1] == pytest.approx(direct.Nc_over_Nc0, rel=1e-2)


def test_csv_round_trip(reference_map, tmp_path):
    path = tmp_path / "map.csv"
    reference_map.to_csv(path)
    lines = path.read_text().splitlines()
    comments = [line for line in lines if line.startswith("#")]
    header = dict(line[2:].split(": ", 1) for line in comments)
    assert header["kind"] == "regime_map" and header["version"] == sweeps_version()
    assert header["tol"] == "0.01" and header["points"] == "4"
    back = sweeps.read_csv(path)
    assert_same(back, reference_map)
    assert back.settings["beta"] == "self" and back.settings["atol"] is None
    table = np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding="utf-8",
                          skip_header=len(comments))
    assert list(table.dtype.names) == REGIME_MAP_COLUMNS
    np.testing.assert_array_equal(table["FTx_over_mu0FN"], reference_map.columns["FTx_over_mu0FN"])
    rows = list(csv.DictReader(lines[len(comments):]))
    dy_dx = [float(row["Dy_over_Dx"]) for row in rows]
    assert dy_dx == reference_map.columns["Dy_over_Dx"].tolist()


def sweeps_version():
    from model import __version__
    return __version__


def test_load_sweep_rows_and_falling_friction():
    r = sweeps.load_sweep(regimes=("pendulum", "soft"), F_N=(0.3, 3.0), tol=1e-2)
    assert r.kind == "load" and len(r) == 4
    assert r.columns["regime"].tolist() == ["pendulum", "pendulum", "soft", "soft"]
    np.testing.assert_array_equal(r.columns["F_N"], [0.3, 3.0, 0.3, 3.0])
    assert r.columns["k_r"].tolist() == [3.0, 3.0, 0.03, 0.03]
    fx = r.columns["FTx_over_mu0FN"].reshape(2, 2)
    assert np.all(fx[:, 1] < fx[:, 0])  # Fig. 6: a larger load lowers the apparent friction


def test_stiffness_sweep_work_split_closes():
    r = sweeps.stiffness_sweep(k_theta=(0.03, 3.0), **FAST)
    assert r.kind == "stiffness" and len(r) == 4
    np.testing.assert_array_equal(r.columns["k_theta"], [0.03, 0.03, 3.0, 3.0])
    split = sum(r.columns[k] for k in ("Dx_over_W", "Dy_over_W", "Uel_over_W", "K_over_W"))
    np.testing.assert_allclose(split, 1.0, atol=1e-3)  # W = D_x + D_y + U_el + K (Eq. 12)
    nc = r.columns["Nc_over_Nc0"].reshape(2, 2)
    assert np.all(nc[:, 0] > nc[:, 1])  # Fig. 8a: compliant radial springs stay longer


def test_orientation_table_matches_orientation_sweep():
    r = sweeps.orientation_table("slider", n=5)
    assert r.kind == "orientation" and len(r) == 5
    assert list(r.columns) == ["theta0", "FTx_over_mu0FN", "FTy_over_mu0FN", "Dy_over_Dx",
                               "Nc_over_Nc0", "dtheta_rms", "dr_rms", "r_max", "beta", "pivot_approach",
                               "relative_residual", "success"]
    midpoints = (np.arange(5) + 0.5) * math.pi / 5  # off the exact axis orientations
    np.testing.assert_array_equal(r.columns["theta0"], midpoints)
    direct = orientation_sweep(REGIMES["slider"], midpoints)
    np.testing.assert_array_equal(r.columns["FTx_over_mu0FN"], direct.FTx_over_mu0FN)
    ends = sweeps.orientation_table("slider", theta0=[0.0, math.pi])  # on the axis: F_y = 0
    assert ends.columns["FTy_over_mu0FN"][0] == 0.0 and ends.columns["FTy_over_mu0FN"][-1] == 0.0
    assert r.settings["k_r"] == 0.01 and r.settings["rtol"] == 1e-6


@pytest.mark.parametrize("method", ["fork", "forkserver"])
def test_workers_give_identical_results(reference_map, monkeypatch, method):
    monkeypatch.setattr(parallel, "START_METHOD", method)
    _uniform.cache_clear()  # so that forked workers cannot inherit the serial results
    calls = []
    r = sweeps.regime_map(**FAST, workers=2, progress=lambda d, t: calls.append((d, t)))
    assert_same(r, reference_map)
    assert calls == [(i, 4) for i in range(1, 5)]
    assert r.settings["workers"] == 2


def test_progress_is_called_after_every_point():
    calls = []
    sweeps.regime_map(**FAST, progress=lambda done, total: calls.append((done, total)))
    assert calls == [(1, 4), (2, 4), (3, 4), (4, 4)]


@pytest.mark.parametrize("workers", [1, 2])
def test_cancel_stops_early(workers):
    _uniform.cache_clear()
    cancel, calls = threading.Event(), []

    def progress(done, total):
        calls.append(done)
        cancel.set()

    start = time.perf_counter()
    with pytest.raises(SweepCancelled) as info:
        sweeps.regime_map(n=3, tol=1e-3, workers=workers, progress=progress, cancel=cancel)
    assert 1 <= info.value.done < info.value.total == 9
    assert calls == list(range(1, info.value.done + 1))
    assert time.perf_counter() - start < 30


def test_cancel_before_start():
    cancel = threading.Event()
    cancel.set()
    with pytest.raises(SweepCancelled, match="after 0 of 4 points"):
        sweeps.regime_map(**FAST, cancel=cancel, progress=lambda d, t: pytest.fail("called"))
    with pytest.raises(SweepCancelled):
        sweeps.orientation_table("pendulum", n=3, cancel=cancel)


BAD = [
    (sweeps.regime_map, dict(k_r=[]), "k_r="),
    (sweeps.regime_map, dict(k_r=[0.1, -1.0]), "k_r="),
    (sweeps.regime_map, dict(k_theta=[0.0]), "k_theta="),
    (sweeps.regime_map, dict(k_theta=[[0.1, 0.2]]), "k_theta="),
    (sweeps.regime_map, dict(k_r=["a"]), "k_r="),
    (sweeps.regime_map, dict(n=0), "n="),
    (sweeps.regime_map, dict(F_N=-1.0), "F_N="),
    (sweeps.regime_map, dict(workers=0), "workers="),
    (sweeps.regime_map, dict(workers=1.5), "workers="),
    (sweeps.regime_map, dict(tol=0.0), "tol="),
    (sweeps.regime_map, dict(beta=2.0), "beta="),
    (sweeps.regime_map, dict(beta="half"), "beta="),
    (sweeps.regime_map, dict(rtol=1.0), "rtol="),
    (sweeps.regime_map, dict(method="rk4"), "method="),
    (sweeps.regime_map, dict(scheduler="tcp://x:1", workers=2), "workers="),
    (sweeps.load_sweep, dict(regimes=("rigid",)), "regimes="),
    (sweeps.load_sweep, dict(regimes=()), "regimes="),
    (sweeps.load_sweep, dict(F_N=[]), "F_N="),
    (sweeps.stiffness_sweep, dict(k_theta=()), "k_theta="),
    (sweeps.orientation_table, dict(params="pendulum", theta0=[]), "theta0="),
    (sweeps.orientation_table, dict(params="pendulum", theta0=[7.0]), "theta0="),
]


@pytest.mark.parametrize("func, kwargs, name", BAD, ids=[f"{b[0].__name__}-{b[1]}" for b in BAD])
def test_bad_input_names_the_argument(func, kwargs, name):
    kwargs = {"n": 2, **kwargs} if func is not sweeps.orientation_table else kwargs
    with pytest.raises(ValueError, match=f"^{name}"):
        func(**kwargs)


def test_dask_cluster_gives_identical_results(reference_map):
    distributed = pytest.importorskip("distributed")
    calls = []
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster:
        with distributed.Client(cluster) as client:
            by_client = sweeps.regime_map(**FAST, scheduler=client)
        by_address = sweeps.regime_map(**FAST, scheduler=cluster.scheduler_address,
                                       progress=lambda d, t: calls.append((d, t)))
    assert_same(by_client, reference_map)
    assert_same(by_address, reference_map)
    assert calls == [(i, 4) for i in range(1, 5)]
    assert by_address.settings["scheduler"] == cluster.scheduler_address


def test_bad_scheduler_address():
    pytest.importorskip("distributed")
    with pytest.raises(ValueError, match="^scheduler='localhost'"):
        sweeps.regime_map(**FAST, scheduler="localhost")
    with pytest.raises(ValueError, match="^scheduler="):
        sweeps.regime_map(**FAST, scheduler=42)


def test_sweep_points_come_from_the_disk_cache(tmp_path, monkeypatch):
    from model.runs import cache as cache_mod
    from model.runs import sweeps as sweeps_mod
    from model.arrays.uniform import _uniform

    monkeypatch.setenv("MICROPILLAR_CACHE_DIR", str(tmp_path))
    first = sweeps_mod.regime_map(k_r=[1.0, 3.0], k_theta=[3.0], tol=1e-2)
    assert len(cache_mod.DiskCache().entries()) == 2
    calls = []
    monkeypatch.setattr(sweeps_mod, "uniform_array", lambda *a, **k: calls.append(a))
    _uniform.cache_clear()
    again = sweeps_mod.regime_map(k_r=[1.0, 3.0], k_theta=[3.0], tol=1e-2)
    assert calls == []  # nothing recomputed
    for name, column in first.columns.items():
        np.testing.assert_array_equal(again.columns[name], column)
    entry = cache_mod.DiskCache().entries()[0]
    entry.write_bytes(entry.read_bytes()[:100])  # corrupt one entry
    monkeypatch.undo()
    monkeypatch.setenv("MICROPILLAR_CACHE_DIR", str(tmp_path))
    third = sweeps_mod.regime_map(k_r=[1.0, 3.0], k_theta=[3.0], tol=1e-2)
    np.testing.assert_array_equal(third.columns["FTx_over_mu0FN"], first.columns["FTx_over_mu0FN"])


@pytest.mark.parametrize("bad", [None, 0, -3, 2.5, "64", True])
def test_bad_max_intervals_is_named_before_any_work(bad):
    with pytest.raises(ValueError, match="max_intervals="):
        sweeps.regime_map(n=1, max_intervals=bad)


def test_grid_plan_covers_every_point_once_coarse_first():
    inner, phases = sweeps._grid_plan(24, 24)
    assert inner == 24 and len(phases) == 2
    first = sorted(i for chain in phases[0] for i in chain)
    assert len(first) == 64  # an 8 x 8 subgrid ...
    rows, cols = sorted({i // 24 for i in first}), sorted({i % 24 for i in first})
    assert rows[0] == cols[0] == 0 and rows[-1] == cols[-1] == 23  # ... with both ends
    every = sorted(i for phase in phases for chain in phase for i in chain)
    assert every == list(range(24 * 24))
    # Each chain runs along the inner axis of one outer value.
    assert all(len({i // 24 for i in chain}) == 1 for phase in phases for chain in phase)
    assert sweeps._grid_plan(3, 5)[1] == [[[0, 1, 2, 3, 4], [5, 6, 7, 8, 9], [10, 11, 12, 13, 14]]]


def test_regime_map_hands_out_the_coarse_subgrid_first(tmp_path, monkeypatch):
    monkeypatch.setenv("MICROPILLAR_CACHE_DIR", str(tmp_path))
    seen = []
    k = np.logspace(-1, 0, 9)
    r = sweeps.regime_map(k_r=k[-2:], k_theta=k, tol=1e-2, coarse=seen.append)
    assert len(seen) == 1 and len(seen[0]) == 2 * 8
    full = {(a, b): f for a, b, f in zip(r.columns["k_r"], r.columns["k_theta"],
                                        r.columns["FTx_over_mu0FN"])}
    for a, b, f in zip(*(seen[0].columns[c] for c in ("k_r", "k_theta", "FTx_over_mu0FN"))):
        assert full[(a, b)] == f  # the same points, not recomputed
    assert np.all(r.columns["success"])


def test_chain_extrapolates_beta_along_the_swept_parameter():
    """Two computed points extrapolate beta linearly in the log of the one parameter that
    changes; a capped beta or a large step falls back to the nearer point's own."""
    from model.runs.sweeps import _extrapolate

    p = [Params(0.1, k, F_N=3.0) for k in (0.1, 0.2, 0.4)]
    row = lambda beta: {"beta": beta, "beta_slope": 1.5}  # noqa: E731
    (beta, slope), close = _extrapolate((p[0], row(0.50)), (p[1], row(0.52)), p[2])
    assert close and beta == pytest.approx(0.54) and slope == 1.5
    assert _extrapolate((p[0], row(0.50)), (p[1], row(1.0)), p[2]) == ((1.0, 1.5), False)
    assert _extrapolate((p[0], row(0.30)), (p[1], row(0.52)), p[2]) == ((0.52, 1.5), False)
    # Two parameters changing at once: no straight line to follow.
    other = Params(0.2, 0.4, F_N=3.0)
    assert _extrapolate((p[0], row(0.50)), (p[1], row(0.52)), other)[1] is False
