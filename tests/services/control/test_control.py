"""Control's services: the seed's refusals (each tagged with its reason), and the setpoints they
produce (unit level)."""

from __future__ import annotations

import math

import pytest

from services.control.node import FLIGHT_ALTITUDE_M, ControlNode
from services.runtime import NodeSettings
from shared_models.geometry_msgs import Point, Pose, PoseStamped
from shared_models.ros_workshop import FlyCommand, Refusal, SimWorld, refusal_reason
from shared_models.std_srvs import Trigger


@pytest.fixture
def control() -> ControlNode:
    return ControlNode(NodeSettings(port=0))


def _pose(node: ControlNode, x: float, y: float, z: float) -> None:
    node.on_pose(PoseStamped(pose=Pose(position=Point(x=x, y=y, z=z))))


def test_take_off_needs_a_pose(control) -> None:
    response = control.handle_take_off(Trigger.Request())
    assert not response.success and "simulator" in response.message
    assert refusal_reason(response.message) is Refusal.NO_POSE


def test_take_off_from_the_ground_sets_setpoint_3m_above(control) -> None:
    _pose(control, 1.0, -2.0, 0.05)
    response = control.handle_take_off(Trigger.Request())
    assert response.success and response.message == "All ok!"
    assert (control.setpoint.x, control.setpoint.y, control.setpoint.z) == (1.0, -2.0, FLIGHT_ALTITUDE_M)
    assert control.state == "taking_off"


def test_take_off_in_the_air_is_refused(control) -> None:
    _pose(control, 0.0, 0.0, 2.0)
    response = control.handle_take_off(Trigger.Request())
    assert not response.success and response.message == "[already_airborne] Seems like the drone is already flying!"
    assert refusal_reason(response.message) is Refusal.ALREADY_AIRBORNE


def test_fly_is_refused_before_take_off(control) -> None:
    _pose(control, 0.0, 0.0, 0.0)
    response = control.handle_fly(FlyCommand.Request(x=5.0, y=5.0))
    assert not response.success and "Take off first" in response.message
    assert refusal_reason(response.message) is Refusal.NOT_AIRBORNE


@pytest.fixture
def flying(control) -> ControlNode:
    _pose(control, 0.0, 0.0, 0.0)
    control.handle_take_off(Trigger.Request())
    _pose(control, 0.0, 0.0, 3.0)
    assert control.state == "flying"
    return control


def test_fly_sets_target_at_flight_altitude(flying) -> None:
    response = flying.handle_fly(FlyCommand.Request(x=5.0, y=-3.0))
    assert response.success
    assert (flying.setpoint.x, flying.setpoint.y, flying.setpoint.z) == (5.0, -3.0, FLIGHT_ALTITUDE_M)


def test_fly_to_current_setpoint_is_refused(flying) -> None:
    assert flying.handle_fly(FlyCommand.Request(x=5.0, y=-3.0)).success
    response = flying.handle_fly(FlyCommand.Request(x=5.0, y=-3.0))
    assert not response.success and "Already flying" in response.message
    assert refusal_reason(response.message) is Refusal.SAME_TARGET


@pytest.mark.parametrize("x, y", [(25.0, 0.0), (0.0, -20.5)])
def test_fly_outside_the_arena_is_refused(flying, x, y) -> None:
    response = flying.handle_fly(FlyCommand.Request(x=x, y=y))
    assert not response.success and "outside the arena" in response.message
    assert refusal_reason(response.message) is Refusal.OUTSIDE_ARENA
    assert flying.setpoint.x == 0.0


def test_fly_non_finite_is_refused_by_control_too(flying) -> None:
    # The request type refuses NaN from JSON; a handler called in-process must refuse it as well.
    request = FlyCommand.Request.model_construct(x=math.inf, y=0.0)
    response = flying.handle_fly(request)
    assert not response.success and refusal_reason(response.message) is Refusal.NOT_FINITE


def test_fly_non_finite_is_refused_by_the_request_type() -> None:
    with pytest.raises(ValueError):
        FlyCommand.Request(x=math.nan, y=0.0)


def test_land_then_landed(flying) -> None:
    response = flying.handle_land(Trigger.Request())
    assert response.success and flying.setpoint.z == 0.0 and flying.state == "landing"
    again = flying.handle_land(Trigger.Request())
    assert not again.success and refusal_reason(again.message) is Refusal.ALREADY_LANDING
    _pose(flying, 0.0, 0.0, 0.05)
    assert flying.state == "landed"
    landed = flying.handle_land(Trigger.Request())
    assert not landed.success and refusal_reason(landed.message) is Refusal.ALREADY_LANDED


def test_a_new_world_puts_control_back_on_the_ground(flying) -> None:
    flying.on_world(SimWorld(id="aaaa"))  # the world control found when it started: nothing to do
    assert flying.handle_fly(FlyCommand.Request(x=5.0, y=-3.0)).success
    flying.on_world(SimWorld(id="aaaa"))  # the same build again (latched, re-linked)
    assert flying.state == "flying"
    flying.on_world(SimWorld(id="bbbb"))  # a reset: the drone stands at the start of a new world
    assert flying.state == "landed"
    streamed: list[object] = []
    flying.setpoint_publisher.publish = streamed.append  # type: ignore[method-assign]
    flying.stream_setpoint()
    assert streamed == []  # no stream while landed: the old goal is not sent to the new drone
    _pose(flying, 0.0, 0.0, 0.05)
    assert flying.handle_take_off(Trigger.Request()).success
