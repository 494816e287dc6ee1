"""``python -m app.reproduce`` (data and report from ``model.reproduce``, pictures drawn by
the app): a coarse reproduction into a temporary folder.

Every figure file and CSV must exist and be non-empty, the CSVs must carry their
parameters and read back, and the report must list every finding of docs/model.md with a
verdict. PNGs are required where a browser is (always in CI).
"""
import json
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
from model.runs.sweeps import read_csv

from browser.conftest import browser_required, unavailable

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


@pytest.mark.slow  # the module's coarse reproduction (~40 s, built once)
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


@pytest.mark.slow  # the module's coarse reproduction (~40 s, built once)
def test_pngs_are_made_when_a_browser_is_available(coarse):
    rep, _ = coarse
    if browser_problem() is None:
        assert rep.png_note == "" and all(f.png is not None for f in rep.figures)
    else:
        assert rep.png_note == browser_problem()


@pytest.mark.slow  # the module's coarse reproduction (~40 s, built once)
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


@pytest.mark.slow  # the module's coarse reproduction (~40 s, built once)
def test_report_lists_every_finding_with_a_verdict(coarse):
    rep, _ = coarse
    text = rep.report.read_text(encoding="utf-8")
    for n in range(1, 8):
        assert f"**Finding {n}**" in text
    rows = [line for line in text.splitlines() if re.match(r"\| (\d|extra) \|", line)]
    assert len(rows) == len(rep.checks) >= 25
    assert all(("**agrees**" in r) != ("**differs**" in r) for r in rows)
    assert f"{len(rep.checks) - rep.n_differ} of {len(rep.checks)} checks agree" in text
    # Known differences stay visible (the quoted mu0 ~ 1.0085; the pendulum stretches).
    assert "1.00824" in text and "Where the model and the paper differ" in text
    assert "## Sensitivity" in text and "200 random supports" in text


@pytest.mark.slow  # the module's coarse reproduction (~40 s, built once)
def test_index_links_every_figure(coarse):
    rep, _ = coarse
    page = rep.index.read_text(encoding="utf-8")
    for f in rep.figures:
        assert f"href='{f.html.name}'" in page and f"href='{f.csv.name}'" in page
    assert page.count("<tr class=") == len(rep.checks)


@pytest.mark.slow  # the module's coarse reproduction (~40 s, built once)
def test_checks_use_the_computed_numbers(coarse):
    rep, _ = coarse
    by_quantity = {c.quantity: c for c in rep.checks}
    stiff = by_quantity["F_T,x/(μ₀F_N), stiff"]
    assert float(stiff.value) == pytest.approx(rep.data.headline["stiff"].FTx_over_mu0FN,
                                               abs=1e-4)
    mu = by_quantity["μ(1) with μ_s = 1.3, A = 1.44, B = −20, ζ = 10"]
    assert not mu.agrees  # 1.00824, not the quoted 1.0085


@pytest.mark.slow  # the module's coarse reproduction (~40 s, built once)
def test_sensitivity_variants(coarse):
    rep, _ = coarse
    names = [v.name for v in rep.variants]
    assert names[0] == "baseline" and "β = 1" in names and "λ = 0.1" in names
    base, random = rep.variants[0], rep.variants[-1]
    for regime, value in base.FTx.items():
        # 200 random supports scatter about the quadrature value.
        assert random.FTx[regime] == pytest.approx(value, abs=0.03)
        assert math.isfinite(base.DyDx[regime])


@pytest.mark.slow  # the module's coarse reproduction (~40 s, built once)
def test_progress_covers_every_stage(coarse):
    rep, stages = coarse
    from model.reproduce import all_stages

    seen = [s for s, _, _ in stages]
    assert sorted(set(seen), key=seen.index) == all_stages("coarse")
    for name in ("CSV tables", "figures"):
        assert any(s == name and d == t for s, d, t in stages)


@pytest.mark.slow  # the module's coarse reproduction (~40 s, built once)
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


# --------------------------------------------------------------------------- figures for papers

import xml.etree.ElementTree as ET  # noqa: E402

from bokeh.models import Plot  # noqa: E402

from app.about import version_text  # noqa: E402
from app.reproduce import draw  # noqa: E402

SVG = "{http://www.w3.org/2000/svg}"


@pytest.fixture(scope="module")
def vector(coarse, tmp_path_factory):
    """The coarse reproduction's figures drawn again as SVG and PDF only."""
    if browser_problem():
        unavailable(f"SVG/PDF pictures need Chromium: {browser_problem()}")
    rep, _ = coarse
    out = tmp_path_factory.mktemp("vector")
    files, note = draw(rep.data, out, lambda done, total: None, formats=("svg", "pdf"))
    return rep, out, files, note


def _svg_texts(root) -> str:
    return " ".join("".join(t.itertext()) for t in root.iter(f"{SVG}text"))


def _pdf_title(data: bytes) -> str:
    found = re.search(rb"/Title\s*(\((?P<lit>[^)]*)\)|<(?P<hex>[0-9A-Fa-f]+)>)", data)
    assert found, "the PDF has no title"
    if found.group("hex"):
        return bytes.fromhex(found.group("hex").decode()).decode("utf-16")
    return found.group("lit").decode("latin-1")


@pytest.mark.slow  # the module's coarse reproduction (~40 s, built once)
def test_every_figure_as_svg_and_pdf(vector):
    rep, out, files, note = vector
    assert note == ""
    assert set(files) == {f.key for f in FIGURES}
    for key, (html, png, svg, pdf) in files.items():
        assert html.is_file() and png is None  # exactly the formats asked for
        assert svg == out / f"{key}.svg" and pdf == out / f"{key}.pdf"
    assert not list(out.glob("*.pdf.svg"))  # no intermediate files left


@pytest.mark.parametrize("key", sorted(DRAW))
@pytest.mark.slow  # the module's coarse reproduction (~40 s, built once)
def test_svg_parses_and_holds_the_figure(vector, key):
    rep, out, files, _ = vector
    root = ET.parse(files[key][2]).getroot()
    assert root.tag == f"{SVG}svg"
    width, height = float(root.get("width")), float(root.get("height"))
    assert width >= 300 and height >= 200
    # Vector drawing: lines and markers are paths, text is text.
    assert len(list(root.iter(f"{SVG}path"))) > 20
    texts = _svg_texts(root)
    model = DRAW[key](rep.data)
    plots = list(model.select({"type": Plot}))
    assert plots
    for plot in plots:
        if plot.title is not None and plot.title.text:
            for line in plot.title.text.split("\n"):  # a title of two lines: two texts
                assert line in texts, (key, plot.title.text)
        for axis in (*plot.xaxis, *plot.yaxis):
            if axis.axis_label and "$" not in str(axis.axis_label):
                assert str(axis.axis_label) in texts, (key, axis.axis_label)
    # Named for what it is, with the version (as the CSV header has it).
    spec = next(f for f in FIGURES if f.key == key)
    assert root.find(f"{SVG}title").text == f"Fig. {spec.number}: {spec.caption}"
    meta = json.loads(root.find(f"{SVG}metadata").text)
    assert meta["software"] == version_text() and meta["paper_doi"].startswith("10.1038/")


@pytest.mark.parametrize("key", ["fig3", "fig5a", "fig11a"])
@pytest.mark.slow  # the module's coarse reproduction (~40 s, built once)
def test_pdf_is_one_vector_page_the_size_of_the_svg(vector, key):
    _, _, files, _ = vector
    data = files[key][3].read_bytes()
    assert data.startswith(b"%PDF-")
    assert len(re.findall(rb"/Type\s*/Page[^s]", data)) == 1
    assert b"/FontFile" in data  # text kept as text, not pixels
    box = [float(v) for v in re.search(rb"/MediaBox\s*\[([^\]]*)\]", data).group(1).split()]
    root = ET.parse(files[key][2]).getroot()
    # Chromium prints 96 px to 72 pt.
    assert box[2] == pytest.approx(float(root.get("width")) * 0.75, abs=1.5)
    assert box[3] == pytest.approx(float(root.get("height")) * 0.75, abs=1.5)
    assert version_text() in _pdf_title(data)


@pytest.mark.slow  # the module's coarse reproduction (~40 s, built once)
def test_the_version_is_in_every_exported_file(coarse):
    rep, _ = coarse
    from PIL import Image

    for f in rep.figures:
        assert f"# version: {rep.version}" in f.csv.read_text(encoding="utf-8")
        head = f.html.read_text(encoding="utf-8")[:5000]
        assert f"({version_text()})</title>" in head
        if f.png is not None:
            with Image.open(f.png) as image:
                assert image.text["Software"] == version_text()
    assert rep.version in rep.index.read_text(encoding="utf-8")
    assert rep.version in rep.report.read_text(encoding="utf-8")


def test_format_flag_bad_usage(capsys, monkeypatch, tmp_path):
    import app.reproduce.__main__ as cli_main

    assert app_main(["--out", str(tmp_path), "--format", "eps"]) == 2
    assert "--format" in capsys.readouterr().err
    assert app_main(["--out", str(tmp_path), "--format", "svg", "--no-png"]) == 2
    assert "--no-png" in capsys.readouterr().err
    monkeypatch.setattr(cli_main, "browser_problem", lambda: "no Chromium found")
    assert app_main(["--out", str(tmp_path / "x"), "--format", "svg"]) == 2
    err = capsys.readouterr().err
    assert "--format" in err and "no Chromium found" in err and not (tmp_path / "x").exists()


def test_bad_formats_in_python():
    with pytest.raises(ValueError, match="formats="):
        reproduce("unused", resolution="coarse", formats=("eps",))
