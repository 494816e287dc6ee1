"""Hostile URLs (hypothesis): the query parser (app/urlstate.py) and the served dashboard.

Any query (unicode, huge numbers, NaN, inf, repeated and unknown keys, bytes that are not
UTF-8) gives a valid state, within the sliders' bounds, and one notice per rejected value;
echoed URL text cannot put HTML, links or formatting on the page; over-long values are
refused unread. The served dashboard under the same URLs: tests/test_url_served.py.
"""
import html
import math
import urllib.error
import urllib.parse
import urllib.request
from html.parser import HTMLParser
from pathlib import Path

import pytest
from hypothesis import Phase, assume, given, settings
from hypothesis import strategies as st

from app.state import ExplorerState
from app.defaults import (AVERAGES, BETA_BOUNDS, DEFAULTS, F_N_BOUNDS, K_BOUNDS, MAP_QUANTITIES,
                          ORIENTATIONS, RTOLS, TABS)
from app.urlstate import MAX_VALUE_CHARS, URL_KEYS, parse, serialize
from model import REGIMES, Params

ROOT = Path(__file__).resolve().parents[1]

PHASES = (Phase.explicit, Phase.reuse, Phase.generate, Phase.shrink)
FUZZ = settings(max_examples=300, deadline=None, database=None, phases=PHASES)

KNOWN = ["k_r", "k_theta", "F_N", "theta0_deg", "rtol", "avg", "map", "tab", "projector"]
SPECIAL = ["regime", "beta"]
# Text a value or key may be: numbers of every kind, names, markup, control characters.
NUMBERS = st.one_of(
    st.floats().map(repr), st.floats().map(lambda x: format(x, "g")),
    st.integers(-10**400, 10**400).map(str), st.floats(0.0, 400.0).map(str),
    st.sampled_from(["nan", "NaN", "-nan", "inf", "-inf", "Infinity", "1e308", "1e999",
                     "-0", "0x10", "1_0", "\u0661", "\uff11", " 2 ", "1e-320", "3" * 400]))
WORDS = st.sampled_from(["self", "paper", "duration", "5a", "5b", "support", "polar", "map",
                         "load", "equations", "1", "0", "true", "off", "yes", "maybe", "",
                         *REGIMES, "Pendulum", "<b>x</b>", "[a](http://e.com)", "www.e.com",
                         "**b**", "`c`", "<img src=\"x\" onerror=\"alert(1)\">", "\x00",
                         "\n# h", "a\r\nb", "\u202e", "\ud800", "\\", "&amp;", "%zz"])
TEXT = st.one_of(NUMBERS, WORDS, st.text(max_size=60))
# Random keys are unknown ones: a random "A" or "play" is a key the parser reads, whose
# rules the tests below do not model (tests of those keys: test_pinned*, test_urlstate).
KEY = st.one_of(st.sampled_from(KNOWN + SPECIAL + ["bokeh-session-id", "bokeh-absolute-url"]),
                st.text(max_size=20).filter(lambda k: k not in URL_KEYS))


def _value(text):
    """A query value in each form ``parse`` accepts: str, bytes, a list of them."""
    raw = text.encode("utf-8", "surrogatepass")
    return st.sampled_from([text, [text], [raw], raw, ["ignored", text], [b"\xff\xfe", raw]])


QUERY = st.dictionaries(KEY, TEXT.flatmap(_value), max_size=8)


def _last(value) -> str:
    """The text ``parse`` reads from a query value: the last of a list, bytes decoded."""
    if isinstance(value, list):
        value = value[-1] if value else ""
    if isinstance(value, bytes):
        value = value.decode("utf-8", errors="replace")
    return str(value).strip()


def _number(text):
    try:
        x = float(text)
    except ValueError:
        return None
    return x if math.isfinite(x) else None


def check_state_values(values: dict):
    """Every value ``parse`` returns is one a control can hold."""
    lo, hi = K_BOUNDS
    for name in ("k_r", "k_theta"):
        if name in values:
            assert lo <= values[name] <= hi
    if "F_N" in values:
        assert F_N_BOUNDS[0] <= values["F_N"] <= F_N_BOUNDS[1]
    if "theta0" in values:
        assert 0.0 <= values["theta0"] < 360.0
    if "beta" in values:
        assert BETA_BOUNDS[0] <= values["beta"] <= BETA_BOUNDS[1]
        assert values["beta_mode"] == "fixed"
    assert values.get("beta_mode", "self") in ("self", "fixed")
    assert values.get("rtol", RTOLS[0]) in RTOLS
    assert values.get("average", "paper") in AVERAGES
    assert values.get("map_quantity", "5a") in MAP_QUANTITIES
    assert values.get("tab", "support") in TABS
    assert values.get("projector", False) in (True, False)
    assert set(values) <= set(DEFAULTS)
    for value in values.values():
        assert not isinstance(value, float) or math.isfinite(value)


# --------------------------------------------------------------------------- the parser

@FUZZ
@given(query=QUERY)
def test_any_query_mapping_gives_a_valid_state(query):
    values, notices = parse(query)
    check_state_values(values)
    assert all(isinstance(n, str) and 0 < len(n) < 300 for n in notices)
    s = ExplorerState()
    assert s.load_query(query) == notices
    assert s.notice == " ".join(notices)
    assert isinstance(s.params, Params)  # the model accepts whatever the page holds
    assert s.to_query()  # and the state can be written back


def _in(lo, hi, hi_open=False):
    def ok(text):
        x = _number(text)
        return x is not None and lo <= x and (x < hi if hi_open else x <= hi)
    return ok


# What each URL key accepts (the table in app/urlstate.py's docstring).
ACCEPTS = {
    "k_r": _in(*K_BOUNDS), "k_theta": _in(*K_BOUNDS), "F_N": _in(*F_N_BOUNDS),
    "theta0_deg": _in(0.0, 360.0, hi_open=True),
    "rtol": lambda t: _number(t) is not None and any(abs(_number(t) - r) <= 1e-9 * r
                                                     for r in RTOLS),
    "avg": lambda t: t in AVERAGES, "map": lambda t: t in MAP_QUANTITIES,
    "tab": lambda t: t in TABS,
    "projector": lambda t: t.lower() in ("1", "true", "yes", "on", "0", "false", "no", "off"),
    "regime": lambda t: t in REGIMES,
    "beta": lambda t: t == "self" or _in(*BETA_BOUNDS)(t),
}


def _accepted(key, text) -> bool:
    return len(text) <= MAX_VALUE_CHARS and ACCEPTS[key](text)


@FUZZ
@given(query=QUERY)
def test_every_rejected_value_gets_one_notice(query):
    values, notices = parse(query)
    texts = {str(k): _last(v) for k, v in query.items()}
    rejected = 0
    for key, text in texts.items():
        if key.startswith("bokeh"):
            continue
        if key not in ACCEPTS:
            rejected += 1
            assert any(n.startswith("Unknown URL parameter") for n in notices), notices
            continue
        mine = [n for n in notices if n.startswith(f"URL parameter {key}=")]
        if _accepted(key, text):
            assert not mine, (key, text, mine)
        else:
            rejected += 1
            assert len(mine) == 1, (key, text, notices)
    assert len(notices) == rejected
    # accepted numbers are taken as given; explicit stiffnesses override a regime
    for key, name in (("k_r", "k_r"), ("k_theta", "k_theta"), ("F_N", "F_N"),
                      ("theta0_deg", "theta0")):
        if key in texts and _accepted(key, texts[key]):
            assert values[name] == float(texts[key])
        elif ("regime" in texts and _accepted("regime", texts["regime"])
              and name in ("k_r", "k_theta")):
            assert values[name] == getattr(REGIMES[texts["regime"]], name)
        else:
            assert name not in values


@FUZZ
@given(pairs=st.lists(st.tuples(KEY, TEXT), max_size=8),
       junk=st.lists(st.sampled_from(["", "&", "=", "==", "%", "%zz", "%ED%A0%80", "%FF",
                                      "k_r", "?", ";", "+", "%00", "k_r=%E2%80%AE1"]),
                     max_size=4))
def test_any_search_string_gives_a_valid_state(pairs, junk):
    encoded = urllib.parse.urlencode([(k.encode("utf-8", "surrogatepass"),
                                       v.encode("utf-8", "surrogatepass")) for k, v in pairs])
    search = "?" + "&".join([encoded, *junk])
    values, notices = parse(search)
    check_state_values(values)
    assert all(0 < len(n) < 300 for n in notices)


class _Tags(HTMLParser):
    def __init__(self):
        super().__init__()
        self.tags, self.text = [], []

    def handle_starttag(self, tag, attrs):
        self.tags.append((tag, attrs))

    def handle_data(self, data):
        self.text.append(data)


def _rendered(markdown: str):
    """The HTML the page makes of a notice (its Alert pane renders Markdown)."""
    import panel as pn

    pane = pn.pane.Alert("", alert_type="warning")
    out = html.unescape(pane._transform_object(markdown)["object"])
    tags = _Tags()
    tags.feed(out)
    tags.close()
    return tags.tags, "".join(tags.text)  # the parser resolves the character references


@settings(max_examples=200, deadline=None, database=None, phases=PHASES)
@given(key=st.sampled_from(["k_r", "F_N", "tab", "regime", "unknown"]),
       text=st.one_of(WORDS, st.text(max_size=45), st.text(
           alphabet=st.sampled_from(list("<>[]()*_`!#&;:/.\\\"' =abcx\n")), max_size=45)))
def test_echoed_url_text_is_shown_literally(key, text):
    """The page renders notices as Markdown: URL text must come out as text, never as
    tags (HTML injection: a crafted link could run script in the page), links or
    formatting."""
    if key == "unknown":  # the text as a key
        assume(text not in URL_KEYS and not text.startswith("bokeh"))  # e.g. "A": a key
        query, given_text = {text: "1"}, text
    else:  # as a value; "!" makes it unusable for every key here
        query, given_text = {key: text + "!"}, (text + "!").strip()
    _, notices = parse(query)
    assert len(notices) == 1
    tags, shown = _rendered(notices[0])
    assert [t for t, _ in tags] == ["p"], tags
    given_text = given_text if len(given_text) <= 40 else given_text[:37] + "..."
    assert repr(given_text) in shown


@settings(max_examples=200, deadline=None, database=None, phases=PHASES)
@given(k_r=st.floats(*K_BOUNDS), k_theta=st.floats(*K_BOUNDS), F_N=st.floats(*F_N_BOUNDS),
       theta0=st.one_of(st.floats(0.0, 360.0, exclude_max=True),
                        st.floats(359.999999, 360.0, exclude_max=True)),
       rtol=st.sampled_from(RTOLS),
       beta=st.one_of(st.none(), st.floats(*BETA_BOUNDS)),
       average=st.sampled_from(AVERAGES), map_quantity=st.sampled_from(MAP_QUANTITIES),
       tab=st.sampled_from(TABS), projector=st.booleans(),
       orientation=st.sampled_from(ORIENTATIONS), play=st.booleans())
def test_every_state_round_trips_through_its_url(k_r, k_theta, F_N, theta0, rtol, beta,
                                                 average, map_quantity, tab, projector,
                                                 orientation, play):
    state = dict(k_r=k_r, k_theta=k_theta, F_N=F_N, theta0=theta0, rtol=rtol,
                 beta_mode="self" if beta is None else "fixed",
                 beta=1.0 if beta is None else beta, average=average,
                 map_quantity=map_quantity, tab=tab, projector=projector,
                 orientation=orientation, play=play)
    values, notices = parse("?" + urllib.parse.urlencode(serialize(state)))
    assert notices == []
    for name, value in state.items():
        if name == "beta" and beta is None:
            continue
        back = values.get(name, DEFAULTS[name])
        if name == "theta0":  # an angle: 359.9999996 deg comes back as 0
            assert abs((back - value + 180.0) % 360.0 - 180.0) <= 1e-5 * 360.0
        elif isinstance(value, float) and name != "rtol":
            assert back == pytest.approx(value, rel=1e-5, abs=1e-300), name
        else:
            assert back == value, name


# --------------------------------------------------------------------------- over-long values

LONG_DIGITS = "1" * 4301  # one digit more than Python converts to an int (sys.int_info)


@pytest.mark.parametrize("key", ["k_r", "F_N", "beta", "regime", "tab"])
def test_over_long_values_are_refused_unread_with_a_notice(key):
    values, notices = parse({key: LONG_DIGITS, "theta0_deg": "45"})
    assert values == {"theta0": 45.0}
    assert len(notices) == 1 and notices[0].startswith(f"URL parameter {key}=")
    assert "too long (4301 characters" in notices[0] and len(notices[0]) < 300


def test_beta_below_the_model_bound_gets_a_notice():
    values, notices = parse("?beta=5e-324")
    assert "beta" not in values and len(notices) == 1 and "0.001" in notices[0]
    assert parse(f"?beta={BETA_BOUNDS[0]!r}")[0]["beta"] == Params(1, 1, beta=BETA_BOUNDS[0]).beta
