"""Skydeck's simulator core: a PyBullet quadrotor and falling boxes, with no networking.

The simulator node (``sim_server.node``) exposes a :class:`World` over topics and services.
:class:`InvalidCommand` (a ``ValueError``) is the one exception raised for bad pilot input;
everything else is a programming error (``ValueError`` for a bad config, ``RuntimeError`` for
a closed world).

The exports load lazily, so other nodes can import ``sim_server.limits`` (the arena and speed
limits) without loading PyBullet.
"""

from __future__ import annotations

from shared_models.lazy import lazy_exports

__all__ = [
    "ControlMode",
    "DroneState",
    "InvalidCommand",
    "World",
    "WorldConfig",
    "render_jpeg",
]

_HOMES = {
    "ControlMode": "sim_server.commands",
    "InvalidCommand": "sim_server.commands",
    "DroneState": "sim_server.world",
    "World": "sim_server.world",
    "WorldConfig": "sim_server.world",
    "render_jpeg": "sim_server.camera",
}


__getattr__ = lazy_exports(__name__, _HOMES)
