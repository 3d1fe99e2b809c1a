"""A new publication's first messages wait a moment for the readers that link late
(``TopicEndpoint.hold_early``): a unit test of the endpoint, its clock moved by hand."""

from __future__ import annotations

import json

import pytest

from services.runtime import endpoint as endpoint_module
from services.runtime.edge.options import StreamOptions
from services.runtime.edge.outbox import Outbox
from services.runtime.edge.topic_socket import TopicConnection
from services.runtime.endpoint import EARLY_FRAMES, TopicEndpoint
from shared_models.std_msgs import String
from tests.fake_clock import FakeClock

pytestmark = pytest.mark.timeout(10)


@pytest.fixture
def clock(monkeypatch: pytest.MonkeyPatch) -> FakeClock:
    clock = FakeClock()
    monkeypatch.setattr(endpoint_module, "_monotonic", clock)
    return clock


def _publishing(*, latched: bool = False) -> TopicEndpoint:
    endpoint = TopicEndpoint("/said", String)
    endpoint.publishing = True
    endpoint.latched = latched
    endpoint.hold_early(2.0)
    return endpoint


async def _link(endpoint: TopicEndpoint) -> tuple[str | None, list[str]]:
    """A reader links: the frame it is sent first, and what waits in its outbox."""
    outbox = Outbox(100)
    initial = endpoint.open(TopicConnection(StreamOptions(), outbox, may_publish=False))
    waiting = [json.loads(frame)["data"] for frame in outbox._frames]  # type: ignore[arg-type]
    return (json.loads(initial)["data"] if initial is not None else None), waiting


async def test_a_reader_linking_in_the_moment_after_advertise_gets_what_was_sent_in_order(clock: FakeClock) -> None:
    endpoint = _publishing()
    endpoint.dispatch(String(data="goal"))
    endpoint.dispatch(String(data="cancel"))
    clock.now += 1.9
    assert await _link(endpoint) == (None, ["goal", "cancel"])
    endpoint.dispatch(String(data="later"))  # it reads live now; a second reader gets the first three
    assert await _link(endpoint) == (None, ["goal", "cancel", "later"])


async def test_after_the_moment_an_unlatched_topic_gives_a_new_reader_nothing(clock: FakeClock) -> None:
    endpoint = _publishing()
    endpoint.dispatch(String(data="goal"))
    clock.now += 2.0
    assert await _link(endpoint) == (None, [])
    endpoint.dispatch(String(data="next"))  # and keeps nothing more
    assert await _link(endpoint) == (None, [])


async def test_a_latched_topic_gives_its_latest_only_as_always(clock: FakeClock) -> None:
    endpoint = _publishing(latched=True)
    endpoint.dispatch(String(data="one"))
    endpoint.dispatch(String(data="two"))
    assert await _link(endpoint) == ("two", [])


async def test_only_the_first_messages_are_kept(clock: FakeClock) -> None:
    endpoint = _publishing()
    for number in range(EARLY_FRAMES + 5):
        endpoint.dispatch(String(data=str(number)))
    assert await _link(endpoint) == (None, [str(number) for number in range(EARLY_FRAMES)])


async def test_a_topic_never_held_gives_a_new_reader_nothing(clock: FakeClock) -> None:
    endpoint = TopicEndpoint("/said", String)
    endpoint.publishing = True
    endpoint.dispatch(String(data="before"))
    assert await _link(endpoint) == (None, [])
