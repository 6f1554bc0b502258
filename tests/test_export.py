"""Exporting recordings: GIF and MP4 frame counts, sizes and pixels; PNG frames; time ranges."""

import imageio.v3 as iio
import numpy as np
import pytest
from PIL import Image

from pge import World
from pge.recording import Recorder, open_recording
from pge.render.export import export, plan_frames

RED = (250, 20, 20)


@pytest.fixture(scope="module")
def red_disc(tmp_path_factory):
    """A big red disc drifting right at 0.1 per second for 1 s, recorded at 20 fps (21 frames)."""
    path = tmp_path_factory.mktemp("export") / "disc.pgerec"
    world = World()
    world.add_circle((0.4, 0.5), 0.25, mass=1.0, velocity=(0.1, 0.0), data={"colour": RED})
    with Recorder(world, path, frame_rate=20):
        world.run_until(1.0)
    return open_recording(path)


def test_gif_has_one_frame_per_recorded_frame_at_the_asked_size(red_disc, tmp_path):
    """A GIF at the recording's rate has 21 frames of 120x80 pixels; the disc's centre is red."""
    out = tmp_path / "disc.gif"
    assert export(red_disc, out, size=(120, 80), progress=False) == 21
    with Image.open(out) as gif:
        assert gif.n_frames == 21 and gif.size == (120, 80)
        assert gif.info["duration"] == 50
        gif.seek(10)  # t = 0.5: centre at x = 0.45
        assert gif.convert("RGB").getpixel((54, 40)) == RED
        assert gif.convert("RGB").getpixel((2, 2)) == red_disc.colours[red_disc.background]


def test_mp4_has_the_right_frame_count_size_and_colour(red_disc, tmp_path):
    """An MP4 at 10 fps has 11 frames of 96x64; the disc's centre is red within codec error."""
    out = tmp_path / "disc.mp4"
    assert export(red_disc, out, size=(96, 64), fps=10, progress=False) == 11
    frames = np.stack(list(iio.imiter(out, plugin="FFMPEG")))
    assert frames.shape == (11, 64, 96, 3)
    centre = frames[5, 32, 43].astype(int)
    assert np.abs(centre - RED).max() <= 24


def test_png_directory_and_time_range(red_disc, tmp_path):
    """PNG export of 0.25-0.5 s writes the six recorded frames of that range, numbered from 0."""
    out = tmp_path / "frames"
    assert export(red_disc, out, size=(40, 40), start=0.25, end=0.5, progress=False) == 6
    names = sorted(p.name for p in out.iterdir())
    assert names == [f"frame_{k:05d}.png" for k in range(6)]
    with Image.open(out / "frame_00000.png") as first:
        assert first.size == (40, 40)


def test_sampling_picks_the_last_frame_at_or_before_each_output_time(red_disc):
    """At 8 fps over 1 s the output shows frames at 0, 0.125, 0.25, ... (the latest recorded before each)."""
    indices, rate = plan_frames(red_disc, fps=8, kind="gif")
    assert rate == 8 and indices == [0, 2, 5, 7, 10, 12, 15, 17, 20]


def test_bad_export_requests_raise_value_errors_naming_the_problem(red_disc, tmp_path):
    """Odd MP4 sizes, unknown suffixes, empty or missed time ranges are refused with a message."""
    with pytest.raises(ValueError, match="even width"):
        export(red_disc, tmp_path / "x.mp4", size=(99, 64), progress=False)
    with pytest.raises(ValueError, match=r"\.gif, \.mp4 or \.html"):
        export(red_disc, tmp_path / "x.avi", progress=False)
    with pytest.raises(ValueError, match="empty time range"):
        export(red_disc, tmp_path / "x.gif", start=0.8, end=0.2, progress=False)
    with pytest.raises(ValueError, match="misses the recording"):
        export(red_disc, tmp_path / "x.gif", start=5.0, progress=False)
