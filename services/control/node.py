"""Control (the workshop's control node): take-off, fly and land as services, turned into a
30 Hz setpoint stream (``/drone/setpoint``) that the simulator's flight controller follows.

Refusals are answers (``success: false``) that say why, as in the seed:
take-off only from the ground, fly only once airborne, never to the current setpoint, never
outside the arena. Each refusal's message begins with its :class:`Refusal` tag, which is what a
program (the AI) reads; the text after it is for people.

A new build of the simulator's world (``/simulator/world``: a reset, or a restarted simulator)
puts the drone back on the ground at the start, so control drops to ``landed`` and stops its
setpoint stream instead of sending the new drone after the old world's goal.
"""

from __future__ import annotations

import argparse
import math
import time

from services.runtime import Node, NodeSettings, spin
from services.runtime.settings import node_settings
from shared_models.geometry_msgs import Point, PoseStamped
from shared_models.mavros_msgs import PositionTarget
from shared_models.ros_workshop import (
    ControlPhase,
    ControlState,
    FlyCommand,
    FlyCommandRequest,
    FlyCommandResponse,
    Refusal,
    SimWorld,
    refusal_message,
)
from shared_models.std_msgs import Header
from shared_models.std_srvs import Trigger, TriggerRequest, TriggerResponse
from sim_server.drone.limits import FLY_HALF_SIZE_M, ON_GROUND_Z_M

__all__ = ["ControlNode", "main"]

DEFAULT_PORT = 8003
FLIGHT_ALTITUDE_M = 3.0
SETPOINT_PERIOD_S = 1.0 / 30.0
STATE_PERIOD_S = 0.5
# Altitude at which a take-off counts as done, and a landing as touched down.
AIRBORNE_Z_M = FLIGHT_ALTITUDE_M - 0.2
# A pose older than this (wall time) means the simulator is gone: control holds and says so.
STALE_POSE_S = 1.0
STALE_MESSAGE = "no drone pose: holding the setpoint (simulator not publishing)"
_SAME_TARGET_M = 1e-3
_NO_POSE = refusal_message(Refusal.NO_POSE, "No drone pose: is the simulator (`skydeck run sim`) running?")


class ControlNode(Node):
    """The drone's flight modes: landed -> taking_off -> flying -> landing -> landed."""

    def __init__(self, settings: NodeSettings | None = None) -> None:
        super().__init__("control", settings=settings or node_settings().with_default_port(DEFAULT_PORT))
        self.drone_position: Point | None = None
        self._pose_wall_s = -math.inf
        self._stale_reported = False
        self.setpoint = Point()
        self.state: ControlPhase = "landed"
        self.setpoint_publisher = self.create_publisher(PositionTarget, "/drone/setpoint", 10)
        self.state_publisher = self.create_publisher(ControlState, "/control/state", 10, latched=True)
        self.world_id: str | None = None
        self.create_subscription(PoseStamped, "/drone/pose", self.on_pose, 1)
        self.create_subscription(SimWorld, "/simulator/world", self.on_world, 1)
        self.create_service(Trigger, "/control/take_off", self.handle_take_off)
        self.create_service(FlyCommand, "/control/fly", self.handle_fly)
        self.create_service(Trigger, "/control/land", self.handle_land)
        self.create_timer(SETPOINT_PERIOD_S, self.stream_setpoint)
        self.create_timer(STATE_PERIOD_S, self.publish_state, wall_clock=True)

    # -- inputs -------------------------------------------------------------------------------

    def on_pose(self, msg: PoseStamped) -> None:
        first = self.drone_position is None
        self.drone_position = msg.pose.position
        self._pose_wall_s = time.monotonic()
        if first and self.state == "landed" and self.drone_position.z > ON_GROUND_Z_M:
            self._adopt_airborne_drone()
        if self._stale_reported:
            self._stale_reported = False
            self.get_logger().info("drone pose is back")
            self.publish_state()
        z = self.drone_position.z
        if self.state == "taking_off" and z >= AIRBORNE_Z_M:
            self._set_state("flying")
        elif self.state == "landing" and z <= ON_GROUND_Z_M:
            self._set_state("landed")

    def _adopt_airborne_drone(self) -> None:
        # A restarted control finds the drone in the air (held by the simulator's failsafe): take
        # it over where it is, at flight altitude, so take-off, fly and land work as before.
        position = self.drone_position or Point()
        self.setpoint = Point(x=position.x, y=position.y, z=FLIGHT_ALTITUDE_M)
        self.get_logger().warning(
            "the drone is already in the air at (%.1f, %.1f, %.1f): holding it there", position.x, position.y, position.z
        )
        self._set_state("flying")

    def on_world(self, msg: SimWorld) -> None:
        known, self.world_id = self.world_id, msg.id
        if known is None or known == msg.id or self.state == "landed":
            return
        # The drone stands at the start of a new world: whatever it was doing is over.
        self.get_logger().info("new world %s: the drone is on the ground at the start", msg.id)
        self.setpoint = Point()
        self._set_state("landed")

    def pose_is_fresh(self) -> bool:
        """Whether the simulator's pose stream is alive."""
        return time.monotonic() - self._pose_wall_s <= STALE_POSE_S

    # -- services -----------------------------------------------------------------------------

    def handle_take_off(self, request: TriggerRequest) -> TriggerResponse:
        self.get_logger().info("Handling take off!")
        if self.drone_position is None or not self.pose_is_fresh():
            return TriggerResponse(success=False, message=_NO_POSE)
        if self.drone_position.z > ON_GROUND_Z_M:
            return TriggerResponse(
                success=False, message=refusal_message(Refusal.ALREADY_AIRBORNE, "Seems like the drone is already flying!")
            )
        self.setpoint = Point(x=self.drone_position.x, y=self.drone_position.y, z=FLIGHT_ALTITUDE_M)
        self._set_state("taking_off")
        return TriggerResponse(success=True, message="All ok!")

    def handle_fly(self, request: FlyCommandRequest) -> FlyCommandResponse:
        x, y = float(request.x), float(request.y)
        if self.state in ("landed", "landing"):
            return _fly_refusal(Refusal.NOT_AIRBORNE, "Take off first: the drone is not in the air.")
        if not (math.isfinite(x) and math.isfinite(y)):
            return _fly_refusal(Refusal.NOT_FINITE, f"Target ({x}, {y}) is not a finite position.")
        if abs(x) > FLY_HALF_SIZE_M or abs(y) > FLY_HALF_SIZE_M:
            return _fly_refusal(
                Refusal.OUTSIDE_ARENA,
                f"Target ({x:g}, {y:g}) is outside the arena: x and y must be within ±{FLY_HALF_SIZE_M:g} m.",
            )
        if abs(x - self.setpoint.x) < _SAME_TARGET_M and abs(y - self.setpoint.y) < _SAME_TARGET_M:
            return _fly_refusal(Refusal.SAME_TARGET, f"Already flying to ({x:g}, {y:g}).")
        self.setpoint = Point(x=x, y=y, z=FLIGHT_ALTITUDE_M)
        self.get_logger().info("Flying to (%g, %g)", x, y)
        self.publish_state()
        return FlyCommandResponse(success=True, message=f"Flying to ({x:g}, {y:g}).")

    def handle_land(self, request: TriggerRequest) -> TriggerResponse:
        if self.state in ("landed", "landing"):
            reason = Refusal.ALREADY_LANDED if self.state == "landed" else Refusal.ALREADY_LANDING
            return TriggerResponse(success=False, message=refusal_message(reason, f"Already {self.state}."))
        position = self.drone_position or self.setpoint
        self.setpoint = Point(x=position.x, y=position.y, z=0.0)
        self._set_state("landing")
        return TriggerResponse(success=True, message="Landing.")

    # -- outputs ------------------------------------------------------------------------------

    def stream_setpoint(self) -> None:
        """The offboard stream: re-sent at 30 Hz while the drone is under control."""
        if self.state == "landed":
            return
        self.setpoint_publisher.publish(
            PositionTarget(
                header=Header(stamp=self.get_clock().now().to_msg(), frame_id="map"),
                coordinate_frame=PositionTarget.FRAME_LOCAL_NED,
                type_mask=PositionTarget.IGNORE_VX | PositionTarget.IGNORE_VY | PositionTarget.IGNORE_VZ
                | PositionTarget.IGNORE_AFX | PositionTarget.IGNORE_AFY | PositionTarget.IGNORE_AFZ
                | PositionTarget.IGNORE_YAW_RATE,
                position=self.setpoint,
            )
        )

    def _set_state(self, state: ControlPhase) -> None:
        if state != self.state:
            self.state = state
            self.publish_state()

    def publish_state(self) -> None:
        """``/control/state``, on change and twice a second (wall time, so also when the simulator
        and its clock are gone: that is when the stale pose must be noticed and reported)."""
        if not self.pose_is_fresh() and not self._stale_reported and self.drone_position is not None:
            self._stale_reported = True
            self.get_logger().warning(
                "no drone pose for %.1f s: holding the setpoint, is the simulator running?", STALE_POSE_S
            )
        self.state_publisher.publish(
            ControlState(
                header=Header(stamp=self.get_clock().now().to_msg(), frame_id="map"),
                state=self.state,
                setpoint=self.setpoint,
                message=STALE_MESSAGE if self._stale_reported else "",
            )
        )


def _fly_refusal(reason: Refusal, text: str) -> FlyCommandResponse:
    return FlyCommandResponse(success=False, message=refusal_message(reason, text))


def main(argv: list[str] | None = None) -> int:
    """``skydeck run control``."""
    argparse.ArgumentParser(prog="skydeck run control", description="Take-off, fly and land services.").parse_args(argv)
    spin(ControlNode())
    return 0
