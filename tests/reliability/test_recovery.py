"""The pieces that let a mission survive a restarted neighbour, at unit level: timers on sim time
survive a simulator restart (its clock starts again at zero), a restarted control takes over a
drone that is in the air and reports a stale pose, and the AI plans only on boxes at rest,
re-plans for a new world on /ai/start, re-sends a goal that a restarted control forgot, and waits
for a service nobody can locate while the core restarts.
"""

from __future__ import annotations

import asyncio
import logging
import time

import pytest

from services.ai.node import CONTROL_FORGOT_S, AiNode
from services.ai.progress import ProgressStore
from services.control.node import FLIGHT_ALTITUDE_M, ControlNode
from services.runtime import NodeSettings, ServiceTimeoutError, ServiceUnavailableError
from services.runtime.clock import Clock
from services.runtime.timer import Timer
from shared_models.builtin_interfaces import Time
from shared_models.geometry_msgs import Point, Point32, Polygon, Pose, PoseStamped
from shared_models.ros_workshop import ControlState, FlyCommand, SimWorld
from shared_models.std_srvs import Trigger
from tests.conftest import wait_until


def _pose(x: float, y: float, z: float) -> PoseStamped:
    return PoseStamped(pose=Pose(position=Point(x=x, y=y, z=z)))


async def test_sim_time_timer_keeps_ticking_after_the_clock_jumps_back() -> None:
    clock = Clock(use_sim_time=True)
    ticks: list[float] = []
    timer = Timer(0.1, lambda: ticks.append(clock.now_s()), clock)
    task = asyncio.create_task(timer.run(logging.getLogger("test")))
    async def at(seconds: float) -> None:
        clock.set_sim_time(Time.from_seconds(seconds))
        for _ in range(10):  # let the timer task see it
            await asyncio.sleep(0)

    try:
        for step in range(1, 201):  # a simulator that ran 100 s...
            await at(step * 0.5)
        before = len(ticks)
        assert before > 150
        for step in range(20):  # ...was restarted: its clock begins again at zero
            await at(step * 0.1)
        assert clock.jumps_back == 1
        assert len(ticks) - before >= 15, "the timer waited for the old sim time to come back"
    finally:
        task.cancel()


def test_restarted_control_takes_over_a_drone_in_the_air() -> None:
    control = ControlNode(NodeSettings(port=0))
    control.on_pose(_pose(4.0, -2.0, 2.7))  # its first pose: hovering (the simulator's failsafe)
    assert control.state == "flying"
    assert (control.setpoint.x, control.setpoint.y, control.setpoint.z) == (4.0, -2.0, FLIGHT_ALTITUDE_M)
    assert control.handle_fly(FlyCommand.Request(x=5.0, y=5.0)).success
    on_ground = ControlNode(NodeSettings(port=0))
    on_ground.on_pose(_pose(0.0, 0.0, 0.05))
    assert on_ground.state == "landed"
    assert on_ground.handle_take_off(Trigger.Request()).success


def test_control_reports_a_stale_pose_on_its_state_and_rosout(caplog) -> None:
    control = ControlNode(NodeSettings(port=0))
    published: list[ControlState] = []
    control.state_publisher.publish = published.append  # type: ignore[method-assign]
    control.on_pose(_pose(0.0, 0.0, 0.05))
    control.publish_state()
    assert published[-1].message == ""
    control._pose_wall_s = time.monotonic() - 5  # the simulator went quiet five seconds ago
    with caplog.at_level(logging.WARNING):
        control.publish_state()  # the wall-clock state timer, which runs even with no /clock
    assert "no drone pose" in published[-1].message
    assert "no drone pose" in caplog.text
    control.on_pose(_pose(0.0, 0.0, 0.05))
    assert published[-1].message == ""


def _boxes(*xy: tuple[float, float], z: float = 1.0) -> Polygon:
    return Polygon(points=[Point32(x=x, y=y, z=z) for x, y in xy])


async def test_ai_plans_on_boxes_at_rest_and_on_the_new_world_after_a_reset(tmp_path) -> None:
    ai = AiNode(NodeSettings(port=0), store=ProgressStore(tmp_path))
    ai.on_world(SimWorld(id="old"))
    old = ((5.0, 5.0), (-6.0, 7.0))
    for _ in range(3):
        ai.tracker.on_boxes(_boxes(*old))
    assert ai.tracker.ready.is_set() and ai.tracker.boxes == list(old)
    await ai.handle_start(Trigger.Request())
    first = ai._mission
    try:
        # A reset builds a new world; its id comes before the new boxes have even been received.
        ai.on_world(SimWorld(id="new", build=1))
        assert ai._mission is not first and first is not None and first.cancelling()  # a new tour
        for _ in range(3):
            ai.tracker.on_boxes(_boxes(*old))  # old messages still in flight through perception
        assert not ai.tracker.ready.is_set()
        ai.tracker.on_boxes(_boxes((9.0, -9.0), (-3.0, -8.0), z=6.0))  # the new boxes, falling
        ai.tracker.on_boxes(_boxes((9.0, -9.0), (-3.0, -8.0), z=4.0))
        assert not ai.tracker.ready.is_set()
        new = ((9.1, -9.0), (-3.0, -8.2))
        for _ in range(3):
            ai.tracker.on_boxes(_boxes(*new))  # at rest
        assert ai.tracker.ready.is_set() and ai.tracker.boxes == list(new)
        # The new mission took the new world (and now waits for a drone pose).
        await wait_until(lambda: "waiting for the drone pose" in ai.status.message, what="the mission to wait for a pose")
        saved = ai.store.load("new")
        assert saved is not None and saved.boxes == 2 and saved.visited == []
    finally:
        ai._mission.cancel()  # type: ignore[union-attr]


def test_ai_notices_when_control_forgot_its_goal(tmp_path) -> None:
    ai = AiNode(NodeSettings(port=0), store=ProgressStore(tmp_path))
    target = (3.0, 4.0)

    def there(state: ControlState) -> bool:
        return (state.setpoint.x, state.setpoint.y) == target

    long_ago = time.monotonic() - CONTROL_FORGOT_S - 0.1
    ai.on_control_state(ControlState(state="flying", setpoint=Point(x=3.0, y=4.0, z=3.0)))
    assert not ai._control_forgot(long_ago, there)  # on its way: never re-sent
    ai.on_control_state(ControlState(state="flying", setpoint=Point(x=-1.0, y=2.0, z=3.0)))  # restarted
    assert ai._control_forgot(long_ago, there)
    assert not ai._control_forgot(time.monotonic(), there)  # just sent: control's state may lag


async def test_ai_waits_for_a_service_nobody_can_locate_and_calls_again(tmp_path) -> None:
    """The core is restarting (or control has not registered again) when the AI first needs
    /control/land: the mission says it waits, and lands once the service can be located."""
    ai = AiNode(NodeSettings(port=0), store=ProgressStore(tmp_path))
    ai._update(message="returning to the start")
    located = asyncio.Event()
    calls: list[Trigger.Request] = []

    async def call(request: Trigger.Request, *, timeout_s: float | None = None) -> Trigger.Response:
        calls.append(request)
        if not located.is_set():
            raise ServiceUnavailableError("/control/land", "cannot ask the core where /control/land is")
        return Trigger.Response(success=True, message="Landing.")

    async def wait_for_service(timeout_s: float | None = None) -> bool:
        await located.wait()
        return True

    ai.land.call = call  # type: ignore[method-assign]
    ai.land.wait_for_service = wait_for_service  # type: ignore[method-assign]
    landing = asyncio.create_task(ai._call(ai.land, Trigger.Request()))
    try:
        await wait_until(lambda: "waiting for /control/land" in ai.status.message, what="the AI to say it waits")
        assert not landing.done() and len(calls) == 1
        located.set()  # the core is back and control registered again
        async with asyncio.timeout(10):
            response = await landing
    finally:
        landing.cancel()
    assert response.success and len(calls) == 2
    assert ai.status.message == "returning to the start"


async def test_ai_still_fails_on_a_service_that_does_not_answer(tmp_path) -> None:
    """Only a service nobody can locate is waited for: a hung control still ends the mission."""
    ai = AiNode(NodeSettings(port=0), store=ProgressStore(tmp_path))

    async def call(request: Trigger.Request, *, timeout_s: float | None = None) -> Trigger.Response:
        raise ServiceTimeoutError("/control/land", "/control/land did not answer within 5 s")

    ai.land.call = call  # type: ignore[method-assign]
    with pytest.raises(ServiceTimeoutError):
        async with asyncio.timeout(10):
            await ai._call(ai.land, Trigger.Request())
