"""The viewer in a real browser: headless Chromium driven by Selenium.

Needs Debian's ``chromium`` and ``chromium-driver`` packages (or another
Chromium/Chrome and its chromedriver on PATH); skipped, saying so, where no
browser can be found. Selenium itself comes with the ``test`` extra.
"""

from __future__ import annotations

import shutil
import time
from io import BytesIO

import numpy as np
import pytest
from PIL import Image
from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By

from pge.recording import open_recording
from pge.render.recorded import render_frame
from pge.viewer import write_html
from pge.viewer.server import ViewerServer
from recording_helpers import record_small

BROWSERS = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")
SIDE = 256  # canvas pixels of the compared frame (?size=256: one canvas pixel per CSS pixel)


def find_browser():
    binary = next((found for name in BROWSERS if (found := shutil.which(name))), None)
    driver = shutil.which("chromedriver")
    return binary, driver


@pytest.fixture(scope="module")
def browser():
    binary, driver = find_browser()
    if binary is None or driver is None:
        pytest.skip(
            "no headless browser: install Chromium and its driver (Debian: apt-get install chromium chromium-driver)"
        )
    options = webdriver.ChromeOptions()
    options.binary_location = binary
    for argument in (
        "--headless=new",
        "--no-sandbox",  # CI runs as root, where Chromium's sandbox cannot start
        "--disable-gpu",
        "--disable-dev-shm-usage",
        "--force-device-scale-factor=1",
        "--window-size=1100,700",
    ):
        options.add_argument(argument)
    # an explicit driver path: Selenium must not try to download one (no internet here)
    session = webdriver.Chrome(service=Service(driver), options=options)
    yield session
    session.quit()


@pytest.fixture(scope="module")
def recording(tmp_path_factory):
    path = tmp_path_factory.mktemp("browser") / "small.pgerec"
    record_small(path, until=1.0, frame_rate=20.0)
    return open_recording(path)


@pytest.fixture(scope="module")
def server(recording):
    with ViewerServer(recording).start() as running:
        yield running


def state(browser) -> dict:
    return browser.execute_script("return window.pgeViewer.state()")


def open_page(browser, url: str) -> None:
    browser.get(url)
    deadline = time.monotonic() + 15
    while time.monotonic() < deadline:
        ready, error = browser.execute_script("return [window.pgeViewer && window.pgeViewer.ready, window.pgeViewer && window.pgeViewer.error]")
        assert not error, error
        if ready:
            return
        time.sleep(0.05)
    raise AssertionError(f"the viewer did not load {url}: {browser.find_element(By.ID, 'pge-status').text}")


def test_served_page_loads_the_recording(browser, server, recording):
    open_page(browser, server.url)
    shown = state(browser)
    assert shown["frames"] == len(recording) == 21 and shown["index"] == 0 and not shown["playing"]
    assert browser.find_element(By.ID, "pge-title").text == "small.pgerec"
    assert "t 0.0000 s" in browser.find_element(By.ID, "pge-status").text


def test_play_runs_to_the_end(browser, server):
    open_page(browser, server.url + "?speed=4")
    browser.find_element(By.ID, "pge-play").click()
    # A quarter of a second of playing may be over before the browser answers (a loaded
    # machine): then it must have played to the end.
    label = browser.find_element(By.ID, "pge-play").text
    started = state(browser)
    if started["playing"]:
        assert label == "Pause"  # still playing after the label was read: it was playing then
    else:
        assert started["index"] == started["frames"] - 1
    deadline = time.monotonic() + 10  # 1 s of recording at 4x: a quarter of a second of playing
    while state(browser)["playing"] and time.monotonic() < deadline:
        time.sleep(0.05)
    shown = state(browser)
    assert not shown["playing"] and shown["index"] == shown["frames"] - 1
    assert "end" in browser.find_element(By.ID, "pge-status").text


def test_step_buttons_and_keys(browser, server):
    open_page(browser, server.url)
    forward = browser.find_element(By.ID, "pge-forward")
    forward.click()
    forward.click()
    assert state(browser)["index"] == 2
    browser.find_element(By.ID, "pge-back").click()
    assert state(browser)["index"] == 1
    browser.find_element(By.TAG_NAME, "body").send_keys("\ue014")  # the right arrow key
    assert state(browser)["index"] == 2
    browser.find_element(By.ID, "pge-last").click()
    assert state(browser)["index"] == 20


def test_seek_slider_moves_to_the_frame_and_lists_its_events(browser, server, recording):
    open_page(browser, server.url)
    browser.execute_script(
        "var s = document.getElementById('pge-seek'); s.value = 12; s.dispatchEvent(new Event('input'));"
    )
    shown = state(browser)
    assert shown["index"] == 12 and shown["time"] == pytest.approx(recording.times[12])
    listed = sum(len(recording.frame(k).collisions.times) + len(recording.frame(k).timers.times) for k in range(13))
    assert shown["events"] == listed > 0
    assert "frame 12/20" in browser.find_element(By.ID, "pge-status").text
    # the event list is beside the scene, not on it
    canvas = browser.find_element(By.ID, "pge-canvas").rect
    events = browser.find_element(By.ID, "pge-events").rect
    assert events["x"] >= canvas["x"] + canvas["width"]


def canvas_picture(browser) -> np.ndarray:
    png = browser.find_element(By.ID, "pge-canvas").screenshot_as_png
    return np.asarray(Image.open(BytesIO(png)).convert("RGB"), dtype=np.float64)


def drawn(picture: np.ndarray, background) -> np.ndarray:
    """Pixels clearly not background: the shapes."""
    return np.abs(picture - np.asarray(background, dtype=np.float64)).sum(axis=2) > 60


def compare(browser_picture, pillow_picture, background) -> tuple[float, float]:
    """Mean absolute difference per channel (0-255) and the IoU of the drawn masks."""
    mean = float(np.abs(browser_picture - pillow_picture).mean())
    a, b = drawn(browser_picture, background), drawn(pillow_picture, background)
    return mean, float((a & b).sum() / max(1, (a | b).sum()))


def test_exported_file_draws_the_frame_as_pillow_does(browser, recording, tmp_path):
    out = tmp_path / "small.html"
    write_html(recording, out)
    frame = 14
    open_page(browser, f"{out.as_uri()}?size={SIDE}&frame={frame}")
    assert state(browser)["canvas"] == [SIDE, SIDE]
    seen = canvas_picture(browser)
    assert seen.shape == (SIDE, SIDE, 3)
    background = recording.colours[recording.background]
    same = np.asarray(render_frame(recording, recording.frame(frame), (SIDE, SIDE)), dtype=np.float64)
    other = np.asarray(render_frame(recording, recording.frame(2), (SIDE, SIDE)), dtype=np.float64)
    # The two draw the same shapes and differ only in anti-aliasing along edges (Pillow
    # supersamples, the canvas blends coverage) and colour rounding: the mean difference stays
    # below 2 of 255 (0.64 seen) and the shape masks overlap above 0.97 of their union (0.993 seen). Frame 2, with the
    # bodies elsewhere, scores far outside both bounds: the comparison can fail.
    mean, iou = compare(seen, same, background)
    assert mean < 2.0 and iou > 0.97, (mean, iou)
    mean_other, iou_other = compare(seen, other, background)
    assert mean_other > 2.0 and iou_other < 0.97, (mean_other, iou_other)
