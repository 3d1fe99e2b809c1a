"""What a rosbridge connection sends: ``status`` replies, ``publish`` envelopes and fragments.

The ``publish`` envelope of a topic's frame is made once and shared by every connection
(:class:`PublishEnvelopes`), in each compression a subscription asks for: ``none`` (JSON text),
``png`` (:mod:`.png`), ``cbor`` (a binary frame, :mod:`.cbor`) and ``cbor-raw`` (a binary frame
whose ``msg`` is the message's CDR bytes and its receive time). Fragments are made per
connection, where a client asked for them; a binary frame is never fragmented (as rosbridge_suite
sends it).
"""

from __future__ import annotations

import itertools
import json
import logging
from collections.abc import Awaitable, Callable, Iterator, Sequence
from typing import Any

from services.protocols.rosbridge.cbor import dumps, message_values
from services.protocols.rosbridge.png import png_op
from services.protocols.rosbridge.ros1_times import speaks_ros1, with_ros1_times
from services.runtime.edge.pump import Encode
from shared_models import Message
from shared_models.cdr import codec_of

__all__ = ["COMPRESSIONS", "PublishEnvelopes", "Replies", "Status", "fragments", "merged_compression", "status_frame"]

logger = logging.getLogger("skydeck.rosbridge")

COMPRESSIONS = ("none", "png", "cbor", "cbor-raw")
"""What ``subscribe``'s ``compression`` may ask for (rosbridge_suite's four)."""

_REPLY_COMPRESSIONS = ("none", "png")  # call_service's and send_action_goal's, as the document lists


def merged_compression(asked: Sequence[str]) -> str:
    """One topic's compression for all its subscriptions on a connection: the most compact asked
    for (``cbor-raw``, ``cbor``, ``png``, then ``none``), as rosbridge_suite merges them."""
    for kind in ("cbor-raw", "cbor", "png"):
        if kind in asked:
            return kind
    return "none"


Status = Callable[[str, str, Any], Awaitable[None]]
"""``status(level, text, op_id)``: a connection's status reply, if the client's level asks for it."""


def status_frame(level: str, text: str, op_id: str | int | None = None) -> str:
    """A ``status`` message, with the id of the op it answers."""
    status: dict[str, Any] = {"op": "status", "level": level, "msg": text}
    if op_id is not None:
        status["id"] = op_id
    return json.dumps(status)


def _text(message: str) -> dict[str, Any]:
    return {"type": "websocket.send", "text": message}


class _Envelope:
    """A topic's publish message of its latest frame, kept while that frame is the newest."""

    __slots__ = ("frame", "make", "messages")

    def __init__(self, make: Callable[[str], dict[str, Any] | None]) -> None:
        self.make = make
        self.frame: str | None = None
        self.messages: Sequence[dict[str, Any]] = ()

    def encode(self, frame: str) -> Sequence[dict[str, Any]]:
        if frame is not self.frame:  # every reader gets the same str: one envelope per message
            try:
                message = self.make(frame)
            except Exception:  # a frame this compression cannot carry is skipped, never raised into a publisher
                logger.exception("rosbridge: could not encode a frame")
                message = None
            self.messages = () if message is None else (message,)
            self.frame = frame
        return self.messages


class PublishEnvelopes:
    """The ``publish`` message of each frame, made once for every rosbridge connection.

    ``message_type(topic)`` is the topic's type (what ``cbor`` and ``cbor-raw`` need to write a
    message), ``receive_time()`` the ROS time ``cbor-raw`` stamps a message with.
    """

    def __init__(
        self, message_type: Callable[[str], type[Message] | None], receive_time: Callable[[], tuple[int, int]]
    ) -> None:
        self._message_type = message_type
        self._receive_time = receive_time
        self._envelopes: dict[tuple[str, str], _Envelope] = {}

    def encoder(self, topic: str, compression: str = "none") -> Encode:
        envelope = self._envelopes.get((topic, compression))
        if envelope is None:
            envelope = self._envelopes[topic, compression] = _Envelope(self._maker(topic, compression))
        return envelope.encode

    def _maker(self, topic: str, compression: str) -> Callable[[str], dict[str, Any] | None]:
        prefix = '{"op":"publish","topic":' + json.dumps(topic) + ',"msg":'
        if compression in ("none", "png"):
            ros1: list[bool] = []  # decided at the first frame of a known type (:mod:`.ros1_times`)

            def make_text(frame: str) -> dict[str, Any]:
                if not ros1:
                    cls = self._message_type(topic)
                    if cls is not None:
                        ros1.append(speaks_ros1(cls))
                if ros1 and ros1[0]:
                    frame = with_ros1_times(frame)
                text = prefix + frame + "}"
                return _text(png_op(text) if compression == "png" else text)

            return make_text
        raw = compression == "cbor-raw"

        def make_cbor(frame: str) -> dict[str, Any] | None:
            cls = self._message_type(topic)
            values = json.loads(frame)
            if raw:
                if cls is None:
                    return None  # no type yet: no CDR
                secs, nsecs = self._receive_time()
                msg: Any = {"secs": secs, "nsecs": nsecs, "bytes": codec_of(cls).encode(values)}
            else:
                msg = values if cls is None else message_values(cls)(values)
            return {"type": "websocket.send", "bytes": dumps({"op": "publish", "topic": topic, "msg": msg})}

        return make_cbor


def fragments(encode: Encode, size: int, label: str, numbers: Iterator[int] | None = None) -> Encode:
    """``encode``, with each text message longer than ``size`` characters sent as ``fragment``
    ops (ids ``LABEL:N``, N from ``numbers``)."""
    numbers = numbers if numbers is not None else itertools.count(1)

    def fragmenting(frame: str) -> Sequence[dict[str, Any]]:
        messages = encode(frame)
        if all(len(message.get("text", "")) <= size for message in messages):
            return messages
        out = []
        for message in messages:
            text = message.get("text")
            if text is None or len(text) <= size:
                out.append(message)
                continue
            fragment_id = f"{label}:{next(numbers)}"
            pieces = [text[start : start + size] for start in range(0, len(text), size)]
            out += [
                _text(json.dumps({"op": "fragment", "id": fragment_id, "data": piece, "num": num, "total": len(pieces)}))
                for num, piece in enumerate(pieces)
            ]
        return out

    return fragmenting


class Replies:
    """A connection's replies of its own (``service_response``, ``action_feedback``...), in the
    compression and fragment size their op asked for; fragment ids are numbered per connection."""

    def __init__(self) -> None:
        self._numbers = itertools.count(1)

    @staticmethod
    def check(compression: str | None) -> None:
        """Raise ValueError for a compression a reply cannot have (``none`` and ``png`` can)."""
        if compression not in (None, *_REPLY_COMPRESSIONS):
            raise ValueError(f"compression {compression!r} is not one of {', '.join(_REPLY_COMPRESSIONS)} for this op")

    def texts(self, message: dict[str, Any], *, compression: str | None, fragment_size: int | None, label: str) -> list[str]:
        """The text frames that carry ``message``."""
        text = json.dumps(message)
        if compression == "png":
            text = png_op(text)
        if not fragment_size or len(text) <= fragment_size:
            return [text]
        sent = fragments(lambda whole: (_text(whole),), fragment_size, label, self._numbers)(text)
        return [piece["text"] for piece in sent]
