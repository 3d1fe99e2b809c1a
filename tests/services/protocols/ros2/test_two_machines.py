"""Two machines: two Skydeck systems in two network namespaces joined by a veth pair, which the
test makes and removes itself (root). Nothing leaves them: each namespace has its own loopback
and the veth's two ends, on addresses that exist only there.

In namespace A runs the robot world with its bridge; in B a Skydeck system with its bridge, and an
unmodified rclpy node. They find each other over the veth by DDS's own discovery (multicast, as
on a lab's network): B's system reads A's topics and calls A's services; the rclpy node in B
reads A's /scan and /odom and drives A's robot with /cmd_vel.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from collections.abc import Iterator

import pytest

from services.launch.background import BackgroundProcess
from tests.services.protocols.ros2.conftest import NODES, REPO, RosSystem

pytestmark = [pytest.mark.slow, pytest.mark.e2e, pytest.mark.timeout(300)]

_TAG = f"{os.getpid() % 100000}"
_SUBNET = f"10.{200 + os.getpid() % 50}.{os.getpid() % 250}"  # only inside the two namespaces


def _ip(*args: str) -> None:
    subprocess.run(["ip", *args], check=True, capture_output=True, text=True, timeout=10)


@pytest.fixture(scope="module")
def machines(real_ros: None) -> Iterator[tuple[str, str]]:
    """Namespaces A and B joined by a veth pair, removed afterwards whatever happens."""
    if os.geteuid() != 0 or shutil.which("ip") is None:
        pytest.skip("two machines need root and iproute2's `ip` (network namespaces)")
    a, b = f"skyA{_TAG}", f"skyB{_TAG}"
    made: list[str] = []
    try:
        for name in (a, b):
            _ip("netns", "add", name)
            made.append(name)
        _ip("link", "add", f"va{_TAG}", "type", "veth", "peer", "name", f"vb{_TAG}")
        for name, end, host in ((a, f"va{_TAG}", 1), (b, f"vb{_TAG}", 2)):
            _ip("link", "set", end, "netns", name)
            _ip("-n", name, "addr", "add", f"{_SUBNET}.{host}/24", "dev", end)
            _ip("-n", name, "link", "set", end, "up", "multicast", "on")
            _ip("-n", name, "link", "set", "lo", "up")
            _ip("-n", name, "route", "add", "224.0.0.0/4", "dev", end)  # DDS discovery's multicast
    except (subprocess.CalledProcessError, OSError) as error:
        for name in made:
            subprocess.run(["ip", "netns", "delete", name], check=False, capture_output=True, timeout=10)
        pytest.skip(f"network namespaces cannot be made here: {getattr(error, 'stderr', error)}")
    yield a, b
    for name in made:  # deleting a namespace deletes its end of the veth, and so the pair
        subprocess.run(["ip", "netns", "delete", name], check=False, capture_output=True, timeout=10)


class _Machine(RosSystem):
    """A RosSystem whose processes run inside a network namespace, with DDS on its subnet."""

    namespace: str = ""

    def env(self) -> dict[str, str]:
        return {**super().env(), "ROS_AUTOMATIC_DISCOVERY_RANGE": "SUBNET"}

    def start(self, argv: list[str], *, name: str) -> BackgroundProcess:
        return super().start(["ip", "netns", "exec", self.namespace, *argv], name=f"{name} in {self.namespace}")

    def skydeck(self, *args: str, timeout_s: float = 30) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            ["ip", "netns", "exec", self.namespace, sys.executable, "-m", "services.cli", *args],
            capture_output=True, text=True, env=self.env(), cwd=REPO, timeout=timeout_s, check=False,
        )


def test_two_machines_exchange_topics_and_services_and_an_rclpy_node_drives_the_other_machines_robot(
    machines: tuple[str, str],
) -> None:
    domain = 40 + os.getpid() % 50
    a, b = _Machine(domain=domain), _Machine(domain=domain)
    a.namespace, b.namespace = machines
    try:
        a.launch("robot", "--seed", "5")
        b.launch("robot", "--exclude", "sim")
        # B's Skydeck reads A's odometry (A's bridge -> DDS over the veth -> B's bridge)
        echoed = b.skydeck("topic", "echo", "/odom", "-n", "1", "--timeout", "60", "--field", "child_frame_id", timeout_s=80)
        assert echoed.returncode == 0 and "base_link" in echoed.stdout, echoed.stderr
        # ... and calls A's simulator's service
        b.wait_for(lambda: "/simulator/reset" in b.skydeck("service", "list").stdout.split(), "A's services in B", 60)
        reset = b.skydeck("service", "call", "/simulator/reset", "--timeout", "30", timeout_s=60)
        assert reset.returncode == 0 and "success: true" in reset.stdout, reset.stderr
        # An unmodified rclpy node in B drives the robot simulated in A
        driver = b.start([sys.executable, str(NODES / "robot_driver.py")], name="rclpy robot_driver.py")
        moved = driver.lines[driver.wait_for_line(lambda line: line.startswith("moved "), 150)]
        assert float(moved.split()[1]) >= 0.3
        scan = next(line for line in driver.lines if line.startswith("scan "))
        assert scan.split()[1] == "360"
    finally:
        b.stop()
        a.stop()
