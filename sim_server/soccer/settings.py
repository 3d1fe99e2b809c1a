"""The soccer room's options: the robot world's (``--robots``, ``--obstacles``) and every world's
(the camera's rate and size are its robots' cameras' too). Pure settings: importing this loads no
PyBullet."""

from __future__ import annotations

from sim_server.robot.settings import RobotSettings

__all__ = ["SoccerSettings"]


class SoccerSettings(RobotSettings):
    """The soccer room's settings: the robot world's; the ball stands where it always does."""
