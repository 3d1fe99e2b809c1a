"""Which families a run measures, in the order they run: each is built from the run's
:class:`~benchmarks.suite.Suite` by the module of its kind (topics, worlds, the system)."""

from __future__ import annotations

from benchmarks.camera import camera_family
from benchmarks.class_families import class_room, fences
from benchmarks.runner import Family
from benchmarks.suite import Suite
from benchmarks.system_families import bag, http_clients, registry, services, startup, viewers
from benchmarks.topic_families import (
    fanout,
    latency,
    ros2,
    rosbridge,
    throughput,
    throughput_by_size,
)
from benchmarks.world_families import flight, grading, mission, robot, rtf_by_boxes, sim

__all__ = ["families"]


def families(suite: Suite, only: set[str] | None = None) -> list[Family]:
    """Every family, or those named in ``only`` (by family name or by one of its rows)."""
    every = [
        throughput(suite),
        latency(suite),
        fanout(suite),
        services(suite),
        http_clients(suite),
        sim(suite),
        robot(suite),
        mission(suite),
        flight(suite),
        startup(suite),
        registry(suite),
        viewers(suite),
        camera_family(suite.core, window_s=max(suite.settings.sim_window_s, 3.0), repetitions=suite.settings.sim_repetitions),
        rosbridge(suite),
        bag(suite),
        grading(suite),
        *ros2(suite),
        fences(suite),
        class_room(suite),
    ]
    if suite.plots:
        every += [throughput_by_size(suite), rtf_by_boxes(suite)]
    if only:
        every = [f for f in every if f.name in only or only.intersection(f.rows)]
    return every
