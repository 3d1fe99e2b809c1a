"""The seed's whole exercise, end to end: the mission flies over every box once and lands."""

from __future__ import annotations

import asyncio
import itertools
import json
import math
import os
import signal

import pytest
from websockets.asyncio.client import connect

from services.runtime.edge.links import stream_url

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(240)]

SPEED = "10"


def optimal_open_tour_m(start: tuple[float, float], boxes: list[tuple[float, float]]) -> float:
    """Brute force, independent of the planner."""
    best = math.inf
    for order in itertools.permutations(range(len(boxes))):
        length, here = 0.0, start
        for index in order:
            length += math.dist(here, boxes[index])
            here = boxes[index]
        best = min(best, length)
    return best


async def _track_closest_approach(core_url: str, boxes: list[tuple[float, float]], closest: list[float]) -> None:
    async with connect(stream_url(core_url, "/drone/pose", queue=10_000), max_size=None) as websocket:
        async for frame in websocket:
            position = json.loads(frame)["pose"]["position"]
            for i, (x, y) in enumerate(boxes):
                closest[i] = min(closest[i], math.hypot(position["x"] - x, position["y"] - y))


async def test_mission_visits_every_box_once_and_lands(launch) -> None:
    system = await launch("--speed", SPEED, "--seed", "11")
    polygon = await system.messages("/perception/boxes", lambda m: len(m["points"]) == 8, 30)
    boxes = [(p["x"], p["y"]) for p in polygon["points"]]
    closest = [math.inf] * len(boxes)
    tracker = asyncio.create_task(_track_closest_approach(system.core_url, boxes, closest))
    try:
        status = await system.messages("/ai/status", lambda m: m["state"] in ("done", "error"), 180)
    finally:
        tracker.cancel()
    assert status["state"] == "done", status
    assert sorted(status["visited"]) == list(range(8)) and len(status["visited"]) == 8
    # Physically there: the drone passed within the visit radius of every box.
    assert max(closest) <= 0.3 + 0.05, closest
    assert status["tour_length"] <= optimal_open_tour_m((0.0, 0.0), boxes) * 1.02 + 0.5
    control = await system.messages("/control/state", lambda m: True, 10)
    assert control["state"] == "landed"
    pose = await system.messages("/drone/pose", lambda m: True, 10)
    assert pose["pose"]["position"]["z"] <= 0.1


async def test_ai_killed_mid_mission_resumes_without_revisiting(launch) -> None:
    system = await launch("--speed", SPEED, "--seed", "5")
    await system.messages("/ai/status", lambda m: len(m["visited"]) >= 2, 120)
    graph = await system.graph()
    ai = next(node for node in graph["nodes"] if node["name"] == "/ai")
    os.kill(ai["pid"], signal.SIGKILL)
    await system.wait_for_line("[launch] ai exited", timeout_s=20)
    await system.wait_for_line("[launch] ai ready", timeout_s=30)
    status = await system.messages("/ai/status", lambda m: m["state"] in ("done", "error"), 180)
    assert status["state"] == "done", status
    assert sorted(status["visited"]) == list(range(8)), status["visited"]
    assert len(status["visited"]) == len(set(status["visited"]))
    assert any("resuming" in line for line in system.lines)
