"""Every state of the lesson (docs/teaching.md, app.lesson.STEPS) opens in the offline
explorer: the dashboard link's keys, in the file's fragment, are read by the page's own
fragment code (app/offline/fragment.js, run in Node with the page's configuration) into
the same state, without a notice for any key the page has; a tab it does not have opens
its closest with a notice naming what needs the server."""
from __future__ import annotations

import json
import math
import re
import subprocess
from importlib import resources
from pathlib import Path
from urllib.parse import parse_qsl, urlsplit

import pytest

from app.lesson import STEPS, lesson_url, offline_url
from app.offline.pack import CLOSEST_TABS, OFFLINE_TABS, config
from model.contact.params import REGIMES

from test_offline_kernel import _node

FRAGMENT = resources.files("app.offline") / "fragment.js"
DOC = (Path(__file__).resolve().parents[1] / "docs" / "teaching.md").read_text(encoding="utf-8")
RUNNER = """
const F = require(process.argv[1]);
let text = "";
process.stdin.on("data", (c) => { text += c; });
process.stdin.on("end", () => {
  const {config, hashes} = JSON.parse(text);
  process.stdout.write(JSON.stringify(hashes.map((h) => {
    const parsed = F.parse(h, config);
    return {state: parsed.state, notices: parsed.notices, written: F.write(parsed.state, config)};
  })));
});
"""


def parse(hashes: list[str]) -> list[dict]:
    """fragment.js's reading of each fragment, with the pack's configuration."""
    done = subprocess.run([_node(), "-e", RUNNER, str(FRAGMENT)], text=True, capture_output=True,
                          input=json.dumps({"config": config(), "hashes": hashes}), timeout=120)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def _links_in_doc() -> list[str]:
    return re.findall(r"\]\((http://localhost:5006/app\?[^)]*)\)", DOC)


def test_the_lesson_lists_its_offline_links():
    for i, step in enumerate(STEPS, 1):
        assert f"Q{i}  {offline_url(step)}" in DOC, step.key


@pytest.mark.parametrize("projector", [True, False])
def test_every_lesson_link_opens_in_its_state_offline(projector):
    links = _links_in_doc()
    assert len(links) == len(STEPS)
    steps = [next(s for s in STEPS if lesson_url(s) == link) for link in links]
    # The dashboard link's query is the offline link's fragment.
    for link, step in zip(links, steps):
        assert urlsplit(offline_url(step)).fragment == urlsplit(link).query
    results = parse(["#" + urlsplit(offline_url(s, projector)).fragment for s in steps])
    for step, got in zip(steps, results):
        keys = dict(parse_qsl(urlsplit(offline_url(step, projector)).fragment))
        state, notices = got["state"], got["notices"]
        regime = REGIMES[step.regime]
        assert (state["k_r"], state["k_theta"]) == (regime.k_r, regime.k_theta), step.key
        assert math.isclose(state["theta0_deg"], step.theta0_deg) and state["F_N"] == step.F_N
        assert state["projector"] is projector and state["play"] is False
        if step.tab in OFFLINE_TABS:
            assert state["tab"] == step.tab and notices == [], (step.key, notices)
        else:  # the closest tab, one notice, about the tab alone
            closest, why = CLOSEST_TABS[step.tab]
            assert state["tab"] == closest, step.key
            assert len(notices) == 1 and notices[0].startswith(
                f"the {step.tab} tab is not in the offline explorer (it needs the server)")
            assert why in notices[0]
        assert set(keys) <= {"regime", "theta0_deg", "F_N", "tab", "projector"}
        # The page rewrites the fragment into its own keys: read back, the same state.
        again = parse([got["written"]])[0]
        assert again["notices"] == [] and again["state"] == state, step.key
