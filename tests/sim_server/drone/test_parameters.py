"""The simulator's seed, boxes and speed are read-only parameters: what the world was built with
(a drawn seed included), set by the flags or by ``--ros-args -p``."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from services.runtime import NodeSettings, Parameter
from services.runtime.parameters import InvalidParameterValueException
from services.runtime.ros_args import RosArguments, parse_ros_args, set_process_ros_arguments
from sim_server.drone.node import DroneSimNode
from sim_server.drone.settings import DroneSettings


@pytest.fixture
def ros_args() -> Iterator[None]:
    yield
    set_process_ros_arguments(RosArguments())


def _sim(sim: DroneSettings) -> DroneSimNode:
    node = DroneSimNode(sim, NodeSettings(port=0))
    node.world.close()
    return node


def test_the_world_options_are_read_only_parameters(ros_args) -> None:
    sim = _sim(DroneSettings(seed=3, boxes=2, speed=None))
    assert [sim.get_parameter(n).value for n in ("seed", "boxes", "speed")] == [3, 2, "max"]
    [result] = sim.set_parameters([Parameter("seed", value=4)])
    assert not result.successful and "read-only" in result.reason
    drawn = _sim(DroneSettings())
    assert drawn.get_parameter("seed").value == drawn.world.seed and drawn.get_parameter("speed").value == 1.0


def test_an_override_builds_the_world(ros_args) -> None:
    set_process_ros_arguments(parse_ros_args(["-p", "seed:=5", "-p", "boxes:=3", "-p", "speed:=2"]))
    sim = _sim(DroneSettings(seed=1))
    assert sim.world.seed == 5 and sim.sim.boxes == 3 and sim.sim.speed == 2.0
    set_process_ros_arguments(parse_ros_args(["-p", "speed:=fast"]))
    with pytest.raises(InvalidParameterValueException, match="'speed'"):
        _sim(DroneSettings())
    set_process_ros_arguments(parse_ros_args(["-p", "boxes:=99"]))
    with pytest.raises(InvalidParameterValueException, match="outside its range"):
        _sim(DroneSettings())
