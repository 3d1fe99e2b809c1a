"""The workshop starts where the seed starts: `skydeck launch` (`make up`) brings the drone up
landed, the AI waiting for /ai/start, so the guide's first command (`curl -X POST
.../control/take_off`) answers as written; the dashboard's Start mission (/ai/start) then flies."""

from __future__ import annotations

import pytest

from sim_server.drone.limits import ON_GROUND_Z_M

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(180)]


async def test_the_drone_waits_landed_until_asked(launch) -> None:
    system = await launch("--speed", "4", "--seed", "7")  # the workshop, every node: `make up`
    await system.messages("/ai/status", lambda m: "waiting for /ai/start" in m["message"], 30)
    assert (await system.messages("/control/state", lambda m: True, 10))["state"] == "landed"
    pose = await system.messages("/drone/pose", lambda m: m["header"]["stamp"]["sec"] >= 4, 30)
    assert pose["pose"]["position"]["z"] <= ON_GROUND_Z_M, "nobody took off by itself"
    status = await system.messages("/ai/status", lambda m: True, 10)
    assert (status["state"], status["visited"]) == ("idle", [])

    assert await system.call("/control/take_off") == {"success": True, "message": "All ok!"}
    await system.messages("/drone/pose", lambda m: m["pose"]["position"]["z"] > 1.0, 30)

    assert (await system.call("/ai/start"))["success"] is True  # the dashboard's Start mission
    await system.messages("/ai/status", lambda m: len(m["visited"]) >= 1, 90)
