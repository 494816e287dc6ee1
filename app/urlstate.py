"""The dashboard state in the page URL: ``serialize`` writes it, ``parse`` reads it back.

A shared link carries every control (``?k_r=0.03&k_theta=0.03&F_N=1&theta0_deg=90``), so a
reload or a colleague's browser shows the same view. ``parse`` never raises: a value it
cannot use (not a number, NaN, infinite, out of range, unknown choice, longer than
``MAX_VALUE_CHARS``) is dropped, the control keeps its default, and a notice naming the
parameter is returned for the page. Panel itself never reads the address: the page is
served without Panel's ``Location`` (``servable(location=False)``, ``app/main.py``).

URL keys (values in the units of the controls):

=============  ====================================================================
``k_r``        radial stiffness k~_r, in [0.01, 3]
``k_theta``    torsional stiffness k~_theta, in [0.01, 3]
``F_N``        normal load F~_N, in [0.1, 10]
``theta0_deg`` rest orientation theta0 in degrees, in [0, 360)
``regime``     ``pendulum``/``slider``/``stiff``/``soft``: sets k_r, k_theta (explicit
               ``k_r``/``k_theta`` override it)
``rtol``       solver tolerance, one of 1e-4 ... 1e-8
``beta``       ``self`` (self-consistent N_c0/N_c) or a fixed value in ``BETA_BOUNDS``
``avg``        ``paper`` (Eq. 10) or ``duration`` (duration-weighted average)
``map``        ``5a`` (F_T,x/(mu0 F_N)) or ``5b`` (D_y/D_x) on the regime map
``tab``        ``support``, ``array``, ``polar``, ``map``, ``load`` or ``equations``
``orient``     ``uniform`` or ``fixed``: the orientations of the array under the slab
``play``       ``1`` to start the animations playing when the page opens
``projector``  ``1`` for projector mode
``d_<input>``  Design tab: a pillar-array input with its unit (``d_D=5 um``, ``d_V0=1 m/s``;
               see ``DESIGN_INPUTS``); ``d_G`` empty means G from Poisson's ratio ``d_nu``;
               the friction law of Eq. (4) is ``d_Vs`` (with its unit), ``d_mus``, ``d_A``
               and ``d_B`` (within ``model.contact.params.RANGES``)
``dist``       Design tab: ``fixed``, ``pair``, ``vonmises``, ``uniform`` or ``histogram``
``hist``       Design tab: an uploaded histogram of <= 40 equal bins (``app.histogram``)
``dist_deg``   Design tab: theta0 (fixed, pair) or the mean (von Mises) in degrees, [0, 360)
``kappa``      Design tab: the von Mises concentration, in [0, 1e4]
``psi_deg``    Design tab: the sliding direction psi to the array in degrees, [-180, 180]
``mix``        Design tab: the weight of a second component in [0, 1] (0: no mixture),
               which ``dist2``, ``dist2_deg`` and ``kappa2`` describe as above
``objective``  Design tab: ``min-FTx`` or ``max-FTy``, what Optimise seeks
``bound``      Design tab: its bound, |F_T,y|/(mu0 F_N) or F_T,x/(mu0 F_N), in [0, 2]
``A``          the pinned state of a comparison, its keys and values as above joined as
               ``key:value`` by commas: ``A=k_r:0.5,k_theta:0.2,F_N:1,theta0_deg:90``
               (``rtol``, ``beta`` and the Design tab's keys only when not the default;
               at most ``MAX_PINNED_CHARS``; see ``app.pinned_state``)
=============  ====================================================================
"""
from __future__ import annotations

import math
import re
from collections.abc import Mapping
from urllib.parse import parse_qs, unquote, urlencode

from model import REGIMES
from model.controls import CONTROLS, OBJECTIVES
from model.lab.friction_law import COEFFICIENTS, FrictionLaw
from model.contact.params import RANGES
from model.designs.units import quantity, to_si

from .defaults import (AVERAGES, BETA_BOUNDS, BOUND_BOUNDS, DEFAULTS, DESIGN_DEFAULTS,
                       DESIGN_INPUTS, DIST_DEG, DIST_FAMILIES, F_N_BOUNDS, K_BOUNDS,
                       KAPPA_BOUNDS, MAP_QUANTITIES, MIX_BOUNDS, ORIENTATIONS, PSI_BOUNDS, RTOLS,
                       TABS, THETA0_DEG)
from .histogram import LINK_MAX_BINS, from_link, link_text
from .pinned_state import PINNED_URL_KEYS, complete

#: Longest URL value read, in characters (the page writes at most a histogram's 100); a
#: longer one is refused unread: Python converts at most 4300 digits to an int (Panel's
#: parser fails on ``?x=`` + 4301 digits), and no request may make the server convert more.
MAX_VALUE_CHARS = 100

#: The longest ``A=`` value read (``app.pinned_state``): the support's values (under 100
#: characters) and every design input at its longest (40; the friction law's included)
#: with every distribution value take under 1100.
MAX_PINNED_CHARS = 1200

#: The Design tab's numeric distribution and optimisation controls: URL key -> parameter.
_DESIGN_NUMBERS = (("dist_deg", "dist_deg"), ("kappa", "dist_kappa"), ("psi_deg", "dist_psi"),
                   ("mix", "mix_weight"), ("dist2_deg", "dist2_deg"), ("kappa2", "dist2_kappa"))

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
    "k_r": ("k_r", _in(*K_BOUNDS), CONTROLS["k_r"].expected()),
    "k_theta": ("k_theta", _in(*K_BOUNDS), CONTROLS["k_theta"].expected()),
    "F_N": ("F_N", _in(*F_N_BOUNDS), CONTROLS["F_N"].expected()),
    "theta0_deg": ("theta0", _in(THETA0_DEG.lo, THETA0_DEG.hi, hi_open=THETA0_DEG.hi_open),
                   f"degrees in {THETA0_DEG}"),
    "rtol": ("rtol", _rtol, CONTROLS["rtol"].expected()),
    "avg": ("average", _choice(AVERAGES), " or ".join(map(repr, AVERAGES))),
    "map": ("map_quantity", _choice(MAP_QUANTITIES), " or ".join(map(repr, MAP_QUANTITIES))),
    "tab": ("tab", _choice(TABS), "one of " + ", ".join(TABS)),
    "projector": ("projector", _flag, "1 or 0"),
    "orient": ("orientation", _choice(ORIENTATIONS), "'uniform' or 'fixed'"),
    "play": ("play", _flag, "1 or 0"),
    "dist": ("dist_family", _choice(DIST_FAMILIES), "one of " + ", ".join(DIST_FAMILIES)),
    "dist_deg": ("dist_deg", _in(DIST_DEG.lo, DIST_DEG.hi, hi_open=DIST_DEG.hi_open),
                 f"degrees in {DIST_DEG}"),
    "kappa": ("dist_kappa", _in(*KAPPA_BOUNDS), f"a number in {list(KAPPA_BOUNDS)}"),
    "psi_deg": ("dist_psi", _in(*PSI_BOUNDS), f"degrees in {list(PSI_BOUNDS)}"),
    "mix": ("mix_weight", _in(*MIX_BOUNDS), CONTROLS["mix_weight"].expected()),
    "dist2": ("dist2_family", _choice(DIST_FAMILIES), "one of " + ", ".join(DIST_FAMILIES)),
    "dist2_deg": ("dist2_deg", _in(DIST_DEG.lo, DIST_DEG.hi, hi_open=DIST_DEG.hi_open),
                  f"degrees in {DIST_DEG}"),
    "kappa2": ("dist2_kappa", _in(*KAPPA_BOUNDS), f"a number in {list(KAPPA_BOUNDS)}"),
    "objective": ("opt_objective", _choice(OBJECTIVES), " or ".join(map(repr, OBJECTIVES))),
    "bound": ("opt_bound", _in(*BOUND_BOUNDS), CONTROLS["bound"].expected()),
    "hist": ("dist_hist", from_link, f"first edge:bin width:weights, <= {LINK_MAX_BINS} bins"),
}


def _design_text(field):
    def check(text):
        if text == "" and field == "G":  # no shear modulus: from Poisson's ratio
            return ""
        if len(text) > 40:
            return None
        try:
            quantity(field, text)
            if field in COEFFICIENTS:  # within the law's bounds (``model.contact.params.RANGES``)
                FrictionLaw(**{field: to_si(field, text)})
        except ValueError:
            return None
        return text
    return check


for _name, (_key, _field, *_) in DESIGN_INPUTS.items():
    _READERS[_key] = (_name, _design_text(_field), f"a number in {RANGES[_field][0]}"
                      if _field in COEFFICIENTS and _field in RANGES else
                      f"a quantity like {DESIGN_DEFAULTS[_name] or '0.36 GPa'!r}")
#: Every URL key ``parse`` reads (any other, except ``bokeh*``, gets an "Unknown" notice).
URL_KEYS = (*_READERS, "regime", "beta", "A")


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
    for key, name in (("avg", "average"), ("map", "map_quantity"), ("tab", "tab"),
                      ("orient", "orientation")):
        if values[name] != DEFAULTS[name]:
            out[key] = str(values[name])
    for key in ("projector", "play"):
        if values[key]:
            out[key] = "1"
    # The Design tab's values, when given, are written where they differ from the defaults.
    design = {name: values.get(name, DEFAULTS[name]) for name in DEFAULTS}
    for name, (key, *_) in DESIGN_INPUTS.items():
        if design[name] != DEFAULTS[name]:
            out[key] = str(design[name])
    for key, name in (("dist", "dist_family"), ("dist2", "dist2_family"),
                      ("objective", "opt_objective")):
        if design[name] != DEFAULTS[name]:
            out[key] = design[name]
    for key, name in _DESIGN_NUMBERS:
        if design[name] != DEFAULTS[name]:
            out[key] = _fmt(design[name])
            if key.endswith("_deg") and key != "psi_deg" and float(out[key]) >= 360.0:
                out[key] = "0"  # an angle in [0, 360) that rounds to 360, as theta0
    if design["opt_bound"] is not None:
        out["bound"] = _fmt(design["opt_bound"])
    if link_text(design["dist_hist"]):
        out["hist"] = link_text(design["dist_hist"])
    if values.get("pinned"):
        out["A"] = pinned_text(values["pinned"])
    return out


def to_search(values: Mapping) -> str:
    """``serialize`` as a URL search string, ``?k_r=...&...``."""
    # ":" and "," stay readable in the pinned state, ``A=k_r:0.5,k_theta:0.2,...``.
    return "?" + urlencode(serialize(values), safe=":,")


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
        if len(regime) > MAX_VALUE_CHARS:
            notices.append(_too_long("regime", regime))
        elif regime in REGIMES:
            values.update(k_r=REGIMES[regime].k_r, k_theta=REGIMES[regime].k_theta)
        else:
            notices.append(_notice("regime", regime, "one of " + ", ".join(REGIMES)))
    for key, text in items.items():
        if key.startswith("bokeh"):
            continue
        if key not in ("beta", "A") and key not in _READERS:
            notices.append(f"Unknown URL parameter {_shown(key)} ignored.")
            continue
        if len(text) > (MAX_PINNED_CHARS if key == "A" else MAX_VALUE_CHARS):
            notices.append(_too_long(key, text))
            continue
        if key == "A":
            pinned = parse_pinned(text)
            if pinned is None:
                notices.append(_notice("A", text, PINNED_EXPECTED))
            else:
                values["pinned"] = pinned
            continue
        if key == "beta":
            value = "self" if text == "self" else _in(*BETA_BOUNDS)(text)
            if value == "self":
                values["beta_mode"] = "self"
            elif value is not None:
                values.update(beta_mode="fixed", beta=value)
            else:
                notices.append(_notice("beta", text, "'self' or a number in "
                                       f"{CONTROLS['beta'].interval}"))
            continue
        name, read, expected = _READERS[key]
        value = read(text)
        if value is None:
            notices.append(_notice(key, text, expected))
        else:
            values[name] = value
    return values, notices


#: Markdown/HTML and link characters ("." and ":" stop autolinks), escaped in notices.
_MARKUP = re.compile(r"([\\`*_{}\[\]()#!|<>&~\".:])")


def _shown(text: str) -> str:
    """``text`` from the URL as echoed in a notice (Markdown): quoted, at most 40 characters,
    its markup characters backslash-escaped so it shows literally, never as HTML or links."""
    shown = repr(text if len(text) <= 40 else text[:37] + "...")
    return _MARKUP.sub(r"\\\1", shown)


def _too_long(key: str, text: str) -> str:
    most = MAX_PINNED_CHARS if key == "A" else MAX_VALUE_CHARS
    return (f"URL parameter {key}={_shown(text)} is too long ({len(text)} characters, at most "
            f"{most}); the default is used.")


def _notice(key: str, text: str, expected: str) -> str:
    return (f"URL parameter {key}={_shown(text)} is not usable ({expected} expected); "
            "the default is used.")


# ---------------------------------------------------------------- the pinned state A
#: What ``A=`` holds, for notices.
PINNED_EXPECTED = ("key:value pairs joined by commas, of " + ", ".join(PINNED_URL_KEYS[:6])
                   + " and the Design tab's keys, such as k_r:0.5,k_theta:0.2,F_N:1,"
                   "theta0_deg:90")


def _escape(text: str) -> str:
    return text.replace("%", "%25").replace(",", "%2C")


def pinned_text(pinned: Mapping) -> str:
    """The ``A=`` text of a pinned state (``app.pinned_state``): its URL values, as
    ``serialize`` writes them, as ``key:value,...``."""
    query = serialize({**DEFAULTS, **complete(pinned)})
    return ",".join(f"{key}:{_escape(query[key])}" for key in PINNED_URL_KEYS if key in query)


def parse_pinned(text: str) -> dict | None:
    """The pinned state an ``A=`` text describes (defaults for keys it omits), or None when
    any part is unusable."""
    pairs = [part.split(":", 1) for part in text.split(",") if part.strip()]
    if not pairs or any(len(pair) != 2 for pair in pairs):
        return None
    query = {key.strip(): unquote(value.strip()) for key, value in pairs}
    if not set(query) <= set(PINNED_URL_KEYS):
        return None
    values, notices = parse(query)
    return None if notices else complete(values)
