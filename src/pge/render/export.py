"""Export a recording as PNG frames, an animated GIF (Pillow), an MP4 video (imageio + ffmpeg)
or a self-contained HTML page that plays it in a browser (``pge.viewer``).

``export(recording, out)`` picks the kind from ``out``: a name ending in
``.gif``, ``.mp4`` or ``.html`` (the browser viewer with every frame in
``[start, end]`` embedded; ``size`` and ``fps`` do not apply), otherwise a directory that receives ``frame_00000.png``,
``frame_00001.png``, ... Frames are sampled at ``fps`` frames per second of
simulation time over ``[start, end]``: output frame k shows the recording's
last frame at or before ``start + k / fps``. Without ``fps`` every recorded
frame in the range is used (PNG), or the recording's frame rate capped at
50 (GIF: browsers slow faster GIFs down) or 60 (MP4).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from pge.render.recorded import render_frame

__all__ = ["export", "plan_frames", "export_kind"]

_DEFAULT_FPS = {"gif": 50.0, "mp4": 60.0}
_PROGRESS_FROM = 50  # frames: shorter exports print no progress bar


def export_kind(out) -> str:
    """``"gif"``, ``"mp4"``, ``"html"`` or ``"png"`` (a directory), from the output name."""
    suffix = Path(out).suffix.lower()
    if suffix in (".gif", ".mp4", ".html"):
        return suffix[1:]
    if suffix == ".htm":
        return "html"
    if suffix:
        raise ValueError(
            f"cannot export to {str(out)!r}: use a .gif, .mp4 or .html name, or a directory for PNG frames"
        )
    return "png"


def plan_frames(recording, fps=None, start=None, end=None, kind: str = "png") -> tuple[list[int], float]:
    """The recording's frame indices to export, and the output frame rate.

    Raises ValueError for an empty recording, a bad rate or an empty time range.
    """
    if len(recording) == 0:
        raise ValueError(f"{recording.path}: the recording has no frames")
    first, last = recording.start_time, float(recording.times[-1])
    start = first if start is None else float(start)
    end = last if end is None else float(end)
    if not (math.isfinite(start) and math.isfinite(end)):
        raise ValueError(f"time range must be finite, got {start:g} to {end:g} s")
    if start > last or end < first:
        raise ValueError(f"time range {start:g} to {end:g} s misses the recording ({first:g} to {last:g} s)")
    if end < start:
        raise ValueError(f"empty time range: start {start:g} s is after end {end:g} s")
    if fps is not None and not (math.isfinite(fps) and fps > 0):
        raise ValueError(f"frame rate must be positive, got {fps:g}")
    if fps is None and kind in _DEFAULT_FPS and recording.frame_rate:
        fps = min(recording.frame_rate, _DEFAULT_FPS[kind])
    if fps is None:
        indices = [k for k in range(len(recording)) if start <= recording.times[k] <= end]
        rate = recording.frame_rate or _typical_rate(recording.times, _DEFAULT_FPS.get(kind, 60.0))
        if not indices:
            raise ValueError(f"no frame between {start:g} s and {end:g} s")
        return indices, rate
    count = int(math.floor((end - start) * fps + 1e-9)) + 1
    return [recording.index_at(start + k / fps) for k in range(count)], float(fps)


def _typical_rate(times, cap: float) -> float:
    """Frames per second implied by the median frame interval (30 if there is none), at most ``cap``."""
    steps = np.diff(times)
    steps = steps[steps > 0]
    return min(cap, 1.0 / float(np.median(steps))) if len(steps) else min(cap, 30.0)


def export(recording, out, size=(512, 512), fps=None, start=None, end=None, progress: bool = True, supersample: int = 2) -> int:
    """Write frames of ``recording`` to ``out`` (see the module docstring); returns the frame count.

    ``size`` is ``(width, height)`` in pixels (even numbers for MP4).
    """
    width, height = size
    if width < 1 or height < 1:
        raise ValueError(f"size must be positive, got {width}x{height}")
    kind = export_kind(out)
    if kind == "html":
        from pge.viewer import write_html

        return write_html(recording, out, start, end)
    if kind == "mp4" and (width % 2 or height % 2):
        raise ValueError(f"MP4 needs an even width and height, got {width}x{height}")
    indices, rate = plan_frames(recording, fps, start, end, kind)
    out = Path(out)
    pictures = _pictures(recording, indices, (width, height), supersample, progress, out)
    if kind == "png":
        out.mkdir(parents=True, exist_ok=True)
        for k, picture in enumerate(pictures):
            picture.save(out / f"frame_{k:05d}.png")
    elif kind == "gif":
        out.parent.mkdir(parents=True, exist_ok=True)
        first = next(pictures)
        first.save(
            out,
            save_all=True,
            append_images=pictures,
            duration=1000.0 / rate,
            loop=0,
            optimize=False,
        )
    else:
        _write_mp4(out, pictures, rate)
    return len(indices)


def _pictures(recording, indices, size, supersample, progress, out):
    from tqdm import tqdm

    bar = tqdm(
        total=len(indices),
        unit="frame",
        desc=f"pge export {out.name}",
        disable=None if progress and len(indices) >= _PROGRESS_FROM else True,
        leave=False,
    )
    with bar:
        for index in indices:
            yield render_frame(recording, recording.frame(index), size, supersample)
            bar.update(1)


def _write_mp4(out: Path, pictures, rate: float) -> None:
    import imageio.v2 as imageio

    out.parent.mkdir(parents=True, exist_ok=True)
    writer = imageio.get_writer(
        out,
        format="FFMPEG",
        fps=rate,
        codec="libx264",
        pixelformat="yuv420p",
        macro_block_size=1,
        ffmpeg_log_level="error",
    )
    try:
        for picture in pictures:
            writer.append_data(np.asarray(picture))
    finally:
        writer.close()
