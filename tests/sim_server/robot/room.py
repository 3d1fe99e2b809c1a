"""Helpers for tests against a running robot world: the core and `skydeck run sim --world robot`
as subprocesses (``tests.web_ui.system.System``), spoken to over plain HTTP and WebSocket."""

from __future__ import annotations

import json
import math
import os
import signal
import sys
import threading
import time
import urllib.error
import urllib.request
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

from websockets.sync.client import connect

from services.launch.background import BackgroundProcess
from tests.conftest import free_port_block
from tests.web_ui.system import REPO, System


def start_room(*sim_args: str) -> System:
    """The core and the robot world's simulator on free ports, once the core knows the
    simulator's names (the caller stops it)."""
    base = free_port_block(2)
    system = System(base)
    try:
        system.start("core", ["core"], base)
        system.start("sim", ["run", "sim", "--world", "robot", *sim_args], base + 1)
        wait_for(system, "/simulator/world", lambda m: True)  # registered: the core routes its names
    except BaseException:
        system.stop()
        raise
    return system


def reset_room(system: System) -> System:
    """Reset the world and wait until robot 1 stands at the start again (the caller's ``fresh``)."""
    if call(system, "/simulator/reset")["success"] is not True:
        raise AssertionError("/simulator/reset refused")
    wait_for(system, "/simulator/robots", lambda m: math.hypot(m["poses"][0]["position"]["x"], m["poses"][0]["position"]["y"]) < 1e-3)
    return system


def latest(system: System, topic: str) -> dict[str, Any] | None:
    """GET the topic's latest message through the core (None before the first); also any
    other JSON the core serves (``/api/graph``)."""
    try:
        with urllib.request.urlopen(system.url + topic, timeout=5) as reply:
            return json.loads(reply.read())  # type: ignore[no-any-return]
    except urllib.error.HTTPError as error:
        if error.code == 404:
            return None
        raise


def call(system: System, name: str, body: dict[str, Any] | None = None) -> dict[str, Any]:
    """POST a service call through the core."""
    request = urllib.request.Request(
        system.url + name, data=json.dumps(body or {}).encode(),
        headers={"Content-Type": "application/json"}, method="POST",
    )  # fmt: skip
    with urllib.request.urlopen(request, timeout=10) as reply:
        return json.loads(reply.read())  # type: ignore[no-any-return]


def wait_for(system: System, topic: str, until: Callable[[dict[str, Any]], bool], timeout_s: float = 20.0) -> dict[str, Any]:
    """Poll the topic's latest message until ``until`` holds; that message."""
    deadline = time.monotonic() + timeout_s
    message = None
    while time.monotonic() < deadline:
        message = latest(system, topic)
        if message is not None and until(message):
            return message
        time.sleep(0.02)
    raise AssertionError(f"{topic} did not satisfy the condition in {timeout_s} s; last: {str(message)[:300]}")


def stamp_s(message: dict[str, Any]) -> float:
    stamp = message["header"]["stamp"]
    return stamp["sec"] + stamp["nanosec"] * 1e-9


def clock_s(message: dict[str, Any]) -> float:
    """A /clock message (builtin_interfaces/Time) in seconds."""
    return message["sec"] + message["nanosec"] * 1e-9  # type: ignore[no-any-return]


def yaw_of(q: dict[str, float]) -> float:
    return math.atan2(2 * (q["w"] * q["z"] + q["x"] * q["y"]), 1 - 2 * (q["y"] ** 2 + q["z"] ** 2))


def truth(system: System, robot: int = 0) -> tuple[float, float, float]:
    """Robot ``robot``'s true pose from /simulator/robots."""
    pose = latest(system, "/simulator/robots")["poses"][robot]  # type: ignore[index]
    return pose["position"]["x"], pose["position"]["y"], yaw_of(pose["orientation"])


@contextmanager
def twist_stream(system: System, topic: str = "/cmd_vel", period_s: float = 0.05) -> Iterator[dict[str, float]]:
    """Publish raw Twist frames on ``topic`` through the core at 1/period_s Hz while in the
    block; set ``["x"]`` and ``["z"]`` of the yielded dict to change the command."""
    command = {"x": 0.0, "z": 0.0}
    stop = threading.Event()
    with connect(f"{system.ws_url}{topic}?mode=publish&type=geometry_msgs/msg/Twist") as websocket:

        def send() -> None:
            while not stop.is_set():
                frame = {"linear": {"x": command["x"], "y": 0.0, "z": 0.0}, "angular": {"x": 0.0, "y": 0.0, "z": command["z"]}}
                websocket.send(json.dumps(frame))
                stop.wait(period_s)

        thread = threading.Thread(target=send, daemon=True)
        thread.start()
        try:
            yield command
        finally:
            stop.set()
            thread.join(5)


class Recorder:
    """Every message of a topic, read through the core in a thread while in a ``with`` block."""

    def __init__(self, system: System, topic: str) -> None:
        self.messages: list[dict[str, Any]] = []
        self._url = f"{system.ws_url}{topic}"
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._read, daemon=True)
        self._connected = threading.Event()

    def __enter__(self) -> Recorder:
        self._thread.start()
        if not self._connected.wait(10):
            raise AssertionError(f"could not read {self._url}")
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        self._thread.join(5)

    def _read(self) -> None:
        with connect(self._url, max_size=None) as websocket:
            self._connected.set()
            while not self._stop.is_set():
                try:
                    self.messages.append(json.loads(websocket.recv(timeout=0.2)))
                except TimeoutError:
                    continue


@contextmanager
def behaviour(system: System, *args: str) -> Iterator[BackgroundProcess]:
    """``skydeck run ARGS --use-sim-time`` against ``system``'s core; stopped with Ctrl-C (SIGINT)
    after the block, which must end it cleanly."""
    process = BackgroundProcess(
        [sys.executable, "-m", "services.cli", "run", *args[:1], "--use-sim-time", *args[1:]],
        name=f"skydeck run {' '.join(args)}",
        cwd=REPO,
        env={**os.environ, "SKYDECK_CORE_URL": system.url, "PYTHONUNBUFFERED": "1"},
    )
    try:
        yield process
    finally:
        process.stop(signal.SIGINT, timeout_s=10)
    assert not any("Traceback" in line for line in process.lines), process.tail()
