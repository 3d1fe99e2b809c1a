"""rosbridge v2's frames: the ops a client sends, read as typed models, and what goes back.

Each op is a pydantic model that ignores fields it does not use (clients send more, e.g.
roslibjs's ``latch`` and ``queue_size``), so a bad field is named in the ``status`` reply. The
``publish`` envelope of a topic's frame is made once and shared by every connection
(:class:`PublishEnvelopes`); fragments are made per connection, where a client asked for them.
"""

from __future__ import annotations

import itertools
import json
from collections.abc import Sequence
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, ValidationError

from services.runtime.edge.pump import Encode
from shared_models import Message
from shared_models.errors import SkydeckError

__all__ = [
    "OPS",
    "Advertise",
    "AdvertiseService",
    "Auth",
    "CallService",
    "Fragment",
    "FragmentBuffer",
    "Op",
    "Publish",
    "PublishEnvelopes",
    "Refused",
    "ServiceResponse",
    "SetLevel",
    "Subscribe",
    "Unadvertise",
    "UnadvertiseService",
    "Unsubscribe",
    "describe_error",
    "fragments",
    "request_body",
    "status_frame",
]

Id = str | int | None


class Refused(SkydeckError):
    """An op that cannot be carried out: answered with a ``status`` error, nothing else happens."""

    http_status = 400


class Op(BaseModel):
    """Fields every op may carry."""

    model_config = ConfigDict(extra="ignore", strict=True)

    op: str
    id: Id = None


class Advertise(Op):
    topic: str
    type: str


class Unadvertise(Op):
    topic: str


class Publish(Op):
    topic: str
    msg: dict[str, Any]


class Subscribe(Op):
    topic: str
    type: str | None = None
    throttle_rate: int = Field(default=0, ge=0)  # ms between messages
    queue_length: int = Field(default=0, ge=0, le=10_000)
    fragment_size: int | None = Field(default=None, gt=0)
    compression: str | None = None


class Unsubscribe(Op):
    topic: str


class CallService(Op):
    service: str
    args: dict[str, Any] | list[Any] | None = None
    type: str | None = None
    timeout: float | None = Field(default=None, gt=0, allow_inf_nan=False)  # seconds
    fragment_size: int | None = Field(default=None, gt=0)
    compression: str | None = None


class ServiceResponse(Op):
    service: str
    values: Any = None
    result: bool = True


class AdvertiseService(Op):
    service: str
    type: str


class UnadvertiseService(Op):
    service: str


class SetLevel(Op):
    level: str


class Auth(Op):
    mac: str  # the token (rosauth's other fields are not used)


class Fragment(Op):
    id: str | int
    data: str
    num: int = Field(ge=0)
    total: int = Field(gt=0, le=100_000)


OPS: dict[str, type[Op]] = {
    "advertise": Advertise,
    "unadvertise": Unadvertise,
    "publish": Publish,
    "subscribe": Subscribe,
    "unsubscribe": Unsubscribe,
    "call_service": CallService,
    "service_response": ServiceResponse,
    "advertise_service": AdvertiseService,
    "unadvertise_service": UnadvertiseService,
    "set_level": SetLevel,
    "auth": Auth,
    "fragment": Fragment,
}


def describe_error(op: str, error: ValidationError) -> str:
    """One line naming the first bad field of an op."""
    first = error.errors(include_url=False)[0]
    where = ".".join(str(part) for part in first["loc"]) or "(op)"
    return f"{op}: {where}: {first['msg']}"


def status_frame(level: str, text: str, op_id: Id = None) -> str:
    """A ``status`` message, with the id of the op it answers."""
    status: dict[str, Any] = {"op": "status", "level": level, "msg": text}
    if op_id is not None:
        status["id"] = op_id
    return json.dumps(status)


def request_body(args: dict[str, Any] | list[Any] | None, request_type: type[Message] | None) -> bytes:
    """A call's ``args`` as a request body: an object as it is, a list in field order."""
    if args is None:
        return b""
    if isinstance(args, list):
        if not args:
            return b""
        if request_type is None:
            raise Refused("args given as a list need the service's type: pass an object instead")
        names = list(request_type.model_fields)
        if len(args) > len(names):
            raise Refused(f"{len(args)} args for {len(names)} request fields ({', '.join(names)})")
        args = dict(zip(names, args, strict=False))
    return json.dumps(args).encode()


# -- out: publish envelopes and fragments -----------------------------------------------------------


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


class FragmentBuffer:
    """A client's fragmented frames, put together again (bounded like any frame)."""

    _MAX_PENDING = 16

    def __init__(self, max_bytes: int) -> None:
        self._max_bytes = max_bytes
        self._pending: dict[str | int, dict[int, str]] = {}

    def add(self, op: Fragment) -> str | None:
        """Keep one fragment; returns the whole frame once every fragment of it is here."""
        if op.num >= op.total:
            raise Refused(f"fragment {op.num} of {op.total}: num must be below total")
        pieces = self._pending.get(op.id)
        if pieces is None:
            if len(self._pending) >= self._MAX_PENDING:
                raise Refused(f"over {self._MAX_PENDING} fragmented frames are incomplete: finish one first")
            pieces = self._pending[op.id] = {}
        pieces[op.num] = op.data
        if sum(map(len, pieces.values())) > self._max_bytes:
            del self._pending[op.id]
            raise Refused(f"fragmented frame {op.id!r} is over {self._max_bytes} bytes")
        if len(pieces) < op.total:
            return None
        del self._pending[op.id]
        return "".join(pieces[num] for num in range(op.total))

