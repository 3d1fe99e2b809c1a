"""The ROS 2 bridge's rows: Skydeck <-> rclpy through the bridge, against rclpy <-> rclpy.

Each trial is a subscriber and a publisher (:mod:`benchmarks.ros2_worker`) in processes of
their own, on a DDS domain of this run's, discovery on this machine only; the bridged ones go
through a core and ``skydeck bridge ros2`` started once for the family. The reference, rclpy ->
rclpy over the same Fast DDS, is measured in the same run, so each row is a ratio.
"""

from __future__ import annotations

import os
import sys
from typing import Any

from benchmarks.processes import BenchError, Worker, start_core, wait_http, worker_env
from benchmarks.report import Result
from benchmarks.runner import Family, Readings, Trial, median_of

__all__ = ["ros2_family"]

_DOMAIN = 150 + os.getpid() % 80
_LATENCY_RATE_HZ = 200.0
_IMAGE_RATE_HZ = 30.0
# A 640x480 rgb8 image is 1.2 MB as a JSON frame (base64): over Skydeck's 1 MiB default.
_MAX_MESSAGE_BYTES = str(4 * 1024 * 1024)
# (key, publisher, subscriber, topic, rate, image)
_TRIALS = {
    "direct:throughput": ("rclpy-pub", "rclpy-sub", "/bench/ros2/direct_t", 0.0, False),
    "out:throughput": ("skydeck-pub", "rclpy-sub", "/bench/ros2/out_t", 0.0, False),
    "in:throughput": ("rclpy-pub", "skydeck-sub", "/bench/ros2/in_t", 0.0, False),
    "direct:latency": ("rclpy-pub", "rclpy-sub", "/bench/ros2/direct_l", _LATENCY_RATE_HZ, False),
    "out:latency": ("skydeck-pub", "rclpy-sub", "/bench/ros2/out_l", _LATENCY_RATE_HZ, False),
    "in:latency": ("rclpy-pub", "skydeck-sub", "/bench/ros2/in_l", _LATENCY_RATE_HZ, False),
    "out:image": ("skydeck-pub", "rclpy-sub", "/bench/ros2/image", _IMAGE_RATE_HZ, True),
    # Skydeck -> Skydeck, not bridged (no ROS 2 reader): the hop a bridged message makes on
    # Skydeck's side, so a latency row reads as rclpy -> rclpy plus this plus the bridge's own.
    "link:latency": ("skydeck-pub", "skydeck-sub", "/bench/ros2/link_l", _LATENCY_RATE_HZ, False),
}


class _Bridge:
    """A core and a bridge for the family's bridged trials, started on first use."""

    def __init__(self) -> None:
        self.workers: list[Worker] = []
        self.env: dict[str, str] | None = None

    def environment(self) -> dict[str, str]:
        if self.env is None:
            core, url = start_core("ros2-core")
            self.workers.append(core)
            self.env = worker_env(
                url, ROS_DOMAIN_ID=str(_DOMAIN), ROS_AUTOMATIC_DISCOVERY_RANGE="LOCALHOST",
                SKYDECK_MAX_MESSAGE_BYTES=_MAX_MESSAGE_BYTES,
            )
            bridge = Worker(
                "ros2-bridge", argv=[sys.executable, "-m", "services.cli", "bridge", "ros2", "--topics", "^/bench/ros2/"],
                env={**self.env, "SKYDECK_LOG_LEVEL": "INFO"},
            )
            self.workers.append(bridge)
            wait_http(f"{url}/api/nodes/ros2_bridge_{_DOMAIN}", 30.0, what="the ROS 2 bridge", worker=bridge)
        return self.env

    def close(self) -> None:
        for worker in reversed(self.workers):
            worker.stop(timeout_s=5.0)
        self.workers.clear()
        self.env = None


def _run(bridge: _Bridge, key: str, duration_s: float) -> dict[str, Any]:
    publisher_mode, subscriber_mode, topic, rate, image = _TRIALS[key]
    env = bridge.environment()
    options = ["--rate", str(rate), "--duration", str(duration_s), *(["--image"] if image else [])]
    subscriber = Worker(f"ros2-{subscriber_mode}", "benchmarks.ros2_worker", subscriber_mode, topic, *options, env=env)
    publisher = None
    try:
        subscriber.expect("READY", 30)
        publisher = Worker(f"ros2-{publisher_mode}", "benchmarks.ros2_worker", publisher_mode, topic, *options, env=env)
        publisher.expect("READY", 30)
        return subscriber.expect("RESULT", duration_s + 40)
    except BenchError:
        raise
    finally:
        for worker in (publisher, subscriber):
            if worker is not None:
                worker.stop(timeout_s=5.0)


def ros2_family(repetitions: int, duration_s: float) -> Family:
    """The family ``ros2``: throughput and latency both ways, and a camera's images."""
    bridge = _Bridge()
    trials = [Trial(key, key.replace(":", " "), lambda key=key: _run(bridge, key, duration_s)) for key in _TRIALS]  # type: ignore[misc]

    def summarise(readings: Readings) -> list[Result]:
        rate = {key: median_of(readings[key], "rate") for key in _TRIALS}
        p50 = {key: median_of(readings[key], "p50_us") / 1000 for key in _TRIALS}
        rows = []
        for direction, path in (("out", "Skydeck publisher -> bridge -> rclpy subscriber"),
                                ("in", "rclpy publisher -> bridge -> Skydeck subscriber")):
            throughput = Result(
                f"ros2_bridge_throughput_{direction}", rate[f"{direction}:throughput"], "msg/s",
                "rclpy -> rclpy (Fast DDS)", rate["direct:throughput"], target=">= 0.5x rclpy -> rclpy",
                samples=[r["rate"] for r in readings[f"{direction}:throughput"]], detail={"path": path},
            )
            throughput.met = throughput.ratio is not None and throughput.ratio >= 0.5
            latency = Result(
                f"ros2_bridge_latency_{direction}_p50", p50[f"{direction}:latency"], "ms",
                "rclpy -> rclpy (Fast DDS)", p50["direct:latency"], target="<= 2x rclpy -> rclpy",
                samples=[r["p50_us"] / 1000 for r in readings[f"{direction}:latency"]],
                detail={"path": path, "rate": f"{_LATENCY_RATE_HZ:g} msg/s",
                        "p99_ms": median_of(readings[f"{direction}:latency"], "p99_us") / 1000,
                        "skydeck_link_p50_ms": p50["link:latency"]},
            )
            latency.met = latency.ratio is not None and latency.ratio <= 2.0
            rows += [throughput, latency]
        image = Result(
            "ros2_bridge_image_30hz", rate["out:image"], "Hz", "the camera's rate", _IMAGE_RATE_HZ,
            target=">= 0.9x: every frame of a 640x480 rgb8 camera at 30 Hz",
            samples=[r["rate"] for r in readings["out:image"]],
            detail={"p50_ms": p50["out:image"], "path": "Skydeck publisher -> bridge -> rclpy subscriber"},
        )
        image.met = image.ratio is not None and image.ratio >= 0.9
        return [*rows, image]

    rows = ("ros2_bridge_throughput_out", "ros2_bridge_latency_out_p50", "ros2_bridge_throughput_in",
            "ros2_bridge_latency_in_p50", "ros2_bridge_image_30hz")  # fmt: skip
    return Family("ros2", trials, repetitions, summarise, rows=rows, close=bridge.close)
