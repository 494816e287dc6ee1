"""The page's "Make animation for slides" buttons (app/views/export.py): the file is made
in the background on request, then offered for download with the current state's name;
the request never runs on a control change."""
from __future__ import annotations


import pytest
from PIL import Image

from app import slot, worker
from app.state import ExplorerState
from fakes import InProcessPool


@pytest.mark.parametrize("what", ["support", "array"])
def test_make_then_download(monkeypatch, what, tmp_path):
    from app.views import Dashboard

    pool = InProcessPool()
    monkeypatch.setattr(slot, "work_pool", lambda: pool)
    monkeypatch.setattr(worker, "EXPORT_FRAMES", 4)
    monkeypatch.setattr(worker, "EXPORT_SIZE", (320, 180))
    page = Dashboard(ExplorerState(tab=what))
    view = page.support if what == "support" else page.array
    export = view.export
    assert export.download.disabled
    page.state.F_N = 2.0  # a control change makes no animation
    assert "compute_animation" not in pool.calls
    export.format.value = "gif"
    export._make()
    assert pool.calls.count("compute_animation") == 1
    assert not export.download.disabled and "Ready" in export.status.object, (
        export.status.object, page.results.errors)
    assert export.download.filename.endswith(".gif") and "FN2" in export.download.filename
    path = tmp_path / "a.gif"
    path.write_bytes(export._file().getvalue())
    with Image.open(path) as im:
        assert im.size == (320, 180) and im.n_frames == 4
