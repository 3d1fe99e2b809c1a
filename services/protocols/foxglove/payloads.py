"""What Foxglove reads of a Skydeck topic: its channel's schema, and each frame as a payload.

Channels are ``encoding: json`` with ``schemaEncoding: jsonschema`` and the ROS type as the
schema name (``geometry_msgs/msg/PoseStamped``), so Foxglove's and Lichtblick's panels (3D,
plots, raw messages) treat them as the ROS types they are; the schema is the one writer's
(:mod:`shared_models.json_schema`), as in recordings.

Foxglove reads a time as ``{sec, nsec}``; ROS 2's JSON says ``nanosec``. Every time in a payload
therefore carries both (``"nanosec": 5, "nsec": 5``): ROS 2 code reading the JSON and Foxglove's
panels each find their field. The payload of a frame is made once for every connection
(:class:`Payloads`); only a type that holds a time pays for the rewrite.
"""

from __future__ import annotations

from typing import Any

from shared_models import Message, ServiceType
from shared_models.json_schema import has_time, json_schema_text, with_nsec, without_nsec

__all__ = ["Payloads", "channel", "publishable_text", "service_schemas"]


def channel(cid: int, topic: str, msg_type: type[Message]) -> dict[str, Any]:
    """An ``advertise`` entry for ``topic``."""
    return {
        "id": cid,
        "topic": topic,
        "encoding": "json",
        "schemaName": msg_type.__ros_type__,
        "schema": json_schema_text(msg_type),
        "schemaEncoding": "jsonschema",
    }


def service_schemas(srv: type[ServiceType]) -> dict[str, Any]:
    """An ``advertiseServices`` entry's request and response descriptions (and the older
    ``requestSchema``/``responseSchema``, which some clients still read)."""
    request, response = json_schema_text(srv.Request), json_schema_text(srv.Response)
    return {
        "request": {
            "encoding": "json",
            "schemaName": srv.Request.__ros_type__,
            "schemaEncoding": "jsonschema",
            "schema": request,
        },
        "response": {
            "encoding": "json",
            "schemaName": srv.Response.__ros_type__,
            "schemaEncoding": "jsonschema",
            "schema": response,
        },
        "requestSchema": request,
        "responseSchema": response,
    }


class _Payload:
    __slots__ = ("frame", "payload", "times")

    def __init__(self, times: bool) -> None:
        self.times = times
        self.frame: str | None = None
        self.payload = b""


class Payloads:
    """Each topic's latest frame as a Foxglove payload, made once for every connection."""

    def __init__(self) -> None:
        self._topics: dict[tuple[str, type[Message]], _Payload] = {}

    def payload(self, topic: str, msg_type: type[Message], frame: str) -> bytes:
        slot = self._topics.get((topic, msg_type))
        if slot is None:
            slot = self._topics[(topic, msg_type)] = _Payload(has_time(msg_type))
        if frame is not slot.frame:  # every reader gets the same str object
            text = with_nsec(frame) if slot.times else frame
            slot.payload, slot.frame = text.encode(), frame
        return slot.payload


def publishable_text(payload: bytes) -> str:
    """A client's JSON payload as a Skydeck frame: a time it wrote as ``{sec, nsec}`` (Foxglove's
    way) gets ROS 2's ``nanosec``; raises ValueError for text that is not UTF-8 JSON."""
    return without_nsec(payload.decode())
