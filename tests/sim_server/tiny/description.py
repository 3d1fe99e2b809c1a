"""The ball world as its clients see it."""

from __future__ import annotations

from sim_server.description import WorldDescription
from tests.sim_server.tiny.world import BALL_RADIUS_M

DESCRIPTION = WorldDescription(constants={"ball_radius_m": BALL_RADIUS_M}, topics={"balls": "/tiny/balls"})
