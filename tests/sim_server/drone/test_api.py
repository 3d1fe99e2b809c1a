"""The drone world's public surface, pinned so the node and the workshop's nodes can rely on it."""

from __future__ import annotations

import sim_server
import sim_server.drone
from sim_server.drone import limits


def test_public_names() -> None:
    assert sorted(sim_server.drone.__all__) == [
        "ControlMode",
        "DroneState",
        "InvalidCommand",
        "World",
        "WorldConfig",
        "render_jpeg",
    ]
    for name in sim_server.drone.__all__:
        assert getattr(sim_server.drone, name) is not None
    assert sim_server.__all__ == ["InvalidCommand"]


def test_world_module_exports_what_the_node_imports() -> None:
    from sim_server.drone.world import InvalidCommand, World, WorldConfig

    assert issubclass(InvalidCommand, ValueError) and InvalidCommand is sim_server.InvalidCommand
    assert World is sim_server.drone.World and WorldConfig is sim_server.drone.WorldConfig


def test_limits_the_node_and_control_share() -> None:
    assert limits.ARENA_HALF_SIZE_M == 15.0
    assert limits.CEILING_M == 50.0
    assert limits.MAX_SPEED_XY == 8.0
    assert limits.MAX_SPEED_Z == 3.0
    assert limits.FLY_HALF_SIZE_M > limits.ARENA_HALF_SIZE_M
    assert limits.PHYSICS_HZ == 240
    assert limits.STREAM_TIMEOUT_S == 0.5
    assert limits.ON_GROUND_Z_M == 0.1
