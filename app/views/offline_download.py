"""The dashboard's "Download offline explorer" button: the offline explorer (``micropillar
pack``, app/offline, docs/offline.md), one HTML file that computes in the browser, packed
with the session's state as its initial fragment, so the file opens where the page is
(springs, load, orientation, load factor β, tab, projector mode). What the file cannot show
(a server-only tab, the Design tab's inputs) it opens at its closest, with a notice."""
from __future__ import annotations

import asyncio
import io

import panel as pn

from ..offline.pack import initial_fragment, page_bytes
from ..state import ExplorerState
from .layout import BUTTON_CSS
from .widgets import look

FILENAME = "micropillar_explorer.html"


def offline_fragment(state: ExplorerState) -> str:
    """The offline page's fragment for the session's state: its link's keys the file reads."""
    return initial_fragment(state.to_query())


async def offline_file(state: ExplorerState) -> io.BytesIO:
    """The offline explorer opening in ``state`` (the download's content). The state is read
    at once; the file is packed in a thread (the first time in a process takes seconds:
    the page's figures are drawn by the model), so the session never waits for it."""
    fragment = offline_fragment(state)
    return io.BytesIO(await asyncio.to_thread(page_bytes, fragment))


def offline_button(state: ExplorerState) -> pn.widgets.FileDownload:
    """The download button: packs the file when pressed (≈ 2.3 MB)."""
    async def packed():
        return await offline_file(state)

    return pn.widgets.FileDownload(
        callback=packed, filename=FILENAME,
        label="Download offline explorer", css_classes=["download-offline"],
        description="the explorer in one file that computes in the browser, with no server "
                    "or network: it opens in this state",
        **look("light"), sizing_mode="stretch_width", margin=(2, 3), stylesheets=[BUTTON_CSS])
