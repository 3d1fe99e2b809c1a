"""rosbridge v2's ops, as a client sends them: typed models, read by :class:`~services.protocols.ops.JsonOps`.

Each op is a pydantic model that ignores fields it does not use (clients send more, e.g.
roslibjs's ``latch`` and ``queue_size``), so a bad field is named in the ``status`` reply. A
client's fragmented frames are put together again by :class:`FragmentBuffer`; what goes back is
in :mod:`.frames`.
"""

from __future__ import annotations

import json
from typing import Any, Literal

from pydantic import Field

from services.protocols.ops import Op, Refused
from shared_models import Message

__all__ = [
    "Advertise",
    "AdvertiseService",
    "Auth",
    "CallService",
    "Fragment",
    "FragmentBuffer",
    "Publish",
    "RosbridgeOp",
    "ServiceResponse",
    "SetLevel",
    "Subscribe",
    "Unadvertise",
    "UnadvertiseService",
    "Unsubscribe",
    "request_body",
    "ros2_time_names",
]

Id = str | int | None


class RosbridgeOp(Op):
    """Fields every rosbridge op may carry: its ``id`` comes back in the replies to it."""

    id: Id = None


class Advertise(RosbridgeOp):
    topic: str
    type: str
    latch: bool = False  # roslibjs's and roslibpy's: the latest message goes to late subscribers
    queue_size: int = Field(default=100, ge=0)  # read as rosbridge_suite reads it, not used (every reader has its own queue)


class Unadvertise(RosbridgeOp):
    topic: str


class Publish(RosbridgeOp):
    topic: str
    msg: dict[str, Any] = Field(default_factory=dict)
    latch: bool = False  # for a topic published without an advertise first


class Subscribe(RosbridgeOp):
    topic: str
    type: str | None = None
    throttle_rate: int = Field(default=0, ge=0)  # ms between messages
    queue_length: int = Field(default=0, ge=0, le=10_000)
    fragment_size: int | None = Field(default=None, gt=0)
    compression: Literal["none", "png", "cbor", "cbor-raw"] | None = None


class Unsubscribe(RosbridgeOp):
    topic: str


class CallService(RosbridgeOp):
    service: str
    args: dict[str, Any] | list[Any] | None = None
    type: str | None = None
    timeout: float | None = Field(default=None, gt=0, allow_inf_nan=False)  # seconds
    fragment_size: int | None = Field(default=None, gt=0)
    compression: str | None = None


class ServiceResponse(RosbridgeOp):
    service: str
    values: Any = None  # the response's fields; a text with result false is the reason it failed
    result: bool = True


class AdvertiseService(RosbridgeOp):
    service: str
    type: str


class UnadvertiseService(RosbridgeOp):
    service: str


class SetLevel(RosbridgeOp):
    level: str


class Auth(RosbridgeOp):
    """ROS 1's rosauth op: ``mac`` is the token itself, or rosauth's MAC made with it (:mod:`.auth`)."""

    mac: str
    client: str = ""
    dest: str = ""
    rand: str = ""
    t: float | dict[str, int] = 0
    level: str = ""
    end: float | dict[str, int] = 0


class Fragment(RosbridgeOp):
    id: str | int
    data: str
    num: int = Field(ge=0)
    total: int = Field(gt=0, le=100_000)


def request_body(args: dict[str, Any] | list[Any] | None, request_type: type[Message] | None) -> bytes:
    """A call's ``args`` as a request body: an object as it is, a list in field order; ROS 1's
    time fields under ROS 2's names (roslibpy's TFClient sends its timeout ``{secs, nsecs}``)."""
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
    return ros2_time_names(json.dumps(args), args).encode()


def ros2_time_names(text: str, msg: dict[str, Any]) -> str:
    """A published message's JSON with ROS 1's time fields (``{"secs": 0, "nsecs": 0}``, as
    roslibpy's and roslibjs's actionlib stamp a goal) under ROS 2's names (``sec``, ``nanosec``),
    or left out where ROS 2's are there too;
    ``text`` (``msg`` as JSON) as it is when it has none, which a substring test tells cheaply."""
    if '"secs"' not in text and '"nsecs"' not in text:
        return text

    def renamed(value: Any) -> Any:
        if isinstance(value, list):
            return [renamed(item) for item in value]
        if not isinstance(value, dict):
            return value
        if "secs" in value or "nsecs" in value:
            if "sec" not in value and "nanosec" not in value:
                value = {_ROS1_TIME.get(key, key): item for key, item in value.items()}
            else:  # both names, as the core sends ROS 1's types (:mod:`.ros1_times`) and a client echoes
                value = {key: item for key, item in value.items() if key not in _ROS1_TIME}
        return {key: renamed(item) for key, item in value.items()}

    return json.dumps(renamed(msg))


_ROS1_TIME = {"secs": "sec", "nsecs": "nanosec"}


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

