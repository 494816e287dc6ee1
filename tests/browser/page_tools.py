"""Helpers that drive the served dashboard in headless Chromium and read it back.

Everything here works on the Bokeh document in the page: widgets are found by their
titles (Bokeh ``Slider.title``, button labels), plotted data is read from the
``ColumnDataSource`` models of ``Bokeh.documents[0].all_models``.

``measure_slider_latency`` (also used by the benchmarks) times, inside the page, a slider
key press to the first animation frame in which plotted data has changed.
"""
from __future__ import annotations

import math
import re
import statistics
import time
from dataclasses import dataclass, field
from pathlib import Path


# A JavaScript function (as source) that fingerprints every ColumnDataSource in the page:
# {id: {name, type, columns: {column: "length:sum:weighted sum"}}}.  It is cheap enough to
# run on every animation frame.  An optional list of names restricts it to those sources.
_FINGERPRINT_JS = r"""
function __mpFingerprint(names) {
  const sig = (v) => {
    if (v == null) return "null";
    if (typeof v === "string") return "s" + v.length + ":" + v.slice(0, 32);
    if (typeof v === "number" || typeof v === "boolean") return String(v);
    if (typeof v.length !== "number") return typeof v;
    let s1 = 0, s2 = 0, parts = [];
    for (let i = 0; i < v.length; i++) {
      const x = v[i];
      if (typeof x === "number") {
        if (Number.isFinite(x)) { s1 += x; s2 += x * ((i % 997) + 1); }
        else s1 += 0.123456789;
      } else if (x != null && typeof x === "object" && typeof x.length === "number") {
        parts.push(sig(x));
      } else if (x != null) {
        parts.push(String(x));
      }
    }
    return v.length + ":" + s1.toPrecision(12) + ":" + s2.toPrecision(12) +
           (parts.length ? ":" + parts.join("|").slice(0, 4000) : "");
  };
  const out = {};
  if (!window.Bokeh || !Bokeh.documents) return out;
  for (const doc of Bokeh.documents) {
    for (const m of doc.all_models) {
      if (!/DataSource$/.test(m.type) || m.data == null) continue;
      if (names && names.length && !names.includes(m.name)) continue;
      const data = m.data instanceof Map ? Object.fromEntries(m.data) : m.data;
      const cols = {};
      for (const key of Object.keys(data)) cols[key] = sig(data[key]);
      out[m.id] = {name: m.name, type: m.type, columns: cols};
    }
  }
  return out;
}
"""

_INSTALL_JS = "() => {\n" + _FINGERPRINT_JS + r"""
  window.__mpFingerprint = __mpFingerprint;
  if (!window.__mpKeyListener) {
    window.__mpKeyListener = true;
    window.__mpLastKey = null;
    window.addEventListener("keydown", () => { window.__mpLastKey = performance.now(); }, true);
  }
  return true;
}
"""


def install(page) -> None:
    """Put the fingerprint function and a key-press clock into the page (idempotent)."""
    page.evaluate(_INSTALL_JS)


def wait_for_app(page, url: str, timeout_ms: float = 45_000) -> float:
    """Open ``url`` and wait until Bokeh has rendered the document and gone idle.

    Returns the seconds from navigation to a rendered, connected document.
    """
    start = time.monotonic()
    page.goto(url, wait_until="load", timeout=timeout_ms)
    return time.monotonic() - start + wait_for_rendered(page, timeout_ms)


def wait_for_busy_page_to_pass(page, timeout_ms: float = 90_000) -> int:
    """While ``page`` shows the server's busy page, wait for it to reload itself (it does
    so after 3-6 s until the server admits it); the number of busy pages seen."""
    seen, deadline = 0, time.monotonic() + timeout_ms / 1e3
    while "(busy)" in page.title():
        seen += 1
        remaining = deadline - time.monotonic()
        if remaining <= 0:
            raise TimeoutError("the page stayed busy")
        page.wait_for_event("load", timeout=remaining * 1e3)
    return seen


def wait_for_rendered(page, timeout_ms: float = 45_000) -> float:
    """Wait until Bokeh has rendered the open page's dashboard and gone idle; seconds.

    The server sends a light page first and the dashboard once the browser has it
    (``app.opening``): its root (CSS class ``DASHBOARD_CLASS``) is what is waited for."""
    from app.views.page import DASHBOARD_CLASS

    start = time.monotonic()
    page.wait_for_selector(f".{DASHBOARD_CLASS}", state="attached", timeout=timeout_ms)
    page.wait_for_function(
        "() => window.Bokeh && Bokeh.documents && Bokeh.documents.length > 0 "
        "&& Bokeh.documents[0].roots().length > 0 "
        "&& (Bokeh.documents[0].is_idle === undefined || Bokeh.documents[0].is_idle)",
        timeout=timeout_ms)
    elapsed = time.monotonic() - start
    install(page)
    return elapsed


def settle(page, quiet_ms: int = 600, timeout_ms: float = 30_000,
           names: list[str] | None = None) -> None:
    """Wait until no ColumnDataSource (of ``names``, default all) has changed for
    ``quiet_ms`` (the page is at rest); a playing animation changes its sources on every
    frame, so a page that plays settles only on ``names`` it does not animate."""
    page.evaluate(
        """([quiet, timeout, names]) => new Promise((resolve) => {
          let last = JSON.stringify(window.__mpFingerprint(names));
          let since = performance.now();
          const start = since;
          const tick = () => {
            const now = JSON.stringify(window.__mpFingerprint(names));
            if (now !== last) { last = now; since = performance.now(); }
            if (performance.now() - since >= quiet || performance.now() - start >= timeout)
              resolve(true);
            else setTimeout(tick, 50);
          };
          tick();
        })""", [quiet_ms, timeout_ms, names or []])


def data_sources(page, names: list[str] | None = None) -> dict:
    """The fingerprints of the page's ColumnDataSources (all, or those with ``names``)."""
    return page.evaluate("(names) => window.__mpFingerprint(names)", names or [])


def changed_sources(before: dict, after: dict) -> list[str]:
    """Ids (with names) of the sources that differ, appeared or disappeared."""
    out = []
    for key in sorted(set(before) | set(after)):
        if before.get(key, {}).get("columns") != after.get(key, {}).get("columns"):
            name = (after.get(key) or before.get(key) or {}).get("name")
            out.append(f"{key} ({name})" if name else key)
    return out


def read_source(page, name: str) -> dict | None:
    """The data of the ColumnDataSource called ``name`` as plain lists, or None."""
    return page.evaluate(
        """(name) => {
          for (const m of Bokeh.documents[0].all_models) {
            if (/DataSource$/.test(m.type) && m.name === name) {
              const data = m.data instanceof Map ? Object.fromEntries(m.data) : m.data;
              const out = {};
              for (const k of Object.keys(data)) {
                const v = data[k];
                out[k] = (v != null && typeof v.length === "number" && typeof v !== "string")
                  ? Array.from(v, (x) => (typeof x === "number" && !Number.isFinite(x)) ? null : x)
                  : v;
              }
              return out;
            }
          }
          return null;
        }""", name)


# ---------------------------------------------------------------------------- widgets

@dataclass
class SliderInfo:
    id: str
    title: str
    value: float
    start: float
    end: float
    step: float
    type: str
    classes: tuple = ()
    extra: dict = field(default_factory=dict)


def sliders(page) -> list[SliderInfo]:
    """Every slider model of the page (Bokeh ``Slider``/``RangeSlider`` and Panel's)."""
    rows = page.evaluate(
        """() => {
          const out = [];
          for (const m of Bokeh.documents[0].all_models) {
            if (!/Slider$/.test(m.type) || !("value" in m)) continue;
            out.push({id: m.id, title: String(m.title ?? m.name ?? ""),
                      value: (typeof m.value === "number") ? m.value : null,
                      start: m.start ?? null, end: m.end ?? null, step: m.step ?? null,
                      type: m.type, visible: m.visible !== false, disabled: !!m.disabled,
                      classes: Array.from(m.css_classes || [])});
          }
          return out;
        }""")
    return [SliderInfo(r["id"], r["title"], r["value"], r["start"], r["end"], r["step"],
                       r["type"], tuple(r["classes"]),
                       {"visible": r["visible"], "disabled": r["disabled"]})
            for r in rows]


def find_slider(page, css_class: str | None = None, title_pattern: str | None = None):
    """The slider carrying ``css_class``, else the one titled like ``title_pattern``."""
    found = sliders(page)
    by_class = [s for s in found if css_class and css_class in s.classes]
    by_title = [s for s in found if title_pattern and re.search(title_pattern, s.title)]
    return (by_class or by_title or [None])[0]


def slider_handle(page, css_class: str | None = None, title_pattern: str | None = None):
    """A Playwright locator for the noUiSlider handle of a slider (by CSS class or title)."""
    if css_class and page.locator(f".{css_class} .noUi-handle").count():
        return page.locator(f".{css_class} .noUi-handle").first
    group = page.locator(".bk-input-group").filter(
        has=page.locator(".bk-slider-title", has_text=re.compile(title_pattern or "$^")))
    return group.locator(".noUi-handle").first


def slider_handles(page):
    """Locators of every visible slider handle of the page, in document order."""
    handles = page.locator(".noUi-handle")
    return [handles.nth(i) for i in range(handles.count()) if handles.nth(i).is_visible()]


def move_slider(page, handle, key: str = "ArrowRight", presses: int = 3) -> None:
    """Focus a slider handle and press ``key`` ``presses`` times, as a keyboard user does."""
    handle.focus()
    for _ in range(presses):
        page.keyboard.press(key)


def wait_for_data_change(page, before: dict, names: list[str] | None = None,
                         timeout_s: float = 30.0) -> list[str]:
    """Wait until a ColumnDataSource differs from ``before``; return the changed ones."""
    deadline = time.monotonic() + timeout_s
    while True:
        after = data_sources(page, names)
        changed = changed_sources(before, after)
        if changed or time.monotonic() > deadline:
            return changed
        page.wait_for_timeout(100)


def click_button(page, label_pattern: str) -> None:
    """Click the (first visible) button whose text matches the regex ``label_pattern``."""
    page.get_by_role("button", name=re.compile(label_pattern)).first.click()


# ---------------------------------------------------------------------------- latency

def measure_slider_latency(page, handle, key: str = "ArrowRight", names: list[str] | None = None,
                           timeout_s: float = 15.0) -> dict:
    """Time one key press on a slider handle until the plotted data has changed.

    The clock runs inside the page: it starts at the ``keydown`` event and stops at the
    first animation frame in which a ColumnDataSource (restricted to ``names`` if given)
    differs; ``paint_ms`` adds the frame after that, when the new data is drawn.
    Returns ``{"change_ms": float, "paint_ms": float}``; both are ``inf`` on a time-out.
    """
    install(page)
    handle.focus()
    page.evaluate(
        """([names, timeout]) => {
          const base = JSON.stringify(window.__mpFingerprint(names));
          window.__mpLatency = null;
          window.__mpLastKey = null;
          const start = performance.now();
          const tick = () => {
            const t = performance.now();
            if (window.__mpLastKey !== null &&
                JSON.stringify(window.__mpFingerprint(names)) !== base) {
              const key = window.__mpLastKey;
              requestAnimationFrame(() => {
                window.__mpLatency = {change_ms: t - key, paint_ms: performance.now() - key};
              });
              return;
            }
            if (t - start > timeout) {
              window.__mpLatency = {change_ms: Infinity, paint_ms: Infinity};
              return;
            }
            requestAnimationFrame(tick);
          };
          requestAnimationFrame(tick);
        }""", [names or [], timeout_s * 1000])
    page.keyboard.press(key)
    page.wait_for_function("() => window.__mpLatency !== null", timeout=(timeout_s + 5) * 1000)
    result = page.evaluate("() => window.__mpLatency")
    return {k: (math.inf if v is None else float(v)) for k, v in result.items()}


def latency_summary(samples: list[float]) -> dict:
    """p50, p95 and max of a list of milliseconds (inf when any sample timed out)."""
    ordered = sorted(samples)
    if not ordered:
        return {"n": 0, "p50": math.inf, "p95": math.inf, "max": math.inf}
    p95_index = min(len(ordered) - 1, math.ceil(0.95 * len(ordered)) - 1)
    return {"n": len(ordered), "p50": statistics.median(ordered),
            "p95": ordered[p95_index], "max": ordered[-1]}


def screenshot(page, path: Path, full_page: bool = True) -> Path:
    """Save a PNG of the page to ``path`` (folders are created)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(path), full_page=full_page)
    return path


# ---------------------------------------------------------------------------- plots

_FIND_PLOT_VIEW_JS = """(name) => {
  const fig = [...Bokeh.documents[0].all_models].find(
    (m) => m.name === name && !/DataSource$/.test(m.type) && "x_range" in m);
  const view = fig ? Bokeh.index.find_one(fig) : null;
  if (!view || !view.canvas_view) return false;
  const rect = view.canvas_view.el.getBoundingClientRect();
  return rect.width > 0 && rect.height > 0 && view.frame.bbox.width > 0;
}"""


def wait_for_plot(page, figure_name: str, timeout_ms: float = 30_000) -> None:
    """Wait until the Bokeh figure ``figure_name`` is rendered with a non-empty frame."""
    page.wait_for_function(_FIND_PLOT_VIEW_JS, arg=figure_name, timeout=timeout_ms)


def plot_point(page, figure_name: str, x: float, y: float) -> tuple[float, float]:
    """Page coordinates (CSS px) of the data point (x, y) in the Bokeh figure ``figure_name``."""
    sx, sy = page.evaluate(
        """([name, x, y]) => {
          const fig = [...Bokeh.documents[0].all_models].find(
            (m) => m.name === name && !/DataSource$/.test(m.type) && "x_range" in m);
          if (!fig) throw new Error(`no figure named ${name}`);
          const view = Bokeh.index.find_one(fig);
          if (!view) throw new Error(`figure ${name} has no view`);
          const rect = view.canvas_view.el.getBoundingClientRect();
          return [rect.left + view.frame.x_scale.compute(x),
                  rect.top + view.frame.y_scale.compute(y)];
        }""", [figure_name, x, y])
    return float(sx), float(sy)


def click_plot(page, figure_name: str, x: float, y: float) -> None:
    """Click the figure ``figure_name`` at the data point (x, y), as a mouse user does."""
    wait_for_plot(page, figure_name)
    sx, sy = plot_point(page, figure_name, x, y)
    page.mouse.click(sx, sy)


def open_tab(page, title_pattern: str, tab: str | None = None) -> None:
    """Click the button of the dashboard's tab bar whose text matches ``title_pattern``;
    given ``tab`` (its key), wait until the address names it (``support`` is left out)."""
    page.locator(".tab-bar button").filter(has_text=re.compile(title_pattern)).first.click()
    if tab is not None:
        wait_for(page, lambda: f"tab={tab}" in page.url or tab == "support", what=f"the {tab} tab")


def model_value(page, type_pattern: str, attribute: str = "value", css_class: str | None = None):
    """``attribute`` of the first model whose type matches (and carries ``css_class``)."""
    return page.evaluate(
        """([pattern, attribute, cls]) => {
          const re = new RegExp(pattern);
          for (const m of Bokeh.documents[0].all_models) {
            if (!re.test(m.type)) continue;
            if (cls && !(m.css_classes || []).includes(cls)) continue;
            return m[attribute];
          }
          return undefined;
        }""", [type_pattern, attribute, css_class])


def live_html(page, css_class: str) -> str:
    """The HTML of the text written in place with ``css_class`` (``LiveHTML``), or ""."""
    return page.evaluate("""(cls) => { for (const m of Bokeh.documents[0].all_models)
        if ((m.css_classes || []).includes(cls) && m.data && "html" in m.data)
          return String(m.data.html);
      return ""; }""", css_class)


def wait_for(page, predicate, timeout_s: float = 20.0, what="condition") -> None:
    """Poll ``predicate()`` every 100 ms of page time; fail the test (naming ``what``, or
    what ``what()`` says then) after ``timeout_s`` seconds."""
    import pytest

    deadline = time.monotonic() + timeout_s
    while not predicate():
        if time.monotonic() > deadline:
            what = what() if callable(what) else what
            pytest.fail(f"timed out after {timeout_s:.0f} s waiting for {what}", pytrace=False)
        page.wait_for_timeout(100)
