"""The AI's side of control's refusals: it acts on the reason tag, never on the English text."""

from __future__ import annotations

import asyncio

import pytest

import services.ai.node as ai_node
from services.ai.node import AiNode, MissionError
from services.ai.progress import ProgressStore
from services.runtime import NodeSettings
from shared_models.ros_workshop import FlyCommand, Refusal, refusal_message


@pytest.fixture
def ai(tmp_path, monkeypatch) -> AiNode:
    monkeypatch.setattr(ai_node, "_RETRY_S", 0.01)
    return AiNode(NodeSettings(port=0), store=ProgressStore(tmp_path))


def _answering(ai: AiNode, *answers: FlyCommand.Response) -> list[FlyCommand.Request]:
    """Make the AI's /control/fly client answer with ``answers`` in turn; the requests it got."""
    pending, requests = list(answers), []

    async def call(request: FlyCommand.Request, *, timeout_s: float | None = None) -> FlyCommand.Response:
        requests.append(request)
        return pending.pop(0)

    ai.fly.call = call  # type: ignore[method-assign]
    return requests


def _refused(reason: Refusal | None, text: str) -> FlyCommand.Response:
    return FlyCommand.Response(success=False, message=text if reason is None else refusal_message(reason, text))


async def test_same_target_counts_as_done_whatever_the_text(ai) -> None:
    requests = _answering(ai, _refused(Refusal.SAME_TARGET, "Déjà en route."))
    await asyncio.wait_for(ai._send_fly((1.0, 2.0)), 5)
    assert len(requests) == 1


async def test_the_english_text_alone_is_not_read(ai) -> None:
    # The old AI took this text for "already flying there"; untagged, it is an unknown refusal.
    requests = _answering(ai, _refused(None, "Already flying to (1, 2)."), FlyCommand.Response(success=True))
    await asyncio.wait_for(ai._send_fly((1.0, 2.0)), 5)
    assert len(requests) == 2


async def test_not_airborne_is_asked_again_until_accepted(ai) -> None:
    requests = _answering(
        ai,
        _refused(Refusal.NOT_AIRBORNE, "Take off first."),
        _refused(Refusal.NO_POSE, "No pose."),
        FlyCommand.Response(success=True, message="Flying."),
    )
    await asyncio.wait_for(ai._send_fly((1.0, 2.0)), 5)
    assert len(requests) == 3


@pytest.mark.parametrize("reason", [Refusal.OUTSIDE_ARENA, Refusal.NOT_FINITE])
async def test_a_target_control_can_never_fly_to_ends_the_mission(ai, reason) -> None:
    _answering(ai, _refused(reason, "no"))
    with pytest.raises(MissionError, match=reason.value):
        await asyncio.wait_for(ai._send_fly((1.0, 2.0)), 5)


def test_trigger_refusals_that_mean_already_done_let_the_mission_go_on(ai) -> None:
    for reason in (Refusal.ALREADY_AIRBORNE, Refusal.ALREADY_LANDING, Refusal.ALREADY_LANDED):
        assert ai._check(False, refusal_message(reason, "text"), "take-off")
    assert not ai._check(False, refusal_message(Refusal.NO_POSE, "text"), "take-off")
    assert not ai._check(False, "Seems like the drone is already flying!", "take-off")
