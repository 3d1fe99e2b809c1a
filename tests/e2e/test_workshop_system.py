"""The seed's whole exercise, end to end: the mission flies over every box once and lands, and
the whole flight, take-off to touchdown, is as short as the landing policy allows."""

from __future__ import annotations

import asyncio
import math

import pytest

from benchmarks.mission import optimal_flight_m
from services.ai.landing import BOX_FOOTPRINT_RADIUS_M, DRONE_RADIUS_M
from sim_server.drone.limits import START_XY_M
from tests.e2e.mission import ai_process, box_positions, recording

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(240)]

SPEED = "10"
# The drone cuts a little off each corner (a box counts within 0.3 m) and overshoots a little
# at each stop; flying back to the start instead of landing beside the last box was ~1.3x.
FLOWN_OVER_OPTIMAL = 1.05


async def _fly(launch, tmp_path, seed: str, boxes: int, *ai_args: str):  # type: ignore[no-untyped-def]
    """Launch without the AI, record the track, run the AI until the mission ends; the track,
    the boxes and the final status."""
    system = await launch("--speed", SPEED, "--seed", seed, "--boxes", str(boxes), "--exclude", "ai")
    positions = await box_positions(system, boxes)
    async with recording(system, positions) as track, ai_process(system, tmp_path / "state", *ai_args):
        status = await system.messages("/ai/status", lambda m: m["state"] in ("done", "error"), 180)
        async with asyncio.timeout(20):
            while not track.landed:
                await asyncio.sleep(0.05)
    control = await system.messages("/control/state", lambda m: True, 10)
    assert control["state"] == "landed"
    return track, positions, status


async def test_mission_visits_every_box_once_and_lands_beside_the_last_one(launch, tmp_path) -> None:
    track, boxes, status = await _fly(launch, tmp_path, "11", 8)
    assert status["state"] == "done", status
    assert sorted(status["visited"]) == list(range(8)) and len(status["visited"]) == 8
    # Physically there: the drone passed within the visit radius of every box.
    assert max(track.closest) <= 0.3 + 0.05, track.closest
    # On the ground (not on a box's roof, 2 m up), clear of every box, beside the last one.
    assert track.position is not None and track.position[2] <= 0.1
    touchdown = track.position[:2]
    assert min(math.dist(touchdown, box) for box in boxes) >= BOX_FOOTPRINT_RADIUS_M + DRONE_RADIUS_M
    assert math.dist(touchdown, boxes[status["visited"][-1]]) < 3.5
    # The whole flight against the optimum for landing beside the last box.
    optimum = optimal_flight_m(START_XY_M, boxes, "beside_last_box")
    assert track.missed == 0  # every pose was read: the track is the drone's
    assert track.track_m <= optimum * FLOWN_OVER_OPTIMAL, (track.track_m, optimum)
    # The plan was the optimum (planned from where the take-off ended, a few mm from the start).
    assert status["tour_length"] == pytest.approx(optimum, rel=1e-3)


async def test_landing_home_flies_the_closed_tour(launch, tmp_path) -> None:
    track, boxes, status = await _fly(launch, tmp_path, "12", 5, "--landing", "home")
    assert status["state"] == "done" and sorted(status["visited"]) == list(range(5)), status
    assert max(track.closest) <= 0.3 + 0.05, track.closest
    assert track.position is not None and track.position[2] <= 0.1
    assert math.dist(track.position[:2], START_XY_M) <= 0.5
    optimum = optimal_flight_m(START_XY_M, boxes, "home")
    assert track.missed == 0
    assert track.track_m <= optimum * FLOWN_OVER_OPTIMAL, (track.track_m, optimum)
    assert status["tour_length"] == pytest.approx(optimum, rel=1e-3)
