"""The regime map of Fig. 5 shipped with the package, and its regeneration."""
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

import model
from model import Params, uniform_array
from model.arrays.uniform import BETA_GTOL
from model.runs.shipped_map import (SHIPPED_LOADS, RegimeMap, compute_regime_map, load_regime_map, main,
                              packaged_path, save_regime_map)

#: A recomputed beta and a shipped one agree to within the sum of the residuals each was
#: accepted at (|G| <= BETA_GTOL tol now, tol/1000 when the maps were made; slope of G >= 1).
BETA_AGREE = BETA_GTOL + 1e-3

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def shipped():
    return load_regime_map()


def test_shipped_map_is_packaged():
    assert packaged_path().is_file()
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text())
    patterns = pyproject["tool"]["setuptools"]["package-data"]["model"]
    assert packaged_path().relative_to(Path(model.__file__).parent).match(patterns[0])


def test_shipped_map_shape_and_grid(shipped):
    n, m = shipped.shape
    assert n >= 24 and m >= 24
    assert shipped.k_r.shape == (n,) and shipped.k_theta.shape == (m,)
    for axis in (shipped.k_r, shipped.k_theta):
        assert axis[0] == pytest.approx(0.01) and axis[-1] == pytest.approx(3.0)
        np.testing.assert_allclose(np.diff(np.log(axis)), math.log(300) / (axis.size - 1))
    for name in ("FTx_over_mu0FN", "FTx_over_mu0FN_duration", "Dy_over_Dx", "Nc_over_Nc0",
                 "beta", "quadrature_error", "success", "n_failed", "n_pivot"):
        assert getattr(shipped, name).shape == (n, m), name


def test_shipped_metadata_records_settings_and_version(shipped):
    meta = shipped.metadata
    assert meta["F_N"] == 1.0
    assert 0 < meta["tol"] <= 1e-2 and 0 < meta["rtol"] <= 1e-4
    assert meta["beta_mode"] == "self" and meta["method"] == "auto"
    assert isinstance(meta["package_version"], str) and meta["package_version"]
    assert meta["date"][:2] == "20" and meta["seconds"] > 0
    assert meta["max_quadrature_error"] == pytest.approx(shipped.quadrature_error.max())
    assert meta["n_unsuccessful"] == int(np.sum(~shipped.success))
    assert len(meta["unsuccessful"]) == meta["n_unsuccessful"]


def test_shipped_values_finite_and_plausible(shipped):
    ok = shipped.success
    assert ok.any()
    for name in ("FTx_over_mu0FN", "FTx_over_mu0FN_duration", "Dy_over_Dx", "Nc_over_Nc0",
                 "beta", "quadrature_error"):
        assert np.all(np.isfinite(getattr(shipped, name)[ok])), name
    # Within tolerance where successful; self-consistent beta = N_c0/N_c.
    assert np.all(shipped.quadrature_error[ok] <= shipped.metadata["tol"])
    np.testing.assert_allclose(shipped.beta[ok] * shipped.Nc_over_Nc0[ok], 1.0, atol=1e-3)
    # Friction reduction is largest in the soft corner, none to speak of in the stiff one.
    F = shipped.FTx_over_mu0FN
    assert F[0, 0] < 0.9 and abs(F[-1, -1] - 1) < 0.01
    assert np.all((F[ok] > 0.5) & (F[ok] < 1.05))
    assert np.all(shipped.Nc_over_Nc0[ok] > 0.99) and np.all(shipped.Dy_over_Dx[ok] >= 0)


@pytest.mark.parametrize("i, j", [(-1, -1), (-1, -2), (-2, -1)])
def test_shipped_points_recompute(shipped, i, j):
    """Cheap (stiff) points recomputed with the recorded settings match the stored values."""
    meta = shipped.metadata
    r = uniform_array(Params(shipped.k_r[i], shipped.k_theta[j], F_N=meta["F_N"]),
                      tol=meta["tol"], rtol=meta["rtol"], method=meta["method"])
    assert r.success == shipped.success[i, j]
    bound = 2 * shipped.quadrature_error[i, j] + 1e-6
    assert abs(r.FTx_over_mu0FN - shipped.FTx_over_mu0FN[i, j]) <= bound
    for name in ("FTx_over_mu0FN_duration", "Dy_over_Dx", "Nc_over_Nc0"):
        bound = 2 * r.quadrature_error[name] + 1e-6
        assert abs(getattr(r, name) - getattr(shipped, name)[i, j]) <= bound, name
    assert abs(r.beta - shipped.beta[i, j]) <= BETA_AGREE * meta["tol"] + 1e-6


def test_save_load_round_trip(tmp_path):
    rng = np.random.default_rng(3)
    k = np.array([0.1, 1.0])
    grid = lambda: rng.random((2, 2))  # noqa: E731
    m = RegimeMap(k_r=k, k_theta=k * 2, FTx_over_mu0FN=grid(), FTx_over_mu0FN_duration=grid(),
                  Dy_over_Dx=grid(), Nc_over_Nc0=grid(), beta=grid(), quadrature_error=grid(),
                  success=np.array([[True, False], [True, True]]),
                  n_failed=np.array([[0, 2], [0, 0]]), n_pivot=np.zeros((2, 2), int),
                  metadata={"F_N": 1.0, "note": "x", "nested": {"a": [1, 2]}})
    back = load_regime_map(save_regime_map(m, tmp_path / "sub" / "map.npz"))
    assert back.metadata == m.metadata
    for name, a in m.arrays().items():
        np.testing.assert_array_equal(getattr(back, name), a)
        assert getattr(back, name).dtype == a.dtype


def test_compute_small_map_matches_shipped_corners(shipped, tmp_path, capsys):
    """A 2 x 2 map (the four corners of the grid) through the command line."""
    out = tmp_path / "map2.npz"
    assert main(["--n", "2", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "largest quadrature error" in printed and "2x2 points" in printed
    small = load_regime_map(out)
    assert small.shape == (2, 2) and small.metadata["grid"]["n"] == 2
    corners = np.ix_([0, -1], [0, -1])
    bound = 2 * np.maximum(small.quadrature_error, shipped.quadrature_error[corners]) + 1e-6
    assert np.all(np.abs(small.FTx_over_mu0FN - shipped.FTx_over_mu0FN[corners]) <= bound)
    with pytest.raises(ValueError):
        compute_regime_map(n=1)


def test_regime_map_name_stays_the_sweep_function():
    import model
    import model.runs.shipped_map  # noqa: F401  (a submodule import must not shadow the function)

    assert callable(model.regime_map) and model.regime_map.__module__ == "model.runs.sweeps"


@pytest.mark.parametrize("F_N", SHIPPED_LOADS)
def test_each_shipped_load_is_packaged_and_recomputes(F_N):
    """Every shipped load: settings recorded, grid as at F_N = 1, and points of the
    stiff row (cheap) and the soft corner recomputed from scratch match."""
    m = load_regime_map(F_N=F_N)
    meta = m.metadata
    assert meta["F_N"] == F_N and m.shape == (24, 24) and meta["beta_mode"] == "self"
    assert meta["tol"] == 1e-3 and packaged_path(F_N).is_file()
    np.testing.assert_allclose(m.k_r, load_regime_map().k_r)
    assert np.all(m.quadrature_error[m.success] <= meta["tol"])
    np.testing.assert_allclose(m.beta[m.success] * m.Nc_over_Nc0[m.success], 1.0, atol=1e-3)
    for i, j in [(-1, -1), (-1, 0), (0, 0)]:
        r = uniform_array(Params(m.k_r[i], m.k_theta[j], F_N=F_N), tol=meta["tol"],
                          rtol=meta["rtol"], method=meta["method"])
        assert r.success == m.success[i, j]
        assert abs(r.FTx_over_mu0FN - m.FTx_over_mu0FN[i, j]) <= 2 * m.quadrature_error[i, j] + 1e-6
        assert abs(r.Nc_over_Nc0 - m.Nc_over_Nc0[i, j]) <= 2 * r.quadrature_error["Nc_over_Nc0"] + 1e-6
        assert abs(r.beta - m.beta[i, j]) <= BETA_AGREE * meta["tol"] + 1e-6


def test_unshipped_load_is_named():
    with pytest.raises(ValueError, match=r"F_N=2.*0\.1, 0\.3, 1, 3, 10"):
        load_regime_map(F_N=2.0)
    assert load_regime_map(F_N=1).metadata == load_regime_map().metadata
