"""Browser-test fixtures: the real system (see ``system.py``) once per module, and Chromium.

The browser is Debian's Chromium driven by Playwright (never a downloaded one), headless.
"""

from __future__ import annotations

import contextlib
import json
import threading
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from websockets.sync.client import connect

from tests.conftest import free_port_block
from tests.web_ui.system import System

CHROMIUM = "/usr/bin/chromium"
CHROMIUM_ARGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]


@pytest.fixture(scope="module")
def system(tmp_path_factory: pytest.TempPathFactory) -> Iterator[System]:
    """Core on P, sim on P+1 (seed 1, real time), control on P+3; stopped after the module."""
    base = free_port_block(5)
    running = System(base)
    try:
        running.start("core", ["core"], base)
        running.start("sim", ["run", "sim", "--speed", "1", "--seed", "1"], base + 1)
        running.start("control", ["run", "control"], base + 3)
        yield running
    finally:
        running.stop()


@pytest.fixture(scope="module")
def browser() -> Iterator[object]:
    playwright_sync = pytest.importorskip("playwright.sync_api")
    if not Path(CHROMIUM).exists():
        pytest.skip(f"no Chromium at {CHROMIUM} (`make test-deps` installs it)")
    with playwright_sync.sync_playwright() as playwright:
        chromium = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS, headless=True)
        yield chromium
        chromium.close()


@dataclass
class Recorder:
    """What a page did: console errors, uncaught exceptions, every URL it requested."""

    errors: list[str] = field(default_factory=list)
    urls: list[str] = field(default_factory=list)

    def attach(self, page: object) -> None:
        page.on("console", lambda message: message.type == "error" and self.errors.append(message.text))  # type: ignore[attr-defined]
        page.on("pageerror", lambda error: self.errors.append(f"uncaught: {error}"))  # type: ignore[attr-defined]
        page.on("request", lambda request: self.urls.append(request.url))  # type: ignore[attr-defined]
        page.on("websocket", lambda websocket: self.urls.append(websocket.url))  # type: ignore[attr-defined]


@contextlib.contextmanager
def open_dashboard(browser: object, url: str, ready: str) -> Iterator[tuple[object, Recorder]]:
    """A fresh page on the dashboard at ``url``, once the JavaScript ``ready`` is true."""
    context = browser.new_context(viewport={"width": 1440, "height": 900})  # type: ignore[attr-defined]
    page = context.new_page()
    recorder = Recorder()
    recorder.attach(page)
    page.goto(url + "/")
    page.wait_for_function(ready, timeout=20_000)
    yield page, recorder
    with contextlib.suppress(Exception):
        context.close()


@pytest.fixture
def dashboard(system: System, browser: object) -> Iterator[tuple[object, Recorder]]:
    """A fresh page on the dashboard, once it shows the drone's pose."""
    with open_dashboard(browser, system.url, "window.skydeck && window.skydeck.pose !== null") as opened:
        yield opened


@pytest.fixture
def my_point(system: System) -> Iterator[None]:
    """The seed's send_message node, as a client of the gateway: PointStamped (1, 2, 0) in odom at 10 Hz."""
    stop = threading.Event()
    url = f"{system.ws_url}/my_point?type=geometry_msgs/msg/PointStamped&rate=1"
    message = json.dumps({"header": {"frame_id": "odom"}, "point": {"x": 1.0, "y": 2.0, "z": 0.0}})

    def publish() -> None:
        with connect(url) as websocket:
            while not stop.is_set():
                websocket.send(message)
                stop.wait(0.1)

    thread = threading.Thread(target=publish, daemon=True)
    thread.start()
    yield
    stop.set()
    thread.join(timeout=5)
