"""Fixtures for the simulator tests: worlds that close themselves, a drone in a hover."""

from __future__ import annotations

from collections.abc import Callable, Iterator

import pytest

from sim_server.drone.world import World, WorldConfig
from tests.sim_server.drone.flight import stream_setpoint


@pytest.fixture
def make_world() -> Iterator[Callable[..., World]]:
    """Build worlds that are closed after the test: ``make_world(seed=1, boxes=0)``."""
    worlds: list[World] = []

    def make(*, seed: int | None = None, boxes: int = 8) -> World:
        world = World(WorldConfig(seed=seed, boxes=boxes))
        worlds.append(world)
        return world

    yield make
    for world in worlds:
        world.close()


@pytest.fixture
def empty_world(make_world: Callable[..., World]) -> World:
    """A world with no boxes, for flight tests that should not meet obstacles."""
    return make_world(seed=1, boxes=0)


@pytest.fixture
def hovering(empty_world: World) -> World:
    """An empty world with the drone settled in a hover at (0, 0, 3)."""
    stream_setpoint(empty_world, (0.0, 0.0, 3.0), seconds=5.0)
    return empty_world
