"""The AI (the workshop's final task): take off, fly over every box exactly once in the
shortest order it can find, land. Progress is saved per world, so a restarted AI carries on.

One fly command per box, sent when the drone has reached the previous one (within 0.3 m
horizontally): never spamming control. ``/ai/status`` reports every change and once a second.

Control's services are called directly, but where they live is asked of the core (once, and again
after control moved). When that cannot be answered (the core is restarting, or control has not
registered again yet), the mission waits for the service and calls again instead of failing.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import math
import time
from collections.abc import Callable
from typing import TypeVar

from services.ai.planner import plan_tour
from services.ai.progress import ProgressStore, default_state_dir, world_key
from services.runtime import Client, Node, NodeSettings, ServiceError, ServiceUnavailableError, spin
from services.runtime.settings import process_settings
from shared_models import Message
from shared_models.geometry_msgs import Point, Polygon, PoseStamped
from shared_models.ros_workshop import AiStatus, ControlState, FlyCommand
from shared_models.std_msgs import Header
from shared_models.std_srvs import Trigger, TriggerRequest, TriggerResponse
from sim_server.limits import START_XY_M

__all__ = ["AiNode", "main"]

DEFAULT_PORT = 8004
TAKE_OFF_DONE_Z_M = 2.5
VISIT_RADIUS_M = 0.3
HOME_XY_M = START_XY_M
STATUS_PERIOD_S = 1.0
STALE_POSE_S = 1.0
_RETRY_S = 1.0
# A service nobody could locate is looked up again after this pause (wait_for_service polls on).
_UNAVAILABLE_PAUSE_S = 0.2
# Boxes count as at rest (and their world key as final) when this many consecutive box messages
# agree within the tolerance: falling boxes would give a plan, and a key, of a world in motion.
SETTLED_MESSAGES = 3
SETTLED_TOLERANCE_M = 0.02
# Control reporting another goal than the AI's for this long means it lost the command (it was
# restarted): the command is sent again. Long enough for control's state to catch up with a call.
CONTROL_FORGOT_S = 1.5

R = TypeVar("R", bound=Message)


class AiNode(Node):
    """The mission as one task; ``/ai/start`` restarts it, ``/ai/stop`` hovers."""

    def __init__(self, settings: NodeSettings | None = None, *, store: ProgressStore | None = None) -> None:
        super().__init__("ai", settings=settings or process_settings(NodeSettings, port=DEFAULT_PORT))
        self.store = store or ProgressStore(default_state_dir())
        self.drone_position: Point | None = None
        self.boxes: list[tuple[float, float]] = []
        self._pose_wall_s = -math.inf
        self._pose_event = asyncio.Event()
        self._boxes_event = asyncio.Event()  # set while the latest boxes are at rest
        self._recent_boxes: list[list[tuple[float, float, float]]] = []
        self.status = AiStatus(state="idle", target=-1)
        self.take_off = self.create_client(Trigger, "/control/take_off")
        self.fly = self.create_client(FlyCommand, "/control/fly")
        self.land = self.create_client(Trigger, "/control/land")
        self.status_publisher = self.create_publisher(AiStatus, "/ai/status", 10, latched=True)
        self.create_subscription(PoseStamped, "/drone/pose", self.on_pose, 1)
        self.create_subscription(Polygon, "/perception/boxes", self.on_boxes, 1)
        self.control_state: ControlState | None = None
        self.create_subscription(ControlState, "/control/state", self.on_control_state, 1)
        self.create_service(Trigger, "/ai/start", self.handle_start)
        self.create_service(Trigger, "/ai/stop", self.handle_stop)
        self.create_timer(STATUS_PERIOD_S, self.publish_status, wall_clock=True)
        self._mission: asyncio.Task[None] | None = None

    # -- inputs -------------------------------------------------------------------------------

    def on_pose(self, msg: PoseStamped) -> None:
        self.drone_position = msg.pose.position
        self._pose_wall_s = time.monotonic()
        self._pose_event.set()

    def on_boxes(self, msg: Polygon) -> None:
        self._recent_boxes = [*self._recent_boxes[1 - SETTLED_MESSAGES :], [(p.x, p.y, p.z) for p in msg.points]]
        if _at_rest(self._recent_boxes):
            self.boxes = [(p.x, p.y) for p in msg.points]
            self._boxes_event.set()
        else:
            self._boxes_event.clear()

    def on_control_state(self, msg: ControlState) -> None:
        self.control_state = msg

    async def handle_start(self, request: TriggerRequest) -> TriggerResponse:
        # Plan on boxes that arrive from now on: after a simulator reset, the new world's.
        self._recent_boxes.clear()
        self._boxes_event.clear()
        self._start_mission()
        return TriggerResponse(success=True, message="Mission (re)started.")

    async def handle_stop(self, request: TriggerRequest) -> TriggerResponse:
        if self._mission is None or self._mission.done():
            return TriggerResponse(success=False, message="No mission is running.")
        self._mission.cancel()
        self._update(state="idle", target=-1, message="stopped: hovering")
        if self.drone_position is not None:
            with contextlib.suppress(ServiceError):
                await self.fly.call(FlyCommand.Request(x=self.drone_position.x, y=self.drone_position.y), timeout_s=2.0)
        return TriggerResponse(success=True, message="Mission stopped; hovering where the drone is.")

    # -- running ------------------------------------------------------------------------------

    async def start(self) -> None:
        await super().start()
        self._start_mission()  # as in the seed: the mission starts by itself once the world is ready

    def _start_mission(self) -> None:
        if self._mission is not None:
            self._mission.cancel()
        self._mission = asyncio.get_running_loop().create_task(self._run_mission())

    async def _run_mission(self) -> None:
        try:
            await self._mission_steps()
        except asyncio.CancelledError:
            raise
        except ServiceError as error:
            self.get_logger().error("mission failed: %s", error)
            self._update(state="error", message=str(error))

    async def _mission_steps(self) -> None:
        self._update(state="idle", message="waiting for the drone pose and the boxes (at rest)")
        await self._boxes_event.wait()
        position = await self._fresh_position()
        boxes = list(self.boxes)
        key = world_key(boxes)
        visited = [i for i in self.store.load(key) if 0 <= i < len(boxes)]
        if visited:
            self.get_logger().info("resuming: %d of %d boxes already visited in this world", len(visited), len(boxes))
        self._update(visited=visited)
        if position.z < TAKE_OFF_DONE_Z_M:
            await self.take_off.wait_for_service()
            if position.z <= 0.1:
                response = await self._call(self.take_off, Trigger.Request())
                if not response.success:
                    self.get_logger().warning("take-off refused: %s", response.message)
            self._update(state="taking_off", message="taking off")
            while (await self._fresh_position()).z < TAKE_OFF_DONE_Z_M:
                pass
        remaining = [i for i in range(len(boxes)) if i not in visited]
        position = await self._fresh_position()
        tour = plan_tour((position.x, position.y), [boxes[i] for i in remaining])
        order = [remaining[i] for i in tour.order]
        self._update(state="flying", tour=order, tour_length=tour.length_m, remaining=len(order))
        self.get_logger().info("tour of %d boxes, %.1f m (%s)", len(order), tour.length_m, "optimal" if tour.optimal else "2-opt")
        for index in order:
            target = boxes[index]
            self._update(target=index, message=f"flying to box {index} at ({target[0]:.1f}, {target[1]:.1f})")
            await self._fly_to(target)
            visited.append(index)
            self.store.save(key, visited)
            left = [i for i in order if i not in visited]
            self._update(visited=list(visited), tour=left, remaining=len(left))
        # Boxes are 2 m tall: landing over the last one would set the drone down on its roof.
        # Return to the start, which the world keeps clear of boxes, and land there.
        self._update(state="landing", target=-1, message="all boxes visited: returning to the start to land")
        await self._fly_to(HOME_XY_M)
        await self._call(self.land, Trigger.Request())
        sent_s = time.monotonic()
        while (await self._fresh_position()).z > 0.1:
            if self._control_forgot(sent_s, lambda state: state.state in ("landing", "landed")):
                self.get_logger().warning("control is not landing (was it restarted?): asking again")
                await self._call(self.land, Trigger.Request())
                sent_s = time.monotonic()
        self._update(state="done", message=f"visited {len(visited)} boxes")

    async def _fly_to(self, target: tuple[float, float]) -> None:
        """One fly command, then wait until the drone is within the visit radius.

        The command is sent again only if control stops reporting it as its goal (a restarted
        control starts with none): never while control is on its way.
        """
        await self._send_fly(target)
        sent_s = time.monotonic()

        def flying_there(state: ControlState) -> bool:
            return math.hypot(state.setpoint.x - target[0], state.setpoint.y - target[1]) <= 1e-3

        while True:
            position = await self._fresh_position()
            if math.hypot(position.x - target[0], position.y - target[1]) <= VISIT_RADIUS_M:
                return
            if self._control_forgot(sent_s, flying_there):
                self.get_logger().warning("control is not flying to (%.1f, %.1f) (was it restarted?): sending it again", *target)
                await self._send_fly(target)
                sent_s = time.monotonic()

    async def _send_fly(self, target: tuple[float, float]) -> None:
        while True:
            response = await self._call(self.fly, FlyCommand.Request(x=target[0], y=target[1]))
            if response.success or response.message.startswith("Already flying"):
                return
            self.get_logger().warning("fly refused: %s; retrying in %.0f s", response.message, _RETRY_S)
            await asyncio.sleep(_RETRY_S)

    async def _call(self, client: Client[R], request: Message) -> R:
        """``client.call(request)``; while nobody can say where the service is (the core is
        restarting, or control has not registered again yet), wait for it and call again.

        Only ServiceUnavailableError is waited out: a timeout or a refused body still ends the
        mission. The calls the mission makes (take off, fly to a point, land) may be repeated.
        """
        waiting, held = False, ""
        while True:
            try:
                response = await client.call(request)
            except ServiceUnavailableError as error:
                if not waiting:
                    waiting = True
                    held = self.status.message
                    self.get_logger().warning("%s: waiting for %s", error, client.srv_name)
                    self._update(message=f"waiting for {client.srv_name} ({error})")
                await asyncio.sleep(_UNAVAILABLE_PAUSE_S)  # never a busy loop on a node that is gone
                await client.wait_for_service()
                continue
            if waiting:
                self.get_logger().info("%s is back", client.srv_name)
                self._update(message=held)
            return response

    def _control_forgot(self, sent_s: float, doing_it: Callable[[ControlState], bool]) -> bool:
        """Whether control's state has shown something else than the command sent at ``sent_s``
        for longer than CONTROL_FORGOT_S (only judged on states received since then)."""
        state = self.control_state
        if state is None or time.monotonic() - sent_s < CONTROL_FORGOT_S:
            return False
        return not doing_it(state)

    async def _fresh_position(self) -> Point:
        """The next drone pose (waits for one; says so when the simulator goes quiet)."""
        self._pose_event.clear()
        try:
            async with asyncio.timeout(STALE_POSE_S):
                await self._pose_event.wait()
        except TimeoutError:
            held = self.status.state
            self.get_logger().warning("no drone pose for %.0f s: holding, is the simulator running?", STALE_POSE_S)
            self._update(message="waiting for the drone pose (simulator not publishing)")
            await self._pose_event.wait()
            self.get_logger().info("drone pose is back")
            self._update(state=held, message="drone pose is back")
        if self.drone_position is None:
            raise RuntimeError("pose event without a pose")
        return self.drone_position

    # -- status -------------------------------------------------------------------------------

    def _update(self, **changes: object) -> None:
        status = self.status.model_copy(update=changes)
        if status != self.status:
            self.status = status
            self.publish_status()

    def publish_status(self) -> None:
        self.status.header = Header(stamp=self.get_clock().now().to_msg(), frame_id="map")
        self.status_publisher.publish(self.status.model_copy())


def _at_rest(recent: list[list[tuple[float, float, float]]]) -> bool:
    """Whether the last few box messages agree: same boxes, none moved more than the tolerance."""
    if len(recent) < SETTLED_MESSAGES:
        return False
    first = recent[0]
    return all(
        len(boxes) == len(first)
        and all(math.dist(a, b) <= SETTLED_TOLERANCE_M for a, b in zip(boxes, first, strict=True))
        for boxes in recent[1:]
    )


def main(argv: list[str] | None = None) -> int:
    """``skydeck run ai``."""
    argparse.ArgumentParser(prog="skydeck run ai", description="The box-visiting mission.").parse_args(argv)
    spin(AiNode())
    return 0
