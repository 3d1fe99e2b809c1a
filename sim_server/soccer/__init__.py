"""The soccer room: the robot world (``sim_server.robot``) with a ball the robots push and a
forward camera on every robot, for the course's computer-vision day.

:class:`SoccerWorld` is the simulation; ``sim_server.soccer.node`` puts it on topics
(``skydeck run sim --world soccer``, ``skydeck launch soccer``). ``sim_server.soccer.limits``
holds its numbers and loads no PyBullet.
"""

from __future__ import annotations

from shared_models.lazy import lazy_exports

__all__ = ["SoccerWorld"]

_HOMES = {"SoccerWorld": "sim_server.soccer.world"}

__getattr__ = lazy_exports(__name__, _HOMES)
