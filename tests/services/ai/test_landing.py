"""Where the AI lands: a clear spot beside the last box, or home; and the finishing legs."""

from __future__ import annotations

import math
import random

import pytest

from services.ai.landing import CLEARANCE_M, finishing_legs, is_clear, landing_spot
from sim_server.drone.limits import ARENA_HALF_SIZE_M


def test_the_spot_is_straight_ahead_at_the_clearance() -> None:
    spot = landing_spot((5.0, 5.0), [(5.0, 5.0)], arriving_from=(5.0, 0.0))  # flying north
    assert spot is not None
    assert spot[0] == pytest.approx(5.0) and spot[1] == pytest.approx(5.0 + CLEARANCE_M)


def test_a_box_ahead_turns_the_spot_aside() -> None:
    boxes = [(0.0, 0.0), (3.0, 0.0)]  # the next box stands 3 m ahead, on the way
    spot = landing_spot((0.0, 0.0), boxes, arriving_from=(-5.0, 0.0))
    assert spot is not None and is_clear(spot, boxes)
    assert math.dist(spot, (0.0, 0.0)) == pytest.approx(CLEARANCE_M)
    assert spot[0] > -1.0  # still ahead of the box rather than back where the drone came from


def test_at_the_arena_edge_the_spot_stays_inside() -> None:
    spot = landing_spot((15.0, 0.0), [(15.0, 0.0)], arriving_from=(0.0, 0.0))
    assert spot is not None and abs(spot[0]) <= ARENA_HALF_SIZE_M
    assert math.dist(spot, (15.0, 0.0)) >= CLEARANCE_M - 1e-9


def test_a_hemmed_in_box_lands_further_out_or_at_home() -> None:
    ring = [(math.cos(a) * 3.2, math.sin(a) * 3.2) for a in (k * math.tau / 8 for k in range(8))]
    boxes = [(0.0, 0.0), *ring]
    spot = landing_spot((0.0, 0.0), boxes, arriving_from=(-1.0, 0.0))
    assert spot is None or (is_clear(spot, boxes) and math.dist(spot, (0.0, 0.0)) > CLEARANCE_M)


def test_spots_are_always_clear_in_random_worlds() -> None:
    rng = random.Random(5)
    for _ in range(200):
        boxes = [(rng.uniform(-15, 15), rng.uniform(-15, 15)) for _ in range(8)]
        last = boxes[rng.randrange(8)]
        spot = landing_spot(last, boxes, arriving_from=(rng.uniform(-15, 15), rng.uniform(-15, 15)))
        if spot is not None:
            assert is_clear(spot, boxes)


def test_finishing_legs_per_policy() -> None:
    boxes = [(3.0, 4.0), (10.0, 0.0)]
    assert finishing_legs("home", boxes, home=(0.0, 0.0)) == [5.0, 10.0]
    beside = finishing_legs("beside_last_box", boxes, home=(0.0, 0.0))
    assert beside == [pytest.approx(CLEARANCE_M)] * 2
    # The leg is the same whichever way the drone arrives (the planner relies on that).
    for arriving_from in [(0.0, 0.0), (20.0, 20.0), (3.0, -9.0)]:
        spot = landing_spot(boxes[0], boxes, arriving_from=arriving_from)
        assert spot is not None and math.dist(spot, boxes[0]) == pytest.approx(beside[0])


def test_the_policy_is_a_setting_with_a_flag(monkeypatch, capsys) -> None:
    from services.ai.node import AiSettings, main

    assert AiSettings().landing == "beside_last_box"
    monkeypatch.setenv("SKYDECK_AI_LANDING", "home")
    assert AiSettings().landing == "home"
    with pytest.raises(SystemExit) as exited:
        main(["--landing", "nowhere"])
    assert exited.value.code == 2
    assert capsys.readouterr().err.splitlines()[-1] == (
        "skydeck run ai: error: --landing: Input should be 'beside_last_box' or 'home'"
    )
