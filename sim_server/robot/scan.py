"""The Neato's laser: 360 beams in one batched ray test.

Beam ``i`` points ``i`` degrees counter-clockwise from straight ahead, level, from the laser at
LASER_HEIGHT_M above base_link. Each ray starts just outside the laser's own housing (so the
robot never sees itself) and is cast to RANGE_MAX_M; a beam with no return, or one closer than
RANGE_MIN_M, reads NO_RETURN (0.0), as the Neato driver reports it. The rays test everything
but the floor (``SCAN_MASK``).
"""

from __future__ import annotations

from operator import itemgetter

import numpy as np
import pybullet as p

from sim_server.robot.bodies import SCAN_MASK
from sim_server.robot.limits import (
    LASER_HEIGHT_M,
    LASER_HOUSING_RADIUS_M,
    NO_RETURN,
    RANGE_MAX_M,
    RANGE_MIN_M,
    SCAN_ANGLE_INCREMENT,
    SCAN_BEAMS,
)

__all__ = ["Laser"]

_START_M = LASER_HOUSING_RADIUS_M + 0.01
"""Where each ray starts, from the laser's centre: outside the housing."""
_SPAN_M = RANGE_MAX_M - _START_M
_MIN_FRACTION = (RANGE_MIN_M - _START_M) / _SPAN_M
_BODY = itemgetter(0)
_FRACTION = itemgetter(2)


class Laser:
    """Casts a scan for a robot at a pose; one ``rayTestBatch`` call per scan."""

    def __init__(self, client: int) -> None:
        self._client = client
        angles = np.arange(SCAN_BEAMS) * SCAN_ANGLE_INCREMENT
        self._cos = np.cos(angles)
        self._sin = np.sin(angles)
        self._from = np.empty((SCAN_BEAMS, 3))
        self._to = np.empty((SCAN_BEAMS, 3))

    def scan(self, x: float, y: float, yaw: float) -> list[float]:
        """The ranges (m) seen by a robot whose base_link is at (x, y) facing ``yaw``."""
        c, s = np.cos(yaw), np.sin(yaw)
        dx = c * self._cos - s * self._sin  # each beam's direction in the world
        dy = s * self._cos + c * self._sin
        start, reach = self._from, self._to
        start[:, 0] = x + _START_M * dx
        start[:, 1] = y + _START_M * dy
        start[:, 2] = LASER_HEIGHT_M
        reach[:, 0] = x + RANGE_MAX_M * dx
        reach[:, 1] = y + RANGE_MAX_M * dy
        reach[:, 2] = LASER_HEIGHT_M
        hits = p.rayTestBatch(start, reach, collisionFilterMask=SCAN_MASK, physicsClientId=self._client)
        # hit = (body, link, fraction, position, normal); body -1: no return. Read in bulk: a
        # Python test per beam costs a tenth of the ray batch itself.
        bodies = np.fromiter(map(_BODY, hits), dtype=np.int64, count=SCAN_BEAMS)
        fractions = np.fromiter(map(_FRACTION, hits), dtype=np.float64, count=SCAN_BEAMS)
        returned = (bodies >= 0) & (fractions >= _MIN_FRACTION)
        ranges: list[float] = np.where(returned, _START_M + fractions * _SPAN_M, NO_RETURN).tolist()
        return ranges
