"""axe-core (the npm package) in a page: WCAG 2.1 A/AA rules, run on the whole document;
and what a screen reader is given: Chromium's accessibility tree (``ax_tree``).

axe-core is installed next to the repository, never committed:
``npm install --prefix .browser-tools axe-core@4`` (``.ci/run`` does it). ``AXE_JS`` is
where the tests look for it; ``MICROPILLAR_AXE_JS`` names another copy.
"""
from __future__ import annotations

import os
from pathlib import Path

from playwright.sync_api import TimeoutError as PlaywrightTimeout

from .serving import ROOT

AXE_JS = Path(os.environ.get("MICROPILLAR_AXE_JS")
              or ROOT / ".browser-tools" / "node_modules" / "axe-core" / "axe.min.js")
#: The rule set: WCAG 2.0 and 2.1, levels A and AA.
WCAG_TAGS = ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa"]
INSTALL_HINT = "npm install --prefix .browser-tools axe-core@4"


#: Slider handles (in every shadow root) that have no accessible name yet.
UNNAMED_HANDLES_JS = """() => {
  let n = 0;
  const visit = (root) => {
    for (const h of root.querySelectorAll(".noUi-handle")) if (!h.getAttribute("aria-label")) n += 1;
    for (const el of root.querySelectorAll("*")) if (el.shadowRoot) visit(el.shadowRoot);
  };
  visit(document);
  return n;
}"""


def violations(page) -> list[dict]:
    """axe's WCAG 2.1 A/AA violations on the page as it is now (axe is injected once):
    [{id, impact, help, nodes: [target, ...], summary}].

    The page names slider handles in a pass that runs 100 ms after the page changes
    (``app/figures/access_js.py``): on a loaded machine a handle drawn just before the scan
    may not be named yet, so the scan waits up to 5 s for every handle's name; one still
    unnamed then is axe's to report."""
    try:
        page.wait_for_function(f"({UNNAMED_HANDLES_JS})() === 0", timeout=5_000)
    except PlaywrightTimeout:
        pass  # axe reports the handle left unnamed
    if not page.evaluate("() => typeof window.axe === 'object'"):
        page.add_script_tag(path=str(AXE_JS))
    return page.evaluate(
        """async (tags) => {
          const result = await axe.run(document, {runOnly: {type: "tag", values: tags},
                                                  resultTypes: ["violations"]});
          return result.violations.map((v) => ({
            id: v.id, impact: v.impact, help: v.help,
            nodes: v.nodes.map((n) => n.target.map(String).join(" >> ")),
            summary: v.nodes.slice(0, 3).map((n) => n.failureSummary)}));
        }""", WCAG_TAGS)


def describe(found: list[dict]) -> str:
    """Violations as text, one rule a line with a few of its elements."""
    return "\n".join(f"{v['id']} ({len(v['nodes'])} elements, {v['impact']}): {v['help']}; "
                     f"e.g. {v['nodes'][:3]} {v['summary'][:1]}" for v in found)


def ax_tree(page) -> list[dict]:
    """The page's accessibility tree: the nodes a screen reader is given (not ignored),
    as {role, name, description}."""
    cdp = page.context.new_cdp_session(page)
    try:
        cdp.send("Accessibility.enable")
        nodes = cdp.send("Accessibility.getFullAXTree")["nodes"]
    finally:
        cdp.detach()
    out = []
    for node in nodes:
        if node.get("ignored"):
            continue
        value = lambda key: str((node.get(key) or {}).get("value") or "").strip()  # noqa: E731
        out.append({"role": value("role"), "name": value("name"),
                    "description": value("description")})
    return out


def ax_figures(page) -> dict:
    """The figures a screen reader is given: {name: description}."""
    return {n["name"]: n["description"] for n in ax_tree(page) if n["role"] == "figure"}
