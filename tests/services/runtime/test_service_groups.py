"""The kinds of service, in the order `skydeck service list` and `/docs` show them."""

from __future__ import annotations

import httpx

from services.core.core_node import CORE_NODE
from services.launch.control import LAUNCH_NODE
from services.runtime.service_groups import SYSTEM_NODES, ServiceGroup, service_group


def test_commands_then_parameter_services_then_skydeck_s_own() -> None:
    assert service_group("/control/take_off", "/control") is ServiceGroup.COMMAND
    assert service_group("/talker/ping", "/talker") is ServiceGroup.COMMAND
    assert service_group("/control/get_parameters", "/control") is ServiceGroup.PARAMETERS
    assert service_group("/robot1/estop/set_parameters", "/robot1/estop") is ServiceGroup.PARAMETERS
    # another node's parameter-like name is that node's command
    assert service_group("/control/get_parameters", "/ai") is ServiceGroup.COMMAND
    assert service_group("/rosapi/topics", "/rosapi") is ServiceGroup.SYSTEM
    assert service_group("/skydeck_launch/kill_node", LAUNCH_NODE) is ServiceGroup.SYSTEM
    assert service_group("/skydeck_launch/get_parameters", LAUNCH_NODE) is ServiceGroup.SYSTEM
    assert sorted(ServiceGroup) == [ServiceGroup.COMMAND, ServiceGroup.PARAMETERS, ServiceGroup.SYSTEM]


async def test_the_system_nodes_are_the_core_s_the_launch_s_and_rosapi_s(core) -> None:
    assert {CORE_NODE, LAUNCH_NODE} <= SYSTEM_NODES
    async with httpx.AsyncClient() as http:
        graph = (await http.get(core.url + "/api/graph", timeout=5)).json()
    rosapi = {service["node"] for service in graph["services"] if service["name"].startswith("/rosapi/")}
    assert rosapi and rosapi <= SYSTEM_NODES
    republisher = {s["node"] for s in graph["services"] if s["name"].startswith("/tf2_web_republisher/")}
    assert republisher and republisher <= SYSTEM_NODES
