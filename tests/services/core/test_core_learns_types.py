"""A node's own types (its workspace's msg files) reach the core with its registration: the core
builds them, hands them on at /api/interfaces, and refuses a node whose version of a type
differs from the one it holds, or cannot be read, in one line."""

from __future__ import annotations

import asyncio
import itertools
import json

import httpx
import pytest
from websockets.asyncio.client import connect
from websockets.exceptions import ConnectionClosed

from services.runtime import Node
from services.runtime.edge.links import stream_url
from services.runtime.protocol import NodeDescription, RegisterFrame
from shared_models import get_interface
from shared_models.definitions.loader import learn_definitions

_packages = itertools.count()


def package() -> str:
    return f"core_learns{next(_packages)}"


def register(name: str, interfaces: dict[str, str], topic_type: str) -> str:
    node = NodeDescription(
        name=name,
        url="http://127.0.0.1:9",
        pid=1,
        publications=[{"name": f"{name}/out", "type": topic_type}],  # type: ignore[list-item]
        interfaces=interfaces,
    )
    return RegisterFrame(node=node).model_dump_json()


async def session_reply(core_url: str, frame: str) -> tuple[dict, int | None, str]:
    """The core's first frame, and the close code and reason if it closes."""
    async with connect(stream_url(core_url, "/api/session")) as websocket:
        await websocket.send(frame)
        reply = json.loads(await asyncio.wait_for(websocket.recv(), 5))
        try:
            await asyncio.wait_for(websocket.recv(), 1)
        except ConnectionClosed as closed:
            return reply, closed.rcvd.code if closed.rcvd else None, closed.rcvd.reason if closed.rcvd else ""
        except TimeoutError:
            pass
        return reply, None, ""


async def test_the_core_learns_a_nodes_types_and_hands_them_on(core) -> None:  # type: ignore[no-untyped-def]
    pkg = package()
    texts = {f"{pkg}/msg/Reading": "# one reading\nInner inner\nfloat64 value 1.5\n", f"{pkg}/msg/Inner": "int8 x\n"}
    reply, code, _ = await session_reply(core.url, register("/sensor", texts, f"{pkg}/msg/Reading"))
    assert reply["op"] == "registered" and code is None
    async with httpx.AsyncClient() as http:
        described = (await http.get(f"{core.url}/api/interfaces/{pkg}/msg/Reading")).json()
    assert described["definitions"] == texts
    assert described["default"] == {"inner": {"x": 0}, "value": 1.5}
    assert described["text"] == "# one reading\n\nInner inner\n\tint8 x\nfloat64 value 1.5"


async def test_another_version_of_a_type_is_refused_in_one_line(core) -> None:  # type: ignore[no-untyped-def]
    pkg = package()
    first, _, _ = await session_reply(core.url, register("/first", {f"{pkg}/msg/Status": "int32 level\n"}, f"{pkg}/msg/Status"))
    assert first["op"] == "registered"
    reply, code, reason = await session_reply(core.url, register("/second", {f"{pkg}/msg/Status": "int64 level\n"}, f"{pkg}/msg/Status"))
    assert reply["op"] == "rejected" and code == 1008
    assert reply["reason"].startswith(f"{pkg}/msg/Status (from node /second) differs from the definition")
    assert "restart the core" in reply["reason"] and "\n" not in reply["reason"]
    assert reason and "/second" not in core.registry.nodes


async def test_an_unreadable_definition_is_refused_naming_its_line(core) -> None:  # type: ignore[no-untyped-def]
    pkg = package()
    reply, code, _ = await session_reply(core.url, register("/broken", {f"{pkg}/msg/Bad": "int32 a\nflaot64 b\n"}, f"{pkg}/msg/Bad"))
    assert reply["op"] == "rejected" and code == 1008
    assert reply["reason"].startswith(f"{pkg}/msg/Bad (from node /broken):2: unknown type 'flaot64'")


async def test_a_node_using_such_a_type_sends_its_definitions(core, start_node) -> None:  # type: ignore[no-untyped-def]
    pkg = package()
    learn_definitions({f"{pkg}/msg/Count": "int64 n\n", f"{pkg}/srv/Reset": "---\nbool done\n"})
    count, reset = get_interface(f"{pkg}/msg/Count"), get_interface(f"{pkg}/srv/Reset")

    class Counter(Node):
        def __init__(self, settings) -> None:  # type: ignore[no-untyped-def]
            super().__init__("counter", settings=settings)
            self.create_publisher(count, "/count", 10)
            self.create_service(reset, "/reset", lambda request: reset.Response(done=True))

    node = await start_node(Counter)
    assert node.describe().interfaces == {f"{pkg}/msg/Count": "int64 n\n", f"{pkg}/srv/Reset": "---\nbool done\n"}
    async with httpx.AsyncClient() as http:
        graph = (await http.get(core.url + "/api/graph")).json()
    assert {"name": "/count", "type": f"{pkg}/msg/Count"}.items() <= next(t for t in graph["topics"] if t["name"] == "/count").items()


@pytest.mark.parametrize("shipped", ["geometry_msgs/msg/PoseStamped", "example_interfaces/action/Fibonacci"])
def test_shipped_types_are_never_sent(shipped: str) -> None:
    from shared_models.definitions.loader import definitions_of

    assert definitions_of([get_interface(shipped)]) == {}


def test_rosapi_and_foxglove_describe_a_learned_type_as_a_shipped_one() -> None:
    from services.protocols.rosbridge.rosapi import typedefs
    from shared_models.json_schema import json_schema_text

    pkg = package()
    learn_definitions({f"{pkg}/msg/Pose2": "# a pose\ngeometry_msgs/Point position\nuint8[] tag\nint32 MODE=1\n"})
    cls = get_interface(f"{pkg}/msg/Pose2")
    defs = {d.type: d for d in typedefs(cls)}
    ours = defs[f"{pkg}/msg/Pose2"]
    assert ours.fieldnames == ["position", "tag"] and "geometry_msgs/msg/Point" in defs
    assert ours.fieldtypes == ["geometry_msgs/msg/Point", "uint8"] and ours.fieldarraylen == [-1, 0]
    assert (ours.constnames, ours.constvalues) == (["MODE"], ["1"])
    schema = json.loads(json_schema_text(cls))  # a Foxglove channel's, and a recording's
    assert schema["properties"]["position"]["properties"]["x"]["type"] == "number"
    assert schema["properties"]["tag"]["contentEncoding"] == "base64"
