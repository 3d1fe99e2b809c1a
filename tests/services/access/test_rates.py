"""Each student's limits: messages and bytes per second through the core, refilled as time goes
(a second's worth may come at once), and calls waiting at once; one bucket per student, however
many connections they open. Time is the test's own clock here: no timing is asserted."""

from __future__ import annotations

import pytest

import services.access.rates as rates
from services.access import RateLimited, RateLimits
from tests.fake_clock import FakeClock

pytestmark = pytest.mark.timeout(30)


@pytest.fixture
def clock(monkeypatch: pytest.MonkeyPatch) -> FakeClock:
    fake = FakeClock()
    monkeypatch.setattr(rates, "_monotonic", fake)
    return fake


def test_a_seconds_worth_passes_then_a_flood_is_caught_and_time_refills_it(clock: FakeClock) -> None:
    bucket = RateLimits(messages_per_s=10, bytes_per_s=10_000, calls_in_flight=2).bucket("alice")
    for _ in range(10):
        bucket.spend(10)
    with pytest.raises(RateLimited) as limited:
        bucket.spend(10)
    assert limited.value.close_code == 4002 and limited.value.http_status == 429
    assert str(limited.value).startswith("rate limit: alice sent over 10 messages/s")
    clock.now += 0.5
    for _ in range(5):
        bucket.spend(10)
    with pytest.raises(RateLimited):
        bucket.spend(10)


def test_bytes_are_counted_too(clock: FakeClock) -> None:
    bucket = RateLimits(messages_per_s=1000, bytes_per_s=1000, calls_in_flight=2).bucket("bob")
    bucket.spend(900)
    with pytest.raises(RateLimited, match="over 1000 bytes/s"):
        bucket.spend(200)
    clock.now += 0.2
    bucket.spend(200)


def test_idle_time_does_not_save_up_more_than_a_second(clock: FakeClock) -> None:
    bucket = RateLimits(messages_per_s=5, bytes_per_s=1e9, calls_in_flight=2).bucket("alice")
    clock.now += 3600
    for _ in range(5):
        bucket.spend(1)
    with pytest.raises(RateLimited):
        bucket.spend(1)


def test_one_bucket_per_student_whatever_the_connections(clock: FakeClock) -> None:
    limits = RateLimits(messages_per_s=3, bytes_per_s=1e9, calls_in_flight=2)
    assert limits.bucket("alice") is limits.bucket("alice") and limits.bucket("alice") is not limits.bucket("bob")
    for _ in range(3):
        limits.bucket("alice").spend(1)
    with pytest.raises(RateLimited):
        limits.bucket("alice").spend(1)
    limits.bucket("bob").spend(1)  # bob's own allowance is whole


def test_calls_waiting_at_once_are_bounded() -> None:
    bucket = RateLimits(messages_per_s=100, bytes_per_s=1e9, calls_in_flight=2).bucket("alice")
    with bucket.calling(), bucket.calling():
        assert bucket.calls_in_flight == 2
        with pytest.raises(RateLimited, match="2 service calls waiting"):
            bucket.call_started()
    assert bucket.calls_in_flight == 0
    with bucket.calling():
        pass


def test_the_clock_is_read_every_few_messages_and_a_flood_is_still_caught_within_them(clock: FakeClock, monkeypatch: pytest.MonkeyPatch) -> None:
    bucket = RateLimits(messages_per_s=200, bytes_per_s=1e9, calls_in_flight=2).bucket("alice")
    reads = []
    monkeypatch.setattr(rates, "_monotonic", lambda: reads.append(1) or clock.now)
    passed = 0
    with pytest.raises(RateLimited):
        while True:
            bucket.spend(10)
            passed += 1
    assert 200 - 16 <= passed < 200 + 16  # caught within one settling's count of messages
    assert len(reads) <= passed // 16 + 2  # a clock read per 16 messages, not per message
