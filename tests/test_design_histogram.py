"""The Design tab's histogram upload (app.histogram, app/views/design_upload.py): a CSV
file of orientations becomes the edited distribution, is computed and drawn, survives a
shared link when it has at most 40 equal bins (the page says when it does not), and a bad
file is named and changes nothing."""
import numpy as np
import pytest

from app.histogram import (LEVELS, LINK_MAX_BINS, LINK_MAX_CHARS, MAX_BINS,
                           from_link, link_text, read_upload)
from app.state import ExplorerState
from app.urlstate import MAX_VALUE_CHARS, parse
from app.views.page import Dashboard
from model import Params
from model.designs.distribution_array import distribution_array
from model.designs.distributions import Histogram, from_dict

FAST = "?tab=design&d_FN=1%20N&d_V0=100%20m/s&d_Vs=10%20m/s"
#: 36 bins of 10 degrees, four times as many supports between 45 and 85 degrees.
PEAKED = b"theta0_deg,weight\n" + b"".join(
    b"%d,%d\n" % (10 * i, 4 if 5 <= i <= 8 else 1) for i in range(36))
#: Unequal bins: used as read, not in a link.
UNEQUAL = b"lower_deg,upper_deg,weight\n0,30,1\n30,90,3\n90,360,1\n"


def csv_bytes(rows, header="theta0_deg,weight"):
    return (header + "\n" + "".join(",".join(map(str, r)) + "\n" for r in rows)).encode()


@pytest.fixture(scope="module")
def page():
    state = ExplorerState()
    assert state.load_query(FAST) == []
    return Dashboard(state)


def upload(page, data: bytes, filename: str = "h.csv"):
    page.design.upload.file.param.update(value=data, filename=filename)


def test_an_uploaded_histogram_is_the_distribution_computed_and_drawn(page):
    from app.figures import sources
    s, r = page.state, page.results
    upload(page, PEAKED)
    assert s.dist_family == "histogram"
    assert s.distribution["family"] == "histogram"
    assert s.distribution["edges_deg"][0] == -5.0 and len(s.distribution["weights"]) == 36
    a = r.design_array
    assert a is not None and a["success"], r.errors
    assert a["array"]["distribution"]["family"] == "histogram"
    # The model's array for the file as read (the link's rounding is below 1.2e-4 of a bin).
    point = r.design_point["point"]
    params = Params(k_r=point["k_r"], k_theta=point["k_theta"], F_N=point["F_N"],
                    zeta=point["zeta"], L0=point["L0"])
    ref = distribution_array(params, Histogram.from_text(PEAKED.decode()), tol=1e-4)
    err = a["array"]["quadrature_error"]["FTx_over_mu0FN"] + ref.quadrature_error[
        "FTx_over_mu0FN"]
    assert a["array"]["FTx_over_mu0FN"] == pytest.approx(ref.FTx_over_mu0FN, abs=3 * err + 1e-4)
    assert f"{a['array']['FTx_over_mu0FN']:.4f}" in page.design.readouts.object
    # Drawn over the polar curve: the density peaks in the heavy bins (45 to 85 degrees).
    density = sources(page.design.polar_figure)["design_density"].data
    angle = np.degrees(np.arctan2(density["y"], density["x"])) % 360
    radius = np.hypot(density["x"], density["y"])
    assert 45 <= angle[np.argmax(radius)] <= 85
    assert radius[np.argmin(abs(angle - 200))] == pytest.approx(radius.max() / 4, rel=1e-3)
    note = page.design.upload.note.object
    assert "36 bins from -5° to 355°" in note and "In the link" in note
    assert page.design.angle.disabled


@pytest.mark.parametrize("data, named", [
    (b"", "is empty"),
    (b"theta0_deg,weight\n", "is empty"),
    (b"theta0_deg,weight\n10,1\n20,lots\n", "non-numeric value 'lots' on line 3"),
    (b"theta0_deg,weight\n10,1\n20,-2\n", "negative weight -2 on line 3"),
    (b"theta0_deg,weight\n10,1\n20,nan\n", "not finite"),
    (b"theta0_deg,weight\n10,0\n20,0\n", "every weight is 0"),
    (b"angle,count\n10,1\n", "header"),
    (b"theta0_deg,weight\n" + b"0,1\n" * 30000, "too large"),
    (csv_bytes([(0.5 * i, 1) for i in range(MAX_BINS + 1)]), f"at most {MAX_BINS} are used"),
    (b"\xff\xfe\x00t\x00h", "not a text"),
])
def test_a_bad_file_is_named_and_changes_nothing(page, data, named):
    s, r = page.state, page.results
    upload(page, PEAKED)
    before, array = s.values(), r.design_array
    upload(page, data, "bad.csv")
    note = page.design.upload.note.object
    assert "**Not loaded:**" in note and named in note.replace("\\", "")
    assert "Nothing was changed" in note and "'bad.csv'" in note.replace("\\", "")
    assert s.values() == before and r.design_array is array
    with pytest.raises(ValueError, match=named.replace("(", r"\(")):
        read_upload(data, "bad.csv")


def test_the_histogram_survives_a_shared_link(page):
    s = page.state
    upload(page, PEAKED)
    query = s.to_query()
    assert query["dist"] == "histogram" and len(query["hist"]) <= MAX_VALUE_CHARS
    t = ExplorerState()
    assert t.load_query(s.to_search()) == []
    assert t.dist_hist == s.dist_hist and t.distribution == s.distribution
    # The weights held are the link's levels: within 1/(2 LEVELS) of the file's, relative
    # to the largest bin.
    held = from_dict(s.distribution)
    read = Histogram.from_text(PEAKED.decode())
    assert np.allclose(held.edges, read.edges, atol=1e-12)
    w, v = np.asarray(held.weights), np.asarray(read.weights)
    assert np.max(abs(w / w.max() - v / v.max())) <= 0.5 / LEVELS


def test_a_histogram_a_link_cannot_carry_is_said_to_be_left_out(page):
    s = page.state
    upload(page, UNEQUAL)
    assert s.dist_hist["weights"] == pytest.approx([0.2, 0.6, 0.2])
    note = page.design.upload.note.object
    assert "Not in the link" in note and f"at most {LINK_MAX_BINS} equally wide bins" in note
    query = s.to_query()
    assert "hist" not in query and query["dist"] == "histogram"
    # That link opens with the uniform distribution and says a file is needed.
    t = ExplorerState()
    assert t.load_query(s.to_search()) == []
    assert t.dist_family == "histogram" and t.dist_hist is None
    assert t.distribution == {"family": "uniform"}
    other = Dashboard(t)
    assert "No histogram uploaded" in other.design.upload.note.object


@pytest.mark.parametrize("bins, linked", [(36, True), (LINK_MAX_BINS, True),
                                          (LINK_MAX_BINS + 1, False), (72, False)])
def test_the_link_carries_at_most_its_bins(bins, linked):
    width = 360 / bins
    hist = read_upload(csv_bytes([(width * (i + 0.5), 1 + i % 7) for i in range(bins)]))
    text = link_text(hist)
    assert (text is not None) is linked
    if linked:
        assert len(text) <= LINK_MAX_CHARS == MAX_VALUE_CHARS
        assert from_link(text) == hist


@pytest.mark.parametrize("text", ["-5:10:", "-5:10:AAAA", "-5:10:A", "x:10:AB", "-5:0:AB",
                                  "-5:10:A*", "-5:100:ABABABAB", "0:nan:AB", "-5:10:AB:CD"])
def test_an_unusable_link_histogram_keeps_the_default_with_a_notice(text):
    values, notices = parse({"hist": text})
    assert values == {} and len(notices) == 1 and "hist=" in notices[0]
