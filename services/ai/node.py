"""The AI (the workshop's final task): take off, fly over every box exactly once, land beside the
last one; the whole flight, take-off to touchdown, as short as it can be.

One fly command per box, sent when the drone has reached the previous one (within 0.3 m
horizontally): never spamming control. ``/ai/status`` reports every change and once a second.
Control's refusals are read by their reason (:class:`shared_models.ros_workshop.Refusal`), never
by their text.

The mission starts on ``/ai/start`` (the dashboard's Start mission button), or at once with
``--start-mission`` (``skydeck launch start_mission:=true``); until then the drone stands landed
and the workshop's first commands (``take_off``...) are the user's. Progress is saved per world
(``/simulator/world``'s id, a new one for every build of the world), so an AI restarted in the
middle of a mission carries on by itself without visiting a box twice, a finished world stays
finished, and once a mission has started a new world (a reset, a restarted simulator) gets a new
tour, started by itself.

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

from pydantic_settings import BaseSettings, SettingsConfigDict

from services.ai.landing import (
    DEFAULT_LANDING,
    LANDING_POLICIES,
    LandingPolicy,
    finishing_legs,
    landing_spot,
)
from services.ai.planner import plan_tour
from services.ai.progress import ProgressStore, WorldProgress
from services.ai.world import WorldTracker
from services.runtime import (
    Client,
    Node,
    NodeSettings,
    Parameter,
    ServiceError,
    ServiceUnavailableError,
    spin,
)
from services.runtime.settings import node_settings, settings_from_flags
from shared_models import Message
from shared_models.errors import SkydeckError
from shared_models.geometry_msgs import Point, Polygon, PoseStamped
from shared_models.rcl_interfaces import ParameterDescriptor, SetParametersResult
from shared_models.ros_workshop import (
    AiStatus,
    ControlState,
    FlyCommand,
    Refusal,
    SimWorld,
    refusal_reason,
)
from shared_models.std_msgs import Header
from shared_models.std_srvs import Trigger, TriggerRequest, TriggerResponse
from sim_server.drone.limits import ON_GROUND_Z_M, START_XY_M

__all__ = ["AiNode", "AiSettings", "main"]

DEFAULT_PORT = 8004
TAKE_OFF_DONE_Z_M = 2.5
VISIT_RADIUS_M = 0.3
# Control lands where the drone is when asked: the AI asks once the drone is this close to its
# landing spot (and so nearly stopped there), keeping the touchdown clear of the boxes.
LANDING_RADIUS_M = 0.1
HOME_XY_M = START_XY_M
STATUS_PERIOD_S = 1.0
STALE_POSE_S = 1.0
_RETRY_S = 1.0
# A service nobody could locate is looked up again after this pause (wait_for_service polls on).
_UNAVAILABLE_PAUSE_S = 0.2
# Control reporting another goal than the AI's for this long means it lost the command (it was
# restarted): the command is sent again. Long enough for control's state to catch up with a call.
CONTROL_FORGOT_S = 1.5
# Refusals that mean "already done": the mission carries on as if the call had succeeded.
_NOTHING_TO_DO = {Refusal.SAME_TARGET, Refusal.ALREADY_AIRBORNE, Refusal.ALREADY_LANDING, Refusal.ALREADY_LANDED}
# Refusals that no repetition can change: the mission ends in error.
_CANNOT_FLY = {Refusal.OUTSIDE_ARENA, Refusal.NOT_FINITE}

R = TypeVar("R", bound=Message)
Point2 = tuple[float, float]


class AiSettings(BaseSettings):
    """The mission's options: ``skydeck run ai --landing ...`` or ``SKYDECK_AI_*`` variables."""

    model_config = SettingsConfigDict(env_prefix="SKYDECK_AI_", extra="ignore")

    landing: LandingPolicy = DEFAULT_LANDING
    """beside_last_box: land at the nearest clear spot beside the last box; home: fly back to the
    start and land there (the tour is then planned closed)."""
    start_mission: bool = False
    """True: start the mission as soon as the node runs (as the seed's AI did); False: wait for
    ``/ai/start``, the drone landed, unless this world's mission was already under way."""


class MissionError(SkydeckError):
    """The mission cannot go on (control refused a command that no retry can change)."""


class AiNode(Node):
    """The mission as one task; ``/ai/start`` (re)starts it, ``/ai/stop`` hovers."""

    def __init__(
        self,
        settings: NodeSettings | None = None,
        *,
        ai: AiSettings | None = None,
        store: ProgressStore | None = None,
    ) -> None:
        if settings is None:
            settings = node_settings().with_default_port(DEFAULT_PORT)
            # A node of the simulated world: it follows the simulator's clock unless told otherwise
            # (SKYDECK_USE_SIM_TIME=false, -p use_sim_time:=false), so /ai/status is stamped in sim
            # time as the simulator's and control's messages are, also when run by hand.
            if "use_sim_time" not in settings.model_fields_set:
                settings = settings.model_copy(update={"use_sim_time": True})
        super().__init__("ai", settings=settings)
        self.ai = ai or AiSettings()
        # The landing policy is a parameter too (`-p landing:=home`, `skydeck param set /ai landing
        # home`), its default the flag's; a new value applies from the next tour planned.
        self.add_on_set_parameters_callback(_check_landing)
        self.declare_parameter(
            "landing",
            self.ai.landing,
            ParameterDescriptor(
                description="where to land once every box is visited (read when a tour is planned)",
                additional_constraints=f"one of: {', '.join(LANDING_POLICIES)}",
            ),
        )
        # Starting on its own is a parameter too (`-p start_mission:=true`, as `skydeck grade`'s
        # drone assignment gives it), its default the flag's; read once, when the node starts.
        self.declare_parameter(
            "start_mission",
            self.ai.start_mission,
            ParameterDescriptor(description="start the mission as soon as the node runs (else wait for /ai/start)", read_only=True),
        )
        self.store = store or ProgressStore(self.settings.skydeck_state_dir, warn=self.get_logger().warning)
        self.drone_position: Point | None = None
        self.tracker = WorldTracker()
        self._pose_wall_s = -math.inf
        self._pose_event = asyncio.Event()
        self.status = AiStatus(state="idle", target=-1)
        self.take_off = self.create_client(Trigger, "/control/take_off")
        self.fly = self.create_client(FlyCommand, "/control/fly")
        self.land = self.create_client(Trigger, "/control/land")
        self.status_publisher = self.create_publisher(AiStatus, "/ai/status", 10, latched=True)
        self.create_subscription(PoseStamped, "/drone/pose", self.on_pose, 1)
        self.create_subscription(Polygon, "/perception/boxes", self.tracker.on_boxes, 1)
        self.create_subscription(SimWorld, "/simulator/world", self.on_world, 1)
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

    def on_world(self, msg: SimWorld) -> None:
        if self.tracker.on_world(msg) and self._mission is not None:
            self.get_logger().info("the simulator built a new world (%s): a new tour", msg.id)
            self._start_mission()
        elif self._mission is None and _under_way(self.store.load(msg.id)):
            # An AI restarted in the middle of a mission carries on without being asked again.
            self._start_mission()

    def on_control_state(self, msg: ControlState) -> None:
        self.control_state = msg

    async def handle_start(self, request: TriggerRequest) -> TriggerResponse:
        self._start_mission(again=True)
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
        if self.get_parameter("start_mission").value:
            self._start_mission()  # as the seed's AI: the mission starts once the world is ready
        else:
            self.get_logger().info("waiting for /ai/start (the dashboard's Start mission button)")
            self._update(message="waiting for /ai/start (the dashboard's Start mission button)")

    def _start_mission(self, *, again: bool = False) -> None:
        """(Re)start the mission task. ``again``: asked for by a user, so a world whose mission
        is finished is flown once more; otherwise a finished world stays finished."""
        if self._mission is not None:
            self._mission.cancel()
        self._mission = asyncio.get_running_loop().create_task(self._run_mission(again))

    async def _run_mission(self, again: bool) -> None:
        try:
            await self._mission_steps(again)
        except asyncio.CancelledError:
            raise
        except (ServiceError, MissionError) as error:
            self.get_logger().error("mission failed: %s", error)
            self._update(state="error", message=str(error))

    async def _mission_steps(self, again: bool) -> None:
        self._update(state="idle", target=-1, message="waiting for the world, the drone pose and the boxes (at rest)")
        await self.tracker.ready.wait()
        world, boxes = self.tracker.world, list(self.tracker.boxes)
        if world is None:
            raise RuntimeError("boxes ready without a world")
        progress = self._progress_of(world, boxes, again=again)
        visited = progress.visited
        self._update(visited=list(visited), tour=[], remaining=len(boxes) - len(visited))
        if progress.done:
            self._update(state="done", message=f"world {world.id} is done: {len(visited)} boxes visited")
            return
        position = await self._fresh_position()
        remaining = [i for i in range(len(boxes)) if i not in visited]
        came_from: Point2 = (position.x, position.y)
        landing: LandingPolicy = self.get_parameter("landing").value
        if remaining:
            await self._take_off()
            position = await self._fresh_position()
            legs = finishing_legs(landing, boxes, home=HOME_XY_M)
            tour = plan_tour(
                (position.x, position.y), [boxes[i] for i in remaining], finish=[legs[i] for i in remaining]
            )
            order = [remaining[i] for i in tour.order]
            self._update(state="flying", tour=order, tour_length=tour.length_m, remaining=len(order))
            self.get_logger().info(
                "tour of %d boxes, landing %s: %.1f m (%s)",
                len(order), landing.replace("_", " "), tour.length_m, "optimal" if tour.optimal else "2-opt",
            )
            came_from = (position.x, position.y)
            for index in order:
                target = boxes[index]
                self._update(target=index, message=f"flying to box {index} at ({target[0]:.1f}, {target[1]:.1f})")
                await self._fly_to(target)
                visited.append(index)
                self.store.save(progress)
                left = [i for i in order if i not in visited]
                self._update(visited=list(visited), tour=left, remaining=len(left))
                if left:
                    came_from = target
        await self._land(boxes, visited, came_from, landing)
        progress.done = True
        self.store.save(progress)
        self._update(state="done", target=-1, message=f"visited {len(visited)} boxes")

    def _progress_of(self, world: SimWorld, boxes: list[Point2], *, again: bool) -> WorldProgress:
        """This world's saved progress, or a new one; says which in one log line."""
        saved = self.store.load(world.id)
        if saved is not None and saved.boxes != len(boxes):
            self.get_logger().warning(
                "world %s: saved progress is for %d boxes, perception sees %d: starting afresh",
                world.id, saved.boxes, len(boxes),
            )
            saved = None
        if saved is None or (saved.done and again):
            if saved is None:
                self.get_logger().info("new world %s: %d boxes", world.id, len(boxes))
            else:
                self.get_logger().info("world %s was done: a new tour of its %d boxes, as asked", world.id, len(boxes))
            progress = WorldProgress(world=world.id, boxes=len(boxes))
            self.store.save(progress)
            return progress
        saved.visited = [i for i in dict.fromkeys(saved.visited) if 0 <= i < len(boxes)]
        self.get_logger().info("resuming world %s: %d of %d visited", world.id, len(saved.visited), len(boxes))
        return saved

    async def _take_off(self) -> None:
        """Take off (unless already in the air) and wait until z >= TAKE_OFF_DONE_Z_M. Asks
        again while the drone is on the ground and control still says ``landed`` (it refused
        for want of a pose, or it was restarted)."""
        if (await self._fresh_position()).z >= TAKE_OFF_DONE_Z_M:
            return
        await self.take_off.wait_for_service()
        self._update(state="taking_off", message="taking off")
        sent_s: float | None = None
        while (position := await self._fresh_position()).z < TAKE_OFF_DONE_Z_M:
            if position.z > ON_GROUND_Z_M:
                continue  # climbing
            if sent_s is not None and not self._control_forgot(sent_s, lambda state: state.state != "landed"):
                continue
            response = await self._call(self.take_off, Trigger.Request())
            sent_s = time.monotonic()
            self._check(response.success, response.message, "take-off")

    async def _land(self, boxes: list[Point2], visited: list[int], came_from: Point2, landing: LandingPolicy) -> None:
        """Fly to where the policy lands, land there, and wait for the touchdown."""
        if (await self._fresh_position()).z > ON_GROUND_Z_M:
            spot = HOME_XY_M
            if landing == "beside_last_box" and visited:
                spot = landing_spot(boxes[visited[-1]], boxes, arriving_from=came_from) or HOME_XY_M
            where = "at the start" if spot == HOME_XY_M else "beside the last box"
            self._update(
                state="landing", target=-1, tour=[], message=f"all boxes visited: landing {where} at ({spot[0]:.1f}, {spot[1]:.1f})"
            )
            await self._fly_to(spot, within_m=LANDING_RADIUS_M)
        response = await self._call(self.land, Trigger.Request())
        self._check(response.success, response.message, "land")
        sent_s = time.monotonic()
        while (await self._fresh_position()).z > ON_GROUND_Z_M:
            if self._control_forgot(sent_s, lambda state: state.state in ("landing", "landed")):
                self.get_logger().warning("control is not landing (was it restarted?): asking again")
                await self._call(self.land, Trigger.Request())
                sent_s = time.monotonic()

    async def _fly_to(self, target: Point2, *, within_m: float = VISIT_RADIUS_M) -> None:
        """One fly command, then wait until the drone is within ``within_m`` of the target.

        The command is sent again only if control stops reporting it as its goal (a restarted
        control starts with none): never while control is on its way.
        """
        await self._send_fly(target)
        sent_s = time.monotonic()

        def flying_there(state: ControlState) -> bool:
            return math.hypot(state.setpoint.x - target[0], state.setpoint.y - target[1]) <= 1e-3

        while True:
            position = await self._fresh_position()
            if math.hypot(position.x - target[0], position.y - target[1]) <= within_m:
                return
            if self._control_forgot(sent_s, flying_there):
                self.get_logger().warning("control is not flying to (%.1f, %.1f) (was it restarted?): sending it again", *target)
                await self._send_fly(target)
                sent_s = time.monotonic()

    async def _send_fly(self, target: Point2) -> None:
        while True:
            response = await self._call(self.fly, FlyCommand.Request(x=target[0], y=target[1]))
            if self._check(response.success, response.message, f"fly to ({target[0]:.1f}, {target[1]:.1f})"):
                return
            await asyncio.sleep(_RETRY_S)

    def _check(self, success: bool, message: str, what: str) -> bool:
        """Whether a command's answer lets the mission go on: accepted, or refused because it was
        done already. Raises MissionError for a refusal no retry can change; else (the drone not
        in the air yet, no pose, a reason this AI does not know) logs it and returns False."""
        if success:
            return True
        reason = refusal_reason(message)
        if reason in _NOTHING_TO_DO:
            return True
        if reason in _CANNOT_FLY:
            raise MissionError(f"{what} refused: {message}")
        self.get_logger().warning("%s refused: %s; asking again", what, message)
        return False

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


def _under_way(progress: WorldProgress | None) -> bool:
    """Whether saved progress is of a mission started and not finished."""
    return progress is not None and not progress.done


def _check_landing(parameters: list[Parameter]) -> SetParametersResult:
    for parameter in parameters:
        if parameter.name == "landing" and parameter.value not in LANDING_POLICIES:
            return SetParametersResult(
                successful=False, reason=f"landing must be one of {', '.join(LANDING_POLICIES)}; got {parameter.value!r}"
            )
    return SetParametersResult(successful=True)


def main(argv: list[str] | None = None) -> int:
    """``skydeck run ai [--landing beside_last_box|home] [--start-mission [true|false]]``."""
    parser = argparse.ArgumentParser(prog="skydeck run ai", description="The box-visiting mission.")
    parser.add_argument(
        "--landing",
        help=f"where to land once every box is visited: {' or '.join(LANDING_POLICIES)} (default {DEFAULT_LANDING})",
    )
    parser.add_argument(
        "--start-mission",
        nargs="?",
        const="true",
        metavar="true|false",
        help="start the mission at once (default: wait for /ai/start, the dashboard's Start mission button)",
    )
    spin(AiNode(ai=settings_from_flags(parser, AiSettings, argv)))
    return 0
