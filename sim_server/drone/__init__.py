"""The drone world: a PyBullet quadrotor flown by forces, and falling boxes (the first seed's
workshop).

:class:`World` is the simulation; ``sim_server.drone.node`` puts it on topics (``skydeck run
sim``). ``sim_server.drone.limits`` holds its numbers and loads no PyBullet, so the workshop's
nodes, the core and the dashboard can read them. :class:`InvalidCommand` (a ``ValueError``) is
the one exception raised for bad pilot input; everything else is a programming error
(``ValueError`` for a bad config, ``RuntimeError`` for a closed world).

The exports load lazily, so importing the package loads no PyBullet.
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
    "ControlMode": "sim_server.drone.commands",
    "InvalidCommand": "sim_server.checks",
    "DroneState": "sim_server.drone.world",
    "World": "sim_server.drone.world",
    "WorldConfig": "sim_server.drone.world",
    "render_jpeg": "sim_server.drone.camera",
}


__getattr__ = lazy_exports(__name__, _HOMES)
