"""Drive forward, and stop before hitting anything: a safety stop.

The robot drives straight ahead at ``speed`` and stops as soon as the laser sees anything
closer than ``distance`` metres within ``half_angle`` degrees of straight ahead (wide enough to
cover its own width at that distance), and drives on once the way is clear again (a person who
walked past). The bumper is the last resort: a press stops the robot for good, since something
the laser missed is in the way. Braking takes a few centimetres at 0.3 m/s, so ``distance``
is where it starts to stop, not where it ends.

    skydeck run estop --ros-args -p distance:=0.5
"""

from __future__ import annotations

import math

from services.behaviours.laser import nearest_in_sector
from services.behaviours.robot import RobotBehaviour, run_behaviour
from services.runtime import NodeSettings

__all__ = ["EmergencyStop", "main"]


class EmergencyStop(RobotBehaviour):
    """``estop``: forward until something is close; a bump stops it for good."""

    def __init__(self, namespace: str = "/", settings: NodeSettings | None = None) -> None:
        super().__init__("estop", namespace, settings)
        self.declare_parameter("speed", 0.2)  # m/s
        self.declare_parameter("distance", 0.5)  # m: stop when anything ahead is this close
        self.declare_parameter("half_angle", 30.0)  # degrees either side of straight ahead
        self.state = "waiting"  # waiting (no scan yet) -> driving <-> stopped; bumped
        self.nearest = math.inf

    def control(self) -> tuple[float, float] | None:
        scan = self.sensors.scan
        if self.sensors.bumped and self.state != "bumped":
            self._enter("bumped", "bumper pressed: stopped for good")
        if self.state == "bumped":
            return 0.0, 0.0
        if scan is None:
            return None
        self.nearest = nearest_in_sector(scan, 0.0, self.get_parameter("half_angle").value)
        if self.nearest < self.get_parameter("distance").value:
            if self.state != "stopped":
                self._enter("stopped", f"something {self.nearest:.2f} m ahead: stopped")
            return 0.0, 0.0
        if self.state != "driving":
            self._enter("driving", "the way ahead is clear: driving")
        return self.get_parameter("speed").value, 0.0

    def _enter(self, state: str, why: str) -> None:
        self.state = state
        self.get_logger().info("%s", why)


def main(argv: list[str] | None = None) -> int:
    """``skydeck run estop``."""
    return run_behaviour(EmergencyStop, argv, prog="estop", description=__doc__.splitlines()[0])
