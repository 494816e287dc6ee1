"""How a load-test session behaves once its page is open (``load_client.Session``): the
slider moves of a student, in the two profiles of ``PROFILES``, and the wait for each move's
data; see load_test.py for the method."""
from __future__ import annotations

import asyncio
import math
import time

UPDATE_TIMEOUT_S = 30.0
#: The drag profile: the pause between moves, and how often a move is a drag, of how many
#: positions how far apart.
THINK_S = (0.2, 0.8)
DRAG_PROBABILITY, DRAG_STEPS, DRAG_GAP_S = 0.2, 4, 0.03
#: The classroom profile: seconds between one session's moves (uniform, mean 3 s),
#: whether or not the previous move's data has arrived (open loop).
CLASS_GAP_S = (2.0, 4.0)
#: The ways a session moves its sliders (``Session.run``).
PROFILES = {
    "class": f"open loop: a slider move every {CLASS_GAP_S[0]:g}-{CLASS_GAP_S[1]:g} s "
             "(mean 3 s), sent on schedule whether or not the last one's data has arrived",
    "drag": f"closed loop: move, wait for the pushed data, pause {THINK_S[0]}-{THINK_S[1]} s, "
            f"again; one theta0 move in {round(1 / DRAG_PROBABILITY)} is a {DRAG_STEPS}-position "
            f"drag ({DRAG_GAP_S * 1e3:.0f} ms apart)",
    "drags": f"closed loop as drag, every move a {DRAG_STEPS}-position theta0 drag: the most "
             "updates whose last position must reach the page (0 lost is the check)",
}


class SessionFailure(Exception):
    """A session could not open, stalled or lost its connection."""


class SliderMoves:
    """A session's slider moves (mixed into ``load_client.Session``, which gives it the
    page's ``sliders``, ``readout``, the pushes counted and ``_flush``)."""

    def _readout_shows(self, degrees: float) -> bool:
        return f"θ₀ = {degrees:g}°" in (self.readout.html or "")

    async def _set(self, name: str, value: float, end: bool = True) -> float:
        """Move the slider; when its message had left (``time.perf_counter``). As BokehJS:
        a key press or a drag's end (``end``) sets ``value`` and ``value_throttled``, a
        drag's position on the way ``value`` alone."""
        slider = self.sliders[name]
        slider.value = value
        if end:  # read-only in Python: set as BokehJS sets it
            slider.set_from_json("value_throttled", value)
        await self._flush()
        return time.perf_counter()

    def _record(self, latencies: list, sent: float, wrote: float, now: float) -> None:
        latencies.append(max(0.0, self.last_orbit_read - wrote))
        self.client_latencies.append(now - sent)

    def _movable(self) -> list[str]:
        """The sliders whose move changes the motion (only changed data is sent): with
        theta0 on the axis the torsional spring never twists, so k_theta changes nothing."""
        on_axis = round(getattr(self.sliders.get("theta0"), "value", 1.0), 6) % 180 == 0
        return [n for n in self.sliders if not (on_axis and n == "k_theta")] or list(self.sliders)

    def _position(self, name: str, avoid: tuple[float, ...] = ()) -> float:
        """A random position on the slider's grid other than its current one and ``avoid``."""
        s = self.sliders[name]
        steps = int(round((s.end - s.start) / s.step))
        value = s.start + self.rng.randint(0, steps) * s.step
        taken = (s.value, *avoid)
        while any(abs(value - t) < 0.5 * s.step for t in taken):  # a move, not a position held
            value = s.start + ((round((value - s.start) / s.step) + 1) % (steps + 1)) * s.step
        return round(value, 6)

    def _arrived(self, name: str, value: float, pushes: int) -> bool:
        """New orbit data was pushed since ``pushes`` (not necessarily different: on the
        axis, k_theta does not change the motion); for theta0 it must be the requested
        angle's."""
        if self.orbit_pushes == pushes:
            return False
        return name != "theta0" or self._readout_shows(value)

    async def move(self, drags: bool = True, only_drags: bool = False) -> None:
        """One slider move (or drag; ``only_drags``: a theta0 drag) and the wait for its
        update."""
        name = "theta0" if only_drags else self.rng.choice(self._movable())
        drag = only_drags or (drags and name == "theta0"
                              and self.rng.random() < DRAG_PROBABILITY)
        self._patched.clear()
        # A drag ends elsewhere than where it began: the server may merge a quick drag's
        # positions, and one that ends where it began changes nothing (and sends nothing).
        began = self.sliders[name].value
        steps = DRAG_STEPS if drag else 1
        for step in range(steps):
            if step:
                await asyncio.sleep(DRAG_GAP_S)
            value = self._position(name, avoid=(began,))
            sent, pushes = time.perf_counter(), self.orbit_pushes
            wrote = await self._set(name, value, end=step == steps - 1)

        def done() -> bool:
            return self._arrived(name, value, pushes)

        deadline = sent + UPDATE_TIMEOUT_S
        while not done():
            left = deadline - time.perf_counter()
            if left <= 0 or self.errors:
                raise SessionFailure(f"no update within {UPDATE_TIMEOUT_S:.0f} s after "
                                     f"{name} = {value}" + (f" ({self.errors[-1]})"
                                                            if self.errors else "")
                                     + "; " + self._diagnosis(sent))
            self._patched.clear()
            try:
                await asyncio.wait_for(self._patched.wait(), timeout=left)
            except asyncio.TimeoutError:
                pass
        self._record(self.drag_latencies if drag else self.latencies, sent, wrote,
                     time.perf_counter())

    def _diagnosis(self, sent: float) -> str:
        values = {k: round(m.value, 4) for k, m in self.sliders.items()}
        recent = [f"{t - sent:+.1f}s {events}" for t, events in self.recent]
        return f"sliders {values}; latest patches (time after the change): {recent}"

    async def run(self, until: float, profile: str = "drag") -> None:
        try:
            if profile == "class":
                await self.run_class(until)
                return
            while time.perf_counter() < until:
                await self.move(only_drags=profile == "drags")
                await asyncio.sleep(self.rng.uniform(*THINK_S))
        except Exception as exc:  # noqa: BLE001 - counted as a session failure
            self.errors.append(f"{type(exc).__name__}: {exc}")

    async def run_class(self, until: float) -> None:
        """The classroom profile (open loop): a move every ``CLASS_GAP_S`` seconds on a
        schedule of its own, as a student moves a slider whether or not the page has kept
        up. A move's latency runs from its sending until data for it arrives; a move
        overtaken by a later one before its data came (a theta0 angle never shown) counts
        until the later one's data arrives: what the student waited for."""
        # (sent, wrote: its message written, slider, value, pushes)
        pending: list[tuple[float, float, str, float, int]] = []
        next_move = time.perf_counter() + self.rng.uniform(0.0, CLASS_GAP_S[1])
        while True:
            now = time.perf_counter()
            if pending:
                done = [i for i, (*_, n, v, p) in enumerate(pending) if self._arrived(n, v, p)]
                if done:
                    for sent, wrote, *_ in pending[:done[-1] + 1]:
                        self._record(self.latencies, sent, wrote, now)
                    del pending[:done[-1] + 1]
            if pending and now - pending[0][0] > UPDATE_TIMEOUT_S:
                _, _, name, value, _ = pending[0]
                raise SessionFailure(f"no update within {UPDATE_TIMEOUT_S:.0f} s after "
                                     f"{name} = {value}; " + self._diagnosis(pending[0][0]))
            if self.errors:
                raise SessionFailure(self.errors[-1])
            if now >= until and not pending:
                return
            if now >= next_move and now < until:
                name = self.rng.choice(self._movable())
                value = self._position(name)
                sent, pushes = time.perf_counter(), self.orbit_pushes
                wrote = await self._set(name, value)
                pending.append((sent, wrote, name, value, pushes))
                next_move += self.rng.uniform(*CLASS_GAP_S)
                continue
            wake = min(next_move if now < until else math.inf,
                       (pending[0][0] + UPDATE_TIMEOUT_S) if pending else math.inf)
            self._patched.clear()
            try:
                await asyncio.wait_for(self._patched.wait(),
                                       timeout=max(0.0, min(wake - now, 1.0)))
            except asyncio.TimeoutError:
                pass
