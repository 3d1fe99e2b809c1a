"""The robot world's node in-process: a Twist that is not finite, handed over from Python (where
JSON's refusal cannot catch it), is refused with a warning on /rosout and the robot stops."""

from __future__ import annotations

import asyncio
import math

from services.runtime import Node
from shared_models.geometry_msgs import Twist, Vector3
from shared_models.rcl_interfaces import Log
from sim_server.robot.node import RobotSimNode
from sim_server.robot.settings import RobotSettings
from tests.conftest import wait_until


class Listener(Node):
    def __init__(self, settings) -> None:  # type: ignore[no-untyped-def]
        super().__init__("listener", settings=settings)
        self.logs: list[Log] = []
        self.create_subscription(Log, "/rosout", self.logs.append, 100)


async def test_a_non_finite_twist_from_python_is_refused_with_a_warning(start_node) -> None:  # type: ignore[no-untyped-def]
    sim = await start_node(lambda settings: RobotSimNode(RobotSettings(seed=1, speed=1.0), settings))
    listener = await start_node(Listener)
    key = ("/rosout", sim.url)  # the listener reads the simulator's /rosout before anything is said
    await wait_until(lambda: key in listener._participant.links, what="the listener's link to the simulator")
    await asyncio.wait_for(listener._participant.links[key][0].connected.wait(), 5)
    sim.robots[0].on_cmd_vel(Twist(linear=Vector3(x=0.2)))
    await wait_until(lambda: sim.world.robot_velocity(0)[0] > 0.1, timeout_s=10, what="the robot to drive")
    bad = Twist.model_construct(linear=Vector3.model_construct(x=math.nan, y=0.0, z=0.0), angular=Vector3())
    sim.robots[0].on_cmd_vel(bad)
    await wait_until(
        lambda: any("refused cmd_vel: cmd_vel: linear.x=nan" in log.msg for log in listener.logs), what="the warning"
    )
    assert [log.level for log in listener.logs if "refused" in log.msg][0] == Log.WARN
    await wait_until(lambda: sim.world.command(0) == (0.0, 0.0), timeout_s=10, what="the watchdog")
    await wait_until(lambda: abs(sim.world.robot_velocity(0)[0]) < 1e-3, timeout_s=10, what="the robot to stop")
