"""``python -m app.reproduce`` (data and report from ``model.reproduce``, pictures drawn by
the app): a coarse reproduction into a temporary folder.

Every figure file and CSV must exist and be non-empty, the CSVs must carry their
parameters and read back, and the report must list every finding of MODEL.md with a
verdict. PNGs are required where a browser is (always in CI).
"""
import math
import re

import numpy as np
import pytest

from app.reproduce import reproduce
from app.reproduce.__main__ import main as app_main
from app.reproduce.figures import DRAW
from app.reproduce.render import browser_problem
from model.cli import main
from model.reproduce import FIGURES
from model.reproduce import reproduce as compute_only
from model.sweeps import read_csv

from browser.conftest import browser_required

PAPER_FIGURES = {"3", "5a", "5b", "6", "7a", "7b", "8a", "8b", "10a", "10b", "10c", "10d",
                 "10e", "10f", "11a", "11b", "11c"}


@pytest.fixture(scope="module")
def coarse(tmp_path_factory):
    if browser_problem() and browser_required():
        pytest.fail(f"PNG pictures are required here (CI): {browser_problem()}")
    out = tmp_path_factory.mktemp("reproduction")
    stages = []
    rep = reproduce(out, resolution="coarse", progress=lambda s, d, t: stages.append((s, d, t)))
    return rep, stages


def test_every_paper_figure_is_regenerated(coarse):
    rep, _ = coarse
    assert {f.spec.number for f in rep.figures} == PAPER_FIGURES
    for f in rep.figures:
        for path in (f.html, f.csv):
            assert path.is_file() and path.stat().st_size > 500, path
        assert "Bokeh" in f.html.read_text(encoding="utf-8")[:2_000_000]
        if not rep.png_note:
            assert f.png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
            assert f.png.stat().st_size > 5_000


def test_pngs_are_made_when_a_browser_is_available(coarse):
    rep, _ = coarse
    if browser_problem() is None:
        assert rep.png_note == "" and all(f.png is not None for f in rep.figures)
    else:
        assert rep.png_note == browser_problem()


def test_csvs_carry_their_parameters_and_read_back(coarse):
    rep, _ = coarse
    for f in rep.figures:
        text = f.csv.read_text(encoding="utf-8")
        assert f"# figure: {f.spec.number}" in text and "# resolution: coarse" in text
        table = read_csv(f.csv)
        assert len(table) > 0
        numeric = [v for v in table.columns.values() if np.asarray(v).dtype.kind == "f"]
        assert numeric and all(np.isfinite(v).all() for v in numeric), f.spec.key
    fig6 = read_csv(rep.out / "fig6.csv")
    assert set(fig6.columns["regime"]) == {"pendulum", "slider", "stiff", "soft"}
    assert fig6.settings["beta"] == "self" and fig6.settings["tol"] == 1e-2


def test_report_lists_every_finding_with_a_verdict(coarse):
    rep, _ = coarse
    text = rep.report.read_text(encoding="utf-8")
    for n in range(1, 8):
        assert f"**Finding {n}**" in text
    rows = [line for line in text.splitlines() if re.match(r"\| (\d|extra) \|", line)]
    assert len(rows) == len(rep.checks) >= 25
    assert all(("**agrees**" in r) != ("**differs**" in r) for r in rows)
    assert f"{len(rep.checks) - rep.n_differ} of {len(rep.checks)} checks agree" in text
    # Known differences stay visible (MODEL.md mu0 ~ 1.0085; the pendulum stretches).
    assert "1.00824" in text and "Where the model and the paper differ" in text
    assert "## Sensitivity" in text and "200 random supports" in text


def test_index_links_every_figure(coarse):
    rep, _ = coarse
    page = rep.index.read_text(encoding="utf-8")
    for f in rep.figures:
        assert f"href='{f.html.name}'" in page and f"href='{f.csv.name}'" in page
    assert page.count("<tr class=") == len(rep.checks)


def test_checks_use_the_computed_numbers(coarse):
    rep, _ = coarse
    by_quantity = {c.quantity: c for c in rep.checks}
    stiff = by_quantity["F_T,x/(μ₀F_N), stiff"]
    assert float(stiff.value) == pytest.approx(rep.data.headline["stiff"].FTx_over_mu0FN,
                                               abs=1e-4)
    mu = by_quantity["μ(1) with μ_s = 1.3, A = 1.44, B = −20, ζ = 10"]
    assert not mu.agrees  # 1.00824, not MODEL.md's 1.0085


def test_sensitivity_variants(coarse):
    rep, _ = coarse
    names = [v.name for v in rep.variants]
    assert names[0] == "baseline" and "β = 1" in names and "λ = 0.1" in names
    base, random = rep.variants[0], rep.variants[-1]
    for regime, value in base.FTx.items():
        # 200 random supports scatter about the quadrature value.
        assert random.FTx[regime] == pytest.approx(value, abs=0.03)
        assert math.isfinite(base.DyDx[regime])


def test_progress_covers_every_stage(coarse):
    rep, stages = coarse
    from model.reproduce import all_stages

    seen = [s for s, _, _ in stages]
    assert sorted(set(seen), key=seen.index) == all_stages("coarse")
    for name in ("CSV tables", "figures"):
        assert any(s == name and d == t for s, d, t in stages)


def test_a_second_run_reads_the_cache_and_needs_no_drawing(coarse, tmp_path):
    rep, _ = coarse
    again = compute_only(tmp_path, resolution="coarse")
    assert again.data.seconds["regime map (Fig. 5)"] < 1.0
    assert [c.value for c in again.checks] == [c.value for c in rep.checks]
    assert all(f.html is None and f.png is None and f.csv.is_file() for f in again.figures)
    assert [p.name for p in tmp_path.glob("*.html")] == ["index.html"]
    assert (tmp_path / "report.md").is_file()


def test_specs_are_unique_and_complete():
    assert len({f.key for f in FIGURES}) == len(FIGURES) == len(PAPER_FIGURES)
    assert set(DRAW) == {f.key for f in FIGURES}  # every table has its picture


@pytest.mark.parametrize("argv, flag", [
    (["reproduce"], "--out"),
    (["reproduce", "--out", "x", "--resolution", "fine"], "--resolution"),
    (["reproduce", "--out", "x", "--workers", "0"], "--workers"),
    (["reproduce", "--out", "x", "--png"], "--png"),  # pictures are the app's
])
def test_cli_bad_usage(argv, flag, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert flag in err and "Traceback" not in err


@pytest.mark.parametrize("argv, flag", [
    ([], "--out"),
    (["--out", "x", "--png", "--no-png"], "--no-png"),
    (["--out", "x", "--resolution", "fine"], "--resolution"),
])
def test_app_cli_bad_usage(argv, flag, capsys):
    assert app_main(argv) == 2
    err = capsys.readouterr().err
    assert flag in err and "Traceback" not in err


def test_cli_out_must_be_a_folder(tmp_path, capsys):
    target = tmp_path / "file.txt"
    target.write_text("x")
    assert main(["reproduce", "--out", str(target)]) == 2
    assert "--out" in capsys.readouterr().err


def test_bad_resolution_in_python():
    with pytest.raises(ValueError, match="resolution='fine'"):
        reproduce("unused", resolution="fine")
