"""Refusal reasons: tagged at the start of a refusal's message by control, read back by the AI."""

from __future__ import annotations

import pytest

from shared_models.ros_workshop import FlyCommandResponse, Refusal, refusal_message, refusal_reason


@pytest.mark.parametrize("reason", list(Refusal))
def test_every_reason_survives_the_round_trip(reason: Refusal) -> None:
    message = refusal_message(reason, "Some text for people: (1, 2).")
    assert message.startswith(f"[{reason.value}] ")
    assert refusal_reason(message) is reason


@pytest.mark.parametrize(
    "message",
    [
        "",
        "Seems like the drone is already flying!",  # a student's control, untagged
        "Already flying to (5, 3).",  # the English text alone is never read as a reason
        "[not_a_reason] something",  # a reason this version does not know
        "[same_target]no space",  # not the grammar
        " [same_target] leading space",
        "[SAME_TARGET] upper case",
    ],
)
def test_messages_without_a_known_tag_have_no_reason(message: str) -> None:
    assert refusal_reason(message) is None


def test_a_ros1_style_response_still_constructs_with_the_seed_fields() -> None:
    # The seed's srv: `bool success, string message`; rospy code builds responses positionally.
    response = FlyCommandResponse(success=False, message=refusal_message(Refusal.OUTSIDE_ARENA, "too far"))
    assert list(response.model_dump()) == ["success", "message"]
    assert refusal_reason(response.message) is Refusal.OUTSIDE_ARENA
