"""Both compose commands, run as their containers would run them, on this machine's loopback.

No Docker engine here: each service of the configuration the real ``docker-compose config``
resolves is started as a process with its container's exact command line and environment (the
image's ``ENV`` from the Dockerfile's last stage, then the service's ``environment``). Only what
the network and the port table make different changes: ``--host 0.0.0.0`` becomes 127.0.0.1,
every port a free one, every ``http://SERVICE:PORT`` that service's loopback URL, and the core's
rosbridge and Foxglove endpoints (9090 and 8765 in the container) get free ports too, so this
never binds the well-known ones. As compose does, the core starts first and the rest once the
core's healthcheck passes; each must then pass its own healthcheck command (run as written, on
its substituted URL) and be registered with the core under its service's URL.

A token is set, as ``SKYDECK_TOKEN=... docker compose up`` sets it: registering needs it, so a
registered node proves it got it; the core's endpoints refuse a call without it and take one with it.
"""

from __future__ import annotations

import asyncio
import json
import os
import re
import shlex
import signal
import struct
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import httpx
import pytest
from websockets.asyncio.client import connect
from websockets.typing import Subprotocol

from services.launch.background import BackgroundProcess
from services.protocols.endpoints import ENDPOINTS, endpoint_named
from services.runtime.ports import free_port_block
from tests.compose_config import (
    DOCKERFILE,
    VARIANTS,
    container_port,
    health_url,
    resolve,
    started_services,
)
from tests.conftest import await_registered
from tests.services.protocols.test_foxglove import binary
from tests.services.protocols.test_foxglove import receive as foxglove_receive
from tests.services.protocols.test_rosbridge import call as rosbridge_call

pytestmark = [pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(180)]

TOKEN = "c0ntainer-t0ken"
HEALTHY_WITHIN_S = 60.0  # the compose file's start_period (30 s), on a busy shared machine
REGISTERED_WITHIN_S = 30.0
FOXGLOVE = [Subprotocol("foxglove.websocket.v1")]
PROBE = "/sim/list_parameters"  # a service of the simulator: every call to it needs the token


@dataclass
class Container:
    """One service run as a process: its resolved configuration and where it listens here."""

    name: str
    service: dict[str, Any]
    port: int
    process: BackgroundProcess | None = None

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}"


@dataclass
class Deployment:
    """A variant's services running on loopback, and the core's endpoints' ports."""

    variant: str  # "drone" or "robot": the world the simulator runs
    containers: dict[str, Container]
    endpoint_ports: dict[str, int]  # by endpoint name (the table of endpoints)

    @property
    def core(self) -> Container:
        return self.containers["core"]


def image_environment(state_dir: Path) -> dict[str, str]:
    """The ``SKYDECK_*`` variables the image's last stage sets, the host and state folder made
    this machine's (loopback, a temporary folder for the named volume)."""
    final = DOCKERFILE.read_text()
    final = final[final.rindex("\nFROM ") :]
    env: dict[str, str] = {}
    for block in re.findall(r"^ENV ((?:.*\\\n)*.*)$", final, re.MULTILINE):
        for word in shlex.split(block.replace("\\\n", " ")):
            key, _, value = word.partition("=")
            if key.startswith("SKYDECK_"):
                env[key] = value
    assert env.get("SKYDECK_HOST") == "0.0.0.0", "the image listens on every interface"
    return {**env, "SKYDECK_HOST": "127.0.0.1", "SKYDECK_STATE_DIR": str(state_dir)}


def loopback_argv(container: Container, urls: dict[str, str], endpoints: dict[str, int]) -> list[str]:
    """The container's command as a process here: same words, loopback host and ports."""
    words = [str(word) for word in container.service["command"]]
    assert words[0] == "skydeck", "every service runs the image's skydeck command"
    argv = []
    for index, word in enumerate(words[1:], start=1):
        if words[index - 1] == "--host":
            word = "127.0.0.1"
        elif words[index - 1] == "--port":
            word = str(container.port)
        for inside, here in urls.items():
            word = word.replace(inside, here)
        argv.append(word)
    if argv[0] == "core":
        flags = {endpoint.flag for endpoint in ENDPOINTS}
        assert not flags & set(argv), "the core's endpoints keep their defaults in the container"
        argv += [word for name, port in endpoints.items() for word in (endpoint_named(name).flag, str(port))]
    return [sys.executable, "-m", "services.cli", *argv]


def process_environment(container: Container, image_env: dict[str, str]) -> dict[str, str]:
    """This machine's environment without its Skydeck settings, then the image's, then the
    service's (a variable listed without a value is passed on only when set: here it is not)."""
    base = {key: value for key, value in os.environ.items() if not key.startswith("SKYDECK_")}
    service_env = {key: str(value) for key, value in container.service.get("environment", {}).items() if value is not None}
    return {**base, **image_env, **service_env}


def run_healthcheck(container: Container) -> None:
    """The service's healthcheck command, as written, on its loopback URL: it must exit 0."""
    code = container.service["healthcheck"]["test"][3]
    inside = health_url(container.service)
    here = f"{container.url}/health"
    assert inside == f"http://127.0.0.1:{container_port(container.service)}/health"
    check = BackgroundProcess([sys.executable, "-c", code.replace(inside, here)], name=f"{container.name} healthcheck")
    returncode = check.popen.wait(timeout=15)
    check.stop()
    assert returncode == 0, f"{container.name}'s healthcheck failed:\n{check.tail()}"


@pytest.fixture(params=list(VARIANTS))
def deployment(request: pytest.FixtureRequest, tmp_path: Path) -> Iterator[Deployment]:
    """The variant's ``up`` with ``SKYDECK_TOKEN`` set, each service a process on loopback."""
    services = started_services(resolve(request.param, env={"SKYDECK_TOKEN": TOKEN}))
    base = free_port_block(len(services) + len(ENDPOINTS))
    containers = {name: Container(name, service, base + index) for index, (name, service) in enumerate(services.items())}
    endpoints = {endpoint.name: base + len(services) + index for index, endpoint in enumerate(ENDPOINTS)}
    urls = {f"http://{c.name}:{container_port(c.service)}": c.url for c in containers.values()}
    image_env = image_environment(tmp_path)
    # The core first; the rest depend on a healthy core (checked in tests/test_containers.py).
    order = ["core", *(name for name in containers if name != "core")]
    try:
        for name in order:
            container = containers[name]
            container.process = BackgroundProcess(
                loopback_argv(container, urls, endpoints), name=name, env=process_environment(container, image_env)
            )
            if name == "core":
                container.process.wait_healthy(f"{container.url}/health", HEALTHY_WITHIN_S)
                run_healthcheck(container)
        yield Deployment(request.param, containers, endpoints)
    finally:
        for name in reversed(order):
            process = containers[name].process
            if process is not None:
                process.stop(signal.SIGTERM)  # what `docker compose down` sends


async def test_every_service_comes_up_healthy_registered_and_guarded(deployment: Deployment) -> None:
    for container in deployment.containers.values():
        assert container.process is not None
        container.process.wait_healthy(f"{container.url}/health", HEALTHY_WITHIN_S)
        run_healthcheck(container)
    core = deployment.core
    async with httpx.AsyncClient() as http:
        expected = {f"/{c.name}": c.url for c in deployment.containers.values() if c.name != "core"}
        nodes = await await_registered(core.url, set(expected), REGISTERED_WITHIN_S)
        assert {name: nodes[name] for name in expected} == expected, "each node at its service's URL"
        world = (await http.get(f"{core.url}/simulator/world", timeout=5)).json()
        assert world["world"] == deployment.variant, "the simulator runs this command's world"
        # Registering needs the token, so each node got it; the core's own calls want it too.
        reply = await http.post(f"{core.url}{PROBE}", json={}, timeout=10)
        assert reply.status_code == 401, reply.text
        reply = await http.post(
            f"{core.url}{PROBE}", json={}, headers={"Authorization": f"Bearer {TOKEN}"}, timeout=10
        )
        assert reply.status_code == 200, reply.text
    async with asyncio.timeout(30):
        await _call_through_the_endpoints(deployment)


async def _call_through_the_endpoints(deployment: Deployment) -> None:
    """rosbridge and Foxglove, on the ports the container publishes as 9090 and 8765, check
    the core's token: a call to the simulator is refused without it and answered with it."""
    async with connect(f"ws://127.0.0.1:{deployment.endpoint_ports['rosbridge']}") as ws:
        refused = await rosbridge_call(ws, PROBE, "without")
        assert refused["result"] is False and "need the token" in refused["values"]
        await ws.send(json.dumps({"op": "auth", "mac": TOKEN}))
        answered = await rosbridge_call(ws, PROBE, "with")
        assert answered["result"] is True, answered
    foxglove = f"ws://127.0.0.1:{deployment.endpoint_ports['foxglove']}"
    for call_id, url in enumerate((foxglove, f"{foxglove}/?token={TOKEN}")):
        async with connect(url, subprotocols=FOXGLOVE) as ws:
            services = {s["name"]: s["id"] for s in (await foxglove_receive(ws, "advertiseServices"))["services"]}
            await ws.send(struct.pack("<BIII", 2, services[PROBE], call_id, 4) + b"json{}")
            if call_id == 0:
                assert "need the token" in (await foxglove_receive(ws, "serviceCallFailure"))["message"]
            else:
                answer = await binary(ws, 0x03)  # serviceCallResponse
                assert struct.unpack_from("<II", answer, 1) == (services[PROBE], call_id)
