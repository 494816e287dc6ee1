"""The offline page's workaround in BokehJS (``app/offline/bokeh_fix.js``): its guard, in
Node, on a stand-in for BokehJS's ``core/dom``. The browser test on BokehJS itself (and the
canary that fails once the bug is fixed upstream): ``tests/browser/test_offline_fix.py``."""
from __future__ import annotations

import json
import shutil
import subprocess
from importlib import resources

import pytest

from app.edge import TESTED

SCRIPT = resources.files("app.offline") / "bokeh_fix.js"

#: Loads bokeh_fix.js into a fresh context with a stand-in BokehJS whose InlineStyleSheet
#: counts its writes, applies the fix and writes the texts given; prints what happened.
RUN = """
const vm = require("vm"), fs = require("fs");
const [path, version, tested, arity, texts] = JSON.parse(process.argv[1]);
class InlineStyleSheet {
  constructor() { this.el = {textContent: ""}; this.writes = 0; }
  replace(css) { this._update(css); }
}
const update = arity === 1 ? function (css) { this.el.textContent = css; this.writes += 1; }
                           : function (css, more) { this.el.textContent = css; this.writes += 1; };
InlineStyleSheet.prototype._update = update;
const bokeh = {version, require: (name) => name === "core/dom" ? {InlineStyleSheet} : null};
const context = {};
vm.createContext(context);
vm.runInContext(fs.readFileSync(path, "utf8"), context);
const fix = context.MicropillarBokehFix.apply(bokeh, tested);
const sheet = new InlineStyleSheet();
texts.forEach((t) => sheet.replace(t));
console.log(JSON.stringify({applied: fix.applied, reason: fix.reason, writes: sheet.writes,
                            text: sheet.el.textContent,
                            untouched: InlineStyleSheet.prototype._update === update}));
"""


def run(version: str, texts: list[str], arity: int = 1, tested: str = TESTED["bokeh"]) -> dict:
    node = shutil.which("node")
    if node is None:  # a requirement of the suite, like Chromium: never skipped silently
        pytest.fail("node is not installed (Debian: apt-get install nodejs)", pytrace=False)
    done = subprocess.run([node, "-e", RUN, json.dumps([str(SCRIPT), version, tested, arity,
                                                         texts])],
                          text=True, capture_output=True, timeout=60)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def test_on_the_tested_version_an_unchanged_text_is_not_written_again():
    got = run(TESTED["bokeh"], ["a{}", "a{}", "a{}", "b{}", "b{}", "a{}"])
    assert got["applied"] and got["reason"] == ""
    assert got["writes"] == 3  # a{}, b{}, a{}: each change written, no repeat
    assert got["text"] == "a{}"
    assert not got["untouched"]


@pytest.mark.parametrize("version", ["3.9.1", "3.10.0", "4.0.0"])
def test_another_version_runs_on_bokehs_own_behaviour_and_says_why(version):
    got = run(version, ["a{}", "a{}"])
    assert not got["applied"] and got["untouched"]
    assert got["writes"] == 2
    assert version in got["reason"] and TESTED["bokeh"] in got["reason"]


def test_a_changed_method_is_left_alone():
    got = run(TESTED["bokeh"], ["a{}", "a{}"], arity=2)
    assert not got["applied"] and got["untouched"] and got["writes"] == 2
    assert "InlineStyleSheet._update(css)" in got["reason"]
