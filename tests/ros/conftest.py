"""Running ROS files as a user does: ``skydeck run FILE.py ...`` in a subprocess, against a
core (and the robot world) started on free loopback ports."""

from __future__ import annotations

import os
import signal
import sys
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

import pytest

from services.launch.background import BackgroundProcess
from tests.e2e.conftest import launch  # noqa: F401  (the fixture: `skydeck launch` for the ROS 1 corpus)
from tests.web_ui.system import REPO, System

CORPUS = Path(__file__).resolve().parent / "corpus"


@contextmanager
def ros_file(system: System, path: Path | str, *args: str, sim_time: bool = True) -> Iterator[BackgroundProcess]:
    """``skydeck run PATH ARGS [--ros-args -p use_sim_time:=true]`` against ``system``'s core,
    stopped with Ctrl-C (SIGINT) after the block if still running."""
    ros_args = ["--ros-args", "-p", "use_sim_time:=true"] if sim_time else []
    if sim_time and "--ros-args" in args:
        split = args.index("--ros-args")
        args = (*args[:split], *ros_args, *args[split + 1 :])
    elif sim_time:
        args = (*args, *ros_args)
    process = BackgroundProcess(
        [sys.executable, "-m", "services.cli", "run", str(path), *args],
        name=f"skydeck run {Path(path).name} {' '.join(args)}",
        cwd=REPO,
        env={**os.environ, "SKYDECK_CORE_URL": system.url, "PYTHONUNBUFFERED": "1"},
    )
    try:
        yield process
    finally:
        process.stop(signal.SIGINT, timeout_s=10)


def no_skydeck_frames(lines: list[str]) -> bool:
    """Whether no traceback line points into Skydeck's own code."""
    return not any(f"{REPO}/services/" in line or f"{REPO}/shared_models/" in line for line in lines)


@pytest.fixture(scope="module")
def core() -> Iterator[System]:
    """A core of its own (a subprocess) for the façade tests in this process."""
    from services.runtime.ports import free_port_block

    system = System(free_port_block(1))
    system.start("core", ["core"], system.base_port)
    yield system
    system.stop()


@pytest.fixture
def rclpy(core: System, monkeypatch: pytest.MonkeyPatch) -> Iterator[object]:
    """Skydeck's rclpy façade in this process, initialised against ``core`` (shut down after)."""
    from services.ros import rclpy as facade

    monkeypatch.setenv("SKYDECK_CORE_URL", core.url)
    facade.init(args=[])
    yield facade
    facade.shutdown()


@pytest.fixture
def ros_imports() -> Iterator[None]:
    """ROS's module names importable in this process, as in ``skydeck run``, for the test."""
    from services.ros import disable_ros_imports, enable_ros_imports

    enable_ros_imports()
    yield
    disable_ros_imports()


def until(predicate: Callable[[], bool], timeout_s: float = 10.0, what: str = "condition") -> None:
    """Poll ``predicate`` (state changed by another thread) until true; fail after ``timeout_s``."""
    deadline = time.monotonic() + timeout_s
    while not predicate():
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out waiting for {what}")
        time.sleep(0.01)
