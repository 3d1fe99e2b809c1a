"""Which families a run measures, in the order they run: each is built from the run's
:class:`~benchmarks.suite.Suite` by the module of its kind (topics, worlds, the system)."""

from __future__ import annotations

from benchmarks import system_families, topic_families, world_families
from benchmarks.runner import Family
from benchmarks.suite import Suite

__all__ = ["families"]


def families(suite: Suite, only: set[str] | None = None) -> list[Family]:
    """Every family, or those named in ``only`` (by family name or by one of its rows)."""
    every = [
        topic_families.throughput(suite),
        topic_families.latency(suite),
        topic_families.fanout(suite),
        system_families.services(suite),
        world_families.sim(suite),
        world_families.robot(suite),
        world_families.mission(suite),
        world_families.flight(suite),
        system_families.startup(suite),
        system_families.registry(suite),
        system_families.viewers(suite),
        topic_families.rosbridge(suite),
        system_families.bag(suite),
    ]
    if suite.plots:
        every += [topic_families.throughput_by_size(suite), world_families.rtf_by_boxes(suite)]
    if only:
        every = [f for f in every if f.name in only or only.intersection(f.rows)]
    return every
