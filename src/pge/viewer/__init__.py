"""The browser viewer: watch a recording in any web browser, with no internet needed.

* ``pge view FILE`` serves it on 127.0.0.1 (``ViewerServer``);
* ``pge export FILE out.html`` writes it as one self-contained page (``write_html``);
* in a notebook, ``Animation`` (from ``World.animate`` or ``show(recording)``)
  displays it inline.

The page (``static/``) is hand-written JavaScript drawing on a canvas: play,
pause, step, seek, speed, the time and the event list beside the scene.
"""

from __future__ import annotations

import html as _html
from pathlib import Path

from pge.viewer.data import recording_data, to_json
from pge.viewer.page import served_page, standalone_page

__all__ = ["Animation", "show", "write_html", "recording_data", "standalone_page", "served_page", "to_json"]


class Animation:
    """A recorded run ready to be watched: shows itself inline in Jupyter.

    ``data`` is a dictionary from ``recording_data``. ``html()`` is the
    self-contained viewer page, ``save(path)`` writes it, and
    ``_repr_html_`` embeds it in an ``<iframe srcdoc>`` so that each
    animation in a notebook keeps its own page, script and controls.
    """

    #: height of the inline frame in pixels (the scene, its controls and the event list fit).
    height = 560

    def __init__(self, data: dict) -> None:
        if not isinstance(data, dict) or "frames" not in data:
            raise TypeError(f"Animation: data must be a dict from recording_data, got {type(data).__name__}")
        self.data = data

    @classmethod
    def from_recording(cls, recording, start=None, end=None) -> "Animation":
        """An animation of ``recording`` (a ``Recording``, or a path to one) between ``start`` and ``end``."""
        if isinstance(recording, (str, Path)):
            from pge.recording import open_recording

            recording = open_recording(recording)
        return cls(recording_data(recording, start, end))

    @property
    def frames(self) -> int:
        """Number of frames."""
        return len(self.data["times"])

    def html(self) -> str:
        """The self-contained viewer page."""
        return standalone_page(self.data)

    def save(self, path) -> Path:
        """Write ``html()`` to ``path``; returns the path."""
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(self.html(), encoding="utf-8")
        return path

    def _repr_html_(self) -> str:
        return (
            f'<iframe srcdoc="{_html.escape(self.html(), quote=True)}" '
            f'style="width: 100%; height: {self.height}px; border: 0;" '
            'sandbox="allow-scripts" title="pge animation"></iframe>'
        )

    def __repr__(self) -> str:
        return f"<pge Animation: {self.data.get('title')}, {self.frames} frames>"


def show(recording, start=None, end=None) -> Animation:
    """An ``Animation`` of ``recording`` (a ``Recording`` or a path): the last line of a
    notebook cell displays it."""
    return Animation.from_recording(recording, start, end)


def write_html(recording, out, start=None, end=None) -> int:
    """Write the viewer of ``recording`` as the single file ``out``; returns the frame count."""
    animation = Animation(recording_data(recording, start, end))
    animation.save(out)
    return animation.frames
