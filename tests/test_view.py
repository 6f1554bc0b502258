"""The browser viewer without a browser: its data, page, server and CLI; watching a World."""

from __future__ import annotations

import json
import re
import urllib.error
import urllib.request
import warnings
from io import BytesIO

import pytest
from PIL import Image

from pge import World
from pge.cli import main
from pge.recording import open_recording
from pge.viewer import Animation, recording_data, show, standalone_page
from pge.viewer.page import asset
from pge.viewer.server import ViewerServer
from pge.world import LeftWorldWarning
from recording_helpers import raw_batch_file, record_small


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    path = tmp_path_factory.mktemp("view") / "small.pgerec"
    record_small(path, until=0.5, frame_rate=20.0)
    return path


def embedded(page: str) -> dict:
    found = re.search(r'<script id="pge-data" type="application/json" data-src="">(.*?)</script>', page, re.S)
    assert found, "no embedded data"
    return json.loads(found.group(1))


def test_data_holds_every_frame_shape_and_event(small):
    recording = open_recording(small)
    data = recording_data(recording)
    assert data["version"] == 1 and data["bounds"] == [0.0, 0.0, 1.0, 1.0]
    assert len(data["frames"]) == len(data["times"]) == len(recording) == 11
    frame = recording.frame(7)
    shown = data["frames"][7]
    assert len(shown["c"]) == 4 * len(frame.circles.ids) and len(shown["p"]) == len(frame.polygons.ids)
    assert shown["c"][0] == pytest.approx(frame.circles.centres[0, 0], rel=1e-6)
    collisions = sum(len(f.collisions.times) for f in recording.frames())
    assert sum(1 for f in data["frames"] for e in f["e"] if e[1] == "c") == collisions > 0
    assert data["bodies"]["0"] == ["polygon", "floor", True]
    assert data["colours"][0] == list(recording.colours[0])


def test_data_time_range_and_errors(small):
    recording = open_recording(small)
    part = recording_data(recording, start=0.2, end=0.3)
    assert part["times"] == pytest.approx([0.2, 0.25, 0.3])
    with pytest.raises(ValueError, match="empty time range"):
        recording_data(recording, start=0.4, end=0.1)
    with pytest.raises(ValueError, match="no frame at or before"):
        recording_data(recording, end=-1.0)


def test_standalone_page_embeds_script_style_and_data_safely(small):
    data = recording_data(open_recording(small))
    data["title"] = "</script><b>x</b>"
    page = standalone_page(data)
    assert "<script src=" not in page and "<link" not in page  # nothing to fetch: works offline
    assert "window.pgeViewer" in page and ".pge-side" in page
    assert page.count("</script>") == 2  # the data and the viewer: the title cannot close either
    assert embedded(page)["title"] == "</script><b>x</b>"
    for name in ("viewer.js", "viewer.css"):
        assert "</" not in asset(name)  # inlined into <script>/<style>, so it must not close them


def test_export_html_from_the_command_line(small, tmp_path, capsys):
    out = tmp_path / "run.html"
    assert main(["export", str(small), str(out)]) == 0
    assert "11 frames written" in capsys.readouterr().out
    assert len(embedded(out.read_text())["frames"]) == 11


def test_export_html_of_an_original_output_raw(tmp_path):
    raw = tmp_path / "output.raw"
    raw.write_bytes(raw_batch_file(frames=4))
    out = tmp_path / "raw.html"
    assert main(["export", str(raw), str(out), "-q"]) == 0
    data = embedded(out.read_text())
    assert len(data["frames"]) == len(open_recording(raw))
    assert any(len(f["c"]) == 4 and len(f["p"]) == 1 for f in data["frames"])


def test_export_rejects_an_unknown_suffix(small, tmp_path, capsys):
    assert main(["export", str(small), str(tmp_path / "run.txt")]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and ".html" in err


def get(url: str, headers=None) -> tuple[int, bytes, dict]:
    request = urllib.request.Request(url, headers=headers or {})
    try:
        with urllib.request.urlopen(request, timeout=10) as answer:
            return answer.status, answer.read(), dict(answer.headers)
    except urllib.error.HTTPError as error:
        return error.code, b"", {}


def test_server_serves_page_assets_and_data_on_loopback(small):
    with ViewerServer(open_recording(small)).start() as server:
        assert server.url.startswith("http://127.0.0.1:") and server.port > 0
        status, page, headers = get(server.url)
        assert status == 200 and headers["Content-Type"].startswith("text/html")
        assert b'src="viewer.js"' in page and b'data-src="data.json"' in page
        assert get(server.url + "viewer.js")[0] == 200 and get(server.url + "viewer.css")[0] == 200
        status, body, _ = get(server.url + "data.json")
        assert status == 200 and len(json.loads(body)["frames"]) == 11
        status, body, headers = get(server.url + "data.json", {"Accept-Encoding": "gzip"})
        assert headers.get("Content-Encoding") == "gzip"
        assert get(server.url + "../etc/passwd")[0] == 404 and get(server.url + "nothing")[0] == 404


def test_view_command_errors_are_one_line(tmp_path, capsys):
    assert main(["view", str(tmp_path / "missing.pgerec"), "--no-browser"]) == 1
    assert main(["view", "x.pgerec", "--port", "70000"]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 2 and "no such file" in err[0] and "port" in err[1]


def test_view_command_reports_a_busy_port(small, capsys):
    with ViewerServer(open_recording(small)).start() as busy:
        assert main(["view", str(small), "--no-browser", "--port", str(busy.port)]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"port {busy.port}" in err


def test_animation_shows_inline_in_an_iframe(small):
    animation = show(small)
    assert animation.frames == 11
    html = animation._repr_html_()
    assert html.startswith("<iframe srcdoc=") and "&lt;canvas" in html and "<canvas" not in html
    with pytest.raises(TypeError):
        Animation([1, 2])


# ---------------------------------------------------------------- watching a World


def box_world() -> World:
    world = World(gravity=(0.0, -9.81), bounds=(0.0, 0.0, 2.0, 1.0))
    world.add_box(0.0, 0.0, 2.0, 0.05, fixed=True, name="floor")
    world.add_circle((1.0, 0.5), 0.1, mass=1.0, name="ball", data={"colour": (250, 200, 0)})
    return world


def test_picture_follows_the_bounds_aspect_and_size(tmp_path):
    world = box_world()
    image = world.picture(tmp_path / "p.png", size=300)
    assert image.size == (300, 150) and Image.open(tmp_path / "p.png").size == (300, 150)
    assert world.picture(size=(64, 40)).size == (64, 40)
    assert image.getpixel((150, 75)) == pytest.approx((250, 200, 0), abs=2)  # the ball's colour
    with pytest.raises(ValueError):
        world.picture(size=0)
    with pytest.raises(TypeError):
        world.picture(size="big")
    with pytest.raises(ValueError):
        world.picture(bounds=(1, 1, 0, 2))


def test_repr_png_is_a_png_of_the_world():
    picture = Image.open(BytesIO(box_world()._repr_png_()))
    assert picture.format == "PNG" and picture.size == (400, 200)


def test_record_as_a_context_manager_unhooks_the_world(tmp_path):
    world = box_world()
    with world.record(tmp_path / "run.pgerec", frame_rate=10) as recorder:
        world.run_until(0.5)
    assert recorder.closed and recorder.frames == 6
    world.run_until(1.0)  # after closing, frames go nowhere
    assert len(open_recording(tmp_path / "run.pgerec")) == 6


def test_animate_records_a_run_and_keeps_the_frame_rate():
    world = box_world()
    animation = world.animate(0.5)
    assert world.time == 0.5 and world.frame_rate is None
    assert animation.frames == 16 and animation.data["times"][-1] == pytest.approx(0.5)
    assert "World run" in animation.data["title"]
    with pytest.raises(ValueError):
        world.animate(0.1)


def test_a_body_that_can_never_come_back_warns_once():
    world = World(gravity=(0.0, -9.81))
    world.add_polygon([(0.0, 0.5), (1.0, 0.0), (0.0, 0.0)], fixed=True, name="slope")
    world.add_circle((0.1, 0.6), 0.03, mass=1.0, name="ball")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        world.run_until(0.2)  # still on the slope: no warning
        assert not caught
        world.run_until(3.0)
        world.run_until(4.0)
    assert len(caught) == 1 and caught[0].category is LeftWorldWarning
    assert "'ball' left the world's bounds" in str(caught[0].message)
    assert caught[0].filename == __file__  # points at the caller's run_until


def test_no_warning_for_a_body_that_falls_back_in():
    world = World(gravity=(0.0, -9.81))
    world.add_box(0.0, 0.0, 1.0, 0.05, fixed=True)
    world.add_circle((0.5, 0.5), 0.03, mass=1.0, velocity=(0.0, 8.0))  # up through the top, and back
    with warnings.catch_warnings():
        warnings.simplefilter("error", LeftWorldWarning)
        world.run_until(0.5)
        ball = world.bodies[1]
        assert ball.position[1] > 1.5 and ball.velocity[1] > 0  # out and moving away, but gravity turns it
        world.run_until(3.0)


def test_pge_view_prints_the_url_serves_and_stops_on_ctrl_c(small):
    import os
    import signal
    import subprocess
    import sys

    env = dict(os.environ, PYTHONUNBUFFERED="1", PYTHONFAULTHANDLER="1")
    process = subprocess.Popen(
        [sys.executable, "-m", "pge.cli", "view", str(small), "--no-browser"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
        # as from a terminal: a process started in the background by a shell without job
        # control (CI scripts, nohup ... &) has SIGINT ignored, and its children inherit that
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    try:
        line = process.stdout.readline()
        found = re.search(r"http://127\.0\.0\.1:(\d+)/", line)
        assert found, line + process.stderr.read()
        status, body, _ = get(found.group(0) + "data.json")
        assert status == 200 and len(json.loads(body)["frames"]) == 11
        process.send_signal(signal.SIGINT)  # what Ctrl-C sends
        # communicate, not wait: it drains the pipes, so a child that writes on its way out
        # cannot block on a full one
        try:
            _, err = process.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            process.send_signal(signal.SIGABRT)  # faulthandler: where every thread of it is
            _, err = process.communicate()
            pytest.fail("pge view did not stop within 30 s of Ctrl-C; its threads:\n" + err[-6000:])
        assert process.returncode == 0, err
        assert "stopped" in err
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()


def test_a_recording_shows_inline_in_a_notebook(small):
    html = open_recording(small)._repr_html_()
    assert html.startswith("<iframe srcdoc=") and "small.pgerec" in html


def test_a_removed_bodys_handle_raises_value_error():
    world = box_world()
    ball = world.bodies[1]
    world.remove(ball)
    assert not ball.alive
    with pytest.raises(ValueError, match="has been removed from its world"):
        ball.position
    with pytest.raises(ValueError, match="has been removed from its world"):
        world.set_velocity(ball, (1.0, 0.0))


def test_the_notebook_demo_runs_as_a_script(tmp_path, monkeypatch):
    import runpy
    from pathlib import Path

    monkeypatch.chdir(tmp_path)
    runpy.run_path(str(Path(__file__).parent.parent / "examples" / "notebook_demo.py"), run_name="__main__")
    assert Image.open(tmp_path / "out" / "notebook_demo.png").size == (800, 800)
    assert len(embedded((tmp_path / "out" / "notebook_demo.html").read_text())["frames"]) == 61
