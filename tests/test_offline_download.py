"""The dashboard's "Download offline explorer" button (app/views/offline_download.py): the
file it gives is the offline explorer, self-contained, and opens in the session's state
(its initial fragment, read by the page's own fragment code in Node with the page's own
configuration); what the file has no place for opens at its closest, with a notice."""
from __future__ import annotations

import asyncio
import json
import re
import subprocess
from importlib import resources

import pytest

from app.offline.pack import MAX_BYTES
from app.state import ExplorerState

from test_offline_kernel import _node

pn = pytest.importorskip("panel")

FRAGMENT = resources.files("app.offline") / "fragment.js"
RUNNER = """
const F = require(process.argv[1]);
let text = "";
process.stdin.on("data", (c) => { text += c; });
process.stdin.on("end", () => {
  const {config, hash} = JSON.parse(text);
  process.stdout.write(JSON.stringify(F.parse(hash, config)));
});
"""


def _element(html: str, element_id: str):
    found = re.search(rf'<script id="{element_id}" type="application/json">\n(.*?)\n</script>',
                      html, re.S)
    assert found, f"the page has no {element_id}"
    return json.loads(found.group(1))


def opened_state(html: str) -> dict:
    """The state the downloaded page opens in (no fragment in its address)."""
    config, initial = _element(html, "mp-config"), _element(html, "mp-initial")
    done = subprocess.run([_node(), "-e", RUNNER, str(FRAGMENT)], text=True, capture_output=True,
                          input=json.dumps({"config": config, "hash": initial}), timeout=120)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def download(state: ExplorerState) -> str:
    from app.views.offline_download import offline_button

    button = offline_button(state)
    assert isinstance(button, pn.widgets.FileDownload) and button.label == "Download offline explorer"
    data = asyncio.run(button.callback()).getvalue()
    assert len(data) <= MAX_BYTES and button.filename.endswith(".html")
    return data.decode("utf-8")


def test_the_downloaded_explorer_opens_in_the_session_state():
    state = ExplorerState()
    state.param.update(k_r=0.5, k_theta=0.2, F_N=3.0, theta0=120.0, beta_mode="fixed", beta=0.4,
                       tab="polar", projector=True)
    html = download(state)
    assert not re.search(r'<script\b[^>]*\bsrc=', html)  # self-contained
    opened = opened_state(html)
    assert opened["notices"] == []
    s = opened["state"]
    assert (s["k_r"], s["k_theta"], s["F_N"], s["theta0_deg"]) == (0.5, 0.2, 3, 120)
    assert (s["beta_mode"], s["beta"], s["tab"], s["projector"]) == ("fixed", 0.4, "polar", True)


def test_a_server_only_tab_opens_at_its_closest_with_a_notice():
    state = ExplorerState()
    state.param.update(k_r=0.03, k_theta=0.03, tab="load")  # self-consistent beta: the default
    opened = opened_state(download(state))
    s = opened["state"]
    assert (s["k_r"], s["k_theta"], s["beta_mode"], s["tab"]) == (0.03, 0.03, "self", "map")
    assert len(opened["notices"]) == 1 and "the load tab is not in the offline explorer" in \
        opened["notices"][0]


def test_the_dashboard_offers_the_download():
    from app.views.page import Dashboard

    page = Dashboard(ExplorerState())
    buttons = [w for w in page.controls.__panel__().select(pn.widgets.FileDownload)
               if "download-offline" in w.css_classes]
    assert len(buttons) == 1
