"""rosbridge's action ops in a class: the goal's feedback and status are read through the core
only where the connection's token may read (issue 35's fences over issue 34's actions). Unit level:
the transport with a stand-in session; the goal's call itself goes through the one fenced call
path (tests/reliability/test_class_fences.py)."""

from __future__ import annotations

from types import SimpleNamespace
from unittest.mock import MagicMock

import pytest

from services.access import Fences, Forbidden, Policy, RateLimits, TokenSet, make_class_tokens
from services.protocols.rosbridge.actions import CoreTransport
from shared_models.std_msgs import String

pytestmark = pytest.mark.timeout(10)

TOKENS = make_class_tokens(["alice", "bob"])


def _transport(who: str) -> tuple[CoreTransport, MagicMock]:
    fences = Fences(Policy(tokens=TokenSet(TOKENS)), RateLimits(messages_per_s=10, bytes_per_s=1000, calls_in_flight=2))
    core = MagicMock()
    session = SimpleNamespace(visitor=fences.admit(TOKENS[who]), access=SimpleNamespace(core=core), guest=MagicMock())
    return CoreTransport(session), core  # type: ignore[arg-type]


def test_a_student_taps_their_own_actions_feedback() -> None:
    transport, core = _transport("alice")
    transport.subscribe("/alice/fibonacci/_action/feedback", String, lambda message: None)
    assert core.start_reading.call_args.args[0] == "/alice/fibonacci/_action/feedback"


def test_another_students_action_is_refused_before_anything_is_tapped() -> None:
    transport, core = _transport("alice")
    with pytest.raises(Forbidden, match="alice may not read /bob/fibonacci/_action/feedback"):
        transport.subscribe("/bob/fibonacci/_action/feedback", String, lambda message: None)
    core.start_reading.assert_not_called()


def test_the_instructor_taps_any() -> None:
    transport, core = _transport("instructor")
    transport.subscribe("/bob/fibonacci/_action/status", String, lambda message: None)
    core.start_reading.assert_called_once()
