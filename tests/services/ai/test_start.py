"""When the mission starts: on /ai/start, or at once with --start-mission; an AI restarted in
the middle of a mission carries on by itself."""

from __future__ import annotations

import pytest

from services.ai.node import AiNode, AiSettings, main
from services.ai.progress import ProgressStore, WorldProgress
from shared_models.ros_workshop import SimWorld
from shared_models.std_srvs import Trigger
from tests.conftest import wait_until

pytestmark = pytest.mark.timeout(30)


def _ai(tmp_path, **settings: object):  # type: ignore[no-untyped-def]
    return lambda node: AiNode(node, ai=AiSettings(**settings), store=ProgressStore(tmp_path))


async def test_the_ai_waits_for_ai_start(start_node, tmp_path) -> None:
    ai = await start_node(_ai(tmp_path))
    assert ai._mission is None and "waiting for /ai/start" in ai.status.message
    ai.on_world(SimWorld(id="w1"))  # a world, never flown: still waiting
    assert ai._mission is None
    response = await ai.handle_start(Trigger.Request())
    assert response.success and ai._mission is not None


async def test_start_mission_starts_at_once(start_node, tmp_path) -> None:
    ai = await start_node(_ai(tmp_path, start_mission=True))
    assert ai._mission is not None
    await wait_until(lambda: "waiting for the world" in ai.status.message, what="the mission to wait for the world")


async def test_a_restarted_ai_carries_on_a_mission_under_way(start_node, tmp_path) -> None:
    store = ProgressStore(tmp_path)
    store.save(WorldProgress(world="w1", boxes=3, visited=[0]))
    store.save(WorldProgress(world="w0", boxes=3, visited=[0, 1, 2], done=True))
    ai = await start_node(_ai(tmp_path))
    ai.on_world(SimWorld(id="w0"))  # finished: stays finished
    assert ai._mission is None
    ai.on_world(SimWorld(id="w1", build=1))  # under way when the AI stopped: it goes on
    assert ai._mission is not None


@pytest.mark.parametrize(
    ("argv", "expected"), [([], False), (["--start-mission"], True), (["--start-mission", "false"], False)]
)
def test_the_flag(monkeypatch, argv: list[str], expected: bool) -> None:
    built: list[AiSettings] = []
    monkeypatch.setattr("services.ai.node.AiNode", lambda ai: built.append(ai))
    monkeypatch.setattr("services.ai.node.spin", lambda node: None)
    assert main(argv) == 0
    assert built[0].start_mission is expected


def test_a_bad_flag_value_is_one_line(capsys) -> None:
    with pytest.raises(SystemExit):
        main(["--start-mission", "maybe"])
    assert "--start-mission: Input should be a valid boolean" in capsys.readouterr().err
