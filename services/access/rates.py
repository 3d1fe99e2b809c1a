"""Per-subject limits on what enters the core: messages and bytes per second, calls in flight.

    limits = RateLimits(messages_per_s=200, bytes_per_s=1 << 20, calls_in_flight=16)
    bucket = limits.bucket("alice")      # shared by every connection of alice's token
    bucket.spend(len(frame))             # RateLimited (4002, HTTP 429) once she floods
    with bucket.calling():               # RateLimited when 16 of her calls are waiting
        ...

A student's flooding or hanging program must not slow the class: what each student's token
sends through the core (published frames on any protocol, service calls) is counted in one
token bucket per student, refilled at the rate and holding one second of it, so bursts within
that second pass and a flood is caught within it. The edges shed the connection that overflows
it (close 4002 with the reason, HTTP 429 for a call), and nothing else: the student's other
connections go on as long as they stay within the rate. Service calls waiting for an answer are
bounded too, so a student's hung service cannot pile up the core's memory.

Only students are limited; the instructor and the process token are not (the simulator and the
instructor's tools). A message costs a counter; the clock is read every few messages.
"""

from __future__ import annotations

import contextlib
import time
from collections.abc import Iterator

from shared_models.close_codes import Close
from shared_models.errors import SkydeckError

__all__ = ["Bucket", "RateLimited", "RateLimits"]

_monotonic = time.monotonic  # a global's lookup, not a module attribute's
_SETTLE_EVERY = 16  # messages counted between two reads of the clock, at most


class RateLimited(SkydeckError):
    """A subject sent more than its rate allows, or has too many calls waiting (HTTP 429, close 4002)."""

    http_status = 429
    close_code = Close.RATE_LIMITED


class Bucket:
    """One subject's allowance: messages and bytes, refilled continuously; calls in flight."""

    __slots__ = (
        "_bytes", "_bytes_per_s", "_calls", "_last", "_max_calls", "_messages", "_messages_per_s",
        "_settle_bytes", "_settle_messages", "_unsettled", "_unsettled_bytes", "name",
    )  # fmt: skip

    def __init__(self, name: str, messages_per_s: float, bytes_per_s: float, calls_in_flight: int) -> None:
        self.name = name
        self._messages_per_s = messages_per_s
        self._bytes_per_s = bytes_per_s
        self._messages = messages_per_s  # a full second's allowance to start with
        self._bytes = bytes_per_s
        self._last = _monotonic()
        self._max_calls = calls_in_flight
        self._calls = 0
        # Every message a student publishes is counted, but the clock is read and the bucket
        # settled every few messages (or bytes) only: a message costs a counter, and a flood is
        # still caught within an eighth of a second's allowance.
        self._unsettled = 0
        self._unsettled_bytes = 0
        self._settle_messages = max(1, min(_SETTLE_EVERY, int(messages_per_s / 8)))
        self._settle_bytes = max(1.0, bytes_per_s / 64)

    def spend(self, size: int) -> None:
        """Count one message of ``size`` bytes; RateLimited once over the rate."""
        self._unsettled += 1
        self._unsettled_bytes += size
        if self._unsettled >= self._settle_messages or self._unsettled_bytes >= self._settle_bytes:
            self._settle()

    def _settle(self) -> None:
        now = _monotonic()
        elapsed = now - self._last
        self._last = now
        messages = self._messages + elapsed * self._messages_per_s
        if messages > self._messages_per_s:
            messages = self._messages_per_s
        data = self._bytes + elapsed * self._bytes_per_s
        if data > self._bytes_per_s:
            data = self._bytes_per_s
        # What overflows is refused and not charged (its connection is shed; a call answered 429).
        self._messages, self._bytes = messages, data
        messages -= self._unsettled
        data -= self._unsettled_bytes
        self._unsettled = self._unsettled_bytes = 0
        if messages < 0.0:
            raise RateLimited(
                f"rate limit: {self.name} sent over {self._messages_per_s:g} messages/s through the core "
                "(SKYDECK_STUDENT_MESSAGES_PER_S); send less often, or throttle with a timer"
            )
        if data < 0.0:
            raise RateLimited(
                f"rate limit: {self.name} sent over {self._bytes_per_s:g} bytes/s through the core "
                "(SKYDECK_STUDENT_BYTES_PER_S); send smaller or fewer messages"
            )
        self._messages, self._bytes = messages, data

    @contextlib.contextmanager
    def calling(self) -> Iterator[None]:
        """One call in flight for as long as the block runs; RateLimited when too many are."""
        self.call_started()
        try:
            yield
        finally:
            self.call_ended()

    def call_started(self) -> None:
        """A call begins (RateLimited when ``calls_in_flight`` are waiting already); pair with call_ended."""
        if self._calls >= self._max_calls:
            raise RateLimited(
                f"rate limit: {self.name} has {self._max_calls} service calls waiting for an answer "
                "(SKYDECK_STUDENT_CALLS_IN_FLIGHT); wait for them before calling again"
            )
        self._calls += 1

    def call_ended(self) -> None:
        self._calls -= 1

    @property
    def calls_in_flight(self) -> int:
        return self._calls


class RateLimits:
    """Every limited subject's bucket, made when the subject is first seen."""

    def __init__(self, *, messages_per_s: float, bytes_per_s: float, calls_in_flight: int) -> None:
        self.messages_per_s = messages_per_s
        self.bytes_per_s = bytes_per_s
        self.calls_in_flight = calls_in_flight
        self._buckets: dict[str, Bucket] = {}

    def bucket(self, name: str) -> Bucket:
        """The bucket of subject ``name`` (one per subject, however many connections it opens)."""
        bucket = self._buckets.get(name)
        if bucket is None:
            bucket = self._buckets[name] = Bucket(name, self.messages_per_s, self.bytes_per_s, self.calls_in_flight)
        return bucket
