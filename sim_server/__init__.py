"""Skydeck's simulator core: a PyBullet quadrotor and falling boxes, with no networking.

The simulator node (``sim_server.node``) exposes a :class:`World` over topics and services.
:class:`InvalidCommand` (a ``ValueError``) is the one exception raised for bad pilot input;
everything else is a programming error (``ValueError`` for a bad config, ``RuntimeError`` for
a closed world).
"""

from sim_server.camera import render_jpeg
from sim_server.commands import ControlMode, InvalidCommand
from sim_server.world import DroneState, World, WorldConfig

__all__ = [
    "ControlMode",
    "DroneState",
    "InvalidCommand",
    "World",
    "WorldConfig",
    "render_jpeg",
]
