"""The benchmark suite's parameters and a run's shared state (the rows and targets: ``*_families``).

``quick`` is the CI smoke run (each family once, about 4 minutes on 2 cores); the full run repeats more,
measures longer, and gathers the data for the plots. Targets are those of the issue; the
ratios are what count on a shared machine.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from benchmarks.topics import CoreHolder

__all__ = ["FULL", "QUICK", "Settings", "Suite"]


@dataclass(frozen=True)
class Settings:
    """How long and how often each family measures."""

    topic_repetitions: int
    throughput_s: float
    latency_s: float
    latency_rate_hz: float
    fanout_repetitions: int
    fanout_s: float
    service_repetitions: int
    service_calls: int
    sim_repetitions: int
    sim_window_s: float
    sim_bare_steps: int
    mission_worlds: int
    mission_flights: int
    startup_repetitions: int
    viewers_s: float = 3.0
    viewers_repetitions: int = 1
    plot_sizes: tuple[int, ...] = (256, 1024, 4096, 16384, 65536)
    plot_boxes: tuple[int, ...] = (0, 4, 8, 16, 30)
    plot_throughput_s: float = 1.5
    bag_repetitions: int = 1
    bag_window_s: float = 2.0
    http_client_repetitions: int = 3
    grading_repetitions: int = 3
    fence_messages: int = 20_000
    class_students: int = 30
    class_repetitions: int = 1
    class_window_s: float = 3.0


# Quick: each family once (a smoke test of every row; its figures are not quoted).
QUICK = Settings(
    topic_repetitions=1, throughput_s=1.0, latency_s=1.5, latency_rate_hz=1000.0,
    fanout_repetitions=1, fanout_s=2.0,
    service_repetitions=1, service_calls=300, http_client_repetitions=1,
    sim_repetitions=1, sim_window_s=1.0, sim_bare_steps=2400,
    mission_worlds=20, mission_flights=1, startup_repetitions=1, grading_repetitions=1,
)  # fmt: skip
FULL = Settings(
    topic_repetitions=5, throughput_s=3.0, latency_s=5.0, latency_rate_hz=1000.0,
    fanout_repetitions=3, fanout_s=10.0,
    service_repetitions=5, service_calls=2000,
    sim_repetitions=3, sim_window_s=3.0, sim_bare_steps=4800,
    mission_worlds=20, mission_flights=5, startup_repetitions=3,
    viewers_s=10.0, viewers_repetitions=2, class_repetitions=3, class_window_s=10.0,
)  # fmt: skip


class Suite:
    """One run's shared state: its settings, the core the families share, and what the plots need
    (the families themselves are :func:`benchmarks.families.families`)."""

    def __init__(self, settings: Settings, *, plots: bool) -> None:
        self.settings = settings
        self.plots = plots
        self.core = CoreHolder()
        self.plot_data: dict[str, Any] = {}

    def close(self) -> None:
        self.core.close()
