"""How a message travels in a frame: JSON text (the default) or msgpack, chosen per connection.

A client asks for msgpack with ``?encoding=msgpack`` or the WebSocket subprotocol
``skydeck.msgpack``, and then gets binary frames: the message itself as a msgpack map, field
names as in JSON, byte arrays (``uint8[]``) as msgpack binary instead of base64. Everyone else
gets JSON text, so ``websocat`` keeps working. CBOR is not offered (``?encoding=cbor`` and
``skydeck.cbor`` are refused with a reason that says what to ask for instead).

Nodes link to each other in msgpack: a publisher serialises each message once per encoding
that some reader wants (:class:`Frames`), straight from the model, which costs half of
``model_dump_json`` for a pose and a hundredth of it for a camera image.
"""

from __future__ import annotations

import base64
import enum
import json
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import ormsgpack
from pydantic import ValidationError

from services.runtime.edge.frames import FrameRejected, describe_validation_error
from services.runtime.wire import Close
from shared_models import Message

__all__ = ["Encoding", "Frames", "decode", "encode", "negotiate"]

_PACK_OPTIONS = ormsgpack.OPT_SERIALIZE_PYDANTIC | ormsgpack.OPT_NON_STR_KEYS


class Encoding(enum.Enum):
    """A frame encoding a connection may ask for."""

    JSON = "json"
    MSGPACK = "msgpack"

    @property
    def subprotocol(self) -> str:
        return f"skydeck.{self.value}"


_OFFERED = {encoding.value: encoding for encoding in Encoding}
_NOT_OFFERED = ("cbor",)


def negotiate(query: Mapping[str, str], subprotocols: Sequence[str]) -> tuple[Encoding, str | None]:
    """The encoding a handshake asks for, and the subprotocol to accept (if it asked for one).

    ``?encoding=`` wins over subprotocols; an unknown or refused codec raises FrameRejected(1008).
    """
    asked = query.get("encoding")
    chosen_subprotocol = None
    for subprotocol in subprotocols:
        name = subprotocol.removeprefix("skydeck.")
        if subprotocol.startswith("skydeck.") and name in _OFFERED:
            chosen_subprotocol = subprotocol
            asked = asked or name
            break
        if subprotocol.startswith("skydeck.") and name in _NOT_OFFERED:
            asked = asked or name
    if asked is None:
        return Encoding.JSON, chosen_subprotocol
    encoding = _OFFERED.get(asked)
    if encoding is None:
        offered = " or ".join(f"?encoding={e.value} (subprotocol {e.subprotocol})" for e in Encoding)
        raise FrameRejected(Close.POLICY, f"encoding {asked!r} is not offered: ask for {offered}")
    return encoding, chosen_subprotocol


def encode(msg: Message, encoding: Encoding) -> str | bytes:
    """``msg`` as one frame in ``encoding``."""
    if encoding is Encoding.JSON:
        return msg.model_dump_json()
    return ormsgpack.packb(msg, option=_PACK_OPTIONS)


def decode(frame: str | bytes, msg_type: type[Message], type_name: str) -> Message:
    """Validate one frame (JSON text or msgpack bytes) into ``msg_type``, or FrameRejected(1007)."""
    # The type's validator itself, not model_validate(_json): their keyword handling was ~15% of
    # a pose's decode (docs/performance.md).
    if isinstance(frame, bytes):
        try:
            value = ormsgpack.unpackb(frame)
        except (ormsgpack.MsgpackDecodeError, ValueError, TypeError) as error:
            raise FrameRejected(Close.INVALID_FRAME, f"not a msgpack {type_name}: {error}") from None
        return _validate_unpacked(value, msg_type, type_name)
    try:
        return msg_type.__pydantic_validator__.validate_json(frame)  # type: ignore[no-any-return]
    except ValidationError as error:
        raise FrameRejected(Close.INVALID_FRAME, describe_validation_error(type_name, error)) from None


def _validate_unpacked(value: Any, msg_type: type[Message], type_name: str) -> Message:
    """A message unpacked from msgpack (a frame, or one of a batch's), validated into ``msg_type``."""
    try:
        return msg_type.__pydantic_validator__.validate_python(value)  # type: ignore[no-any-return]
    except ValidationError as error:
        raise FrameRejected(Close.INVALID_FRAME, describe_validation_error(type_name, error)) from None
    except (ValueError, TypeError) as error:
        raise FrameRejected(Close.INVALID_FRAME, f"not a msgpack {type_name}: {error}") from None


class Frames:
    """One message in every encoding its readers want, each made at most once.

    Made from the message (a publisher), or from a frame as received (a link, a client) with
    the type, if known, for converting it.
    """

    __slots__ = ("_build", "_json", "_msg", "_packed", "_type", "_unpacked")

    def __init__(
        self,
        msg: Message | None = None,
        *,
        json_text: str | None = None,
        packed: bytes | None = None,
        unpacked: Any = None,
        msg_type: type[Message] | None = None,
    ) -> None:
        self._msg = msg
        self._json = json_text
        self._packed = packed
        self._type = msg_type if msg_type is not None else type(msg) if msg is not None else None
        self._unpacked = unpacked  # a message of a batch, unpacked but not validated
        self._build: Callable[[], Message] | None = None

    @classmethod
    def received(cls, frame: str | bytes, msg_type: type[Message] | None) -> Frames:
        """The frames of one frame as it arrived (the other encoding is made if asked for)."""
        if isinstance(frame, str):
            return cls(json_text=frame, msg_type=msg_type)
        return cls(packed=frame, msg_type=msg_type)

    @classmethod
    def unpacked(cls, value: Any, msg_type: type[Message] | None) -> Frames:
        """The frames of one message of a batch (:mod:`.batch`), as unpacked from it."""
        return cls(unpacked=value, msg_type=msg_type)

    @classmethod
    def deferred(cls, build: Callable[[], Message], msg_type: type[Message]) -> Frames:
        """The frames of a message not made yet: ``build()`` makes it when first asked for (a
        publisher's message that nobody reads now, kept as the topic's latest)."""
        frames = cls(msg_type=msg_type)
        frames._build = build
        return frames

    def get(self, encoding: Encoding) -> str | bytes:
        return self.json if encoding is Encoding.JSON else self.packed

    @property
    def json(self) -> str:
        if self._json is None:
            if self._msg is None and self._type is None:
                unpacked = self._unpacked if self._unpacked is not None else ormsgpack.unpackb(self._packed or b"")
                self._json = _untyped_json(unpacked)
            else:
                self._json = self.message().model_dump_json()
        return self._json

    @property
    def packed(self) -> bytes:
        if self._packed is None:
            if self._unpacked is not None:
                self._packed = ormsgpack.packb(self._unpacked)  # bytes stay bytes
            elif self._msg is None and self._type is None:
                # Without the type, base64 text cannot be told from a string: it stays text.
                self._packed = ormsgpack.packb(json.loads(self._json or "null"))
            else:
                self._packed = ormsgpack.packb(self.message(), option=_PACK_OPTIONS)
        return self._packed

    def message(self) -> Message:
        """The message itself (parsed once, from whichever frame there is)."""
        if self._msg is None and self._build is not None:
            self._msg, self._build = self._build(), None
        if self._msg is None:
            if self._type is None:
                raise TypeError("a frame of an unknown type has no message")
            type_name = self._type.__ros_type__
            if self._unpacked is not None:
                self._msg = _validate_unpacked(self._unpacked, self._type, type_name)
            else:
                source: str | bytes = self._json if self._json is not None else self._packed or b""
                self._msg = decode(source, self._type, type_name)
        return self._msg


def _untyped_json(unpacked: Any) -> str:
    """A msgpack message of a type this process does not know, as JSON: byte arrays as standard
    base64 (as the models write them), so a browser can still put a JPEG in a data: URL."""
    # The C encoder calls _base64 for the byte arrays it meets: no walk of the value in Python
    # first (that walk was a third of this function's time in the core; docs/performance.md).
    return json.dumps(unpacked, default=_base64, separators=(",", ":"), allow_nan=False)


def _base64(value: Any) -> str:
    if isinstance(value, bytes):
        return base64.b64encode(value).decode("ascii")
    raise TypeError(f"a msgpack frame holds a {type(value).__name__}, which JSON cannot carry")
