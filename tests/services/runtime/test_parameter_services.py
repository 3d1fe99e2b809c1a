"""Every node's parameter services (ROS 2's names and types) on real sockets: on the node and
through the core's gateway; ``/parameter_events`` seen by another node; ``use_sim_time`` at run
time; the parameter services on the core's ``/docs``."""

from __future__ import annotations

import asyncio
import base64

import httpx
import pytest

from services.runtime import Node, Parameter
from shared_models.builtin_interfaces import Time
from shared_models.rcl_interfaces import (
    FloatingPointRange,
    ParameterDescriptor,
    ParameterEvent,
    ParameterType,
    SetParametersResult,
)
from tests.conftest import wait_until


class Tuned(Node):
    def __init__(self, settings) -> None:
        super().__init__("tuned", settings=settings)
        speed_range = FloatingPointRange(from_value=0.0, to_value=2.0)
        self.declare_parameter("speed", 0.3, ParameterDescriptor(description="m/s", floating_point_range=[speed_range]))
        self.declare_parameter("robot", "robot1")
        self.declare_parameter("frozen", 7, ParameterDescriptor(read_only=True))
        self.add_on_set_parameters_callback(self.check)
        self.seen: list[list[str]] = []

    def check(self, parameters: list[Parameter]) -> SetParametersResult:
        self.seen.append([p.name for p in parameters])
        for parameter in parameters:
            if parameter.name == "robot" and parameter.value == "evil":
                return SetParametersResult(successful=False, reason="no evil robots here")
            if parameter.name == "robot" and parameter.value == "crash":
                raise RuntimeError("the user's callback broke")
        return SetParametersResult(successful=True)


class EventListener(Node):
    def __init__(self, settings) -> None:
        super().__init__("event_listener", settings=settings)
        self.events: list[ParameterEvent] = []
        self.create_subscription(ParameterEvent, "/parameter_events", self.events.append, 100)


def _double(name: str, value: float) -> dict[str, object]:
    return {"name": name, "value": {"type": ParameterType.PARAMETER_DOUBLE, "double_value": value}}


def _string(name: str, value: str) -> dict[str, object]:
    return {"name": name, "value": {"type": ParameterType.PARAMETER_STRING, "string_value": value}}


@pytest.mark.parametrize("via_core", [False, True])
async def test_list_get_describe_and_types(core, start_node, via_core) -> None:
    node = await start_node(Tuned)
    base = core.url if via_core else node.url
    async with httpx.AsyncClient(base_url=base, timeout=10) as http:
        listed = (await http.post("/tuned/list_parameters", json={})).json()
        assert listed["result"]["names"] == ["frozen", "robot", "speed", "use_sim_time"]
        values = (await http.post("/tuned/get_parameters", json={"names": ["speed", "robot", "nope"]})).json()["values"]
        assert [v["type"] for v in values] == [3, 4, 0]
        assert values[0]["double_value"] == 0.3 and values[1]["string_value"] == "robot1"
        types = (await http.post("/tuned/get_parameter_types", json={"names": ["frozen", "use_sim_time"]})).json()
        assert base64.b64decode(types["types"]) == bytes([ParameterType.PARAMETER_INTEGER, ParameterType.PARAMETER_BOOL])
        described = (await http.post("/tuned/describe_parameters", json={"names": ["speed", "frozen"]})).json()
        speed, frozen = described["descriptors"]
        assert speed["description"] == "m/s" and speed["floating_point_range"][0]["to_value"] == 2.0
        assert frozen["read_only"] is True and frozen["type"] == ParameterType.PARAMETER_INTEGER


@pytest.mark.parametrize("via_core", [False, True])
async def test_set_accepts_and_refuses_with_the_reason(core, start_node, via_core) -> None:
    node = await start_node(Tuned)
    base = core.url if via_core else node.url
    async with httpx.AsyncClient(base_url=base, timeout=10) as http:
        reply = await http.post(
            "/tuned/set_parameters",
            json={"parameters": [_double("speed", 1.5), _string("robot", "evil"), _double("frozen", 1), _double("speed", 9)]},
        )
        assert reply.status_code == 200
        results = reply.json()["results"]
        assert results[0] == {"successful": True, "reason": ""}
        assert results[1] == {"successful": False, "reason": "no evil robots here"}
        assert not results[2]["successful"] and "read-only" in results[2]["reason"]
        assert not results[3]["successful"] and "outside its range" in results[3]["reason"]
        assert node.get_parameter("speed").value == 1.5 and node.get_parameter("robot").value == "robot1"
        atomic = (
            await http.post("/tuned/set_parameters_atomically", json={"parameters": [_double("speed", 0.5), _string("robot", "evil")]})
        ).json()["result"]
        assert atomic == {"successful": False, "reason": "no evil robots here"}
        assert node.get_parameter("speed").value == 1.5  # all or nothing
        undeclared = (await http.post("/tuned/set_parameters", json={"parameters": [_double("ghost", 1)]})).json()
        assert not undeclared["results"][0]["successful"] and "'ghost'" in undeclared["results"][0]["reason"]
        bad_type = (await http.post("/tuned/set_parameters", json={"parameters": [{"name": "speed", "value": {"type": 42}}]})).json()
        assert "not a ParameterType" in bad_type["results"][0]["reason"]
        assert (await http.post("/tuned/set_parameters", json={"parameters": "speed"})).status_code == 422


async def test_a_callback_that_raises_refuses_the_change_and_the_node_keeps_serving(core, start_node, caplog) -> None:
    node = await start_node(Tuned)
    async with httpx.AsyncClient(base_url=core.url, timeout=10) as http:
        result = (await http.post("/tuned/set_parameters", json={"parameters": [_string("robot", "crash")]})).json()
        assert result["results"][0] == {
            "successful": False, "reason": "the node's on-set callback raised RuntimeError: the user's callback broke"
        }
        assert "the user's callback broke" in caplog.text and "test_parameter_services.py" in caplog.text
        again = (await http.post("/tuned/set_parameters", json={"parameters": [_string("robot", "r2")]})).json()
        assert again["results"][0]["successful"] and node.get_parameter("robot").value == "r2"


async def test_parameter_events_reach_a_subscriber(core, start_node) -> None:
    node = await start_node(Tuned)
    listener = await start_node(EventListener)
    await wait_until(lambda: ("/parameter_events", node.url) in listener._participant.links, what="a link to /tuned")
    link, _ = listener._participant.links[("/parameter_events", node.url)]
    await asyncio.wait_for(link.connected.wait(), 5)
    assert node.set_parameters([Parameter("speed", value=0.9)])[0].successful
    node.declare_parameter("late", "x")
    node.undeclare_parameter("late")
    await wait_until(lambda: len([e for e in listener.events if e.node == "/tuned"]) >= 3, what="three events")
    changed, declared, deleted = [e for e in listener.events if e.node == "/tuned"][:3]
    assert changed.changed_parameters[0].name == "speed" and changed.changed_parameters[0].value.double_value == 0.9
    assert declared.new_parameters[0].name == "late" and deleted.deleted_parameters[0].name == "late"
    assert changed.stamp.sec > 0


async def test_use_sim_time_is_a_parameter_the_clock_follows(core, start_node) -> None:
    node = await start_node(Tuned)
    assert node.get_parameter("use_sim_time").value is False and node.get_clock().now().nanoseconds > 10**18
    async with httpx.AsyncClient(base_url=core.url, timeout=10) as http:
        reply = await http.post(
            "/tuned/set_parameters",
            json={"parameters": [{"name": "use_sim_time", "value": {"type": 1, "bool_value": True}}]},
        )
        assert reply.json()["results"][0]["successful"]
    assert node.get_clock().use_sim_time
    async with httpx.AsyncClient(timeout=10) as http:

        async def clock_subscribers() -> list[str]:
            topics = (await http.get(core.url + "/api/graph")).json()["topics"]
            return next((t["subscribers"] for t in topics if t["name"] == "/clock"), [])

        async with asyncio.timeout(5):
            while "/tuned" not in await clock_subscribers():
                await asyncio.sleep(0.02)
    node._clock.set_sim_time(Time(sec=42))
    assert node.get_clock().now().nanoseconds == 42 * 10**9


async def test_the_parameter_services_have_their_own_section_on_docs(core, start_node) -> None:
    await start_node(Tuned)
    async with httpx.AsyncClient(timeout=10) as http:
        schema = (await http.get(core.url + "/openapi.json")).json()
    operation = schema["paths"]["/tuned/set_parameters"]["post"]
    assert operation["tags"] == ["node /tuned parameters"]
    assert operation["summary"] == "/tuned/set_parameters (rcl_interfaces/srv/SetParameters)"
    assert "SetParametersRequest" in str(operation["requestBody"])
    tags = [schema["paths"][path]["post"]["tags"][0] for path in schema["paths"] if path.startswith("/tuned/")]
    assert set(tags) == {"node /tuned parameters"} and len(tags) == 6
