"""What the ROS 2 bridge's tests share: real ROS 2 (the `ros2` extra), kept out of other tests.

The extra installs top-level ``rclpy``, ``std_msgs``... into the venv. Tests that import them do
so through :func:`real_ros`, which takes them out of ``sys.modules`` again afterwards, so the
façade tests of ``services.ros`` (which put Skydeck's own ``std_msgs`` under that name) never meet
a real module left behind, and the other way round.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from services.launch.background import BackgroundProcess
from services.protocols.ros2.extra import missing_extra
from services.runtime.ports import free_port_block


@pytest.fixture(scope="module")
def real_ros() -> Iterator[None]:
    """Real rclpy and message packages importable for the test; skipped without the extra."""
    reason = missing_extra()
    if reason is not None:
        pytest.skip(reason)
    before = set(sys.modules)
    from services.ros.imports import RosImportFinder

    hidden = [finder for finder in sys.meta_path if isinstance(finder, RosImportFinder)]
    for finder in hidden:
        sys.meta_path.remove(finder)
    stale = {name: module for name, module in sys.modules.items() if _is_ros(name)}
    for name in stale:
        del sys.modules[name]
    try:
        yield
    finally:
        for name in set(sys.modules) - before:
            if _is_ros(name):
                del sys.modules[name]
        sys.modules.update(stale)
        sys.meta_path[:0] = hidden


def _is_ros(name: str) -> bool:
    top = name.split(".", 1)[0]
    return top in {"rclpy", "rosidl_parser", "rpyutils"} or top.endswith(("_msgs", "_srvs", "_interfaces"))


# -- real processes on a DDS domain of this test run's own ----------------------------------------


REPO = Path(__file__).resolve().parents[4]
NODES = Path(__file__).resolve().parent / "nodes"
# A domain per test process (ROS 2 has 0-232; other runs on this machine use others), and
# discovery on this machine only: nothing a test sends leaves loopback.
DOMAIN = 100 + os.getpid() % 100


def ros_environment(domain: int = DOMAIN) -> dict[str, str]:
    return {
        **os.environ,
        "ROS_DOMAIN_ID": str(domain),
        "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
        "PYTHONUNBUFFERED": "1",
        "SKYDECK_ROSBRIDGE_PORT": "0",
        "SKYDECK_FOXGLOVE_PORT": "0",
    }


@dataclass
class RosSystem:
    """A Skydeck system (a launch, with the bridge) and ROS 2 programs, on one DDS domain."""

    domain: int = DOMAIN
    base_port: int = 0
    processes: list[BackgroundProcess] = field(default_factory=list)

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.base_port}"

    def env(self) -> dict[str, str]:
        return {**ros_environment(self.domain), "SKYDECK_CORE_URL": self.url}

    def launch(self, *args: str, timeout_s: float = 90) -> BackgroundProcess:
        """``skydeck launch ARGS --ros2`` on free ports, waited for until every node is up."""
        self.base_port = free_port_block(4)
        process = self.start(
            [sys.executable, "-m", "services.cli", "launch", *args, "--ros2", "--base-port", str(self.base_port)],
            name=f"skydeck launch {' '.join(args)} --ros2",
        )
        process.wait_for_line("[launch] all", timeout_s=timeout_s)
        return process

    def rclpy(self, script: str, *args: str) -> BackgroundProcess:
        """An unmodified rclpy program of ``nodes/`` (real ROS 2: plain ``python``)."""
        return self.start([sys.executable, str(NODES / script), *args], name=f"rclpy {script}")

    def start(self, argv: list[str], *, name: str) -> BackgroundProcess:
        process = BackgroundProcess(argv, name=name, cwd=REPO, env=self.env())
        self.processes.append(process)
        return process

    def skydeck(self, *args: str, timeout_s: float = 30) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [sys.executable, "-m", "services.cli", *args], capture_output=True, text=True,
            env=self.env(), cwd=REPO, timeout=timeout_s, check=False,
        )

    @staticmethod
    def wait_for(predicate: Callable[[], bool], what: str, timeout_s: float = 20.0) -> None:
        """Poll ``predicate`` (state of another process, with no event to await) until true."""
        deadline = time.monotonic() + timeout_s
        while not predicate():
            if time.monotonic() > deadline:
                raise AssertionError(f"timed out waiting for {what}")
            time.sleep(0.2)

    def stop(self) -> None:
        for process in reversed(self.processes):
            process.stop(timeout_s=10)
        self.processes.clear()
