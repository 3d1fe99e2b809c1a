"""OpenCV windows in the dashboard, in Chromium: a ROS 2 node of our own
(``opencv_window_node.py``, run by ``skydeck run``) shows a window with a trackbar and a mouse
callback; the Windows tab shows its frames, its slider moves what the node draws (the node's
callback ran, in the thread that calls waitKey), a click reaches the node's mouse callback in
image pixels, and a key typed in the panel is what ``cv2.waitKey`` returns."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

pytest.importorskip("cv2", reason="the vision extra is not installed: make install-vision")

from services.launch.background import BackgroundProcess  # noqa: E402
from tests.ros.conftest import ros_file  # noqa: E402
from tests.web_ui.conftest import Recorder, open_dashboard  # noqa: E402
from tests.web_ui.system import System, started  # noqa: E402

pytestmark = [pytest.mark.browser, pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(120)]

NODE = Path(__file__).with_name("opencv_window_node.py")
TOPIC = "/window_node/opencv/canvas"
PANEL = f".cv-window[data-topic='{TOPIC}']"

# The colour of image pixel (x, y) as the panel shows it: its <img> drawn into a canvas.
PIXEL = """([selector, x, y]) => {
  const img = document.querySelector(selector + ' img');
  if (!img || !img.naturalWidth) return null;
  const canvas = document.createElement('canvas');
  canvas.width = img.naturalWidth; canvas.height = img.naturalHeight;
  const ctx = canvas.getContext('2d');
  ctx.drawImage(img, 0, 0);
  return Array.from(ctx.getImageData(x, y, 1, 1).data.slice(0, 3));
}"""


@pytest.fixture(scope="module")
def core() -> Iterator[System]:
    with started() as system:
        yield system


@pytest.fixture
def node(core: System) -> Iterator[BackgroundProcess]:
    with ros_file(core, NODE, sim_time=False) as process:
        yield process


def _pixel_near(page: object, x: int, y: int, rgb: tuple[int, int, int], tolerance: int = 12) -> None:
    """Wait until the panel shows about ``rgb`` at image pixel (x, y) (JPEG is lossy)."""
    page.wait_for_function(  # type: ignore[attr-defined]
        f"""() => {{
          const p = ({PIXEL})([{PANEL!r}, {x}, {y}]);
          const want = {list(rgb)};
          return p !== null && p.every((v, i) => Math.abs(v - want[i]) <= {tolerance});
        }}""",
        timeout=30_000,
    )


def test_a_nodes_window_is_a_live_panel_with_slider_mouse_and_keys(core: System, node: BackgroundProcess, browser: object) -> None:
    with open_dashboard(browser, core.url, "window.skydeck && window.skydeck.coreReachable") as (page, recorder):
        _use(page, recorder, node)


def _use(page: object, recorder: Recorder, node: BackgroundProcess) -> None:
    page.click("button[data-tab='windows']")  # type: ignore[attr-defined]
    page.wait_for_function(  # type: ignore[attr-defined]
        f"window.skydeck.windows.some(w => w.topic === '{TOPIC}' && w.frames > 0)", timeout=40_000
    )
    shown = page.evaluate(f"window.skydeck.windows.find(w => w.topic === '{TOPIC}')")  # type: ignore[attr-defined]
    assert (shown["name"], shown["node"], shown["width"], shown["height"]) == ("canvas", "/window_node", 160, 120)
    assert shown["shown"] == [160, 120] and shown["mouse"] is True
    assert shown["trackbars"] == [{"name": "level", "value": 40, "minimum": 0, "maximum": 255, "slider": 40}]
    assert page.locator("#windows-tab").inner_text() == "Windows (1)"  # type: ignore[attr-defined]
    _pixel_near(page, 10, 10, (40, 40, 40))

    # The slider: the node's callback runs (in its drawing thread, the one that calls waitKey)
    # and what it draws changes.
    page.locator(f"{PANEL} input[data-trackbar='level']").fill("200")  # type: ignore[attr-defined]
    node.wait_for_line("TRACKBAR 200 drawing", 30)
    _pixel_near(page, 10, 10, (200, 200, 200))

    # A click at image pixel (40, 30): the node's mouse callback gets those coordinates, the
    # left button's flag and its param, and draws a red dot there.
    point = page.evaluate(f"window.skydeck.windowPoint('{TOPIC}', 40, 30)")  # type: ignore[attr-defined]
    page.mouse.click(point["x"], point["y"])  # type: ignore[attr-defined]
    node.wait_for_line("CLICK 40 30 1 clicked drawing", 30)
    _pixel_near(page, 40, 30, (255, 0, 0), tolerance=40)

    # A key typed in the panel (focused by the click) is what cv2.waitKey returns.
    page.keyboard.press("q")  # type: ignore[attr-defined]
    node.wait_for_line("KEY 113 drawing", 30)
    page.keyboard.press("Escape")  # type: ignore[attr-defined]
    node.wait_for_line("KEY 27 drawing", 30)
    assert page.evaluate(f"window.skydeck.windows.find(w => w.topic === '{TOPIC}').input.refused") == 0  # type: ignore[attr-defined]
    assert recorder.errors == []
    assert not any("Traceback" in line for line in node.lines), node.tail()


def test_images_are_sent_only_while_the_tab_is_shown(core: System, node: BackgroundProcess, browser: object) -> None:
    with open_dashboard(browser, core.url, "window.skydeck && window.skydeck.coreReachable") as (page, recorder):
        page.click("button[data-tab='windows']")  # type: ignore[attr-defined]
        page.wait_for_function(f"window.skydeck.windows.some(w => w.topic === '{TOPIC}' && w.frames > 2)", timeout=40_000)  # type: ignore[attr-defined]
        subscribers = f"(window.skydeck.graph.topics.find(t => t.name === '{TOPIC}') || {{subscribers: []}}).subscribers.length"
        page.wait_for_function(f"{subscribers} > 0", timeout=20_000)  # type: ignore[attr-defined]
        page.click("button[data-tab='map']")  # type: ignore[attr-defined]
        page.wait_for_function(f"!window.skydeck.sockets().some(s => s.topic === '{TOPIC}')", timeout=10_000)  # type: ignore[attr-defined]
        # Nobody reads the window's topic any more, so the node encodes nothing (it asks before each image).
        page.wait_for_function(f"{subscribers} === 0", timeout=30_000)  # type: ignore[attr-defined]
        assert page.evaluate("window.skydeck.windows.length") == 1  # type: ignore[attr-defined]  # still listed
        assert recorder.errors == []
