"""Work for a view that is not on screen waits until it is shown.

A served page holds every tab's models, so a view of a hidden tab that redraws on a new
result still sends its data to the browser at every slider move (the One-support tab's
figures and player frames: thirty arrays per move). ``WhenShown`` runs a view's redraw at
once while its tab is on screen, and otherwise once, the latest, when the tab is shown.
"""
from __future__ import annotations

from typing import Callable


class WhenShown:
    """Run redraws of a view on the tab ``tab`` of ``state`` (``ExplorerState.tab``) now
    if it is on screen, else when it is next shown (each redraw once, in the order first
    asked)."""

    def __init__(self, state, tab: str):
        self.state, self.tab = state, tab
        self._waiting: dict[str, Callable[[], None]] = {}
        state.param.watch(self._on_tab, "tab")

    @property
    def shown(self) -> bool:
        return self.state.tab == self.tab

    def run(self, redraw: Callable[[], None]) -> None:
        if self.shown:
            redraw()
        else:
            self._waiting.setdefault(redraw.__name__, redraw)

    @property
    def waiting(self) -> list[str]:
        """The names of the redraws waiting for the tab."""
        return list(self._waiting)

    def _on_tab(self, _event=None) -> None:
        if self.shown and self._waiting:
            waiting, self._waiting = self._waiting, {}
            for redraw in waiting.values():
                redraw()
