"""Faults in a running system (`skydeck launch`, real processes): SIGKILL the simulator, the
core, control and perception in the middle of a mission. Every mission still visits every box
exactly once (the AI's persisted progress) and lands.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import signal
import socket
from collections.abc import Callable

import httpx
import pytest
from websockets.asyncio.client import connect
from websockets.exceptions import ConnectionClosed, InvalidHandshake

from services.runtime.edge.links import stream_url
from tests.conftest import await_registered
from tests.reliability.conftest import LaunchedSystem

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(150)]

SPEED = "10"
NODES = {"/sim", "/perception", "/control", "/ai"}


@contextlib.contextmanager
def _explained(system: LaunchedSystem):  # type: ignore[no-untyped-def]
    """On failure, print what the launched processes said (pytest shows it with the failure)."""
    try:
        yield
    except BaseException:
        print("\n".join(system.lines[-150:]))
        raise


@contextlib.contextmanager
def _holding_port(port: int):  # type: ignore[no-untyped-def]
    """Listen on ``port`` (loopback) for the duration, so a node respawned on it cannot start."""
    with socket.socket() as holder:
        holder.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        holder.bind(("127.0.0.1", port))
        holder.listen(1)
        yield


async def _pid(system: LaunchedSystem, node: str) -> int:
    graph = await system.graph()
    return next(n["pid"] for n in graph["nodes"] if n["name"] == node)


async def _kill_and_wait_respawn(system: LaunchedSystem, name: str) -> None:
    """SIGKILL node ``name`` (launch name); wait until launch says it died and is ready again."""
    pid = await _pid(system, "/" + name)
    mark = len(system.lines)
    os.kill(pid, signal.SIGKILL)
    await system.wait_for_line(f"[launch] {name} exited", timeout_s=20, after=mark)
    await system.wait_for_line(f"[launch] {name} ready", timeout_s=40, after=mark)
    await await_registered(system.core_url, {"/" + name}, timeout_s=10)
    assert await _pid(system, "/" + name) != pid


def _assert_every_box_once(status: dict, boxes: int = 8) -> None:
    assert status["state"] == "done", status
    assert sorted(status["visited"]) == list(range(boxes)), status["visited"]


async def _collect(url: str, topic: str, into: list[dict], **query: object) -> None:
    """Append every message of ``topic`` at ``url`` to ``into`` (reconnecting), until cancelled."""
    while True:
        # Only the connection may fail (a node or the core restarting); anything else is a bug.
        with contextlib.suppress(OSError, TimeoutError, InvalidHandshake, ConnectionClosed):
            async with connect(stream_url(url, topic, **query), max_size=None) as websocket:
                async for frame in websocket:
                    into.append(json.loads(frame))
        await asyncio.sleep(0.1)


def _stop_readers(readers: list[asyncio.Task[None]]) -> None:
    """Cancel the collectors; one that already ended crashed (they only end when cancelled), and
    its error, not a later wait's timeout, is the test's failure."""
    for reader in readers:
        if reader.done():
            reader.result()
        reader.cancel()


async def _until(messages: list[dict], predicate: Callable[[dict], bool], timeout_s: float, what: str) -> dict:
    try:
        async with asyncio.timeout(timeout_s):
            while True:
                for message in messages:
                    if predicate(message):
                        return message
                await asyncio.sleep(0.05)
    except TimeoutError:
        last = messages[-1] if messages else "none"
        raise AssertionError(f"timed out after {timeout_s:g} s waiting for {what}; the last message: {last}") from None


async def test_killed_control_and_perception_respawn_and_the_mission_completes(launch) -> None:
    system = await launch("--speed", SPEED, "--seed", "3", "start_mission:=true")
    with _explained(system):
        await system.messages("/ai/status", lambda m: len(m["visited"]) >= 2, 60)
        await _kill_and_wait_respawn(system, "control")
        await system.messages("/ai/status", lambda m: len(m["visited"]) >= 4, 60)
        await _kill_and_wait_respawn(system, "perception")
        status = await system.messages("/ai/status", lambda m: m["state"] in ("done", "error"), 90)
        _assert_every_box_once(status)
        assert len(status["visited"]) == 8  # no box twice
        # The restarted control took over the drone in the air and the AI sent its goal again.
        assert any("already in the air" in line for line in system.lines)
        control = await system.messages("/control/state", lambda m: True, 10)
        assert control["state"] == "landed"


async def test_killed_core_respawns_streams_flow_meanwhile_and_nodes_register_again(launch) -> None:
    system = await launch("--speed", SPEED, "--seed", "4", "start_mission:=true")
    with _explained(system):
        base = int(system.core_url.rsplit(":", 1)[1])
        sim_url, ai_url = f"http://127.0.0.1:{base + 1}", f"http://127.0.0.1:{base + 4}"
        async with httpx.AsyncClient() as http:
            core_pid = (await http.get(system.core_url + "/health", timeout=5)).json()["pid"]
        # Read the AI's status from its own port throughout: it must keep moving while the core is gone.
        statuses: list[dict] = []
        reader = asyncio.create_task(_collect(ai_url, "/ai/status", statuses))
        try:
            await _until(statuses, lambda m: len(m["visited"]) >= 1, 60, "the first box visited")
            mark = len(system.lines)
            os.kill(core_pid, signal.SIGKILL)
            await system.wait_for_line("[launch] core exited", timeout_s=20, after=mark)
            # The core is gone (nothing answers on its port)...
            with pytest.raises(httpx.ConnectError):
                async with httpx.AsyncClient() as http:
                    await http.get(system.core_url + "/health", timeout=2)
            # ...and stays gone: launch respawns it within a second, so the test holds its port
            # (the respawns fail until the test lets go) for as long as the outage must last.
            with _holding_port(base):
                # The sim's pose streams straight to readers...
                async with connect(stream_url(sim_url, "/drone/pose")) as websocket:
                    poses = [json.loads(await asyncio.wait_for(websocket.recv(), 5)) for _ in range(10)]
                assert len({p["header"]["stamp"]["nanosec"] + 10**9 * p["header"]["stamp"]["sec"] for p in poses}) == 10
                # ...and the mission goes on: the AI visits the remaining boxes and, to land, needs
                # /control/land, which it has never looked up. No core can say where it is now, so
                # the AI says it waits for it (before the fix, the mission ended in "error" here).
                waiting = await _until(
                    statuses,
                    lambda m: m["state"] == "error" or "waiting for /control/land" in m["message"],
                    90,
                    "the AI to wait for /control/land",
                )
                assert waiting["state"] == "landing", waiting
            await system.wait_for_line("[launch] core ready", timeout_s=60, after=mark)
            # ...every node registers again by itself once the core is back...
            await await_registered(system.core_url, NODES, timeout_s=30)
            # ...and the mission, which went on meanwhile, lands and completes with every box once.
            status = await _until(statuses, lambda m: m["state"] in ("done", "error"), 90, "the mission to end")
        finally:
            _stop_readers([reader])
        _assert_every_box_once(status)
        assert len(status["visited"]) == 8


async def test_killed_sim_is_noticed_reported_and_the_mission_restarts_after_a_reset(launch) -> None:
    system = await launch("--speed", SPEED, "--seed", "5", "start_mission:=true")
    sim_port = int(system.core_url.rsplit(":", 1)[1]) + 1
    with _explained(system):
        await system.messages("/ai/status", lambda m: len(m["visited"]) >= 2, 60)
        old_boxes = (await system.messages("/perception/boxes", lambda m: True, 10))["points"]
        logs: list[dict] = []
        statuses: list[dict] = []
        controls: list[dict] = []
        readers = [
            asyncio.create_task(_collect(system.core_url, "/rosout", logs, queue=1000)),
            asyncio.create_task(_collect(system.core_url, "/ai/status", statuses)),
            asyncio.create_task(_collect(system.core_url, "/control/state", controls)),
        ]
        try:
            await _until(statuses, lambda m: True, 10, "the AI's status stream")
            pid = await _pid(system, "/sim")
            mark = len(system.lines)
            os.kill(pid, signal.SIGKILL)
            await system.wait_for_line("[launch] sim exited", timeout_s=20, after=mark)
            # The simulator restarts in well under a second, before anyone could call its pose
            # stale: the test holds its port so that its respawns fail until the test lets go.
            with _holding_port(sim_port):
                # Control and the AI notice the stale pose: on /rosout and on their status topics.
                await _until(logs, lambda m: m["name"].lstrip("/") == "control" and "no drone pose" in m["msg"], 20, "control's warning")
                await _until(logs, lambda m: m["name"].lstrip("/") == "ai" and "no drone pose" in m["msg"], 20, "the AI's warning")
                await _until(statuses, lambda m: "simulator not publishing" in m["message"], 20, "the AI's status")
                await _until(controls, lambda m: "no drone pose" in m["message"], 20, "control's status")
            await system.wait_for_line("[launch] sim ready", timeout_s=40, after=mark)
            await await_registered(system.core_url, {"/sim"}, timeout_s=10)
            # The restarted simulator built a new world: the AI starts a new tour by itself, and
            # a reset (a newer world still) starts another, without /ai/start.
            await system.wait_for_line("the simulator built a new world", timeout_s=20, after=mark)
            started = len(statuses)
            reset = await system.call("/simulator/reset")
            assert reset["success"], reset
            # A fresh mission for the new world: it starts from no visited box and ends with all 8.
            status = await system.messages("/ai/status", lambda m: m["state"] in ("done", "error"), 120)
        finally:
            _stop_readers(readers)
        new_boxes = (await system.messages("/perception/boxes", lambda m: True, 10))["points"]
        assert [(round(p["x"]), round(p["y"])) for p in new_boxes] != [(round(p["x"]), round(p["y"])) for p in old_boxes]
        world = (await system.messages("/simulator/world", lambda m: True, 10))["id"]
        assert any(f"new world {world}: 8 boxes" in line for line in system.lines)
        # Statuses of the old mission, already on their way, may still arrive after the reset: the
        # new mission begins where the AI reports "idle" (waiting for the new world's boxes).
        after_start = statuses[started:]
        begun = next((i for i, m in enumerate(after_start) if m["state"] == "idle"), None)
        assert begun is not None, "the AI never reported the new mission"
        fresh = [m for m in after_start[begun:] if m["state"] == "flying"]
        assert fresh and fresh[0]["visited"] == [], "the new world's mission did not start from scratch"
        _assert_every_box_once(status)
        assert len(status["visited"]) == 8
