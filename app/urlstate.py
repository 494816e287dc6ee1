"""The dashboard state in the page URL: ``serialize`` writes it, ``parse`` reads it back.

A shared link carries every control (``?k_r=0.03&k_theta=0.03&F_N=1&theta0_deg=90``), so a
reload or a colleague's browser shows the same view. ``parse`` never raises: a value it
cannot use (not a number, NaN, infinite, out of range, unknown choice) is dropped, the
control keeps its default, and a notice naming the parameter is returned for the page.

URL keys (values in the units of the controls):

=============  ====================================================================
``k_r``        radial stiffness k~_r, in [0.01, 3]
``k_theta``    torsional stiffness k~_theta, in [0.01, 3]
``F_N``        normal load F~_N, in [0.1, 10]
``theta0_deg`` rest orientation theta0 in degrees, in [0, 360)
``regime``     ``pendulum``/``slider``/``stiff``/``soft``: sets k_r, k_theta (explicit
               ``k_r``/``k_theta`` override it)
``rtol``       solver tolerance, one of 1e-4 ... 1e-8
``beta``       ``self`` (self-consistent N_c0/N_c) or a fixed value in (0, 1]
``avg``        ``paper`` (Eq. 10) or ``duration`` (duration-weighted average)
``map``        ``5a`` (F_T,x/(mu0 F_N)) or ``5b`` (D_y/D_x) on the regime map
``tab``        ``support``, ``polar``, ``map``, ``load`` or ``equations``
``projector``  ``1`` for projector mode
=============  ====================================================================
"""
from __future__ import annotations

import math
import re
from collections.abc import Mapping
from urllib.parse import parse_qs, urlencode

from model import REGIMES

K_BOUNDS = (0.01, 3.0)
F_N_BOUNDS = (0.1, 10.0)
RTOLS = (1e-4, 1e-5, 1e-6, 1e-7, 1e-8)
TABS = ("support", "polar", "map", "load", "equations")
AVERAGES = ("paper", "duration")
MAP_QUANTITIES = ("5a", "5b")

#: The default view: the pendulum support of Fig. 7a (theta0 = 90 deg, F_N = 1).
DEFAULTS = dict(k_r=3.0, k_theta=0.01, F_N=1.0, theta0=90.0, rtol=1e-6, beta_mode="self",
                beta=1.0, average="paper", map_quantity="5a", tab="support", projector=False)

#: Always written to the URL, so a shared link states the physics explicitly.
ALWAYS = ("k_r", "k_theta", "F_N", "theta0")


def _number(text: str) -> float | None:
    try:
        value = float(text)
    except (TypeError, ValueError):
        return None
    return value if math.isfinite(value) else None


def _in(lo: float, hi: float, hi_open: bool = False):
    def check(text):
        v = _number(text)
        ok = v is not None and lo <= v and (v < hi if hi_open else v <= hi)
        return v if ok else None
    return check


def _rtol(text):
    v = _number(text)
    match = [r for r in RTOLS if v is not None and abs(v - r) <= 1e-9 * r]
    return match[0] if match else None


def _choice(options):
    return lambda text: text if text in options else None


def _flag(text):
    return {"1": True, "true": True, "yes": True, "on": True,
            "0": False, "false": False, "no": False, "off": False}.get(text.lower())


# URL key -> (state parameter, reader returning the value or None, what is expected).
_READERS = {
    "k_r": ("k_r", _in(*K_BOUNDS), "a number in [0.01, 3]"),
    "k_theta": ("k_theta", _in(*K_BOUNDS), "a number in [0.01, 3]"),
    "F_N": ("F_N", _in(*F_N_BOUNDS), "a number in [0.1, 10]"),
    "theta0_deg": ("theta0", _in(0.0, 360.0, hi_open=True), "degrees in [0, 360)"),
    "rtol": ("rtol", _rtol, "one of " + ", ".join(f"{r:g}" for r in RTOLS)),
    "avg": ("average", _choice(AVERAGES), "'paper' or 'duration'"),
    "map": ("map_quantity", _choice(MAP_QUANTITIES), "'5a' or '5b'"),
    "tab": ("tab", _choice(TABS), "one of " + ", ".join(TABS)),
    "projector": ("projector", _flag, "1 or 0"),
}


def _fmt(value: float) -> str:
    return format(float(value), ".6g")


def serialize(values: Mapping) -> dict[str, str]:
    """URL query parameters for the state ``values`` (a mapping of state parameters).

    The physical parameters are always written; the other controls only when they
    differ from ``DEFAULTS``. Numbers keep 6 significant digits.
    """
    out = {"k_r": _fmt(values["k_r"]), "k_theta": _fmt(values["k_theta"]),
           "F_N": _fmt(values["F_N"]), "theta0_deg": _fmt(values["theta0"])}
    if float(out["theta0_deg"]) >= 360.0:  # 359.9999996 rounds to 360, which is 0 degrees
        out["theta0_deg"] = "0"
    if values["rtol"] != DEFAULTS["rtol"]:
        out["rtol"] = f"{values['rtol']:g}"
    if values["beta_mode"] == "fixed":
        out["beta"] = _fmt(values["beta"])
    for key, name in (("avg", "average"), ("map", "map_quantity"), ("tab", "tab")):
        if values[name] != DEFAULTS[name]:
            out[key] = str(values[name])
    if values["projector"]:
        out["projector"] = "1"
    return out


def to_search(values: Mapping) -> str:
    """``serialize`` as a URL search string, ``?k_r=...&...``."""
    return "?" + urlencode(serialize(values))


def _text(value) -> str:
    """One query value as text: the last of repeated keys; bytes decoded."""
    if isinstance(value, (list, tuple)):
        value = value[-1] if value else ""
    if isinstance(value, bytes):
        value = value.decode("utf-8", errors="replace")
    return str(value).strip()


def parse(query: Mapping | str) -> tuple[dict, list[str]]:
    """State values read from URL ``query`` and notices about what was not usable.

    ``query`` is a mapping (``pn.state.session_args`` gives lists of bytes; plain
    strings work too) or a search string (``"?k_r=1&F_N=2"``). Returns
    ``(values, notices)``: ``values`` holds only the parameters that were given and
    valid; every other parameter keeps its default. Never raises.
    """
    if isinstance(query, str):
        query = parse_qs(query.lstrip("?"), keep_blank_values=True)
    values, notices = {}, []
    items = {str(k): _text(v) for k, v in query.items()}
    regime = items.pop("regime", None)
    if regime is not None:
        if regime in REGIMES:
            values.update(k_r=REGIMES[regime].k_r, k_theta=REGIMES[regime].k_theta)
        else:
            notices.append(_notice("regime", regime, "one of " + ", ".join(REGIMES)))
    for key, text in items.items():
        if key.startswith("bokeh"):
            continue
        if key == "beta":
            value = "self" if text == "self" else _in(0.0, 1.0)(text)
            if value == "self":
                values["beta_mode"] = "self"
            elif value is not None and value > 0:
                values.update(beta_mode="fixed", beta=value)
            else:
                notices.append(_notice("beta", text, "'self' or a number in (0, 1]"))
            continue
        if key not in _READERS:
            notices.append(f"Unknown URL parameter {_shown(key)} ignored.")
            continue
        name, read, expected = _READERS[key]
        value = read(text)
        if value is None:
            notices.append(_notice(key, text, expected))
        else:
            values[name] = value
    return values, notices


#: Characters of Markdown/HTML markup and of links ("." and ":" stop the page from
#: turning a domain into a link); escaped where URL text is echoed in a notice.
_MARKUP = re.compile(r"([\\`*_{}\[\]()#!|<>&~\".:])")


def _shown(text: str) -> str:
    """``text`` from the URL as it is echoed in a notice: quoted, at most 40 characters,
    and with its markup characters backslash-escaped, so the page (which renders notices
    as Markdown) shows it literally instead of as HTML, links or formatting."""
    shown = repr(text if len(text) <= 40 else text[:37] + "...")
    return _MARKUP.sub(r"\\\1", shown)


def _notice(key: str, text: str, expected: str) -> str:
    return (f"URL parameter {key}={_shown(text)} is not usable ({expected} expected); "
            "the default is used.")
