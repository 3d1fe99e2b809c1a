"""One rosbridge connection's topics: its subscriptions (merged per topic) and advertisements.

As the protocol document (and rosbridge_suite) has them:

- ``subscribe``/``unsubscribe`` by ``id``: a topic a client subscribes to several times is read
  once, with the lowest ``throttle_rate`` and ``fragment_size``, the longest ``queue_length`` and
  the most compact ``compression``; ``unsubscribe`` without an ``id`` ends them all. Without a
  ``type``, a topic nobody has yet cannot be subscribed to.
- ``advertise``/``unadvertise`` counted by ``id``: two components of one client advertising a
  topic (two roslibjs ``Topic`` objects) publish until both have unadvertised; ``latch`` makes
  the latest message go to subscribers that come later (as a latched ROS publisher).
- ``publish``: validated against the topic's type; a message that leaves out its ``header``, or
  the header's ``stamp``, is stamped now; one that leaves out other fields gets them at their
  defaults, with a ``warning`` status for a client that asked for warnings (``set_level``). What
  a client publishes on a topic it reads comes back to it (``ClientSession(echo=True)``).
"""

from __future__ import annotations

import itertools
import json
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from typing import Any

import services.protocols.rosbridge.clock as clock
from services.access import Verb
from services.core.gateway_topic import declared_type
from services.protocols.ops import Refused
from services.protocols.rosbridge.frames import (
    PublishEnvelopes,
    Status,
    fragments,
    merged_compression,
)
from services.protocols.rosbridge.ops import (
    Advertise,
    Publish,
    Subscribe,
    Unadvertise,
    Unsubscribe,
    ros2_time_names,
)
from services.protocols.session import ClientSession
from services.runtime.edge.frames import FrameRejected
from services.runtime.edge.pump import Encode
from services.runtime.wire import DEFAULT_QUEUE
from shared_models import Message, resolve_name
from shared_models._message import Ros1Only
from shared_models.interfaces import field_types

__all__ = ["ConnectionTopics"]

_HEADER = "std_msgs/msg/Header"


@dataclass(frozen=True)
class _Subscription:
    """One subscribe op's options."""

    throttle_ms: int
    queue_length: int
    fragment_size: int | None
    compression: str


class ConnectionTopics:
    """A connection's subscriptions and advertisements (see the module docstring)."""

    def __init__(
        self, session: ClientSession, envelopes: PublishEnvelopes, status: Status, wants: Callable[[str], bool]
    ) -> None:
        self._session = session
        self._envelopes = envelopes
        self._status = status
        self._wants = wants  # whether the client asked for statuses of this level
        self._subscriptions: dict[str, dict[Any, _Subscription]] = {}
        self._reading: dict[str, _Subscription] = {}  # topic -> the merged options it is read with
        self._advertised: dict[str, set[Any]] = {}  # topic -> ids of the advertise ops still standing
        self._fragment_numbers = itertools.count(1)

    # -- subscriptions --------------------------------------------------------------------------

    async def subscribe(self, op: Subscribe) -> None:
        name = resolve_name(op.topic)
        self._session.visitor.check(Verb.READ, name)  # before anything of the op is kept
        known = self._session.access.registry.topic_type(name)
        if op.type:
            declared = declared_type(op.type)
            if declared is not None and known and known != declared.__ros_type__:
                raise Refused(f"{name} is {known}, not {op.type}")
        elif known is None:
            raise Refused(f"{name} does not exist yet and no type was given: subscribe with its type to wait for it")
        self._subscriptions.setdefault(name, {})[op.id] = _Subscription(
            op.throttle_rate, op.queue_length, op.fragment_size, op.compression or "none"
        )
        self._follow(name)
        await self._status("info", f"subscribed to {name}", op.id)

    async def unsubscribe(self, op: Unsubscribe) -> None:
        name = resolve_name(op.topic)
        subscriptions = self._subscriptions.get(name)
        if not subscriptions or (op.id is not None and op.id not in subscriptions):
            await self._status("warning", f"no subscription to {name} with id {op.id!r}", op.id)
            return
        if op.id is None:
            subscriptions.clear()
        else:
            del subscriptions[op.id]
        self._follow(name)

    def _follow(self, topic: str) -> None:
        """(Re)start or stop reading ``topic`` with the merged options of its subscriptions."""
        subscriptions = self._subscriptions.get(topic)
        if not subscriptions:
            self._subscriptions.pop(topic, None)
            self._reading.pop(topic, None)
            self._session.stop_reading(topic)
            return
        sizes = [s.fragment_size for s in subscriptions.values() if s.fragment_size]
        merged = _Subscription(
            throttle_ms=min(s.throttle_ms for s in subscriptions.values()),
            queue_length=max(s.queue_length for s in subscriptions.values()),
            fragment_size=min(sizes) if sizes else None,
            compression=merged_compression([s.compression for s in subscriptions.values()]),
        )
        if self._reading.get(topic) == merged:
            return
        self._reading[topic] = merged
        encode: Encode = self._envelopes.encoder(topic, merged.compression)
        if merged.fragment_size is not None:
            encode = fragments(encode, merged.fragment_size, topic, self._fragment_numbers)
        throttle, queue = merged.throttle_ms, merged.queue_length
        # As rosbridge_server: throttled without a queue_length, the newest message each period;
        # with one, every message that queue holds, one per period, oldest first.
        self._session.start_reading(
            topic,
            queue=queue or DEFAULT_QUEUE,
            rate_hz=1000.0 / throttle if throttle > 0 else None,
            paced_queue=throttle > 0 and queue > 1,
            encode=encode,
        )

    # -- advertisements and messages ------------------------------------------------------------

    async def advertise(self, op: Advertise) -> None:
        name = resolve_name(op.topic)
        self._session.declare(name, declared_type(op.type), latched=op.latch)
        self._advertised.setdefault(name, set()).add(op.id)
        await self._status("info", f"advertised {name} ({op.type})", op.id)

    async def unadvertise(self, op: Unadvertise) -> None:
        name = resolve_name(op.topic)
        ids = self._advertised.get(name)
        if not ids:
            await self._status("warning", f"{name} was not advertised by this client", op.id)
            return
        if op.id is not None and op.id not in ids:
            await self._status("warning", f"{name} was not advertised by this client with id {op.id!r}", op.id)
            return
        if op.id is None:
            ids.clear()
        else:
            ids.discard(op.id)
        if not ids:  # the last of its advertisements: the client publishes it no more
            del self._advertised[name]
            self._session.stop_publishing(name)

    async def publish(self, op: Publish) -> None:
        name = resolve_name(op.topic)
        try:
            view = self._session.publication(name) or self._session.declare(name, None, latched=op.latch)
            msg = op.msg
            cls = view.message_type()
            if _has_header(cls):
                msg = self._stamped(msg)
            text = ros2_time_names(json.dumps(msg), msg)
            if self._wants("warning"):
                missing = _missing_fields(json.loads(text), cls)
                if missing:
                    await self._status("warning", f"publish to {name}: {', '.join(missing)} left out: sent as their defaults", op.id)
            self._session.publish(name, text)
        except FrameRejected as error:
            raise Refused(f"publish to {name}: {error.reason}") from None

    def _stamped(self, msg: dict[str, Any]) -> dict[str, Any]:
        """``msg`` with a header stamped now where it has none, or a header without a stamp."""
        header = msg.get("header")
        if header is None:
            return {**msg, "header": {"stamp": clock.now(self._session.access).model_dump(), "frame_id": ""}}
        if isinstance(header, dict) and "stamp" not in header:
            return {**msg, "header": {**header, "stamp": clock.now(self._session.access).model_dump()}}
        return msg


@cache
def _has_header(cls: type[Message]) -> bool:
    return any(name == "header" and nested is not None and nested.__ros_type__ == _HEADER for name, _, nested in field_types(cls))


@cache
def _fields(cls: type[Message]) -> tuple[tuple[str, type[Message] | None], ...]:
    """Each field of ``cls`` a ROS 2 message has and, for a single nested message (not an
    array), its type."""
    return tuple(
        (name, nested if not text.endswith("]") else None)
        for name, text, nested in field_types(cls)
        if not any(isinstance(mark, Ros1Only) for mark in cls.model_fields[name].metadata)
    )


def _missing_fields(msg: Any, cls: type[Message], prefix: str = "") -> list[str]:
    """The fields of ``cls`` that ``msg`` leaves out, nested ones too (``pose.position.z``)."""
    if not isinstance(msg, dict):
        return []
    missing: list[str] = []
    for name, nested in _fields(cls):
        if name not in msg:
            missing.append(prefix + name)
        elif nested is not None:
            missing += _missing_fields(msg[name], nested, f"{prefix}{name}.")
    return missing
