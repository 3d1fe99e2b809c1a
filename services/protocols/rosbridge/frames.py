"""What a rosbridge connection sends: ``status`` replies, ``publish`` envelopes and fragments.

The ``publish`` envelope of a topic's frame is made once and shared by every connection
(:class:`PublishEnvelopes`); fragments are made per connection, where a client asked for them.
"""

from __future__ import annotations

import itertools
import json
from collections.abc import Sequence
from typing import Any

from services.runtime.edge.pump import Encode

__all__ = ["PublishEnvelopes", "fragments", "status_frame"]


def status_frame(level: str, text: str, op_id: str | int | None = None) -> str:
    """A ``status`` message, with the id of the op it answers."""
    status: dict[str, Any] = {"op": "status", "level": level, "msg": text}
    if op_id is not None:
        status["id"] = op_id
    return json.dumps(status)


class _Envelope:
    """A topic's publish message of its latest frame, kept while that frame is the newest."""

    __slots__ = ("frame", "messages", "prefix")

    def __init__(self, topic: str) -> None:
        self.prefix = '{"op":"publish","topic":' + json.dumps(topic) + ',"msg":'
        self.frame: str | None = None
        self.messages: Sequence[dict[str, Any]] = ()

    def encode(self, frame: str) -> Sequence[dict[str, Any]]:
        if frame is not self.frame:  # every reader gets the same str: one envelope per message
            self.messages = ({"type": "websocket.send", "text": self.prefix + frame + "}"},)
            self.frame = frame
        return self.messages


class PublishEnvelopes:
    """The ``publish`` message of each frame, made once for every rosbridge connection."""

    def __init__(self) -> None:
        self._envelopes: dict[str, _Envelope] = {}

    def encoder(self, topic: str) -> Encode:
        envelope = self._envelopes.get(topic)
        if envelope is None:
            envelope = self._envelopes[topic] = _Envelope(topic)
        return envelope.encode


def fragments(encode: Encode, size: int, label: str) -> Encode:
    """``encode``, with each message longer than ``size`` characters sent as ``fragment`` ops."""
    numbers = itertools.count(1)

    def fragmenting(frame: str) -> Sequence[dict[str, Any]]:
        messages = encode(frame)
        if all(len(message.get("text", "")) <= size for message in messages):
            return messages
        out = []
        for message in messages:
            text = message["text"]
            fragment_id = f"{label}:{next(numbers)}"
            pieces = [text[start : start + size] for start in range(0, len(text), size)]
            out += [
                {
                    "type": "websocket.send",
                    "text": json.dumps(
                        {"op": "fragment", "id": fragment_id, "data": piece, "num": num, "total": len(pieces)}
                    ),
                }
                for num, piece in enumerate(pieces)
            ]
        return out

    return fragmenting
