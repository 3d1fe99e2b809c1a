"""The dashboard's camera in real Chromium: JPEG and raw rgb8 from the simulator at 640x480, both
read in msgpack (bytes as bytes), each drawn and counted; the socket asks for its own rate."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from tests.web_ui.system import System, started

pytestmark = [pytest.mark.browser, pytest.mark.timeout(120)]


@pytest.fixture(scope="module")
def system() -> Iterator[System]:
    """Overrides the conftest's: the core and a simulator whose camera is 640x480."""
    camera = ["--camera-width", "640", "--camera-height", "480", "--camera-rate", "10"]
    with started(("sim", ["run", "sim", "--speed", "1", "--seed", "1", *camera])) as running:
        yield running


def _socket(page, topic: str) -> dict:  # type: ignore[no-untyped-def]
    [state] = [s for s in page.evaluate("window.skydeck.sockets()") if s["topic"] == topic]
    return state


def test_the_camera_shows_jpeg_and_raw_frames_read_in_msgpack(dashboard) -> None:  # type: ignore[no-untyped-def]
    page, recorder = dashboard
    page.check("#camera-toggle")
    page.wait_for_function("window.skydeck.camera.frames > 2", timeout=30_000)
    jpeg = _socket(page, "/simulator/camera")
    assert jpeg["encoding"] == "msgpack" and jpeg["binaryFrames"] >= 3  # the core agreed to msgpack
    # A frame is counted when its Blob URL is set; the <img> decodes it later: wait for that.
    image = page.wait_for_function(
        "(() => { const i = document.getElementById('camera-image');"
        " return i.naturalWidth > 0 && {src: i.src, width: i.naturalWidth, height: i.naturalHeight, hidden: i.hidden}; })()",
        timeout=30_000,
    ).json_value()
    assert image["src"].startswith("blob:") and (image["width"], image["height"]) == (640, 480)
    assert not image["hidden"]

    page.select_option("#camera-kind", "raw")
    page.wait_for_function("window.skydeck.camera.topic === '/simulator/camera/image_raw'", timeout=5_000)
    before = page.evaluate("window.skydeck.camera.frames")
    page.wait_for_function(f"window.skydeck.camera.frames > {before + 2}", timeout=30_000)
    raw = _socket(page, "/simulator/camera/image_raw")
    assert raw["encoding"] == "msgpack" and raw["binaryFrames"] >= 3
    assert all(s["topic"] != "/simulator/camera" for s in page.evaluate("window.skydeck.sockets()"))
    canvas = page.evaluate(
        """(() => {
          const c = document.getElementById('camera-canvas');
          const pixels = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
          const colours = new Set();
          for (let i = 0; i < pixels.length; i += 4) colours.add(pixels[i] << 16 | pixels[i + 1] << 8 | pixels[i + 2]);
          return {width: c.width, height: c.height, colours: colours.size, hidden: c.hidden};
        })()"""
    )
    assert (canvas["width"], canvas["height"]) == (640, 480) and not canvas["hidden"]
    assert canvas["colours"] > 10  # a picture, not a blank canvas
    assert page.evaluate("window.skydeck.camera.error") == ""
    sockets = [url for url in recorder.urls if "/simulator/camera" in url and url.startswith("ws")]
    assert sockets and all("encoding=msgpack" in url and "rate=5" in url for url in sockets)
    assert not recorder.errors
