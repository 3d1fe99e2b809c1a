"""The core's HTTP connections (services.core.gateway_protocol): plain service calls answered
below ASGI, everything else handed to uvicorn with every byte, on real sockets."""

from __future__ import annotations

import asyncio
import datetime
import email.utils
import json

import httptools
import pytest
import uvicorn
from uvicorn.protocols.http.httptools_impl import HttpToolsProtocol

from services.core.gateway_protocol import GatewayHttpProtocol
from services.runtime import Node, NodeSettings
from shared_models.std_srvs import Trigger, TriggerResponse
from tests.conftest import CoreProcess, held_socket, serve_on, wait_until

pytestmark = pytest.mark.timeout(60)


class Counter(Node):
    def __init__(self, settings) -> None:
        super().__init__("counter", settings=settings)
        self.calls = 0
        self.create_service(Trigger, "/counter/count", self.count)

    def count(self, request):
        self.calls += 1
        return TriggerResponse(success=True, message=str(self.calls))


class Reply:
    def __init__(self) -> None:
        self.status = 0
        self.headers: dict[str, str] = {}
        self.body = b""
        self.done = False


async def read_replies(reader: asyncio.StreamReader, count: int) -> list[Reply]:
    """``count`` HTTP replies parsed from ``reader`` (as a client would, with httptools)."""
    replies: list[Reply] = []

    class Callbacks:
        def on_message_begin(self) -> None:
            replies.append(Reply())

        def on_header(self, name: bytes, value: bytes) -> None:
            replies[-1].headers[name.decode().lower()] = value.decode()

        def on_body(self, body: bytes) -> None:
            replies[-1].body += body

        def on_message_complete(self) -> None:
            replies[-1].done = True

    parser = httptools.HttpResponseParser(Callbacks())
    while not (len(replies) == count and replies[-1].done):
        data = await asyncio.wait_for(reader.read(65536), 10)
        assert data, f"the core closed the connection after {len(replies)} of {count} replies"
        before = len(replies)
        parser.feed_data(data)
        for reply in replies[before:]:
            reply.status = parser.get_status_code()
    return replies


def post(path: str, body: bytes = b"{}", **headers: str) -> bytes:
    lines = [f"POST {path} HTTP/1.1", "Host: 127.0.0.1", "Content-Type: application/json", f"Content-Length: {len(body)}"]
    lines += [f"{name.replace('_', '-')}: {value}" for name, value in headers.items()]
    return ("\r\n".join(lines) + "\r\n\r\n").encode() + body


def protocols(core: CoreProcess) -> list[type]:
    """The protocols of the core's HTTP connections (the nodes' session WebSockets left out)."""
    connections = core._server.server_state.connections  # type: ignore[union-attr]
    return [type(c) for c in connections if "websockets" not in type(c).__module__]


async def test_calls_are_answered_in_order_on_one_connection_and_pipelined(core, start_node) -> None:
    counter = await start_node(Counter)
    reader, writer = await asyncio.open_connection("127.0.0.1", core.port)
    writer.write(post("/counter/count"))
    [first] = await read_replies(reader, 1)
    assert first.status == 200 and json.loads(first.body) == {"success": True, "message": "1"}
    assert first.headers["content-type"] == "application/json"
    assert protocols(core) == [GatewayHttpProtocol]  # answered here, not by uvicorn's protocol
    writer.write(post("/counter/count") + post("/counter/count") + post("/counter/count"))  # one write
    replies = await read_replies(reader, 3)
    assert [json.loads(reply.body)["message"] for reply in replies] == ["2", "3", "4"]
    assert counter.calls == 4
    writer.close()


async def test_a_call_answered_here_carries_uvicorns_date_and_server_headers(core, start_node) -> None:
    """As uvicorn's own replies do (the protocol keeps them as bytes until uvicorn replaces them)."""
    await start_node(Counter)
    reader, writer = await asyncio.open_connection("127.0.0.1", core.port)
    writer.write(post("/counter/count"))
    [reply] = await read_replies(reader, 1)
    assert protocols(core) == [GatewayHttpProtocol]
    assert reply.headers["server"] == "uvicorn"
    sent = email.utils.parsedate_to_datetime(reply.headers["date"])
    assert abs((datetime.datetime.now(datetime.UTC) - sent).total_seconds()) < 5  # uvicorn's, once a second
    writer.close()


async def test_any_other_request_hands_the_connection_to_uvicorn_with_its_bytes(core, start_node) -> None:
    await start_node(Counter)
    reader, writer = await asyncio.open_connection("127.0.0.1", core.port)
    writer.write(post("/counter/count"))
    await read_replies(reader, 1)
    request = b"GET /health HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n"
    writer.write(request[:10])  # a request split over writes: no byte may be lost in the hand-off
    await asyncio.sleep(0.05)
    writer.write(request[10:])
    [health] = await read_replies(reader, 1)
    assert health.status == 200 and json.loads(health.body)["status"] == "ok"
    assert protocols(core) == [HttpToolsProtocol]
    writer.write(post("/counter/count"))  # and later calls on that connection are uvicorn's
    [call] = await read_replies(reader, 1)
    assert json.loads(call.body)["message"] == "2"
    writer.close()


async def test_edge_checks_and_errors_answer_as_before() -> None:
    core = CoreProcess(token="s3cret", max_message_bytes=4096)
    await core.start()
    try:
        node = await start_node_on(core, {"token": "s3cret"})
        reader, writer = await asyncio.open_connection("127.0.0.1", core.port)
        cases = [
            (post("/counter/count"), 401),  # no token: refused by the core
            (post("/counter/count", Authorization="Bearer s3cret"), 200),
            (post("/counter/count?token=s3cret"), 200),  # the query's token: uvicorn's path
            (post("/counter/count", Authorization="Bearer s3cret", Origin="http://evil.example"), 403),
            (post("/nobody/here", Authorization="Bearer s3cret"), 404),
            (post("/counter/count", b" " * 5000, Authorization="Bearer s3cret"), 413),
        ]
        statuses = []
        for request, _ in cases:
            writer.write(request)
            [reply] = await read_replies(reader, 1)
            statuses.append(reply.status)
            assert "detail" in json.loads(reply.body) or reply.status == 200
        assert statuses == [expected for _, expected in cases]
        writer.close()
        await node.stop()
        await wait_until(lambda: "/counter" not in core.registry.nodes, what="the node to leave")
    finally:
        await core.stop()


async def start_node_on(core: CoreProcess, extra: dict[str, str]) -> Counter:
    node = Counter(NodeSettings(core_url=core.url, port=0, **extra))
    await node.start()
    await wait_until(lambda: "/counter" in core.registry.nodes, what="the node to register")
    return node


async def test_a_node_gone_is_503_and_a_malformed_request_400(core, start_node) -> None:
    counter = await start_node(Counter)
    await counter._server.stop()  # type: ignore[union-attr]  # still registered, no longer serving
    reader, writer = await asyncio.open_connection("127.0.0.1", core.port)
    writer.write(post("/counter/count"))
    [gone] = await read_replies(reader, 1)
    assert gone.status == 503 and "not reachable" in json.loads(gone.body)["detail"]
    writer.write(b"POST /counter/count HTTP/1.1\r\nContent-Length: x\r\n\r\n")
    [bad] = await read_replies(reader, 1)
    assert bad.status == 400
    writer.close()


class Slow(Node):
    """A service that answers when the test lets it."""

    def __init__(self, settings) -> None:
        super().__init__("slow", settings=settings)
        self.entered = asyncio.Event()
        self.release = asyncio.Event()
        self.create_service(Trigger, "/slow/call", self.call)

    async def call(self, request):
        self.entered.set()
        await self.release.wait()
        return TriggerResponse(success=True, message="late")


async def test_at_shutdown_a_call_in_flight_is_answered_then_its_connection_closed(core, start_node) -> None:
    slow = await start_node(Slow)
    reader, writer = await asyncio.open_connection("127.0.0.1", core.port)
    writer.write(post("/slow/call"))
    await asyncio.wait_for(slow.entered.wait(), 10)
    connections = core._server.server_state.connections  # type: ignore[union-attr]
    [connection] = [c for c in connections if isinstance(c, GatewayHttpProtocol)]
    core._server.should_exit = True  # type: ignore[union-attr]  # a graceful stop, as on SIGTERM
    await wait_until(lambda: connection._closing, what="uvicorn to ask the connection to shut down")
    slow.release.set()
    [reply] = await read_replies(reader, 1)
    assert reply.status == 200 and json.loads(reply.body)["message"] == "late"
    assert await asyncio.wait_for(reader.read(), 10) == b""  # then closed, not kept alive
    writer.close()


async def test_a_fault_of_the_core_while_forwarding_is_a_500_and_a_closed_connection(core, start_node, caplog) -> None:
    await start_node(Counter)

    def broken(*args: object, **kwargs: object) -> None:
        raise RuntimeError("a bug in the forward path")

    core.app.state.calls.start = broken  # type: ignore[union-attr]
    reader, writer = await asyncio.open_connection("127.0.0.1", core.port)
    writer.write(post("/counter/count"))
    [reply] = await read_replies(reader, 1)
    assert (reply.status, reply.body) == (500, b"Internal Server Error")
    assert await asyncio.wait_for(reader.read(), 10) == b""
    assert "forwarding a call to /counter/count failed" in caplog.text
    writer.close()


async def test_an_idle_connection_closes_after_the_keep_alive_timeout() -> None:
    core = CoreProcess()
    await core.start()
    core._server.config.timeout_keep_alive = 0.3  # type: ignore[union-attr]
    try:
        node = await start_node_on(core, {})
        reader, writer = await asyncio.open_connection("127.0.0.1", core.port)
        writer.write(post("/counter/count"))
        await read_replies(reader, 1)
        assert await asyncio.wait_for(reader.read(), 10) == b""  # closed by the core, not the test's timeout
        writer.close()
        await node.stop()
    finally:
        await core.stop()


async def test_a_server_of_another_app_hands_every_connection_over() -> None:
    async def app(scope, receive, send) -> None:  # type: ignore[no-untyped-def]
        await send({"type": "http.response.start", "status": 200, "headers": [(b"content-length", b"2")]})
        await send({"type": "http.response.body", "body": b"ok"})

    server = uvicorn.Server(uvicorn.Config(app, http=GatewayHttpProtocol, lifespan="off", log_level="warning"))
    sock = held_socket()
    task = await serve_on(server, sock)
    try:
        reader, writer = await asyncio.open_connection("127.0.0.1", sock.getsockname()[1])
        writer.write(post("/any"))
        [reply] = await read_replies(reader, 1)
        assert (reply.status, reply.body) == (200, b"ok")
        assert [type(c) for c in server.server_state.connections] == [HttpToolsProtocol]
        writer.close()
    finally:
        server.should_exit = True
        await task
