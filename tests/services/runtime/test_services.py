"""Services: POST at the name, on the node and through the gateway; clients; errors."""

from __future__ import annotations

import asyncio

import httpx
import pytest

from services.runtime import Node, ServiceTimeoutError, ServiceUnavailableError
from shared_models.ros_workshop import FlyCommand
from shared_models.std_srvs import Trigger, TriggerResponse


class Control(Node):
    def __init__(self, settings) -> None:
        super().__init__("control", settings=settings)
        self.z = 0.0
        self.create_service(Trigger, "/control/take_off", self.take_off)  # rospy style
        self.create_service(FlyCommand, "/control/fly", self.fly)  # rclpy style
        self.create_service(Trigger, "/control/hang", self.hang)

    def take_off(self, request):
        if self.z <= 0.1:
            self.z = 3.0
            return TriggerResponse(success=True, message="All ok!")
        return TriggerResponse(success=False, message="Seems like the drone is already flying!")

    async def fly(self, request, response):
        response.success = True
        response.message = f"flying to ({request.x}, {request.y})"
        return response

    async def hang(self, request):
        await asyncio.sleep(3600)


@pytest.mark.parametrize("via_core", [False, True])
async def test_refusal_is_an_answer_not_an_error(core, start_node, via_core) -> None:
    control = await start_node(Control)
    base = core.url if via_core else control.url
    async with httpx.AsyncClient() as http:
        first = await http.post(base + "/control/take_off")  # no body: the empty request
        second = await http.post(base + "/control/take_off", json={})
    assert first.status_code == 200 and first.json() == {"success": True, "message": "All ok!"}
    assert second.status_code == 200 and second.json()["success"] is False


@pytest.mark.parametrize("via_core", [False, True])
async def test_bad_body_gets_422_with_fastapi_detail(core, start_node, via_core) -> None:
    control = await start_node(Control)
    base = core.url if via_core else control.url
    async with httpx.AsyncClient() as http:
        wrong_type = await http.post(base + "/control/fly", json={"x": "far", "y": 1})
        extra = await http.post(base + "/control/fly", json={"x": 1, "y": 1, "z": 3})
        not_json = await http.post(base + "/control/fly", content=b"{x", headers={"content-type": "application/json"})
        nan = await http.post(base + "/control/fly", content=b'{"x": NaN, "y": 0}', headers={"content-type": "application/json"})
        # Over the size limit: refused before the call path, on the node and in the core alike.
        limit = control.settings.max_message_bytes
        oversized = await http.post(base + "/control/fly", content=b" " * (limit + 1), headers={"content-type": "application/json"})
    for reply in (wrong_type, extra, not_json, nan):
        assert reply.status_code == 422, reply.text
        assert isinstance(reply.json()["detail"], list)
    assert wrong_type.json()["detail"][0]["loc"][-1] == "x"
    assert oversized.status_code == 413 and "limit" in oversized.json()["detail"]


@pytest.mark.parametrize("via_core", [False, True])
async def test_a_body_over_the_limit_is_413_even_without_a_length(core, start_node, via_core) -> None:
    """A chunked body declares no length: it is counted as it comes and refused at the limit
    (not read on as a bad body, 422), to a service on the node and through the core's early
    path, and to the core's own routes."""
    control = await start_node(Control)
    base = core.url if via_core else control.url
    limit = control.settings.max_message_bytes

    async def chunks():  # type: ignore[no-untyped-def]
        for _ in range(limit // 65536 + 2):
            yield b" " * 65536

    async with httpx.AsyncClient() as http:
        paths = ["/control/fly"] + (["/no/such/service"] if via_core else [])  # the latter: FastAPI's route
        for path in paths:
            reply = await http.post(base + path, content=chunks(), headers={"content-type": "application/json"})
            assert "content-length" not in reply.request.headers
            assert reply.status_code == 413 and f"over the {limit}-byte limit" in reply.json()["detail"], (path, reply.text)
        after = await http.post(base + "/control/take_off")  # the server goes on
    assert after.status_code == 200


async def test_gateway_errors_say_what_to_do(core, start_node) -> None:
    control = await start_node(lambda s: Control(s.model_copy(update={"port": 0})))
    core.app.state.settings.gateway_timeout_s = 0.3
    async with httpx.AsyncClient() as http:
        unknown = await http.post(core.url + "/control/teleport")
        hung = await http.post(core.url + "/control/hang")
        await control.stop()  # still registered for a moment? the session drop removes it
        gone = await http.post(core.url + "/control/take_off")
    assert unknown.status_code == 404 and "skydeck service list" in unknown.json()["detail"]
    assert hung.status_code == 504 and "did not answer" in hung.json()["detail"]
    assert gone.status_code in (404, 503)


async def test_gateway_503_when_node_unreachable(core) -> None:
    from services.runtime.protocol import Entity, NodeDescription

    port = __import__("tests.conftest", fromlist=["free_port"]).free_port()
    ghost = NodeDescription(
        name="/ghost", url=f"http://127.0.0.1:{port}", pid=1, services=[Entity(name="/ghost/do", type="std_srvs/srv/Trigger")]
    )
    core.registry.register(ghost, lambda frame: None)
    async with httpx.AsyncClient() as http:
        reply = await http.post(core.url + "/ghost/do")
    assert reply.status_code == 503 and "not reachable" in reply.json()["detail"]


async def test_client_calls_and_waits_for_service(start_node) -> None:
    class Ai(Node):
        def __init__(self, settings) -> None:
            super().__init__("ai", settings=settings)
            self.take_off = self.create_client(Trigger, "/control/take_off")
            self.fly = self.create_client(FlyCommand, "/control/fly")

    ai = await start_node(Ai)
    assert await ai.take_off.wait_for_service(timeout_s=0.2) is False
    waiter = asyncio.create_task(ai.take_off.wait_for_service(timeout_s=5))
    await start_node(Control)
    assert await waiter is True
    response = await ai.take_off.call(Trigger.Request())
    assert response.success is True
    flown = await ai.fly.call(FlyCommand.Request(x=5.0, y=-3.0), timeout_s=2)
    assert flown.message == "flying to (5.0, -3.0)"


async def test_client_timeout_and_unavailable(start_node) -> None:
    class Caller(Node):
        def __init__(self, settings) -> None:
            super().__init__("caller", settings=settings)
            self.hang = self.create_client(Trigger, "/control/hang")
            self.missing = self.create_client(Trigger, "/nobody/home")

    caller = await start_node(Caller)
    await start_node(Control)
    with pytest.raises(ServiceTimeoutError, match="did not answer within 0.2 s"):
        await caller.hang.call(timeout_s=0.2)
    with pytest.raises(ServiceUnavailableError, match="no node hosts /nobody/home"):
        await caller.missing.call()


async def test_node_openapi_documents_its_services(start_node) -> None:
    control = await start_node(Control)
    async with httpx.AsyncClient() as http:
        schema = (await http.get(control.url + "/openapi.json")).json()
    assert "post" in schema["paths"]["/control/fly"]
    assert "FlyCommandRequest" in str(schema["paths"]["/control/fly"]["post"]["requestBody"])
