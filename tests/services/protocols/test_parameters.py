"""Node parameters through both protocols: rosapi's get_param/set_param/get_param_names and
Foxglove's getParameters/setParameters/subscribeParameterUpdates, on top of the node's own
rcl_interfaces services (list/get/set_parameters) and /parameter_events."""

from __future__ import annotations

import json

import pytest
from websockets.asyncio.client import connect

from services.protocols.parameters import (
    ParameterError,
    ParameterValueJson,
    from_value,
    split_name,
    to_value,
)
from shared_models.rcl_interfaces import ParameterType
from tests.services.protocols.conftest import Bridge, Tuned
from tests.services.protocols.test_foxglove import receive
from tests.services.protocols.test_rosbridge import call

pytestmark = pytest.mark.timeout(60)


async def test_rosapi_reads_and_writes_parameters(bridge: Bridge, tuned: Tuned) -> None:
    async with connect(bridge.rosbridge_url) as ws:
        names = (await call(ws, "/rosapi/get_param_names", "n"))["values"]["names"]
        assert {"/tuned:max_speed", "/tuned:mode", "/tuned:retries"} <= set(names)
        got = await call(ws, "/rosapi/get_param", "g", args={"name": "/tuned:max_speed"})
        assert got["values"] == {"value": "2.5", "successful": True, "reason": ""}
        set_int_on_float = await call(ws, "rosapi/set_param", "s", args={"name": "/tuned.max_speed", "value": "3"})
        assert set_int_on_float["values"]["successful"] is True and tuned.values["max_speed"] == 3.0
        refused = await call(ws, "/rosapi/set_param", "r", args={"name": "/tuned:mode", "value": "7"})
        assert refused["values"] == {"successful": False, "reason": "parameter 'mode' is of type string; got integer 7"}
        missing = await call(ws, "/rosapi/get_param", "m", args={"name": "/tuned:nope", "default_value": "0"})
        assert missing["values"]["successful"] is False and missing["values"]["value"] == "0"
        # A name without a node is ROS 1's (the core's parameter server), where it is not set.
        unnamed = await call(ws, "/rosapi/get_param", "u", args={"name": "max_speed"})
        assert unnamed["values"] == {"value": "null", "successful": False, "reason": "/max_speed is not set"}
        not_json = await call(ws, "/rosapi/set_param", "j", args={"name": "/tuned:mode", "value": "{"})
        assert "JSON text" in not_json["values"]["reason"]


async def test_rosapi_ros1_parameters_live_on_the_cores_parameter_server(bridge: Bridge) -> None:
    """As ROS 1's rosapi: unset is JSON ``null`` (or the default, ``default`` as ROS 1 names it),
    a namespace reads as a mapping, delete then has answers false."""
    async with connect(bridge.rosbridge_url) as ws:
        unset = await call(ws, "/rosapi/get_param", "a", args={"name": "/robot/max_speed"})
        assert unset["values"]["value"] == "null" and unset["values"]["successful"] is False
        defaulted = await call(ws, "/rosapi/get_param", "b", args={"name": "/robot/max_speed", "default": "1.5"})
        assert defaulted["values"]["value"] == "1.5"
        plain = await call(ws, "/rosapi/get_param", "c", args={"name": "/robot/mode", "default_value": "fast"})
        assert plain["values"]["value"] == '"fast"'  # plain text is taken as a string, as rosapi does
        stored = await call(ws, "/rosapi/set_param", "d", args={"name": "robot/max_speed", "value": "2.0"})
        assert stored["values"] == {"successful": True, "reason": ""}
        got = await call(ws, "/rosapi/get_param", "e", args={"name": "/robot"})
        assert json.loads(got["values"]["value"]) == {"max_speed": 2.0}
        has = await call(ws, "/rosapi/has_param", "f", args={"name": "/robot/max_speed"})
        assert has["values"] == {"exists": True}
        found = await call(ws, "/rosapi/search_param", "g", args={"name": "robot/max_speed"})
        assert found["values"] == {"global_name": "/robot/max_speed"}
        names = (await call(ws, "/rosapi/get_param_names", "h"))["values"]["names"]
        assert "/robot/max_speed" in names
        deleted = await call(ws, "/rosapi/delete_param", "i", args={"name": "/robot/max_speed"})
        assert deleted["values"] == {"successful": True, "reason": ""}
        gone = await call(ws, "/rosapi/has_param", "j", args={"name": "/robot/max_speed"})
        assert gone["values"] == {"exists": False}
        again = await call(ws, "/rosapi/delete_param", "k", args={"name": "/robot/max_speed"})
        assert again["values"]["successful"] is False and "not set" in again["values"]["reason"]
        node_owned = await call(ws, "/rosapi/delete_param", "l", args={"name": "/tuned:mode"})
        assert "parameter of its node" in node_owned["values"]["reason"]


async def test_foxglove_gets_sets_and_follows_parameters(bridge: Bridge, tuned: Tuned) -> None:
    client = await bridge.client("foxglove_client.mjs", bridge.foxglove_url, "parameters", "foxglove.websocket.v1",
                                 "/tuned.mode", '"manual"')  # fmt: skip
    everything = {p["name"]: p for p in (await client.expect("all"))["all"]}
    assert everything["/tuned.max_speed"] == {"name": "/tuned.max_speed", "value": 2.5, "type": "float64"}
    assert everything["/tuned.retries"] == {"name": "/tuned.retries", "value": 3}
    assert (await client.expect("set"))["set"] == [{"name": "/tuned.mode", "value": "manual"}]
    assert (await client.expect("update"))["update"] == [{"name": "/tuned.mode", "value": "manual"}]
    assert (await client.expect("statuses"))["statuses"] == []
    await client.finish()
    assert tuned.values["mode"] == "manual"


async def test_foxglove_set_refused_gets_a_status(bridge: Bridge, tuned: Tuned) -> None:
    async with connect(bridge.foxglove_url, subprotocols=["foxglove.websocket.v1"]) as ws:  # type: ignore[list-item]
        await ws.send(json.dumps({"op": "setParameters", "parameters": [{"name": "/tuned.mode", "value": 1}], "id": "x"}))
        message = await receive(ws, "status")  # binary time frames (the drone's /clock) are skipped
        assert message["level"] == 2 and "/tuned.mode was not set: parameter 'mode' is of type string; got integer 1" in message["message"]
        message = await receive(ws, "parameterValues")
        assert message == {"op": "parameterValues", "parameters": [{"name": "/tuned.mode", "value": "auto"}], "id": "x"}


def test_values_convert_both_ways() -> None:
    assert split_name("/control.max_speed") == split_name("/control:max_speed") == ("/control", "max_speed")
    assert split_name("/ns/node.a.b") == ("/ns/node", "a.b")
    for bad in ("max_speed", "/.x", "/node."):
        with pytest.raises(ParameterError):
            split_name(bad)
    assert to_value(3).type == ParameterType.PARAMETER_INTEGER
    assert to_value(3, "float64").double_value == 3.0
    assert to_value(3, None, ParameterType.PARAMETER_DOUBLE).type == ParameterType.PARAMETER_DOUBLE
    assert to_value([1, 2.5]).double_array_value == [1.0, 2.5]
    assert to_value([True, False]).type == ParameterType.PARAMETER_BOOL_ARRAY
    assert to_value("QUJD", "byte_array").byte_array_value == b"ABC"
    assert to_value([], None, ParameterType.PARAMETER_INTEGER_ARRAY).type == ParameterType.PARAMETER_INTEGER_ARRAY
    assert to_value(None).type == ParameterType.PARAMETER_NOT_SET
    for bad in ({"a": 1}, [1, "a"], object()):
        with pytest.raises(ParameterError):
            to_value(bad)
    assert from_value(to_value(2.0)) == (2.0, "float64")
    assert from_value(to_value(b"ABC" and "QUJD", "byte_array")) == ("QUJD", "byte_array")
    assert ParameterValueJson("/n.p", 1).type is None
