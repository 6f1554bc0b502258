"""The player's event list: the latest collisions and timers up to the frame shown.

A frame of a recording holds the events since the previous frame, so the
events up to frame k are found by walking back from k. Each frame's events are
turned into text lines once and cached; ``note`` takes them from a frame the
player has decoded anyway, so sequential playback decodes nothing twice.
"""

from __future__ import annotations

__all__ = ["EventHistory", "event_lines"]

#: frames looked at when walking back for events (bounds the work after a long seek).
LOOKBACK = 400


def event_lines(frame) -> tuple[str, ...]:
    """One line per collision and timer of ``frame``, oldest first, e.g.
    ``"0.2350 s  collision 3-5"`` and ``"0.5000 s  timer 2"``."""
    items = []
    c = frame.collisions
    for t, a, b in zip(c.times.tolist(), c.a.tolist(), c.b.tolist()):
        other = "?" if b < 0 else str(b)
        items.append((t, f"{t:.4f} s  collision {a}-{other}"))
    timers = frame.timers
    for t, ident in zip(timers.times.tolist(), timers.ids.tolist()):
        items.append((t, f"{t:.4f} s  timer {ident}"))
    items.sort(key=lambda item: item[0])
    return tuple(line for _, line in items)


class EventHistory:
    """Event lines of a ``Recording``, by frame."""

    def __init__(self, recording) -> None:
        self.recording = recording
        counts = recording.event_counts
        self.empty = counts.get("collisions", 0) + counts.get("timers", 0) == 0
        self._lines: dict[int, tuple[str, ...]] = {}

    def note(self, frame) -> None:
        """Remember the events of a frame already decoded."""
        if frame.index not in self._lines:
            self._lines[frame.index] = event_lines(frame)

    def recent(self, index: int, count: int) -> list[str]:
        """The last ``count`` event lines at or before frame ``index``, newest last."""
        if self.empty or count <= 0:
            return []
        found: list[str] = []
        stop = max(-1, index - LOOKBACK)
        for k in range(index, stop, -1):
            lines = self._lines.get(k)
            if lines is None:
                lines = self._lines[k] = event_lines(self.recording.frame(k))
            found[:0] = lines
            if len(found) >= count:
                break
        return found[-count:]
