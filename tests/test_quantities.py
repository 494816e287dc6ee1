"""The registry of quantities: it covers every field of the result types and every CSV
column, both ways, and its labels and formats are what readers see."""
import csv
import dataclasses
import io
import math

import numpy as np
import pytest

from model import REGIMES, Params, csvfile, simulate_support
from model.arrays.contacts import Contacts, run_contacts
from model.arrays.fixed import FixedArrayResult, OrientationSweep, fixed_orientation
from model.contact.options import SolverOptions
from model.arrays.quantities import (AVERAGES, MAP_FIGURES, POLAR_FIGURES, QUANTITIES, STRUCTURE,
                              TABLES, carried_by, describe, format_value, label, quantity,
                              readout, value_of)
from model.contact.results import SupportResult, TimeSeries
from model.runs.shipped_map import RegimeMap
from model.runs.sweeps import orientation_table, regime_map
from model.arrays.uniform import UniformArrayResult

RESULT_TYPES = [SupportResult, TimeSeries, Contacts, FixedArrayResult, OrientationSweep,
                UniformArrayResult, RegimeMap]


@pytest.mark.parametrize("cls", RESULT_TYPES, ids=lambda c: c.__name__)
def test_every_field_is_registered(cls):
    fields = {f.name for f in dataclasses.fields(cls)} - set(STRUCTURE)
    unregistered = fields - set(QUANTITIES)
    assert not unregistered, f"{cls.__name__} fields missing from the registry: {unregistered}"
    claimed = set(carried_by(cls.__name__))
    # A field the registry does not attribute to this type is a registry error too.
    assert fields <= claimed, f"registry does not list {fields - claimed} under {cls.__name__}"


@pytest.mark.parametrize("cls", RESULT_TYPES, ids=lambda c: c.__name__)
def test_every_registration_is_a_field_or_property(cls):
    names = {f.name for f in dataclasses.fields(cls)}
    for name in carried_by(cls.__name__):
        assert name in names or isinstance(getattr(cls, name, None), property), \
            f"{name} registered under {cls.__name__} but not carried by it"


def test_every_table_column_is_registered():
    for layout, names in TABLES.items():
        missing = [n for n in names if n not in QUANTITIES]
        assert not missing, f"TABLES[{layout!r}] has unregistered columns {missing}"
    for mapping in (AVERAGES, MAP_FIGURES, POLAR_FIGURES):
        assert set(mapping.values()) <= set(QUANTITIES)


def test_reproduction_columns_are_registered():
    from model.reproduce import tables

    for names in (tables.SERIES, tables.MAP_COLUMNS, tuple(tables.POLAR_COLUMNS.values())):
        assert set(names) <= set(QUANTITIES)
    columns, _ = tables._law_table(None)
    assert set(columns) <= set(QUANTITIES)


def test_orientation_csv_columns_are_the_registered_layout(tmp_path):
    table = orientation_table("stiff", theta0=[0.5, 1.0], beta=1.0)
    assert tuple(table.columns) == TABLES["orientation"]
    # r_max, the largest distance from the pivot, is a column (and exceeds r_min).
    sweep = table.columns
    contacts, _ = run_contacts(REGIMES["stiff"], [0.5, 1.0], SolverOptions())
    np.testing.assert_array_equal(sweep["r_max"], contacts.r_max)
    assert np.all(contacts.r_max >= contacts.r_min)
    path = tmp_path / "orientation.csv"
    table.to_csv(path)
    text = path.read_text()
    # Every column is described in the header, from the registry.
    for name in TABLES["orientation"]:
        assert f"# column {name}: {label(name, 'text')}: " in text
    rows = list(csv.reader(line for line in text.splitlines() if not line.startswith("#")))
    assert tuple(rows[0]) == TABLES["orientation"] and len(rows) == 3


def test_uniform_sweep_columns_are_the_registered_layout():
    r = regime_map(k_r=[3.0], k_theta=[3.0], tol=0.05, beta=1.0)
    assert tuple(r.columns) == TABLES["regime_map"]
    assert r.columns["quadrature_error_FTx"][0] >= 0


def test_support_json_record_follows_the_registry():
    res = simulate_support(REGIMES["pendulum"])
    d = res.to_dict()
    assert set(d) == set(TABLES["support"]) | {"stats", "params"}
    assert d["F_mean_x"] == float(res.F_mean[0]) and d["r_max"] == res.r_max
    assert d["state_out"] == [float(v) for v in res.state_out]
    assert 1.0 < res.r_max and res.r_min < 1.0  # the pendulum swings out and back


def test_fixed_array_carries_r_max():
    f = fixed_orientation(REGIMES["pendulum"], beta=1.0)
    s = simulate_support(REGIMES["pendulum"])
    assert f.r_max == pytest.approx(s.r_max, rel=1e-9)
    assert "r_max" in f.to_dict()


def test_value_of_reads_sources():
    s = simulate_support(REGIMES["stiff"], samples=50)
    assert value_of(s, "F_mean_y") == float(s.F_mean[1])
    assert value_of(s, "relative_residual") == pytest.approx(abs(s.energy_residual / s.W))
    v = value_of(s.series, "v_R_abs")
    np.testing.assert_allclose(v, np.hypot(s.series.v_x - 1.0, s.series.v_y))


def test_labels():
    assert label("FTx_over_mu0FN") == "F_T,x/(μ₀F_N)"
    assert label("FTx_over_mu0FN", "text") == "F_T,x/(mu0 F_N)"
    assert label("k_theta", "latex") == r"\tilde k_\theta"
    with pytest.raises(KeyError, match="'nope' is not a registered quantity"):
        label("nope")
    with pytest.raises(KeyError):
        label("k_r", "html")


def test_format_value():
    assert format_value("FTx_over_mu0FN", 0.912345678) == "0.9123"
    assert format_value("quadrature_error_FTx", 1.2345e-4) == "0.00012"
    assert format_value("beta", None) == "–"
    assert format_value("beta", math.nan) == "–"
    assert format_value("n_failed", 3.0) == "3"
    assert format_value("success", np.bool_(True)) == "yes"
    assert format_value("W", 2.0) == "2"


def test_readout_rows():
    f = fixed_orientation(REGIMES["stiff"], beta=1.0)
    rows = readout(f, ["FTx_over_mu0FN", "Nc_over_Nc0", "success"])
    assert rows == [("F_T,x/(μ₀F_N)", f"{f.FTx_over_mu0FN:.4g}"),
                    ("N_c/N_c0", f"{f.Nc_over_Nc0:.4g}"), ("success", "yes")]


def test_describe_has_units_and_equation():
    assert describe("t_out") == ("contact duration: the slab slid L0 over the support "
                                 "[r0/V0] (Eq. (9))")
    assert "[" not in describe("Dy_over_Dx")  # a pure number has no units


def test_every_quantity_is_complete():
    for q in QUANTITIES.values():
        assert q.name and q.text and q.unicode and q.latex and q.meaning, q.name
        assert q.units in ("1", "", "r0", "r0/V0", "rad", "m V0^2", "V0", "s"), q.name
        assert not q.equation or q.equation.startswith(("Eq. (", "Fig. ")), q.name
        assert q.name == quantity(q.name).name


def test_csv_round_trip_keeps_values_and_types():
    columns = {"theta0": np.array([0.1, 1 / 3]), "success": np.array([True, False]),
               "n_failed": np.array([0, 2]), "regime": np.array(["soft", "stiff"])}
    text = csvfile.text(columns, {"kind": "test", "beta": "self", "atol": None})
    path = io.StringIO(text)
    assert "# atol: null" in text and "# column theta0: theta0: rest orientation" in text
    import tempfile
    with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as f:
        f.write(path.getvalue())
    header, back = csvfile.read(f.name)
    assert header == {"kind": "test", "beta": "self", "atol": None}
    for name, values in columns.items():
        np.testing.assert_array_equal(back[name], values)
        assert back[name].dtype.kind == values.dtype.kind


def test_params_fields_are_registered_inputs():
    for name in ("k_r", "k_theta", "F_N", "theta0", "beta"):
        assert name in QUANTITIES and name in {f.name for f in dataclasses.fields(Params)}


def test_cli_json_and_summary_carry_r_max(capsys):
    """The demonstration quantity reaches the command line by the registry alone."""
    import json

    from model.cli import main

    assert main(["support", "--regime", "pendulum", "--json"]) == 0
    record = json.loads(capsys.readouterr().out)
    assert set(TABLES["support"]) <= set(record)
    assert record["r_max"] == simulate_support(REGIMES["pendulum"]).r_max
    assert main(["support", "--regime", "pendulum"]) == 0
    assert describe("r_max") in capsys.readouterr().out
    assert main(["array", "--regime", "pendulum", "--theta0", "1.0", "--beta", "1", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["r_max"] > 1.0
