"""The robot world: Neato-like differential-drive robots in a closed room with box obstacles and
a walking person (the second seed's class), in headless PyBullet.

:class:`RobotWorld` is the simulation; ``sim_server.robot.node`` puts it on topics
(``skydeck run sim --world robot``). ``sim_server.robot.limits`` holds its numbers and loads no
PyBullet, so the core and the dashboard can read them.
"""

from __future__ import annotations

from shared_models.lazy import lazy_exports

__all__ = ["Bump", "RobotWorld", "RobotWorldConfig"]

_HOMES = {
    "Bump": "sim_server.robot.world",
    "RobotWorld": "sim_server.robot.world",
    "RobotWorldConfig": "sim_server.robot.world",
}

__getattr__ = lazy_exports(__name__, _HOMES)
