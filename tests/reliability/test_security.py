"""Security: loopback by default, the token on every call and publish (direct, through the
gateway, and on the core's session), never logged, compared in constant time; no CORS; limits on.

Each test starts its own core and nodes in-process on free loopback ports.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import logging
import os
import signal
import socket
import sys
import urllib.error
import urllib.request
from collections.abc import AsyncIterator

import httpx
import pytest
from websockets.asyncio.client import connect
from websockets.exceptions import ConnectionClosed, InvalidStatus

import services.runtime.auth as auth
from services.core.settings import CoreSettings
from services.launch.background import BackgroundProcess
from services.runtime import Node, NodeSettings
from services.runtime.edge.links import stream_url
from services.runtime.protocol import NodeDescription, RegisterFrame
from services.runtime.wire import MAX_MESSAGE_BYTES
from shared_models.geometry_msgs import Twist
from shared_models.std_srvs import Trigger, TriggerResponse
from tests.conftest import CoreProcess, free_port, wait_until

TOKEN = "s3cret-token-for-tests"
WRONG = "wrong-token-for-tests"


class Guarded(Node):
    """A service and a writable topic: what the token protects."""

    def __init__(self, settings: NodeSettings) -> None:
        super().__init__("guarded", settings=settings)
        self.calls = 0
        self.received: list[Twist] = []
        self.create_service(Trigger, "/guarded/poke", self.poke)
        self.create_subscription(Twist, "/guarded/cmd_vel", self.received.append, 100)
        self.publisher = self.create_publisher(Twist, "/guarded/echo", 10, latched=True)

    def poke(self, request: object) -> TriggerResponse:
        self.calls += 1
        return TriggerResponse(success=True, message="poked")


def _settings(core: CoreProcess, token: str) -> NodeSettings:
    return NodeSettings(core_url=core.url, port=0, token=token, ping_interval_s=1.0, ping_timeout_s=2.0)


@pytest.fixture
async def tokened() -> AsyncIterator[tuple[CoreProcess, Guarded]]:
    """A core and a node that both have the token."""
    core = CoreProcess(token=TOKEN)
    await core.start()
    node = Guarded(_settings(core, TOKEN))
    await node.start()
    try:
        await wait_until(lambda: "/guarded" in core.registry.nodes, what="the tokened node to register")
        yield core, node
    finally:
        await node.stop()
        await core.stop()


def _auth(how: str) -> tuple[dict[str, str], dict[str, str]]:
    """Headers and query parameters presenting the token ``how``."""
    if how == "bearer":
        return {"Authorization": f"Bearer {TOKEN}"}, {}
    if how == "query":
        return {}, {"token": TOKEN}
    if how == "wrong":
        return {"Authorization": f"Bearer {WRONG}"}, {}
    return {}, {}


# -- binding --------------------------------------------------------------------------------------


def test_settings_default_to_loopback_and_limits(monkeypatch: pytest.MonkeyPatch) -> None:
    for variable in ("SKYDECK_HOST", "SKYDECK_MAX_MESSAGE_BYTES", "SKYDECK_TOKEN"):
        monkeypatch.delenv(variable, raising=False)
    assert NodeSettings().host == CoreSettings().host == "127.0.0.1"
    assert NodeSettings().max_message_bytes == CoreSettings().max_message_bytes == MAX_MESSAGE_BYTES == 2**20
    assert NodeSettings().token == CoreSettings().token == ""


async def test_node_with_default_settings_listens_on_loopback_only(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("SKYDECK_HOST", raising=False)
    node = Node("bind_probe", settings=NodeSettings(core_url=f"http://127.0.0.1:{free_port()}"))
    await node.start()
    try:
        addresses = {node._server.address}  # type: ignore[union-attr]
    finally:
        await node.stop()
    assert addresses == {"127.0.0.1"}


def _listening_addresses(port: int) -> set[str]:
    """Local addresses with a socket in LISTEN on ``port`` (from /proc/net/tcp and tcp6)."""
    found = set()
    for table in ("/proc/net/tcp", "/proc/net/tcp6"):
        with open(table) as lines:
            next(lines)
            for line in lines:
                local, state = line.split()[1], line.split()[3]
                address, _, hex_port = local.partition(":")
                if state == "0A" and int(hex_port, 16) == port:
                    if len(address) == 8:
                        found.add(socket.inet_ntop(socket.AF_INET, bytes.fromhex(address)[::-1]))
                    else:
                        words = bytes.fromhex(address)
                        raw = b"".join(words[i : i + 4][::-1] for i in range(0, 16, 4))
                        found.add(socket.inet_ntop(socket.AF_INET6, raw))
    return found


@pytest.mark.timeout(60)
@pytest.mark.skipif(not os.path.exists("/proc/net/tcp"), reason="reads the kernel's socket table")
def test_cli_core_and_node_without_host_listen_on_loopback_only() -> None:
    core_port, node_port = free_port(), free_port()
    env = {k: v for k, v in os.environ.items() if k != "SKYDECK_HOST"}
    env["SKYDECK_CORE_URL"] = f"http://127.0.0.1:{core_port}"
    commands = {
        core_port: ["core", "--port", str(core_port), "--rosbridge-port", "0", "--foxglove-port", "0"],
        node_port: ["run", "control", "--port", str(node_port)],
    }
    processes = {
        port: BackgroundProcess([sys.executable, "-m", "services.cli", *argv], name=argv[0], env=env)
        for port, argv in commands.items()
    }
    try:
        for port, process in processes.items():
            process.wait_healthy(f"http://127.0.0.1:{port}/health", timeout_s=15)
            assert _listening_addresses(port) == {"127.0.0.1"}, port
    finally:
        for process in processes.values():
            process.stop(signal.SIGTERM)


# -- the token ------------------------------------------------------------------------------------


async def test_token_comparison_is_constant_time(monkeypatch: pytest.MonkeyPatch) -> None:
    compared: list[tuple[bytes, bytes]] = []
    real = auth.hmac.compare_digest

    def spy(a: bytes, b: bytes) -> bool:
        compared.append((a, b))
        return real(a, b)

    monkeypatch.setattr(auth.hmac, "compare_digest", spy)
    request = httpx.Request("POST", "http://x/y", headers={"Authorization": f"Bearer {WRONG}"})
    from starlette.requests import Request

    scope = {
        "type": "http",
        "headers": [(k.lower().encode(), v.encode()) for k, v in request.headers.items()],
        "query_string": b"",
    }
    assert not auth.token_matches(TOKEN, Request(scope))
    assert compared == [(WRONG.encode(), TOKEN.encode())]


async def test_session_without_the_token_cannot_register(tokened) -> None:
    core, _ = tokened
    frame = RegisterFrame(node=NodeDescription(name="/impostor", url="http://127.0.0.1:9", pid=1))
    for headers in ({}, {"Authorization": f"Bearer {WRONG}"}):
        async with connect(stream_url(core.url, "/api/session"), additional_headers=headers) as websocket:
            with pytest.raises(ConnectionClosed):
                await websocket.send(frame.model_dump_json())
                await asyncio.wait_for(websocket.recv(), 5)
            assert websocket.close_code == 1008
            assert "token" in websocket.close_reason
    assert "/impostor" not in core.registry.nodes


async def test_node_with_a_wrong_token_is_refused_and_says_why(tokened, caplog) -> None:
    core, _ = tokened
    caplog.set_level(logging.WARNING, logger="skydeck")
    impostor = Node("impostor", settings=_settings(core, WRONG))
    await impostor.start()
    try:
        await wait_until(lambda: "refused /impostor" in caplog.text, what="the node to say it was refused")
        assert "token" in caplog.text
        assert "/impostor" not in core.registry.nodes
    finally:
        await impostor.stop()


@pytest.mark.parametrize("via_core", [False, True], ids=["direct", "gateway"])
async def test_service_calls_need_the_token(tokened, via_core: bool) -> None:
    core, node = tokened
    base = core.url if via_core else node.url
    async with httpx.AsyncClient() as http:
        for how, expected in (("none", 401), ("wrong", 401), ("bearer", 200), ("query", 200)):
            headers, params = _auth(how)
            reply = await http.post(base + "/guarded/poke", headers=headers, params=params, timeout=5)
            assert reply.status_code == expected, (how, reply.text)
            if expected == 401:
                assert "token" in reply.json()["detail"]
    assert node.calls == 2  # only the two calls that carried the token reached the handler


async def test_gateway_checks_the_token_even_for_a_node_without_one(caplog) -> None:
    core = CoreProcess(token=TOKEN)
    await core.start()
    node = Guarded(_settings(core, TOKEN))
    await node.start()
    try:
        await wait_until(lambda: "/guarded" in core.registry.nodes, what="registration")
        # Registered with the token, but serving without one (a misconfigured node).
        node.settings = node.settings.model_copy(update={"token": ""})
        async with httpx.AsyncClient() as http:
            refused = await http.post(core.url + "/guarded/poke", timeout=5)
            allowed = await http.post(core.url + "/guarded/poke", headers=_auth("bearer")[0], timeout=5)
        assert refused.status_code == 401 and "token" in refused.json()["detail"]
        assert allowed.status_code == 200
        assert node.calls == 1
    finally:
        await node.stop()
        await core.stop()


@pytest.mark.parametrize("via_core", [False, True], ids=["direct", "gateway"])
async def test_publishing_needs_the_token_reading_does_not(tokened, via_core: bool) -> None:
    core, node = tokened
    base = core.url if via_core else node.url
    for how in ("none", "wrong"):
        headers, params = _auth(how)
        async with connect(stream_url(base, "/guarded/cmd_vel", **params), additional_headers=headers) as websocket:
            await websocket.send(json.dumps({"linear": {"x": 1.0}}))
            with pytest.raises(ConnectionClosed):
                await asyncio.wait_for(websocket.recv(), 5)
            assert websocket.close_code == 1008 and "token" in websocket.close_reason, how
    assert node.received == []
    for value, how in ((2.0, "bearer"), (3.0, "query")):
        headers, params = _auth(how)
        async with connect(stream_url(base, "/guarded/cmd_vel", **params), additional_headers=headers) as websocket:
            await websocket.send(json.dumps({"linear": {"x": value}}))
            await wait_until(lambda v=value: any(t.linear.x == v for t in node.received), what=f"a {how} publish")
    # Reading stays open: the latest message and the stream, without a token.
    node.publisher.publish(Twist(linear={"x": 7.0}))
    async with httpx.AsyncClient() as http:
        latest = await http.get(base + "/guarded/echo", timeout=5)
    assert latest.status_code == 200 and latest.json()["linear"]["x"] == 7.0
    async with connect(stream_url(base, "/guarded/echo")) as websocket:
        assert json.loads(await asyncio.wait_for(websocket.recv(), 5))["linear"]["x"] == 7.0


async def test_nodes_use_the_token_among_themselves(tokened) -> None:
    """A second tokened node subscribes to the first one's topic: its link carries the token."""
    core, node = tokened
    received: list[Twist] = []
    reader = Node("reader", settings=_settings(core, TOKEN))
    reader.create_subscription(Twist, "/guarded/echo", received.append, 10)
    await reader.start()
    try:
        client = reader.create_client(Trigger, "/guarded/poke")
        response = await client.call(Trigger.Request(), timeout_s=5)
        assert response.success and node.calls == 1
        await wait_until(lambda: reader._participant.links, what="a link")
        node.publisher.publish(Twist(linear={"x": 4.0}))
        await wait_until(lambda: any(t.linear.x == 4.0 for t in received), what="the message over the link")
    finally:
        await reader.stop()


async def test_the_token_is_never_logged(tokened, caplog, capfd) -> None:
    """Every path a token travels (calls, publishes, sessions, refusals) at DEBUG, on every logger."""
    core, node = tokened
    caplog.set_level(logging.DEBUG)
    # The test's own clients must not log (httpx and websockets would print the token they
    # send): plain urllib, and websockets with a disabled logger. Only Skydeck's lines remain.
    quiet = logging.getLogger("tests.quiet_client")
    quiet.disabled = True
    for how in ("none", "wrong", "bearer", "query"):
        headers, params = _auth(how)
        for base in (core.url, node.url):
            query = f"?token={params['token']}" if params else ""
            request = urllib.request.Request(base + "/guarded/poke" + query, data=b"{}", headers=headers, method="POST")
            with contextlib.suppress(urllib.error.HTTPError):
                await asyncio.to_thread(urllib.request.urlopen, request, timeout=5)
            async with connect(
                stream_url(base, "/guarded/cmd_vel", **params), additional_headers=headers, logger=quiet
            ) as websocket:
                await websocket.send(json.dumps({"linear": {"x": 1.0}}))
                with contextlib.suppress(ConnectionClosed, TimeoutError):
                    await asyncio.wait_for(websocket.recv(), 0.3)
    for token in (TOKEN, WRONG):
        impostor = Node("log_probe", settings=_settings(core, token))
        impostor.create_subscription(Twist, "/guarded/echo", lambda m: None, 1)
        await impostor.start()
        if token == TOKEN:  # the handshake with the token happened and was logged...
            await wait_until(lambda: "/log_probe" in core.registry.nodes, what="the node to register")
        else:  # ...and so did the one the core refused
            await wait_until(lambda: "refused /log_probe" in caplog.text, what="the refusal to be logged")
        await impostor.stop()
    out, err = capfd.readouterr()
    assert len(caplog.records) > 10  # the calls above were logged, at DEBUG...
    assert "Authorization: Bearer ***" in caplog.text  # ...headers included, redacted...
    for token in (TOKEN, WRONG):  # ...but no line holds a token
        assert token not in caplog.text
        assert token not in out + err


# -- CORS -----------------------------------------------------------------------------------------


async def test_no_cors_anywhere(tokened) -> None:
    core, node = tokened
    preflight = {
        "Origin": "http://evil.example",
        "Access-Control-Request-Method": "POST",
        "Access-Control-Request-Headers": "authorization, content-type",
    }
    async with httpx.AsyncClient() as http:
        for base in (core.url, node.url):
            for path in ("/guarded/poke", "/api/graph", "/health"):
                answers = [
                    await http.options(base + path, headers=preflight, timeout=5),
                    await http.get(base + path, headers={"Origin": "http://evil.example"}, timeout=5),
                    await http.post(base + path, headers={"Origin": "http://evil.example", **_auth("bearer")[0]}),
                ]
                for reply in answers:
                    assert not any(h.lower().startswith("access-control-") for h in reply.headers), (
                        base, path, dict(reply.headers)
                    )
    for app in (core.app, node._app.fastapi):
        assert not any("CORS" in m.cls.__name__ for m in app.user_middleware)


# -- other web sites ------------------------------------------------------------------------------


@pytest.mark.parametrize("via_core", [False, True], ids=["direct", "gateway"])
async def test_pages_of_other_sites_cannot_call_publish_or_stream(tokened, via_core: bool) -> None:
    """A page on another site can send a 'simple' POST without preflight, and open WebSockets
    (which have no CORS): both are refused. The same page served by the core works."""
    core, node = tokened
    base = core.url if via_core else node.url
    bearer = _auth("bearer")[0]
    async with httpx.AsyncClient() as http:
        for origin in ("http://evil.example", "null", "http://127.0.0.1:1"):
            forged = await http.post(
                base + "/guarded/poke", content=b"", timeout=5,
                headers={"Origin": origin, "Content-Type": "text/plain", **bearer},
            )
            assert forged.status_code == 403 and "cross-origin" in forged.json()["detail"], origin
        assert node.calls == 0
        own = await http.post(base + "/guarded/poke", headers={"Origin": base, **bearer}, timeout=5)
        assert own.status_code == 200 and node.calls == 1
    for topic in ("/guarded/echo", "/guarded/cmd_vel"):
        with pytest.raises(InvalidStatus) as refused:
            async with connect(stream_url(base, topic, token=TOKEN), origin="http://evil.example"):
                pass
        assert refused.value.response.status_code == 403
    async with connect(stream_url(base, "/guarded/cmd_vel", token=TOKEN), origin=base) as websocket:
        await websocket.send(json.dumps({"linear": {"x": 5.0}}))
        await wait_until(lambda: any(t.linear.x == 5.0 for t in node.received), what="a same-origin publish")
