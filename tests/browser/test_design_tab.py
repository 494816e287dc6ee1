"""The Design tab of the served dashboard: the pillar array's dimensionless point is
computed and marked on the regime map, and it moves along its speed line when the
sliding speed is typed in; the distribution editor (family, parameters, a histogram file)
redraws the density over the Fig. 11a curve and changes the readouts; a measured friction
curve uploaded is fitted, drawn on Fig. 3 and carried by the link."""
from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from model.lab.friction_curve import read_curve
from model.lab.friction_fit import fit_friction
from model.designs.units import PillarDesign

from . import page_tools as pt

pytestmark = [pytest.mark.browser, pytest.mark.timeout(240)]


def _wait_point(page, predicate, timeout_ms=60_000):
    waited, data = 0, None
    while waited < timeout_ms:
        data = pt.read_source(page, "design_point")
        if data and data.get("k_r") and predicate(data):
            return data
        page.wait_for_timeout(250)
        waited += 250
    pytest.fail(f"the design's point never showed as expected; last: {data}")


def test_the_design_tab_marks_its_point_on_the_map(page, page_log, app_url):
    pt.wait_for_app(page, f"{app_url}?tab=design")
    pt.wait_for_plot(page, "design_map")
    # The default pillars (LDPE, the notes' example) at the default speed of 1 m/s.
    expected = PillarDesign.example(V0="1 m/s").dimensionless()
    point = _wait_point(page, lambda d: True)
    assert point["k_r"][0] == pytest.approx(expected["k_r"], rel=1e-9)
    assert point["k_theta"][0] == pytest.approx(expected["k_theta"], rel=1e-9)
    line = pt.read_source(page, "design_line")
    assert len(line["k_r"]) > 10  # the speed line through it
    # Outside the paper's map: the log axes widen to show it.
    x_end = page.evaluate("""() => [...Bokeh.documents[0].all_models].find(
        (m) => m.name === "design_map" && "x_range" in m).x_range.end""")
    assert x_end > expected["k_r"]
    shown = page.locator(".design-point p").filter(has_text="outside the paper's explored map")
    shown.first.wait_for(timeout=30_000)
    assert "stiff" in shown.first.inner_text()

    # Typing a faster slab moves the point down the diagonal: both k~ scale as 1/V0^2.
    box = page.locator(".ctl-design_V0 input").first
    box.fill("2 m/s")
    box.press("Enter")
    moved = _wait_point(page, lambda d: abs(d["k_r"][0] - expected["k_r"] / 4)
                        <= 1e-6 * expected["k_r"])
    assert moved["k_theta"][0] == pytest.approx(expected["k_theta"] / 4, rel=1e-9)
    assert _wait_url(page, "d_V0=2"), page.url  # the link carries it

    # A wrong unit is named, and nothing is marked.
    box.fill("2 kg")
    box.press("Enter")
    page.locator(".design-point p").filter(has_text="V0='2 kg'").first.wait_for(timeout=30_000)
    page.wait_for_function("""() => { const s = [...Bokeh.documents[0].all_models].find(
        (m) => m.name === "design_point" && /DataSource$/.test(m.type));
        const d = s.data instanceof Map ? Object.fromEntries(s.data) : s.data;
        return d.k_r.length === 0; }""", timeout=30_000)
    assert page_log.errors == [], page_log.errors


def _wait_url(page, fragment, timeout_ms=5_000):
    waited = 0
    while waited < timeout_ms:
        if fragment in page.url:
            return True
        page.wait_for_timeout(200)
        waited += 200
    return False


FAST = "?tab=design&d_FN=1%20N&d_V0=100%20m/s&d_Vs=10%20m/s&dist=pair&dist_deg=40"


def test_optimise_runs_in_the_background_and_sets_the_optimum(page, page_log, app_url):
    pt.wait_for_app(page, f"{app_url}{FAST}")
    _wait_point(page, lambda d: True)
    page.locator(".design-optimise button").first.click()
    # Done (about a second of a worker here) or still running: either way the page says so.
    page.locator(".design-optimum p").filter(has_text="less friction").first.wait_for(
        timeout=90_000)
    text = page.locator(".design-optimum p").filter(has_text="less friction").first.inner_text()
    assert "Optimum (pair)" in text
    # The editor is set to the optimum, and the link carries it.
    page.wait_for_function("() => /dist_deg=/.test(location.search) && "
                           "!/dist_deg=40(&|$)/.test(location.search)", timeout=10_000)
    assert page_log.errors == [], page_log.errors


def test_a_long_optimisation_shows_progress_and_can_be_cancelled(page, page_log, app_url):
    # The default pillars lie far outside the map (k~ ~ 1e3): the search takes long.
    pt.wait_for_app(page, f"{app_url}?tab=design&dist=fixed")
    _wait_point(page, lambda d: True)
    page.locator(".design-optimise button").first.click()
    page.locator(".design-optimum p").filter(has_text="s so far").first.wait_for(
        timeout=20_000)
    page.locator(".design-cancel button").first.click()
    page.locator(".design-optimum p").filter(has_text="Cancelled").first.wait_for(
        timeout=10_000)
    assert not page.locator(".design-cancel button").first.is_enabled()
    assert page.locator(".design-optimise button").first.is_enabled()
    assert page_log.errors == [], page_log.errors


# --------------------------------------------------------------------------- the editor

def _readout(page) -> float | None:
    """F_T,x/(mu0 F_N) of the array as the readouts' table shows it (None while computing)."""
    cells = page.locator(".design-readouts td").all_inner_texts()
    notes = " ".join(page.locator(".design-readouts p").all_inner_texts())
    for label, value in zip(cells, cells[1:]):
        if label.startswith("F_T,x/(μ₀F_N) (Eq. 10)") and "Updating" not in notes:
            match = re.match(r"\s*([0-9.]+)", value)
            return float(match.group(1)) if match else None
    return None


def _wait_readout(page, predicate, what: str) -> float:
    value = {}

    def ready():
        value["x"] = _readout(page)
        return value["x"] is not None and predicate(value["x"])
    # On failure, name what the page showed last (a stale value, an error, "Updating").
    pt.wait_for(page, ready, timeout_s=90.0, what=lambda: "{}; the readouts showed: {!r}".format(
        what, " | ".join(page.locator(".design-readouts").all_inner_texts())))
    return value["x"]


def _density_peak(page) -> tuple[float, int]:
    """(angle in degrees of the density curve's farthest point, number of points)."""
    d = pt.read_source(page, "design_density")
    if not d or not d.get("x"):
        return math.nan, 0
    r = [math.hypot(x, y) for x, y in zip(d["x"], d["y"])]
    i = max(range(len(r)), key=r.__getitem__)
    return math.degrees(math.atan2(d["y"][i], d["x"][i])) % 360.0, len(r)


def _set_number(page, css_class: str, text: str) -> None:
    box = page.locator(f".{css_class} input").first
    box.fill(text)
    box.press("Enter")


def test_the_distribution_editor_redraws_the_density_and_the_readouts(page, page_log, app_url,
                                                                      tmp_path):
    """von Mises at 90 deg (the default) -> mean 30 deg -> the pair +-40 deg -> an uploaded
    histogram: each redraws the density over the Fig. 11a curve and changes the readouts;
    a bad file is named and changes nothing."""
    pt.wait_for_app(page, f"{app_url}?tab=design&d_FN=1%20N&d_V0=100%20m/s&d_Vs=10%20m/s")
    pt.wait_for(page, lambda: len(pt.read_source(page, "polar_FTx")["x"]) > 10,
                timeout_s=90.0, what="the Fig. 11a curve of the design's springs")
    pt.wait_for(page, lambda: abs(_density_peak(page)[0] - 90.0) < 1.0, timeout_s=30.0,
                what="the von Mises density peaking at its mean, 90 deg")
    first = _wait_readout(page, lambda x: True, "the readouts of the default distribution")

    _set_number(page, "ctl-dist_deg", "30")
    pt.wait_for(page, lambda: abs(_density_peak(page)[0] - 30.0) < 1.0, timeout_s=30.0,
                what="the density following the mean to 30 deg")
    at_30 = _wait_readout(page, lambda x: x != first, "the readouts of the mean at 30 deg")

    page.locator(".ctl-dist_family select").first.select_option(label="pair ±θ₀")
    _set_number(page, "ctl-dist_deg", "40")

    def spokes() -> list:
        atoms = pt.read_source(page, "design_atoms")
        return sorted(round(math.degrees(math.atan2(ys[1], xs[1]))) for xs, ys in
                      zip(atoms["xs"], atoms["ys"]))
    # The family's change may be drawn first (the pair at the former 30 deg), then 40 deg.
    pt.wait_for(page, lambda: _density_peak(page)[1] == 0 and spokes() == [-40, 40],
                timeout_s=30.0, what=lambda: "the pair drawn as two spokes at +-40 deg instead "
                f"of a density; drawn: {spokes()}, density peak {_density_peak(page)}")
    pair = _wait_readout(page, lambda x: x not in (first, at_30), "the pair's readouts")
    pt.wait_for(page, lambda: "dist=pair" in page.url and "dist_deg=40" in page.url,
                timeout_s=10.0, what="the pair in the link")

    # A histogram from a file: all supports between 120 and 150 degrees.
    good = tmp_path / "orientations.csv"
    good.write_text("lower_deg,upper_deg,weight\n0,120,0\n120,150,1\n150,360,0\n")
    page.locator(".design-histogram-file input[type=file]").first.set_input_files(str(good))
    pt.wait_for(page, lambda: 120.0 <= _density_peak(page)[0] <= 150.0, timeout_s=30.0,
                what="the uploaded histogram's density between 120 and 150 deg")
    first_histogram = _wait_readout(page, lambda x: x != pair, "the histogram's readouts")
    note = " ".join(page.locator(".design-histogram p").all_inner_texts())
    assert "3 bins from 0° to 360°" in note and "Not in the link" in note  # unequal bins

    # Equal bins are in the link.
    equal = tmp_path / "equal.csv"
    equal.write_text("theta0_deg,weight\n" + "".join(
        f"{10 * i + 5},{3 if i == 13 else 1}\n" for i in range(36)))
    page.locator(".design-histogram-file input[type=file]").first.set_input_files(str(equal))
    pt.wait_for(page, lambda: 130.0 <= _density_peak(page)[0] <= 140.0, timeout_s=30.0,
                what="the second histogram's density peaking in its heavy bin")
    pt.wait_for(page, lambda: "hist=0:10:" in page.url, timeout_s=10.0,
                what="the histogram in the link")
    # The density is redrawn before the array is computed: wait for the second histogram's
    # own readouts, not the first one's still on screen.
    shown = _wait_readout(page, lambda x: x != first_histogram, "the second histogram's readouts")

    bad = tmp_path / "bad.csv"
    bad.write_text("theta0_deg,weight\n10,1\n20,-3\n")
    page.locator(".design-histogram-file input[type=file]").first.set_input_files(str(bad))
    page.locator(".design-histogram p").filter(
        has_text="negative weight -3 on line 3").first.wait_for(timeout=20_000)
    assert 130.0 <= _density_peak(page)[0] <= 140.0 and _readout(page) == shown
    assert "hist=0:10:" in page.url
    assert page_log.errors == [], page_log.errors


# --------------------------------------------------------------------------- friction law

def test_a_measured_friction_curve_is_fitted_drawn_and_carried_by_the_link(page, page_log,
                                                                          app_url):
    """The example curve uploaded: the fitted coefficients with their 95 % intervals in the
    page, the law's inputs set to them, Fig. 3 drawing the points and the band, and the
    link carrying the four coefficients."""
    example = Path(__file__).resolve().parents[2] / "examples" / "flat_friction.csv"
    fit = fit_friction(read_curve(example))
    pt.wait_for_app(page, f"{app_url}?tab=design")
    pt.wait_for_plot(page, "design_law")
    assert "d_mus" not in page.url  # the paper's law: not in a default view's link
    page.locator(".design-friction-file input[type=file]").first.set_input_files(str(example))
    note = page.locator(".design-friction p").filter(has_text="Fitted to")
    note.first.wait_for(timeout=30_000)
    text = " ".join(page.locator(".design-friction p").all_inner_texts())
    lo, hi = fit.ci95["mu_s"]
    assert f"μ_s = {fit.values['mu_s']:.4g} [{lo:.4g}, {hi:.4g}]" in text, text
    lo, hi = fit.ci95["V_s"]
    assert f"V_s = {1e3 * fit.values['V_s']:.4g} [{1e3 * lo:.4g}, {1e3 * hi:.4g}] mm/s" in text
    assert "The design uses this fit." in text
    shown = {key: f"{fit.values[name]:.6g}" for key, name in
             (("d_mus", "mu_s"), ("d_A", "A"), ("d_B", "B"))}
    pt.wait_for(page, lambda: all(f"{k}={v}" in page.url for k, v in shown.items())
                and "d_Vs=1.065" in page.url, timeout_s=20.0,
                what=lambda: f"the fitted coefficients {shown} in the link {page.url}")
    assert page.locator(".ctl-design_mu_s input").first.input_value() == shown["d_mus"]
    pt.wait_for(page, lambda: len((pt.read_source(page, "law_measured") or {}).get("v", []))
                == fit.n_points and len(pt.read_source(page, "law_band")["v"]) > 10,
                timeout_s=20.0, what="the measured points and the fit's band on Fig. 3")
    assert page_log.errors == [], page_log.errors
