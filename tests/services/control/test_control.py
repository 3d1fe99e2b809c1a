"""Control's services: the seed's refusals, and the setpoints they produce (unit level)."""

from __future__ import annotations

import math

import pytest

from services.control.node import FLIGHT_ALTITUDE_M, ControlNode
from services.runtime import NodeSettings
from shared_models.geometry_msgs import Point, Pose, PoseStamped
from shared_models.ros_workshop import FlyCommand
from shared_models.std_srvs import Trigger


@pytest.fixture
def control() -> ControlNode:
    return ControlNode(NodeSettings(port=0))


def _pose(node: ControlNode, x: float, y: float, z: float) -> None:
    node.on_pose(PoseStamped(pose=Pose(position=Point(x=x, y=y, z=z))))


def test_take_off_needs_a_pose(control) -> None:
    response = control.handle_take_off(Trigger.Request())
    assert not response.success and "simulator" in response.message


def test_take_off_from_the_ground_sets_setpoint_3m_above(control) -> None:
    _pose(control, 1.0, -2.0, 0.05)
    response = control.handle_take_off(Trigger.Request())
    assert response.success and response.message == "All ok!"
    assert (control.setpoint.x, control.setpoint.y, control.setpoint.z) == (1.0, -2.0, FLIGHT_ALTITUDE_M)
    assert control.state == "taking_off"


def test_take_off_in_the_air_is_refused(control) -> None:
    _pose(control, 0.0, 0.0, 2.0)
    response = control.handle_take_off(Trigger.Request())
    assert not response.success and response.message == "Seems like the drone is already flying!"


def test_fly_is_refused_before_take_off(control) -> None:
    _pose(control, 0.0, 0.0, 0.0)
    response = control.handle_fly(FlyCommand.Request(x=5.0, y=5.0))
    assert not response.success and "Take off first" in response.message


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


@pytest.mark.parametrize("x, y", [(25.0, 0.0), (0.0, -20.5)])
def test_fly_outside_the_arena_is_refused(flying, x, y) -> None:
    response = flying.handle_fly(FlyCommand.Request(x=x, y=y))
    assert not response.success and "outside the arena" in response.message
    assert flying.setpoint.x == 0.0


def test_fly_non_finite_is_refused_by_the_request_type() -> None:
    with pytest.raises(ValueError):
        FlyCommand.Request(x=math.nan, y=0.0)


def test_land_then_landed(flying) -> None:
    response = flying.handle_land(Trigger.Request())
    assert response.success and flying.setpoint.z == 0.0 and flying.state == "landing"
    _pose(flying, 0.0, 0.0, 0.05)
    assert flying.state == "landed"
    assert not flying.handle_land(Trigger.Request()).success
